// The page's URL hash (web/settings.js) speaks the scene files' words: it writes
// semi_implicit_euler and velocity_products, reads them back, and still reads the
// previous release's words (semi-implicit, euler, velocity, push) as those names. The
// names it accepts and its defaults are the module's (web/module_offer.js), the policy and
// the adaptive integrator's relative tolerance among them.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { DIRECTIONS, EFFECTS, GRAVITY, MOTION_PARAMETERS, adoptOffer, defaultSettings, formatHash, hashOwn, hashRobot, isAdaptive,
  motionFrom, motionInSimulatorTime, parseHash, simulatorOptions } from '../../web/settings.js';
import { moduleOffer } from '../../web/module_offer.js';
import { loadAchd } from './helpers.mjs';

// What web/module_offer.js makes of the module (checked against the real one below).
const OFFER = {
  integrators: ['explicit_euler', 'semi_implicit_euler', 'rk4', 'dormand_prince', 'implicit_euler'],
  policies: ['truncate', 'damped', 'variable_damping'],
  limitPolicies: ['ignore', 'report', 'clamp'],
  adaptiveIntegrators: ['dormand_prince'],
  directions: ['x', 'y', 'z', 'rx', 'ry', 'rz'],
  effects: ['gravity', 'velocity_products', 'external_wrenches', 'damping', 'friction', 'rotor_inertia', 'constraints'],
  gravity: [0, 0, -9.81],
  defaults: { integrator: 'dormand_prince', policy: 'variable_damping', rtol: 1e-9, limits: 'report' },
};
adoptOffer(OFFER);

test('the page\'s directions, effect switches, gravity and adaptive integrators are the offer\'s', () => {
  assert.deepEqual(DIRECTIONS, OFFER.directions);
  // every effect but the two the page keeps on, under the simulator's key and the scene word
  assert.deepEqual(EFFECTS.map((e) => [e.key, e.hash]), [['gravity', 'gravity'], ['velocityProducts', 'velocity_products'],
    ['externalWrenches', 'external_wrenches'], ['damping', 'damping'], ['friction', 'friction']]);
  assert.deepEqual(GRAVITY, [0, 0, -9.81]);
  assert.equal(isAdaptive('dormand_prince'), true);
  assert.equal(isAdaptive('rk4'), false);
  // A module with other lists: the page follows it (no list of its own).
  adoptOffer({ ...OFFER, directions: ['z'], effects: ['gravity', 'constraints'], gravity: [0, 0, -1.62], adaptiveIntegrators: ['rk4'] });
  try {
    assert.deepEqual(DIRECTIONS, ['z']);
    assert.deepEqual(EFFECTS.map((e) => e.hash), ['gravity']);
    assert.deepEqual(GRAVITY, [0, 0, -1.62]);
    assert.equal(isAdaptive('rk4'), true);
    assert.equal(isAdaptive('dormand_prince'), false);
  } finally {
    adoptOffer(OFFER);
  }
});

test('the joint-limit policy: the simulator\'s default unless chosen, then in the hash and the options', () => {
  const s = defaultSettings('panda_fingers', OFFER);
  assert.equal(s.limits, null);
  assert.doesNotMatch(formatHash(s), /limits=/);
  assert.equal(simulatorOptions(s).limits, undefined);
  s.limits = 'clamp';
  const hash = formatHash(s);
  assert.match(hash, /&limits=clamp&/);
  assert.equal(simulatorOptions(s).limits, 'clamp');
  assert.deepEqual(parseHash(hash, defaultSettings('ur5', OFFER), OFFER), { settings: s, problems: [] });
  assert.deepEqual(parseHash('#robot=ur5&limits=soft', defaultSettings('ur5', OFFER), OFFER).problems,
    ['unknown joint-limit policy "soft"']);
});

test('the hash writes the scene names and reads them back', () => {
  const s = defaultSettings('ur5', OFFER);
  s.integrator = 'semi_implicit_euler';
  s.effects.friction = false;
  s.directions.z = 'hold';
  const hash = formatHash(s);
  assert.equal(hash, '#robot=ur5&integrator=semi_implicit_euler&dt=0.001&policy=variable_damping' +
    '&effects=gravity,velocity_products,external_wrenches,damping&dirs=z:hold');
  assert.deepEqual(parseHash(hash, defaultSettings('kuka_lwr4', OFFER), OFFER), { settings: s, problems: [] });
  assert.equal(hashRobot(hash, 'kuka_lwr4'), 'ur5');
  assert.equal(hashRobot('#dt=0.001', 'kuka_lwr4'), 'kuka_lwr4');
});

test('an own URDF\'s place in the link (urdf=, root=, tip=) goes after the robot and comes back', () => {
  const s = defaultSettings('custom', OFFER);
  s.own = { ref: 'local:0123456789abcdef', root: 'base link', tip: 'tool', floating: false };
  const hash = formatHash(s);
  assert.ok(hash.startsWith('#robot=custom&urdf=local:0123456789abcdef&root=base+link&tip=tool&integrator='), hash);
  assert.deepEqual(parseHash(hash, defaultSettings('ur5', OFFER), OFFER), { settings: s, problems: [] });
  assert.deepEqual(hashOwn(hash), s.own);
  assert.equal(hashOwn('#robot=custom&urdf=deflate:AA'), null);
  assert.deepEqual(parseHash('#robot=custom&urdf=deflate:AA', defaultSettings('ur5', OFFER), OFFER).problems,
    ['urdf= needs root= (the own URDF\'s root link; tip= for a chain)']);
});

test('a whole own robot on a floating base is in the link without tip=, with base=floating', () => {
  const s = defaultSettings('custom', OFFER);
  s.own = { ref: 'local:0123456789abcdef', root: 'base_link', tip: null, floating: true };
  const hash = formatHash(s);
  assert.ok(hash.startsWith('#robot=custom&urdf=local:0123456789abcdef&root=base_link&base=floating&integrator='), hash);
  assert.deepEqual(hashOwn(hash), s.own);
  assert.deepEqual(parseHash(hash, defaultSettings('ur5', OFFER), OFFER), { settings: s, problems: [] });
});

test('directions that yield to pushes are stored in the hash; prescribed joints are not', () => {
  const s = defaultSettings('kuka_lwr4', OFFER);
  s.directions.z = 'hold';
  s.yielding.z = true;
  s.prescribed.lwr_joint_1 = motionFrom({ motion: 'constant', position: 0.3 }, 2);
  const hash = formatHash(s);
  assert.match(hash, /&dirs=z:hold&yield=z$/);
  const back = parseHash(hash, defaultSettings('kuka_lwr4', OFFER), OFFER);
  assert.deepEqual(back.problems, []);
  assert.deepEqual(back.settings, { ...s, prescribed: {} });
  assert.deepEqual(parseHash('#yield=up', defaultSettings('ur5', OFFER), OFFER).problems, ['yield: unknown direction "up"']);
});

// The page starts a motion where it is applied: q(t) of the simulator's sine at page time
// t = t0 + its own time passes through the given centre, rising, at the page time of Apply.
test('a page motion starts at its given position when applied, in any simulator\'s time', async () => {
  const achd = await loadAchd();
  assert.deepEqual(Object.keys(MOTION_PARAMETERS), achd.constants.motion_kinds);
  const sine = motionFrom({ motion: 'sine', position: 0.3, amplitude: 0.5, frequency: 0.5 }, 2.25);
  const at = (m, t) => m.position + m.amplitude * Math.sin(2 * Math.PI * m.frequency * t + m.phase);
  assert.ok(Math.abs(at(sine, 2.25) - 0.3) < 1e-15);
  assert.ok(at(sine, 2.3) > 0.3, 'rising');
  const inSim = motionInSimulatorTime(sine, 1.5);  // a simulator built at page time 1.5
  assert.ok(Math.abs(at(inSim, 2.25 - 1.5) - 0.3) < 1e-15);
  const ramp = motionFrom({ motion: 'ramp', position: 1, velocity: 0.2 }, 3);
  assert.ok(Math.abs(motionInSimulatorTime(ramp, 1).position + 0.2 * 2 - 1) < 1e-15);
  assert.throws(() => motionFrom({ motion: 'sine', position: 0, amplitude: 1, frequency: -1 }, 0), /frequency must be >= 0/);
  assert.throws(() => motionFrom({ motion: 'ramp', position: 0 }, 0), /ramp motion: velocity must be a finite number/);
  assert.throws(() => motionFrom({ motion: 'square' }, 0), /unknown motion "square"/);
});

test('the policy and the adaptive integrator\'s rtol are stored in the hash', () => {
  const s = defaultSettings('ur5', OFFER);
  assert.equal(formatHash(s), '#robot=ur5&integrator=dormand_prince&rtol=1e-9&dt=0.001&policy=variable_damping' +
    '&effects=gravity,velocity_products,external_wrenches,damping,friction');
  s.rtol = 1e-8;
  s.policy = 'damped';
  s.directions.y = 0.5;
  const hash = formatHash(s);
  assert.equal(hash, '#robot=ur5&integrator=dormand_prince&rtol=1e-8&dt=0.001&policy=damped' +
    '&effects=gravity,velocity_products,external_wrenches,damping,friction&dirs=y:0.5');
  assert.deepEqual(parseHash(hash, defaultSettings('kuka_lwr4', OFFER), OFFER), { settings: s, problems: [] });
  assert.deepEqual(simulatorOptions(s), {
    integrator: 'dormand_prince', policy: 'damped', rtol: 1e-8, gravity: [0, 0, -9.81],
    effects: { gravity: true, velocityProducts: true, damping: true, friction: true, externalWrenches: true,
      rotorInertia: true, constraints: true },
  });
  // A fixed-step integrator takes no tolerance: none in the hash, none passed.
  s.integrator = 'implicit_euler';
  assert.doesNotMatch(formatHash(s), /rtol/);
  assert.equal(simulatorOptions(s).rtol, undefined);
  assert.deepEqual(parseHash('#policy=magic&rtol=2', defaultSettings('ur5', OFFER), OFFER).problems,
    ['rtol must be a number in (0, 1), got "2"', 'unknown policy "magic"']);
});

test('hashes with the previous release\'s words still parse, as the current names', () => {
  for (const [old, now] of [['semi-implicit', 'semi_implicit_euler'], ['euler', 'explicit_euler']]) {
    const { settings, problems } = parseHash(`#integrator=${old}`, defaultSettings('ur5', OFFER), OFFER);
    assert.deepEqual(problems, []);
    assert.equal(settings.integrator, now);
  }
  const { settings, problems } = parseHash('#effects=velocity,push', defaultSettings('ur5', OFFER), OFFER);
  assert.deepEqual(problems, []);
  assert.deepEqual(settings.effects, Object.fromEntries(EFFECTS.map((e) =>
    [e.key, e.key === 'velocityProducts' || e.key === 'externalWrenches'])));
  assert.deepEqual(parseHash('#integrator=verlet', defaultSettings('ur5', OFFER), OFFER).problems, ['unknown integrator "verlet"']);
  assert.deepEqual(parseHash('#integrator=toString', defaultSettings('ur5', OFFER), OFFER).problems, ['unknown integrator "toString"']);
});

// The real module: what the page offers is what achd.constants lists, with the
// simulator's defaults, and the page's default settings create a simulator.
test('the page offers the module\'s integrators, policies, joint-limit policies, directions, effects, gravity and defaults', async () => {
  const achd = await loadAchd();
  const k = achd.constants;
  const offer = moduleOffer(achd);
  assert.deepEqual(offer, {
    integrators: [...k.integrators],
    policies: [...k.singularity_policies],
    limitPolicies: [...k.limit_policies],
    adaptiveIntegrators: [...k.adaptive_integrators],
    directions: [...k.directions],
    effects: Object.keys(k.effects),
    gravity: [...k.simulator_options.gravity],
    defaults: { integrator: k.simulator_options.integrator, policy: k.simulator_options.solver.policy,
      rtol: k.simulator_options.rtol, limits: k.simulator_options.limits },
  });
  assert.deepEqual(offer, OFFER);
  const robot = achd.loadURDF(`<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>`,
  { root: 'a', tip: 'b' });
  try {
    const options = simulatorOptions(defaultSettings('r', offer));
    assert.equal(options.rtol, 1e-9);
    assert.equal(options.policy, 'variable_damping');
    robot.createSimulator(options).delete();
  } finally {
    robot.delete();
  }
});
