// Floating bases in JS, against the native CLI (ACHD_CLI, `--floating`):
// loadURDF({floating: true}) describes the free joint as `achd info` does; its q takes the
// root's position and quaternion and qd its [v; w], by name or in model order; and wasm
// equals native to the bit on the tree robots of robots/index.json holding their default
// links and on 100 random trees of the C++ suites, each made floating (its root given a mass);
// the JS simulator steps a floating base (a free fall).
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { execFileSync } from 'node:child_process';
import { after, before, test } from 'node:test';

import { assertSameResult, loadAchd, nativeCli, nativeSolve, pool, randomTreeFiles, relativeError, repo, runCli, scratchDir } from './helpers.mjs';
import { rng } from './random_chain.mjs';

const GRAVITY = [0, 0, -9.81];
const XYZ = [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]];

let achd, cli, scratch;
before(async () => {
  achd = await loadAchd();
  cli = nativeCli();
  scratch = scratchDir();
});
after(() => scratch.remove());



// A random pose of the free joint: position, unit quaternion; and a random [v; w].
function randomFreeJoint(r) {
  const u = () => 2 * r() - 1;
  const h = [u(), u(), u(), u()];
  const norm = Math.hypot(...h);
  return { q: [u(), u(), 0.5 + u() * 0.2, ...h.map((x) => x / norm)], qd: [u(), u(), u(), u(), u(), u()] };
}

function indexTrees() {
  const index = JSON.parse(readFileSync(join(repo, 'robots/index.json'), 'utf8'));
  return index.robots.filter((r) => !r.tip).map((r) => ({ ...r, path: join(repo, r.urdf), text: readFileSync(join(repo, r.urdf), 'utf8') }));
}

test('loadURDF({floating: true}) describes the free joint as `achd info --floating` does', async () => {
  const quadruped = indexTrees().find((r) => r.name === 'quadruped');
  const info = JSON.parse(await runCli(cli, ['info', quadruped.path, '--floating']));
  const robot = achd.loadURDF(quadruped.text, { floating: true });
  try {
    assert.equal(robot.floating, true);
    assert.deepEqual(robot.jointNames, info.joints.map((j) => j.name));
    assert.deepEqual(robot.jointTypes, info.joints.map((j) => j.type));
    assert.equal(robot.jointTypes[0], 'floating');
    assert.equal(robot.numRates, 6 + 12);
    assert.equal(robot.numPositions, 7 + 12);
    // numJoints is numRates' old name, kept for one release on the robot, solver and simulator.
    assert.equal(robot.numJoints, robot.numRates);
    const oldNames = [robot.createSolver(), robot.createSimulator()];
    try {
      for (const o of oldNames) assert.equal(o.numJoints, robot.numRates);
    } finally {
      for (const o of oldNames) o.delete();
    }
    // At rest with no torques the whole robot falls with g and no joint moves.
    const r = robot.solve({ q: { lf_kfe: -1.2 }, gravity: GRAVITY });
    assert.deepEqual(r.joints, info.joints.map((j) => j.name));
    r.qdd.forEach((x, i) => assert.ok(Math.abs(x - (i === 2 ? -9.81 : 0)) <= 1e-12, `qdd[${i}] = ${x}`));
    // By name or in model order, the same solve.
    const q = new Array(19).fill(0);
    q[6] = 1;
    q[7 + 2] = -1.2;
    assert.deepEqual(robot.solve({ q, gravity: GRAVITY }).qdd, r.qdd);
    assert.throws(() => robot.solve({ q: { trunk: [0, 0, 0, 1] }, gravity: GRAVITY }),
      (e) => e.message === "q['trunk'] (the floating base): expected 7 values, got 4");
    assert.throws(() => robot.solve({ q: { trunk: [0, 0, 0, 0, 0, 0, 0] }, gravity: GRAVITY }),
      /the floating base's orientation quaternion \(qx, qy, qz, qw\) is zero/);
    // The simulator steps it: a free fall from rest is one body falling, z = z0 - g t^2 / 2
    // (RK4 is exact on a quadratic), the quaternion kept unit, the joints where they were.
    const sim = robot.createSimulator({ integrator: 'rk4' });
    assert.equal(sim.q.length, 19);
    const q0 = [0, 0, 1, 0.1, -0.2, 0.3, 0.9, ...quadruped.q0];
    sim.reset(q0);
    sim.step(1000, 1e-3);
    const h = Math.hypot(0.1, -0.2, 0.3, 0.9);
    const expected = [0, 0, 1 - 9.81 / 2, 0.1 / h, -0.2 / h, 0.3 / h, 0.9 / h, ...quadruped.q0];
    assert.ok(relativeError(Array.from(sim.q), expected) < 1e-9, `q after 1 s: ${Array.from(sim.q)}`);
    sim.delete();
    assert.throws(() => achd.loadURDF(quadruped.text, { floating: 'yes' }),
      (e) => e.message === 'loadURDF: options.floating must be true or false');
  } finally {
    robot.delete();
  }
});

test('the tree robots floating, holding their default links in 3D: wasm == native, to the bit', async () => {
  const r = rng(1503);
  const jobs = [];
  // The trees with default links (the four-bar has none: it is about its loop joint).
  for (const entry of indexTrees().filter((e) => e.constraints)) {
    const load = entry.mimic ? { floating: true, mimic: entry.mimic } : { floating: true };
    const free = randomFreeJoint(r);
    const robot = achd.loadURDF(entry.text, load);
    const q = Object.fromEntries(robot.jointNames.slice(1).map((name, i) => [name, entry.q0[i]]));
    robot.delete();
    q[entry.root] = free.q;
    const c = { q, qd: { [entry.root]: free.qd }, gravity: GRAVITY,
      constraints: entry.constraints.map((link) => ({ link, alpha: XYZ })) };
    jobs.push({ entry, load, c, what: entry.name });
  }
  const natives = await pool(jobs.map((j) => () =>
    nativeSolve(cli, scratch, j.entry.path, j.load, j.c)));
  jobs.forEach((j, i) => {
    const robot = achd.loadURDF(j.entry.text, j.load);
    try {
      assertSameResult(robot.solve(j.c), natives[i], j.what);
    } finally {
      robot.delete();
    }
  });
  assert.equal(jobs.length, 4);
});

test('100 random trees of the C++ suites made floating, with constraint blocks: wasm == native, to the bit', async () => {
  const COUNT = 100;
  const dir = join(scratch.dir, 'random_trees');
  mkdirSync(dir);
  execFileSync(randomTreeFiles(), [dir, '16', String(COUNT)]);
  const r = rng(1601);
  const jobs = [];
  for (let k = 0; k < COUNT; ++k) {
    // The random trees' root link is massless (a fixed base does not feel it): floating, a
    // joint below it could take up a turn of the free joint alone. Given a mass and inertia:
    const urdf = join(dir, `tree${k}_floating.urdf`);
    writeFileSync(urdf, readFileSync(join(dir, `tree${k}.urdf`), 'utf8').replace('<link name="l0"/>',
      '<link name="l0"><inertial><origin xyz="0.02 -0.01 0.03" rpy="0 0 0"/><mass value="1.5"/>' +
      '<inertia ixx="0.01" iyy="0.02" izz="0.015" ixy="0" ixz="0" iyz="0"/></inertial></link>'));
    const fixed = JSON.parse(readFileSync(join(dir, `case${k}.json`), 'utf8'));
    const free = randomFreeJoint(r);
    // (the cases name their joints; the free joint is named after the root link, l0)
    const c = { ...fixed, q: { ...fixed.q, l0: free.q }, qd: { ...fixed.qd, l0: free.qd } };
    jobs.push({ urdf, text: readFileSync(urdf, 'utf8'), c, what: `random tree ${k}` });
  }
  const natives = await pool(jobs.map((j) => () => nativeSolve(cli, scratch, j.urdf, { floating: true }, j.c)));
  jobs.forEach((j, i) => {
    const robot = achd.loadURDF(j.text, { floating: true });
    try {
      assertSameResult(robot.solve(j.c), natives[i], j.what);
    } finally {
      robot.delete();
    }
  });
});

test('the zero-copy solver on a floating base: q has numPositions numbers, solves do not grow memory', () => {
  const quadruped = indexTrees().find((r) => r.name === 'quadruped');
  const robot = achd.loadURDF(quadruped.text, { floating: true });
  try {
    const s = robot.createSolver();
    assert.equal(s.q.length, robot.numPositions);
    assert.equal(s.qd.length, robot.numRates);
    s.q.set([0, 0, 0.3, 0, 0, 0, 1, ...quadruped.q0]);
    s.setConstraints(quadruped.constraints.map((link) => ({ link, alpha: XYZ })));
    s.solve();
    const expected = robot.solve({ q: Array.from(s.q), gravity: [0, 0, -9.81],
      constraints: quadruped.constraints.map((link) => ({ link, alpha: XYZ })) });
    assert.deepEqual(Array.from(s.qdd), expected.qdd);
    const bytes = achd.memoryBytes();
    for (let k = 0; k < 20000; ++k) s.solve();
    assert.equal(achd.memoryBytes(), bytes);
    s.delete();
  } finally {
    robot.delete();
  }
});
