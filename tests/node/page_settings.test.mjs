// The page's URL hash (web/settings.js) speaks the scene files' words: it writes
// semi_implicit_euler and velocity_products, reads them back, and still reads the
// previous release's words (semi-implicit, euler, velocity, push) as those names. The
// names it accepts and its defaults are the module's (web/module_offer.js): a policy and
// a relative tolerance only where the module's simulator takes them.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { EFFECTS, defaultSettings, formatHash, hashRobot, parseHash, simulatorOptions } from '../../web/settings.js';
import { moduleOffer } from '../../web/module_offer.js';
import { loadAchd } from './helpers.mjs';

// A module with the policy option and an adaptive integrator, and one without (the
// module before issue 14's merges): both as web/module_offer.js describes them.
const FULL = {
  integrators: ['explicit_euler', 'semi_implicit_euler', 'rk4', 'dormand_prince', 'implicit_euler'],
  policies: ['truncate', 'damped', 'variable_damping'],
  defaults: { integrator: 'rk4', policy: 'variable_damping', rtol: 1e-6 },
};
const BARE = {
  integrators: ['explicit_euler', 'semi_implicit_euler', 'rk4'],
  policies: [],
  defaults: { integrator: 'rk4', policy: null, rtol: null },
};

test('the hash writes the scene names and reads them back', () => {
  const s = defaultSettings('ur5', BARE);
  s.integrator = 'semi_implicit_euler';
  s.effects.friction = false;
  s.directions.z = 'hold';
  const hash = formatHash(s);
  assert.equal(hash,
    '#robot=ur5&integrator=semi_implicit_euler&dt=0.001&effects=gravity,velocity_products,damping,external_wrenches&dirs=z:hold');
  assert.deepEqual(parseHash(hash, defaultSettings('kuka_lwr4', BARE), BARE), { settings: s, problems: [] });
  assert.equal(hashRobot(hash, 'kuka_lwr4'), 'ur5');
  assert.equal(hashRobot('#dt=0.001', 'kuka_lwr4'), 'kuka_lwr4');
});

test('the policy and the adaptive integrator\'s rtol are stored in the hash where the module takes them', () => {
  const s = defaultSettings('ur5', FULL);
  assert.equal(s.policy, 'variable_damping');
  s.integrator = 'dormand_prince';
  s.rtol = 1e-8;
  s.policy = 'damped';
  s.directions.y = 0.5;
  const hash = formatHash(s);
  assert.equal(hash, '#robot=ur5&integrator=dormand_prince&rtol=1e-8&dt=0.001&policy=damped' +
    '&effects=gravity,velocity_products,damping,friction,external_wrenches&dirs=y:0.5');
  assert.deepEqual(parseHash(hash, defaultSettings('kuka_lwr4', FULL), FULL), { settings: s, problems: [] });
  assert.deepEqual(simulatorOptions(s), {
    integrator: 'dormand_prince', policy: 'damped', rtol: 1e-8, gravity: [0, 0, -9.81],
    effects: { gravity: true, velocityProducts: true, damping: true, friction: true, externalWrenches: true,
      rotorInertia: true, constraints: true },
  });
  // A fixed-step integrator takes no tolerance: none in the hash, none passed.
  s.integrator = 'implicit_euler';
  assert.doesNotMatch(formatHash(s), /rtol/);
  assert.equal(simulatorOptions(s).rtol, undefined);
  assert.deepEqual(parseHash('#policy=magic&rtol=2', defaultSettings('ur5', FULL), FULL).problems,
    ['rtol must be a number in (0, 1), got "2"', 'unknown policy "magic"']);
});

test('without the options in the module, the hash neither writes nor takes them', () => {
  const s = defaultSettings('ur5', BARE);
  assert.equal(s.policy, null);
  assert.equal(s.rtol, null);
  assert.doesNotMatch(formatHash(s), /policy|rtol/);
  assert.deepEqual(Object.keys(simulatorOptions(s)).sort(), ['effects', 'gravity', 'integrator']);
  const { settings, problems } = parseHash('#integrator=dormand_prince&policy=variable_damping&rtol=1e-6',
    defaultSettings('ur5', BARE), BARE);
  assert.deepEqual(problems, ['unknown integrator "dormand_prince"',
    'rtol: this build of the module has no adaptive integrator', 'unknown policy "variable_damping"']);
  assert.deepEqual(settings, defaultSettings('ur5', BARE));
});

test('hashes with the previous release\'s words still parse, as the current names', () => {
  for (const [old, now] of [['semi-implicit', 'semi_implicit_euler'], ['euler', 'explicit_euler']]) {
    const { settings, problems } = parseHash(`#integrator=${old}`, defaultSettings('ur5', BARE), BARE);
    assert.deepEqual(problems, []);
    assert.equal(settings.integrator, now);
  }
  const { settings, problems } = parseHash('#effects=velocity,push', defaultSettings('ur5', BARE), BARE);
  assert.deepEqual(problems, []);
  assert.deepEqual(settings.effects, Object.fromEntries(EFFECTS.map((e) =>
    [e.key, e.key === 'velocityProducts' || e.key === 'externalWrenches'])));
  assert.deepEqual(parseHash('#integrator=verlet', defaultSettings('ur5', BARE), BARE).problems, ['unknown integrator "verlet"']);
  assert.deepEqual(parseHash('#integrator=toString', defaultSettings('ur5', BARE), BARE).problems, ['unknown integrator "toString"']);
});

// The real module: what the page offers is what achd.constants lists, with the
// simulator's defaults; the policy and rtol controls exactly when createSimulator takes
// those options.
test('the page offers the module\'s integrators, policies and defaults', async () => {
  const achd = await loadAchd();
  const offer = moduleOffer(achd);
  const k = achd.constants;
  assert.deepEqual(offer.integrators, k.integrators);
  assert.equal(offer.defaults.integrator, k.simulator_options.integrator);
  const robot = achd.loadURDF(`<robot name="r"><link name="a"/><link name="b"><inertial><mass value="1"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>`,
  { root: 'a', tip: 'b' });
  const takes = (options) => {
    try {
      robot.createSimulator(options).delete();
      return true;
    } catch {
      return false;
    }
  };
  const policy = k.simulator_options.policy ?? k.simulator_options.solver.policy;
  assert.equal(offer.policies.length > 0, takes({ policy }));
  assert.equal(offer.defaults.policy, offer.policies.length ? policy : null);
  if (offer.policies.length) assert.deepEqual(offer.policies, k.singularity_policies);
  assert.equal(offer.defaults.rtol !== null, k.simulator_options.rtol !== undefined && takes({ rtol: k.simulator_options.rtol }));
  console.log(`# module offers policies [${offer.policies}], rtol ${offer.defaults.rtol}, integrators [${offer.integrators}]`);
  robot.delete();
});
