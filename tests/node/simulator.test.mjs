// The simulator behind the JS API: every scene in robots/scenes/ run in wasm ends where
// the native `achd simulate` ends, held directions stay held, energy is conserved, and
// bad input throws an Error naming the problem without breaking the simulator.
import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { before, test } from 'node:test';

import { loadAchd, nativeCli, relativeError, repo, robots, runCli, scratchDir } from './helpers.mjs';

const SCENES = join(repo, 'robots/scenes');
// Scene values are JS values; scene keys are JS keys in camelCase.
const camelCase = (name) => name.replace(/_([a-z])/g, (_, ch) => ch.toUpperCase());
// Scene fields -> createSimulator options (the rest are handled in startScene).
const OPTIONS = ['limits', 'friction_velocity', 'stabilisation_frequency', 'stabilisation_damping', 'rtol', 'atol'];
const HANDLED = ['description', 'urdf', 'root', 'tip', 'q0', 'qd0', 'effects', 'directions', 'direction_weights', 'integrator',
  'dt', 'duration', 'gravity', 'ff_torques', 'f_ext', 'prescribed', 'floating', 'link_directions', 'joint_control',
  'mimic', 'inertia', 'srdf', 'pose', 'loops', ...OPTIONS];
// A scene's output step when it gives none (tools/scene_json.hpp's kDefaultSceneDt).
const sceneDt = (scene) => scene.dt ?? 1e-3;

// The robot of a scene, loaded with its loader fields (the SRDF text for srdf).
function loadSceneRobot(scene) {
  const load = { root: scene.root, tip: scene.tip, floating: scene.floating, mimic: scene.mimic, inertia: scene.inertia };
  if (scene.srdf) Object.assign(load, { srdf: readFileSync(join(repo, scene.srdf), 'utf8'), pose: scene.pose });
  if (scene.loops) load.loops = typeof scene.loops === 'string' ? JSON.parse(readFileSync(join(repo, scene.loops), 'utf8')).loops : scene.loops;
  for (const key of Object.keys(load)) if (load[key] === undefined) delete load[key];
  return achd.loadURDF(readFileSync(join(repo, scene.urdf), 'utf8'), load);
}

let achd, kuka, kukaEntry;
before(async () => {
  achd = await loadAchd();
  kukaEntry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(kukaEntry.text, { root: kukaEntry.root, tip: kukaEntry.tip });
});

const readScene = (file) => JSON.parse(readFileSync(join(SCENES, file), 'utf8'));

// A simulator configured as tools/scene_json.cpp's start_scene configures the native one.
function startScene(scene, robot) {
  for (const key of Object.keys(scene))
    if (!HANDLED.includes(key)) throw new Error(`the test does not map scene field '${key}' to the JS API`);
  const options = { integrator: scene.integrator };
  if (scene.effects)
    options.effects = Object.fromEntries(Object.entries(scene.effects).map(([k, on]) => [camelCase(k), on]));
  if (scene.gravity) options.gravity = scene.gravity;
  for (const field of OPTIONS) if (field in scene) options[camelCase(field)] = scene[field];
  const sim = robot.createSimulator(options);
  sim.reset(scene.q0 ?? robot.startPose, scene.qd0);
  if (scene.ff_torques) sim.ff_torques.set(scene.ff_torques);
  for (const [link, wrench] of Object.entries(scene.f_ext ?? {})) sim.setExternalWrench(link, wrench);
  for (const [name, w] of Object.entries(scene.direction_weights ?? {}))
    sim.setDirectionWeights(name, { wFext: w.w_fext, wFf: w.w_ff });
  for (const [name, mode] of Object.entries(scene.directions ?? {})) sim.setDirection(name, mode);
  for (const set of scene.link_directions ?? []) {
    if (set.point) sim.setDirectionPoint(set.link, set.point);
    for (const [name, w] of Object.entries(set.direction_weights ?? {}))
      sim.setDirectionWeights(name, { wFext: w.w_fext, wFf: w.w_ff }, set.link);
    for (const [name, mode] of Object.entries(set.directions ?? {})) sim.setDirection(name, mode, set.link);
  }
  for (const p of scene.prescribed ?? []) {
    const { joint, ...motion } = p;
    sim.prescribe(joint, motion);  // after the directions: its jump respects them
  }
  if (scene.joint_control) {
    const { damping_ratio: dampingRatio, ...control } = scene.joint_control;
    sim.setJointControl(dampingRatio === undefined ? control : { ...control, dampingRatio });
  }
  return sim;
}

// The 50-link chain falling is chaotic (halving RK4's step changes its state at 2 s by
// 1.4e-7 rad, docs/accuracy/chain50): the last-bit differences of glibc's and musl's
// sin/cos grow exponentially along it, so it is compared after 1 s of its 2 s.
// The undamped LWR's wrist spins up to hundreds of rad/s and its motion is as sensitive:
// it is compared after 0.5 s, all of it (at 1 s the last-bit differences of glibc's and
// musl's sin/cos have grown to 1.5e-9 in qd).
// The real robots standing and the stiff humanoid are compared after 1 s of their 10 s (the
// native suite runs them whole). The LWR holding 6D on a driven base is dragged through
// poses where its holds are lost and resumed, and from there its motion is as sensitive
// (after 10 s the two runs differ by 3% in q): it is compared after 1 s (there q agrees to 1.1e-11, qd to 1.5e-10).
// The undamped 50-joint chain holding its tip is more sensitive still: compared after 0.5 s
// (q agrees there to 4.6e-14; at 1 s the last-bit differences have grown to 2.6e-8).
const HORIZON = { 'chain50_fall.json': 1.0, 'chain50_undamped_hold_xyz.json': 0.5, 'kuka_lwr4_undamped_hold_z_rx.json': 0.5, 'anymal_c_stand.json': 1,
  'go2_stand.json': 1, 'solo12_stand.json': 1, 'talos_stand.json': 1, 'humanoid_stiff_hold.json': 1,
  'kuka_lwr4_hold_6d_driven_base.json': 1 };

// The row of `achd simulate --out` at step `steps` (t, q, qd, tip pose; 17 significant
// digits, so the doubles round-trip exactly).
async function nativeState(file, nq, nj, steps) {
  const tmp = scratchDir();
  try {
    const csv = join(tmp.dir, 'traj.csv');
    await runCli(nativeCli(), ['simulate', join(SCENES, file), '--out', csv]);
    const rows = readFileSync(csv, 'utf8').trim().split('\n');
    const last = rows[1 + steps].split(',').map(Number);
    return { t: last[0], q: last.slice(1, 1 + nq), qd: last.slice(1 + nq, 1 + nq + nj) };
  } finally {
    tmp.remove();
  }
}

for (const file of readdirSync(SCENES).filter((f) => f.endsWith('.json')).sort()) {
  test(`scene ${file}: wasm ends where native achd simulate ends (relative error <= 1e-9)`, async (t) => {
    const scene = readScene(file);
    const robot = loadSceneRobot(scene);
    const sim = startScene(scene, robot);
    try {
      const steps = Math.round(Math.min(scene.duration, HORIZON[file] ?? Infinity) / sceneDt(scene));
      sim.step(steps, sceneDt(scene));
      const native = await nativeState(file, sim.numPositions, robot.numRates, steps);
      assert.equal(sim.t, native.t);
      const eq = relativeError(Array.from(sim.q), native.q), eqd = relativeError(Array.from(sim.qd), native.qd);
      t.diagnostic(`relative error q ${eq.toExponential(2)}, qd ${eqd.toExponential(2)}`);
      assert.ok(eq <= 1e-9, `q: relative error ${eq}`);
      assert.ok(eqd <= 1e-9, `qd: relative error ${eqd}`);
    } finally {
      sim.delete();
      robot.delete();
    }
  });
}

test('held z and rx stay within 1e-6 over 2000 steps of 1 ms; only held directions report a residual', (t) => {
  const sim = startScene(readScene('kuka_lwr4_hold_z_rx.json'), kuka);
  try {
    sim.setDirection('y', 0.05);  // accelerated (5 cm in y over 2 s): no residual, like the free ones
    const q0 = Array.from(sim.q);
    let worst = 0;
    for (let s = 0; s < 2000; ++s) {
      sim.step(1, 1e-3);
      const r = sim.residuals();
      for (const d of ['x', 'y', 'ry', 'rz']) assert.equal(r[d], null, `${d} is not held`);
      worst = Math.max(worst, Math.abs(r.z), Math.abs(r.rx));
    }
    t.diagnostic(`largest held residual ${worst.toExponential(2)}`);
    assert.ok(worst < 1e-6, `largest held residual ${worst}`);
    // The arm did move: the held rows constrain it, they do not freeze it.
    assert.ok(relativeError(Array.from(sim.q), q0) > 1e-2, 'the arm stayed where it was');
  } finally {
    sim.delete();
  }
});

test('gravity + velocity products only, RK4 at 0.25 ms for 2 s: |E - E0| <= 1e-6 max kinetic energy', (t) => {
  const sim = kuka.createSimulator({ integrator: 'rk4', effects: achd.Effects.gravity | achd.Effects.velocityProducts });
  try {
    sim.reset(kukaEntry.q0);
    const E0 = sim.energy().total;
    let maxKinetic = 0, maxError = 0;
    for (let s = 0; s < 8000; ++s) {
      sim.step(1, 2.5e-4);
      const e = sim.energy();
      maxKinetic = Math.max(maxKinetic, e.kinetic);
      maxError = Math.max(maxError, Math.abs(e.total - E0));
    }
    t.diagnostic(`max kinetic ${maxKinetic.toFixed(1)} J, drift ${(maxError / maxKinetic).toExponential(2)} of it`);
    assert.ok(maxKinetic > 1, `the arm barely moved (max kinetic energy ${maxKinetic} J)`);
    assert.ok(maxError <= 1e-6 * maxKinetic, `energy drift ${maxError / maxKinetic} of the max kinetic energy`);
  } finally {
    sim.delete();
  }
});

test('joint limits: report lists the joint, clamp also puts it back, ignore does neither', () => {
  const j = 1, upper = kuka.limits[j].upper, q = Array.from(kukaEntry.q0);
  q[j] = upper + 0.1;
  const qd = [0, 1, 0, 0, 0, 0, 0];
  for (const limits of ['report', 'clamp', 'ignore']) {
    const sim = kuka.createSimulator({ limits });
    try {
      sim.reset(q, qd);
      sim.step(1, 1e-3);
      assert.deepEqual(sim.limitHits(), limits === 'ignore' ? [] : [kuka.jointNames[j]], limits);
      if (limits === 'clamp') {
        assert.equal(sim.q[j], upper);
        assert.equal(sim.qd[j], 0);
      } else {
        assert.ok(sim.q[j] > upper, `${limits}: q[${j}] = ${sim.q[j]}`);
      }
    } finally {
      sim.delete();
    }
  }
});

test('bad input throws an Error naming the problem; the simulator keeps working after reset', () => {
  const throws = (fn, message) =>
    assert.throws(fn, (e) => e instanceof Error && message.test(e.message), `expected ${message}`);
  // Reference: 10 steps from q0 on a fresh simulator.
  const fresh = kuka.createSimulator();
  fresh.reset(kukaEntry.q0);
  fresh.step(10);
  const reference = Array.from(fresh.q);
  fresh.delete();

  throws(() => kuka.createSimulator({ integrator: 'verlet' }), /^options\.integrator: expected/);
  throws(() => kuka.createSimulator({ limits: 'stop' }), /^options\.limits: expected 'ignore' or 'report' or 'clamp'/);
  throws(() => kuka.createSimulator({ frictionVelocity: 0 }), /^options\.frictionVelocity must be a finite number > 0/);
  throws(() => kuka.createSimulator({ stabilisationFrequency: -1 }), /^options\.stabilisationFrequency must be/);
  throws(() => kuka.createSimulator({ dt: 1e-3 }), /^options: unknown field 'dt'$/);

  const sim = kuka.createSimulator();
  sim.reset(kukaEntry.q0);
  throws(() => sim.setDirection('w', 'hold'), /unknown direction 'w'/);
  throws(() => sim.setDirection('z', 'stick'), /mode must be 'hold', 'free' or a finite number, got 'stick'$/);
  throws(() => sim.setDirection('z', NaN), /mode must be/);
  throws(() => sim.reset([1, 2, 3]), /^q: expected 7 values, got 3$/);
  throws(() => sim.reset(kukaEntry.q0, new Float64Array(8)), /^qd: expected 7 values, got 8$/);
  throws(() => sim.step(1.5), /^step: n must be an integer >= 0/);
  throws(() => sim.step(1, 0), /^step: dt must be a finite number > 0/);
  sim.q[3] = NaN;
  throws(() => sim.step(), /^q\[3\] is not finite$/);

  sim.reset(kukaEntry.q0);
  sim.step(10);
  assert.deepEqual(Array.from(sim.q), reference);

  sim.delete();
  throws(() => sim.step(), /^Simulator has been deleted$/);
  throws(() => sim.q, /^Simulator has been deleted$/);
  throws(() => sim.residuals(), /^Simulator has been deleted$/);
  throws(() => sim.delete(), /^Simulator has been deleted$/);
});
