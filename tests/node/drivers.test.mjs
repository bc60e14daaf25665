// The drivers in JS (prescribed joints qdd_given, driver weights w_fext / w_ff on the
// tip's columns and per block, virtual wrenches f_virtual; results prescribed_torques,
// virtual_torques): robot.solve equals the native `achd solve` (ACHD_CLI, the Release
// build) to the bit on chains and trees, by name and in model order; bad inputs get the
// CLI's message word for word; the zero-copy solver gives robot.solve's result and does
// not grow the wasm memory. A block's yields (columns that give way to the joints'
// efforts) too: followed, blended and given up as the native solve, bad ones named alike.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';

import { assertSameResult, loadAchd, nativeCli, nativeError, nativeSolve, pool, randomTreeFiles, repo, robots, scratchDir } from './helpers.mjs';
import { randomCase, randomChain, rng } from './random_chain.mjs';

const GRAVITY = [0, 0, -9.81];

let achd, cli, scratch, kukaEntry, kuka;
before(async () => {
  achd = await loadAchd();
  cli = nativeCli();
  scratch = scratchDir();
  kukaEntry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(kukaEntry.text, { root: kukaEntry.root, tip: kukaEntry.tip });
});
after(() => scratch.remove());

const solveNative = (urdf, load, c, options) => nativeSolve(cli, scratch, urdf, load, c, options);
const errorNative = (urdf, load, c) => nativeError(cli, scratch, urdf, load, c);


async function runParity(jobs) {
  const natives = await pool(jobs.map((j) => () => solveNative(j.urdf, j.load, j.c, j.options)));
  jobs.forEach((j, i) => {
    const robot = achd.loadURDF(j.text, j.load);
    try {
      assertSameResult(robot.solve(j.c, j.options), natives[i], j.what);
    } finally {
      robot.delete();
    }
  });
}

// The drivers added to a case c of `robot`: about a third of the joints prescribed (by name
// or in model order with nulls), weights in [0, 1] (0 and 1 among them) on the tip's
// columns and on every block, virtual wrenches on half the links (by name or as an array).
function withDrivers(r, c, robot, byName) {
  const weight = () => [0, 1, r()][Math.floor(r() * 3)];
  const given = robot.jointNames.map(() => (r() < 0.35 ? 4 * r() - 2 : null));
  c.qdd_given = byName
    ? Object.fromEntries(robot.jointNames.flatMap((n, i) => (given[i] === null ? [] : [[n, given[i]]])))
    : given;
  const nc = c.alpha ? c.alpha.length : 0;
  if (nc) {
    c.w_fext = Array.from({ length: nc }, weight);
    c.w_ff = Array.from({ length: nc }, weight);
  }
  for (const b of c.constraints || []) {
    b.w_fext = b.alpha.map(weight);
    if (r() < 0.5) b.w_ff = b.alpha.map(weight);
  }
  const wrench = () => [0, 0, 0, 0, 0, 0].map(() => 4 * r() - 2);
  const virtual = robot.linkNames.map((l) => (r() < 0.5 ? wrench() : null));
  c.f_virtual = byName
    ? Object.fromEntries(robot.linkNames.flatMap((l, k) => (virtual[k] ? [[l, virtual[k]]] : [])))
    : virtual.map((w) => w || [0, 0, 0, 0, 0, 0]);
  return c;
}

test('chains: the LWR and 60 random chains with prescribed joints, weights and virtual wrenches: wasm == native', async () => {
  const jobs = [];
  const kukaBase = { urdf: kukaEntry.path, text: kukaEntry.text, load: { root: kukaEntry.root, tip: kukaEntry.tip } };
  // The LWR: z and rx held, z yielding to a push, the base joint on a given acceleration.
  jobs.push({ ...kukaBase, what: 'kuka: push yields along z, base joint prescribed',
    c: { q: kukaEntry.q0, gravity: GRAVITY, alpha: [[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0]], beta: [0, 0],
      w_fext: [0, 1], f_ext: { lwr_link_7: [0, 0, 20, 0, 0, 0] }, qdd_given: { lwr_joint_1: 0.5 },
      f_virtual: { lwr_link_4: [1, 0, 0, 0, 0.2, 0] } } });
  jobs.push({ ...kukaBase, what: 'kuka: every joint prescribed (inverse dynamics)',
    c: { q: kukaEntry.q0, gravity: GRAVITY, qdd_given: [0.1, -0.2, 0.3, 0.4, -0.5, 0.6, -0.7] } });
  for (let seed = 1; seed <= 60; ++seed) {
    const r = rng(16000 + seed);
    const nj = 1 + Math.floor(r() * 25);
    const chain = randomChain(seed, nj);
    const robot = achd.loadURDF(chain.text, { root: chain.root, tip: chain.tip });
    const c = withDrivers(r, randomCase(r, nj, robot.numLinks, Math.floor(r() * (Math.min(nj, 3) + 1))), robot, seed % 2 === 0);
    if (seed % 4 === 1) {
      const links = robot.linkNames;
      c.constraints = [{ link: links[Math.floor(r() * links.length)], alpha: [[0, 0, 1, 0, 0, 0]], beta: [0.1] }];
      withDrivers(r, c, robot, true);
    }
    robot.delete();
    jobs.push({ urdf: scratch.write(`chain${seed}.urdf`, chain.text), text: chain.text,
      load: { root: chain.root, tip: chain.tip }, c,
      options: [undefined, { convention: 'kdl' }, { policy: 'damped', damping: 1e-6 }][seed % 3],
      what: `chain seed ${seed} (${nj} joints)` });
  }
  await runParity(jobs);
  const withPrescribed = jobs.filter((j) => Object.values(j.c.qdd_given).some((x) => x !== null)).length;
  console.log(`# chains with drivers: ${jobs.length} cases (${withPrescribed} with a prescribed joint)`);
});

test('trees: the quadruped and 100 random trees of the C++ suites with drivers on their blocks: wasm == native', async () => {
  const COUNT = 100;
  const dir = join(scratch.dir, 'random_trees');
  mkdirSync(dir);
  execFileSync(randomTreeFiles(), [dir, '16', String(COUNT)]);
  const r = rng(1616);
  const jobs = [];
  for (let k = 0; k < COUNT; ++k) {
    const urdf = join(dir, `tree${k}.urdf`), text = readFileSync(urdf, 'utf8');
    const robot = achd.loadURDF(text, {});
    const c = withDrivers(r, JSON.parse(readFileSync(join(dir, `case${k}.json`), 'utf8')), robot, k % 2 === 0);
    robot.delete();
    jobs.push({ urdf, text, load: {}, c, what: `random tree ${k}` });
  }
  const index = JSON.parse(readFileSync(join(repo, 'robots/index.json'), 'utf8'));
  const quadruped = index.robots.find((e) => e.name === 'quadruped');
  const qText = readFileSync(join(repo, quadruped.urdf), 'utf8');
  const xyz = [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]];
  const q = achd.loadURDF(qText, { root: quadruped.root });
  const hip = q.jointNames[0];
  q.delete();
  jobs.push({ urdf: join(repo, quadruped.urdf), text: qText, load: { root: quadruped.root },
    what: `quadruped, feet held, ${hip} prescribed, the front feet yielding to a push`,
    c: { q: quadruped.q0, gravity: GRAVITY, qdd_given: { [hip]: 1.5 },
      f_ext: { lf_foot: [0, 0, 30, 0, 0, 0] }, f_virtual: { rh_foot: [0, 5, 0, 0, 0, 0] },
      constraints: quadruped.constraints.map((link, i) => ({ link, alpha: xyz, w_fext: i < 2 ? [1, 1, 0] : [1, 1, 1] })) } });
  await runParity(jobs);
  console.log(`# trees with drivers: ${jobs.length} cases`);
});

test('qdd_given and f_virtual by name give the results of the arrays', () => {
  const names = kuka.jointNames;
  const base = { q: kukaEntry.q0, gravity: GRAVITY, alpha: [[0, 0, 1, 0, 0, 0]], beta: [0], w_fext: [0.25] };
  const byArray = { ...base, qdd_given: [null, 0.5, null, null, -1, null, null],
    f_virtual: kuka.linkNames.map((l) => (l === 'lwr_link_5' ? [0, 1, 0, 0, 0, 0.3] : [0, 0, 0, 0, 0, 0])) };
  const byName = { ...base, qdd_given: { [names[4]]: -1, [names[1]]: 0.5 }, f_virtual: { lwr_link_5: [0, 1, 0, 0, 0, 0.3] } };
  const a = kuka.solve(byArray);
  assert.deepEqual(kuka.solve(byName), a);
  assert.equal(a.qdd[1], 0.5, 'a prescribed joint has its given acceleration');
  assert.equal(a.qdd[4], -1);
  assert.deepEqual(a.prescribed_torques.map((x) => x === null), [true, false, true, true, false, true, true]);
  assert.equal(a.virtual_torques.length, names.length);
  // No drivers: no driver results; weights of 1 and no prescribed joint: the plain solve.
  const plain = kuka.solve({ q: kukaEntry.q0, gravity: GRAVITY, alpha: [[0, 0, 1, 0, 0, 0]], beta: [0] });
  assert.equal('prescribed_torques' in plain, false);
  assert.equal('virtual_torques' in plain, false);
  assert.deepEqual(kuka.solve({ q: kukaEntry.q0, gravity: GRAVITY, alpha: [[0, 0, 1, 0, 0, 0]], beta: [0],
    w_fext: [1], w_ff: [1], qdd_given: {} }), plain, 'weights of 1 and an empty qdd_given change nothing');
});

test('bad drivers: the CLI\'s message, word for word, naming the field and index', async () => {
  const load = { root: kukaEntry.root, tip: kukaEntry.tip };
  const base = { q: kukaEntry.q0, gravity: GRAVITY, alpha: [[0, 0, 1, 0, 0, 0]], beta: [0] };
  const bad = [
    { ...base, qdd_given: { nope: 1 } },
    { ...base, qdd_given: [1, 2] },
    { ...base, qdd_given: [null, null, 'x', null, null, null, null] },
    { ...base, qdd_given: 3 },
    { ...base, qdd_given: { lwr_joint_2: 'fast' } },
    { ...base, w_fext: [0.5, 1] },
    { ...base, w_ff: [1.5] },
    { ...base, w_fext: [-0.25] },
    { ...base, w_ff: ['a'] },
    { ...base, w_fext: 0 },
    { ...base, constraints: [{ link: 'lwr_link_4', alpha: [[1, 0, 0, 0, 0, 0]], w_fext: [2] }] },
    { ...base, constraints: [{ link: 'lwr_link_4', alpha: [[1, 0, 0, 0, 0, 0]], w_ff: [1, 1] }] },
    { ...base, f_virtual: { lwr_link_0: [0, 0, 1, 0, 0, 0] } },
    { ...base, f_virtual: { nope: [0, 0, 1, 0, 0, 0] } },
    { ...base, f_virtual: [[0, 0, 1, 0, 0, 0]] },
    { ...base, f_virtual: { lwr_link_3: [0, 0, 1] } },
    { ...base, f_virtual: 'up' },
  ];
  const natives = await pool(bad.map((c) => () => errorNative(kukaEntry.path, load, c)));
  bad.forEach((c, i) => {
    assert.ok(natives[i], `case ${i}: the CLI refused it`);
    assert.throws(() => kuka.solve(c), (e) => {
      assert.equal(e.message, natives[i], `case ${i}`);
      return true;
    });
  });
});

test('the zero-copy solver with drivers: robot.solve\'s result, and no memory growth', () => {
  const c = { q: kukaEntry.q0, qd: [0.1, 0, -0.2, 0, 0.3, 0, 0], gravity: GRAVITY,
    alpha: [[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0]], beta: [0, 0], w_fext: [0, 1], w_ff: [0.5, 1],
    f_ext: { lwr_link_7: [0, 0, 20, 0, 0, 0] }, qdd_given: { lwr_joint_1: 0.5, lwr_joint_6: 0 },
    f_virtual: { lwr_link_4: [1, 0, 0, 0, 0.2, 0] },
    constraints: [{ link: 'lwr_link_4', alpha: [[1, 0, 0, 0, 0, 0]], w_fext: [0.5], w_ff: [0] }] };
  const expected = kuka.solve(c);
  const solver = kuka.createSolver();
  const nl = kuka.numLinks;
  solver.q.set(kukaEntry.q0);
  solver.qd.set(c.qd);
  solver.numConstraints = 2;
  solver.alpha.set([...c.alpha[0], ...c.alpha[1]]);
  assert.deepEqual(Array.from(solver.w_fext.subarray(0, 2)), [1, 1], 'weights start at 1');
  solver.w_fext.set([0, 1]);
  solver.w_ff.set([0.5, 1]);
  solver.useExternalWrenches = true;
  solver.f_ext.set([0, 0, 20, 0, 0, 0], 6 * kuka.linkNames.indexOf('lwr_link_7'));
  solver.useVirtualWrenches = true;
  solver.f_virtual.set([1, 0, 0, 0, 0.2, 0], 6 * kuka.linkNames.indexOf('lwr_link_4'));
  solver.setPrescribed(['lwr_joint_1', 'lwr_joint_6']);
  solver.qdd_given[0] = 0.5;
  solver.qdd_given[5] = 0;
  solver.setConstraints(c.constraints);
  solver.solve();
  assert.deepEqual(solver.result(), expected);
  assert.deepEqual(solver.prescribed, [true, false, false, false, false, true, false]);
  assert.equal(solver.prescribed_torques[0], expected.prescribed_torques[0]);
  assert.deepEqual(Array.from(solver.virtual_torques), expected.virtual_torques);
  assert.equal(solver.f_virtual.length, 6 * nl);
  const bytes = achd.memoryBytes();
  for (let i = 0; i < 20000; ++i) {
    solver.qdd_given[0] = Math.sin(1e-3 * i);
    solver.w_fext[0] = (i % 10) / 10;
    solver.solve();
  }
  assert.equal(achd.memoryBytes(), bytes, 'wasm memory grew during the solves');
  // Off again: the plain solve.
  solver.setPrescribed([]);
  solver.useVirtualWrenches = false;
  solver.w_fext.fill(1);
  solver.w_ff.fill(1);
  solver.setConstraints([]);
  solver.solve();
  const out = solver.result();
  assert.equal('prescribed_torques' in out, false);
  assert.equal('virtual_torques' in out, false);
  assert.deepEqual(out, kuka.solve({ q: kukaEntry.q0, qd: c.qd, gravity: GRAVITY, alpha: c.alpha, beta: c.beta,
    f_ext: c.f_ext }));
  assert.throws(() => solver.setPrescribed(['nope']), (e) => e.message === "setPrescribed: no movable joint 'nope' between the root and the tip");
  assert.throws(() => solver.setPrescribed([true]), (e) => e.message === 'setPrescribed: expected 7 booleans (one per joint), got 1');
  solver.delete();
});

test('yields: the UR5 pushed up at its last link gives way as natively; the zero-copy solver reads effort_ratio and yielded', async () => {
  const entry = robots().find((r) => r.name === 'ur5');
  const load = { root: entry.root, tip: entry.tip };
  const ur5 = achd.loadURDF(entry.text, load);
  const options = { policy: 'variable_damping' };
  const pushed = (beta_z, yields) => ({ q: [0, -1.2, 1.5, -0.3, 1.2, 0], gravity: GRAVITY,
    constraints: [{ link: 'wrist_3_link', alpha: [[1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]], beta: [0, beta_z], yields }] });
  try {
    // followed (r <= 1), blended (1 < r < 2), given up (r >= 2)
    const cases = [40, 100, 200].map((b) => pushed(b, [false, true]));
    const natives = await pool(cases.map((c) => () => solveNative(entry.path, load, c, options)));
    const ratios = [], shares = [];
    cases.forEach((c, i) => {
      const out = ur5.solve(c, options);
      assertSameResult(out, natives[i], `beta_z ${c.constraints[0].beta[1]}`);
      ratios.push(out.effort_ratio);
      shares.push(out.yielded);
    });
    assert.ok(ratios[0] < 1 && ratios[2] > 2, `effort ratios ${ratios}`);
    assert.equal(shares[0], 0);
    assert.equal(shares[2], 1);
    // the zero-copy solver
    const solver = ur5.createSolver();
    solver.setOptions(options);
    solver.q.set(cases[2].q);
    solver.setConstraints(cases[2].constraints);
    solver.solve();
    assert.deepEqual(solver.result(), ur5.solve(cases[2], options));
    assert.equal(solver.effort_ratio, ratios[2]);
    assert.equal(solver.yielded, 1);
    solver.delete();
    // bad yields: the CLI's message
    const bad = [pushed(200, [true]), pushed(200, [true, 1]), pushed(200, 'z')];
    const messages = await pool(bad.map((c) => () => errorNative(entry.path, load, c)));
    bad.forEach((c, i) => {
      assert.ok(messages[i], `bad yields ${i}: the CLI refused it`);
      assert.throws(() => ur5.solve(c, options), (e) => e.message === messages[i]);
    });
  } finally {
    ur5.delete();
  }
});

// The simulator's prescribed joint motion in JS: on the trajectory after every step (the
// sine computed here with V8's Math.sin: within 1e-12 of the module's), the torque it
// takes reported, released by name and by reset(), and bad motions named.
test('sim.prescribe: the joint follows its sine, reports its torque, and bad motions are named', () => {
  const sim = kuka.createSimulator({ integrator: 'rk4' });
  try {
    sim.reset(kukaEntry.q0);
    const motion = { motion: 'sine', position: 0.3, amplitude: 0.5, frequency: 0.5, phase: 0.1 };
    sim.prescribe('lwr_joint_1', motion);
    sim.setDirection('z', 'hold');
    assert.deepEqual(sim.prescribedJoints(), ['lwr_joint_1']);
    const at = (t) => motion.position + motion.amplitude * Math.sin(2 * Math.PI * motion.frequency * t + motion.phase);
    assert.ok(Math.abs(sim.q[0] - at(0)) < 1e-12, 'started on the trajectory');
    let worst = 0;
    for (let k = 0; k < 300; ++k) {
      sim.step(1, 1e-3);
      worst = Math.max(worst, Math.abs(sim.q[0] - at(sim.t)));
    }
    assert.ok(worst < 1e-12, `q off the trajectory by ${worst}`);
    const torques = sim.prescribed_torques();
    assert.notEqual(torques[0], 0);
    assert.deepEqual(torques.slice(1), [0, 0, 0, 0, 0, 0]);
    sim.release(0);
    assert.deepEqual(sim.prescribedJoints(), []);
    sim.prescribe(6, { motion: 'constant', position: 0.1 });
    sim.reset(kukaEntry.q0);
    assert.deepEqual(sim.prescribedJoints(), [], 'reset() releases every joint');
    const message = (joint, m) => {
      try {
        sim.prescribe(joint, m);
      } catch (e) {
        return e.message;
      }
      return null;
    };
    assert.equal(message('nope', { motion: 'ramp' }), 'prescribe: unknown joint "nope" (index 0..6 or a joint name)');
    assert.equal(message(0, { motion: 'square' }), "prescribe: motion.motion: expected 'constant', 'ramp', 'sine', got 'square'");
    assert.equal(message(1, { motion: 'sine', frequency: -1 }), "joint 'lwr_joint_2': frequency must be >= 0 (Hz)");
    assert.equal(message(1, { motion: 'ramp', amplitude: 2 }), "joint 'lwr_joint_2': amplitude is not a parameter of a 'ramp' motion");
    assert.equal(message(1, { motion: 'ramp', speed: 2 }), "prescribe: motion: unknown field 'speed'");
    assert.deepEqual(sim.prescribedJoints(), [], 'a refused motion changes nothing');
  } finally {
    sim.delete();
  }
});
