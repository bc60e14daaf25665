// Whole robots in JS, against the native CLI (ACHD_CLI, the Release build): the
// inputs by name give the results of the arrays; results name their joints and links as
// the CLI's do; bad blocks and names get the CLI's message word for word; loadURDF loads
// whole trees, locks side joints and ignores side branches as `achd info` reports; and
// wasm equals native to the bit (the documented claim, as tests/node/parity.test.mjs checks
// it for chains) on the tree robots and on chains with constraint blocks; the zero-copy
// solver takes blocks without allocating. The small tree is tests/fixtures/small_tree.urdf.
import assert from 'node:assert/strict';
import { mkdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';

import { execFileSync } from 'node:child_process';

import { assertSameResult, loadAchd, loadFlags, nativeCli, nativeError, nativeSolve, pool, randomTreeFiles, repo, robots, runCli, scratchDir } from './helpers.mjs';
import { randomChain, randomCase, rng } from './random_chain.mjs';

const TREE = join(repo, 'tests/fixtures/small_tree.urdf');
const TREE_TEXT = readFileSync(TREE, 'utf8');
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
async function nativeInfo(urdf, load) {
  return JSON.parse(await runCli(cli, ['info', urdf, ...loadFlags(load)]));
}


// Each job {urdf, text, load, c, options, what}: wasm == native.
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

// Every entry of robots/index.json, trees (no tip) included, with its URDF text and its
// loops file's loop joints (loopJoints, undefined without one).
function indexRobots() {
  const index = JSON.parse(readFileSync(join(repo, 'robots/index.json'), 'utf8'));
  return index.robots.map((r) => ({ ...r, path: join(repo, r.urdf), text: readFileSync(join(repo, r.urdf), 'utf8'),
    loopJoints: r.loops && JSON.parse(readFileSync(join(repo, r.loops), 'utf8')).loops }));
}

const kukaCase = () => ({ q: kukaEntry.q0, gravity: GRAVITY });

test('inputs by name give the results of the arrays (q, qd, ff_torques by joint, f_ext by link)', () => {
  const names = kuka.jointNames;
  const byArray = { ...kukaCase(), qd: [0.1, -0.2, 0.3, 0, 0.5, 0, 0.7], ff_torques: [1, 0, 0, 2, 0, 0, 0],
    f_ext: kuka.linkNames.map((l) => (l === 'lwr_link_7' ? [0, 0, -5, 0.1, 0, 0] : [0, 0, 0, 0, 0, 0])) };
  const byName = { q: Object.fromEntries(names.map((n, i) => [n, kukaEntry.q0[i]]).reverse()), gravity: GRAVITY,
    qd: { lwr_joint_1: 0.1, lwr_joint_2: -0.2, lwr_joint_3: 0.3, lwr_joint_5: 0.5, lwr_joint_7: 0.7 },
    ff_torques: { lwr_joint_4: 2, lwr_joint_1: 1 }, f_ext: { lwr_link_7: [0, 0, -5, 0.1, 0, 0] } };
  const a = kuka.solve(byArray), n = kuka.solve(byName);
  assert.deepEqual(n, a);
  assert.notDeepEqual(a.qdd, kuka.solve(kukaCase()).qdd, 'the inputs mattered');
  // The other robot methods take joints and links by name too.
  assert.deepEqual(kuka.massMatrix(byName.q), kuka.massMatrix(kukaEntry.q0));
  assert.deepEqual(kuka.rnea(byName.q, byName.qd, { lwr_joint_3: 1 }, { f_ext: byName.f_ext }),
    kuka.rnea(kukaEntry.q0, byArray.qd, [0, 0, 1, 0, 0, 0, 0], { f_ext: byArray.f_ext }));
});

test('results name their joints and links and carry one wrench per block, as the CLI\'s', async () => {
  const wasm = kuka.solve(kukaCase());
  const native = await solveNative(kukaEntry.path, { root: kukaEntry.root, tip: kukaEntry.tip }, kukaCase());
  assert.deepEqual(wasm.joints, kuka.jointNames);
  assert.deepEqual(wasm.links, [kuka.root, ...kuka.linkNames]);
  assert.equal(wasm.links.length, wasm.link_accelerations.length);
  assert.deepEqual(wasm.constraint_wrenches, []);
  assert.equal('locked_joints' in wasm, false);
  assertSameResult(wasm, native, 'kuka q0');
  assert.deepEqual(kuka.lockedJoints, []);
  assert.equal(kuka.tip, 'lwr_link_7');
});

test('bad blocks and names: the CLI\'s message, word for word', async () => {
  const col = [0, 0, 1, 0, 0, 0];
  const bad = [
    { constraints: [{ link: 'lwr_link_7', alpha: [col] }, { link: 'x', alpha: [col] }] },
    { constraints: [{ link: 'lwr_base_link', alpha: [col] }] },
    { constraints: [{ link: 7, alpha: [col] }] },
    { constraints: [{ alpha: [col] }] },
    { constraints: [{ link: 'lwr_link_3' }] },
    { constraints: [{ link: 'lwr_link_3', alpha: [col], where: 1 }] },
    { constraints: [{ link: 'lwr_link_3', alpha: [[0, 0, 1, 0, 0]] }] },
    { constraints: [{ link: 'lwr_link_3', alpha: [[0, 0, 1, 0, 0, 'x']] }] },
    { constraints: [{ link: 'lwr_link_3', alpha: [col], beta: [1, 2] }] },
    { constraints: [{ link: 'lwr_link_3', alpha: [col], beta: ['1'] }] },
    { constraints: [{ link: 'lwr_link_3', alpha: [col], point: [0, 1] }] },
    { constraints: [{ link: 'lwr_link_3', alpha: Array(7).fill(col) }] },
    { constraints: [1] },
    { constraints: 1 },
    { constraints: Array.from({ length: 7 }, () => ({ link: 'lwr_link_7', alpha: Array(6).fill(col) })) },
    { q: { lwr_joint_9: 1 } },
    { qd: { lwr_joint_2: 'fast' } },
    { ff_torques: 'none' },
    { f_ext: { lwr_base_link: col } },
    { f_ext: { lwr_link_9: col } },
    { f_ext: { lwr_link_2: [0, 0] } },
  ];
  const natives = await pool(bad.map((fields) => () =>
    errorNative(kukaEntry.path, { root: kukaEntry.root, tip: kukaEntry.tip }, { ...kukaCase(), ...fields })));
  bad.forEach((fields, i) => {
    const what = JSON.stringify(fields).slice(0, 120);
    assert.ok(natives[i], `${what}: the CLI accepted it`);
    assert.throws(() => kuka.solve({ ...kukaCase(), ...fields }), (e) => e.message === natives[i],
      `${what}: JS should say "${natives[i]}"`);
  });
  // ... and the robot keeps working.
  assert.deepEqual(kuka.solve(kukaCase()).qdd, (await solveNative(kukaEntry.path,
    { root: kukaEntry.root, tip: kukaEntry.tip }, kukaCase())).qdd);
});

test('loadURDF options are checked, naming the option', () => {
  const throws = (fn, message) => assert.throws(fn, (e) => e.message === message, message);
  throws(() => achd.loadURDF(TREE_TEXT, { tip: 'left_foot', locked: { right_knee: '1' } }),
    "loadURDF: options.locked['right_knee'] must be a finite number, got 1");
  throws(() => achd.loadURDF(TREE_TEXT, { tip: 'left_foot', locked: { right_knee: NaN } }),
    "loadURDF: options.locked['right_knee'] must be a finite number, got NaN");
  throws(() => achd.loadURDF(TREE_TEXT, { locked: [] }), 'loadURDF: options.locked must be an object');
  throws(() => achd.loadURDF(TREE_TEXT, { sideBranches: 'drop' }),
    "loadURDF: options.sideBranches: expected 'merge' or 'ignore', got 'drop'");
  throws(() => achd.loadURDF(TREE_TEXT, { root: 3 }), 'loadURDF: options.root must be a link name');
  throws(() => achd.loadURDF(TREE_TEXT, { floating: 1 }), 'loadURDF: options.floating must be true or false');
  throws(() => achd.loadURDF(TREE_TEXT, { fixed: true }), "loadURDF options: unknown field 'fixed'");
});

// Needs the loader of trees (loadURDF without a tip, locked side joints).
test('loadURDF loads the whole tree, locks side joints and ignores side branches as `achd info` reports', async () => {
  const cases = [
    {},
    { root: 'torso' },
    { root: 'base', tip: 'left_foot' },
    { root: 'base', tip: 'left_foot', locked: { right_knee: 0.05, right_hip: -0.3 } },
    { root: 'base', tip: 'left_foot', sideBranches: 'ignore' },
  ];
  for (const load of cases) {
    const what = JSON.stringify(load);
    const info = await nativeInfo(TREE, load);
    const robot = achd.loadURDF(TREE_TEXT, load);
    try {
      assert.equal(robot.root, info.root, what);
      assert.equal(robot.tip, info.tip, what);
      assert.deepEqual(robot.jointNames, info.joints.map((j) => j.name), what);
      assert.deepEqual(robot.jointTypes, info.joints.map((j) => j.type), what);
      assert.deepEqual([robot.root, ...robot.linkNames], info.links.map((l) => l.name), what);
      assert.deepEqual(robot.lockedJoints, info.locked_joints, what);
    } finally {
      robot.delete();
    }
  }
  const tree = achd.loadURDF(TREE_TEXT);
  assert.equal(tree.tip, null);
  assert.equal(tree.numRates, 5);
  assert.throws(() => tree.tipJacobian([0, 0, 0.5, 0, 0]), (e) => /^tip_jacobian: the model is a tree/.test(e.message));
  tree.delete();
  const locked = achd.loadURDF(TREE_TEXT, { root: 'base', tip: 'left_foot', locked: { right_knee: 0.05 } });
  assert.deepEqual(locked.lockedJoints, [{ name: 'right_hip', value: 0 }, { name: 'right_knee', value: 0.05 }]);
  assert.throws(() => locked.solve({ q: { right_hip: 0.1 }, gravity: GRAVITY }),
    (e) => e.message === "q: joint 'right_hip' is locked at 0 (a side joint of the chain; --lock sets its position)");
  assert.deepEqual(locked.solve({ q: {}, gravity: GRAVITY }).locked_joints, locked.lockedJoints);
  locked.delete();
});

// Needs the loader of trees and the solver of constraint blocks.
test('the small tree and the tree robots of robots/index.json: wasm == native, to the bit', async () => {
  const r = rng(15);
  const jobs = [];
  const treeQ = { torso_yaw: 0.3, left_hip: -0.4, left_knee: 0.9, right_hip: 0.2, right_knee: 0.04 };
  const feet = [{ link: 'left_foot', alpha: [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]], beta: [0.1, 0, -0.2] },
    { link: 'right_foot', alpha: [[0, 0, 1, 0, 0, 0]], point: [0.02, 0, -0.01] }];
  const small = { urdf: TREE, text: TREE_TEXT };
  jobs.push({ ...small, load: {}, c: { q: treeQ, gravity: GRAVITY }, what: 'small tree' });
  jobs.push({ ...small, load: {}, c: { q: treeQ, qd: { left_knee: 1, right_hip: -0.5 }, gravity: GRAVITY,
    f_ext: { camera: [0, 0, -2, 0, 0.1, 0] }, constraints: feet }, what: 'small tree, feet held' });
  for (const options of [{ convention: 'kdl' }, { policy: 'damped', damping: 1e-6 }])
    jobs.push({ ...small, load: {}, c: { q: treeQ, gravity: GRAVITY, constraints: feet }, options,
      what: `small tree, feet held, ${JSON.stringify(options)}` });
  jobs.push({ ...small, load: { root: 'base', tip: 'left_foot', locked: { right_knee: 0.05 } },
    c: { q: { left_knee: 0.9 }, gravity: GRAVITY, alpha: [[0, 0, 1, 0, 0, 0]], beta: [0] }, what: 'small tree chain, locked' });
  jobs.push({ ...small, load: { root: 'base', tip: 'left_foot', sideBranches: 'ignore' },
    c: { q: { left_knee: 0.9 }, gravity: GRAVITY }, options: { convention: 'kdl' }, what: 'small tree chain, kdl' });
  // The tree robots (robots/index.json entries without a tip, the four-bar with its loop
  // joint): at their start pose, at a random state, and with their default constraint
  // links (the quadruped's four feet) held in 3D.
  const trees = indexRobots().filter((e) => !e.tip);
  const xyz = [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]];
  for (const entry of trees) {
    const load = { root: entry.root };
    if (entry.mimic) load.mimic = entry.mimic;
    if (entry.loopJoints) load.loops = entry.loopJoints;
    const base = { urdf: entry.path, text: entry.text, load };
    jobs.push({ ...base, c: { q: entry.q0, gravity: GRAVITY }, what: `${entry.name} q0` });
    const robot = achd.loadURDF(entry.text, load);
    const c = randomCase(r, robot.numRates, robot.numLinks, 0);
    robot.delete();
    jobs.push({ ...base, c, what: `${entry.name} random state` });
    if (entry.constraints)
      jobs.push({ ...base, what: `${entry.name}, ${entry.constraints.join(', ')} held in 3D`,
        c: { q: entry.q0, gravity: GRAVITY, constraints: entry.constraints.map((link) => ({ link, alpha: xyz })) } });
  }
  const quadruped = trees.find((e) => e.name === 'quadruped');
  assert.ok(quadruped, 'robots/index.json lists the quadruped (a tree: no tip)');
  assert.deepEqual(quadruped.constraints, ['lf_foot', 'rf_foot', 'lh_foot', 'rh_foot']);
  await runParity(jobs);
  console.log(`# trees: ${jobs.length} cases (${trees.length} tree robots in robots/index.json)`);
});

// The random trees of the C++ suites (tests/native/support/random_tree.hpp: 1 to 60 bodies,
// branching at random, every joint type, random inputs and well-conditioned blocks of up to
// 36 columns), written as files by tests/native/random_tree_files. Needs the loader of
// trees (a URDF loaded without a tip).
test('300 random trees of the C++ suites, with constraint blocks: wasm == native, to the bit', async () => {
  const COUNT = 300;
  const dir = join(scratch.dir, 'random_trees');
  mkdirSync(dir);
  execFileSync(randomTreeFiles(), [dir, '15', String(COUNT)]);
  const jobs = [];
  let blocks = 0;
  for (let k = 0; k < COUNT; ++k) {
    const urdf = join(dir, `tree${k}.urdf`);
    const c = JSON.parse(readFileSync(join(dir, `case${k}.json`), 'utf8'));
    if (c.constraints.length) ++blocks;
    jobs.push({ urdf, text: readFileSync(urdf, 'utf8'), load: {}, c, what: `random tree ${k}` });
  }
  assert.ok(blocks >= COUNT / 2, `only ${blocks} of ${COUNT} trees have constraint blocks`);
  await runParity(jobs);
  console.log(`# random trees: ${COUNT} (${blocks} with constraint blocks)`);
});

// Needs the solver of constraint blocks.
test('random chains with constraint blocks on their links: wasm == native, to the bit', async () => {
  const jobs = [];
  for (let seed = 1; seed <= 40; ++seed) {
    const r = rng(5000 + seed);
    const nj = 2 + Math.floor(r() * 20);
    const chain = randomChain(seed, nj);
    const robot = achd.loadURDF(chain.text, { root: chain.root, tip: chain.tip });
    const links = robot.linkNames;
    robot.delete();
    const urdf = scratch.write(`blocks${seed}.urdf`, chain.text);
    const c = randomCase(r, nj, links.length, seed % 3 === 0 ? 1 : 0);
    // One or two blocks of one or two columns each on random links: few columns against
    // the joints, so that the coupling is well conditioned (as documented).
    c.constraints = Array.from({ length: 1 + (seed % 2) }, () => ({
      link: links[Math.floor(r() * links.length)],
      alpha: Array.from({ length: 1 + Math.floor(r() * 2) }, () => [0, 0, 0, 0, 0, 0].map(() => 2 * r() - 1)),
      point: [r() - 0.5, r() - 0.5, r() - 0.5],
    }));
    c.constraints.forEach((b) => { b.beta = b.alpha.map(() => r() - 0.5); });
    jobs.push({ urdf, text: chain.text, load: { root: chain.root, tip: chain.tip }, c,
      options: [undefined, { convention: 'kdl' }, { policy: 'damped', damping: 1e-6 }][seed % 3],
      what: `chain seed ${seed} (${nj} joints), ${c.constraints.length} blocks` });
  }
  await runParity(jobs);
});

// Needs the solver of constraint blocks.
test('the zero-copy solver takes blocks: the result of robot.solve, no allocation per solve', () => {
  const blocks = [{ link: 'lwr_link_7', alpha: [[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0]], beta: [0.2, 0] },
    { link: 'lwr_link_4', alpha: [[1, 0, 0, 0, 0, 0]], point: [0, 0.05, 0] }];
  const expected = kuka.solve({ ...kukaCase(), constraints: blocks });
  const solver = kuka.createSolver();
  solver.q.set(kukaEntry.q0);
  solver.setConstraints(blocks);
  assert.equal(solver.numBlocks, 2);
  solver.solve();
  assert.deepEqual(solver.result(), expected);
  assert.deepEqual(Array.from(solver.nu), expected.nu, 'nu view: the tip\'s columns, then the blocks\'');
  assert.deepEqual(Array.from(solver.constraint_wrenches), expected.constraint_wrenches.flat());
  const bytes = achd.memoryBytes();
  for (let i = 0; i < 2000; ++i) {
    solver.q[0] = 0.3 + 1e-4 * i;
    solver.solve();
  }
  assert.equal(achd.memoryBytes(), bytes, 'wasm memory grew during the solves');
  solver.setConstraints([]);
  solver.solve();
  assert.deepEqual(solver.result().constraint_wrenches, []);
  assert.throws(() => solver.setConstraints([{ link: 'nope', alpha: [] }]),
    (e) => e.message === "constraints[0].link: no link 'nope' on the chain");
  assert.equal(solver.numBlocks, 0, 'a refused set leaves the blocks as they were');
  solver.delete();
});
