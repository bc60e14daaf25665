// Views cannot outlive their object: a Float64Array taken from a solver or simulator
// before its delete() is zero-length afterwards, so writing through it (an element is
// dropped, a fill or set throws a TypeError) reaches no memory the allocator or a later
// object owns; every call of the module keeps working and a new robot's solve gives the
// answer of a fresh module. Views of live objects are made again by their getters.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAchd, robots } from './helpers.mjs';

let achd, entry;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
});

const SOLVER_VIEWS = ['q', 'qd', 'ff_torques', 'gravity', 'alpha', 'beta', 'f_ext', 'qdd', 'nu', 'joint_torques',
  'constraint_torques', 'total_torques', 'link_accelerations', 'constraint_wrench', 'constraint_wrenches',
  'qdd_given', 'w_fext', 'w_ff', 'f_virtual', 'prescribed_torques', 'virtual_torques'];
const SIMULATOR_VIEWS = ['q', 'qd', 'ff_torques', 'f_ext'];

const CASE = { q: [0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1], qd: [0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.7],
  gravity: [0.5, 0, -9.81], alpha: [[1, 0, 0, 0, 0, 0]], beta: [0.1] };

function load() { return achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip }); }

// Writes through every stale view as a careless caller would: an element assignment is
// dropped; fill and set on a detached view throw a TypeError (they write nothing either).
function scribble(views) {
  for (const v of views) {
    v[0] = 1.5;
    assert.throws(() => v.fill(NaN), TypeError);
    assert.throws(() => v.set([1e300, -1e300, 7]), TypeError);
  }
}

test('a solver\'s views are zero-length after delete(), and writing through them harms nothing', () => {
  const robot = load();
  const expected = robot.solve(CASE);
  const solver = robot.createSolver();
  solver.numConstraints = 1;
  const views = SOLVER_VIEWS.map((name) => solver[name]);
  assert.equal(views[0].length, 7);
  assert.equal(views[SOLVER_VIEWS.indexOf('nu')].length, 1);
  solver.delete();
  assert.ok(views.every((v) => v.length === 0), 'every view is detached');
  scribble(views);
  assert.equal(views[0][0], undefined);
  // the module still works: a new robot loads and solves as before
  const again = load();
  assert.deepEqual(again.solve(CASE), expected);
  assert.deepEqual(robot.solve(CASE), expected);
  again.delete();
  robot.delete();
});

test('a simulator\'s views are zero-length after delete(); a new simulator runs as a fresh one', () => {
  const robot = load();
  const reference = robot.createSimulator();
  reference.reset(entry.q0);
  reference.step(50);
  const expected = Array.from(reference.q), expectedT = reference.t;
  reference.delete();

  const sim = robot.createSimulator();
  const views = SIMULATOR_VIEWS.map((name) => sim[name]);
  sim.delete();
  assert.ok(views.every((v) => v.length === 0));
  scribble(views);
  const fresh = robot.createSimulator();  // likely at the very addresses the old one had
  scribble(views);
  fresh.reset(entry.q0);
  fresh.step(50);
  assert.deepEqual(Array.from(fresh.q), expected);
  assert.equal(fresh.t, expectedT);
  fresh.delete();
  robot.delete();
});

test('views of live objects are made again after another object\'s delete()', () => {
  const robot = load();
  const a = robot.createSolver(), b = robot.createSolver();
  const oldQ = a.q;
  a.q.set(CASE.q);
  b.gravity.fill(0);
  b.delete();  // b's views were handed out: every view on this memory is detached
  assert.equal(oldQ.length, 0, 'a view held across a delete() is detached too (read the property again)');
  assert.deepEqual(Array.from(a.q), CASE.q, 'the getter gives a working view with the values written before');
  a.gravity.set(CASE.gravity);
  a.solve();
  assert.ok(Number.isFinite(a.qdd[0]));
  a.delete();
  robot.delete();
});

test('many create, view, delete rounds leave the memory size bounded and the module working', () => {
  const robot = load();
  const before = achd.memoryBytes();
  for (let i = 0; i < 2000; ++i) {
    const s = robot.createSolver();
    const q = s.q;
    s.delete();
    q[3] = 1e308;
  }
  assert.ok(achd.memoryBytes() <= before + (1 << 20), `memory grew from ${before} to ${achd.memoryBytes()}`);
  const other = load();
  assert.deepEqual(other.solve(CASE), robot.solve(CASE));
  other.delete();
  robot.delete();
});
