// The zero-copy solver: its views are the solver's own buffers (writing q and calling
// solve() gives robot.solve()'s answer), they survive wasm memory growth, and a million
// solves leave the wasm memory size unchanged.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAchd, robots } from './helpers.mjs';

let achd, entry, kuka;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
});

const CASE = {
  q: [0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1],
  qd: [0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.7],
  ff_torques: [1, -2, 0.5, 3, -0.1, 0.2, 0.05],
  gravity: [0.5, 0, -9.81],
  alpha: [[1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0], [0, 0, 0, 0, 1, 0]],
  beta: [0.1, -0.3, 0.2],
  f_ext: Array.from({ length: 7 }, (_, i) => [i, -1, 0.5, 0.1 * i, 0, -0.2]),
};

function fill(solver, c) {
  solver.q.set(c.q);
  solver.qd.set(c.qd);
  solver.ff_torques.set(c.ff_torques);
  solver.gravity.set(c.gravity);
  solver.numConstraints = c.alpha.length;
  c.alpha.forEach((col, k) => solver.alpha.set(col, 6 * k));
  solver.beta.set(c.beta);
  solver.useExternalWrenches = true;
  c.f_ext.forEach((w, l) => solver.f_ext.set(w, 6 * l));
}

function assertViewsEqual(solver, expected) {
  for (const key of ['qdd', 'nu', 'joint_torques', 'constraint_torques', 'total_torques', 'constraint_wrench'])
    assert.deepEqual(Array.from(solver[key]), expected[key], key);
  assert.deepEqual(Array.from(solver.link_accelerations), expected.link_accelerations.flat());
  assert.equal(solver.rank, expected.rank);
  assert.equal(solver.sigma_min, expected.sigma_min);
}

test('views on the solver buffers give robot.solve()\'s answer, options included', () => {
  const solver = kuka.createSolver({ convention: 'kdl' });
  fill(solver, CASE);
  solver.solve();
  assertViewsEqual(solver, kuka.solve(CASE, { convention: 'kdl' }));
  assert.deepEqual(solver.result(), kuka.solve(CASE, { convention: 'kdl' }));
  // Turning external wrenches off is the case without f_ext.
  solver.useExternalWrenches = false;
  solver.setOptions({});
  solver.solve();
  const { f_ext, ...without } = CASE;
  assert.ok(f_ext);
  assertViewsEqual(solver, kuka.solve(without));
  solver.delete();
});

test('views are re-created after wasm memory grows', () => {
  const solver = kuka.createSolver();
  const before = solver.q;
  const bytes = achd.memoryBytes();
  const block = achd._malloc(64 << 20);  // forces memory growth: the old buffer detaches
  assert.ok(achd.memoryBytes() > bytes, 'memory grew');
  assert.equal(before.length, 0, 'the old view is detached');
  fill(solver, CASE);
  solver.solve();
  assertViewsEqual(solver, kuka.solve(CASE));
  achd._free(block);
  solver.delete();
});

test('one million zero-copy solves leave the wasm memory size unchanged', () => {
  const solver = kuka.createSolver();
  fill(solver, CASE);
  solver.solve();
  const expected = solver.result();
  const bytes = achd.memoryBytes();
  const q = solver.q, qdd = solver.qdd;
  let checksum = 0;
  for (let i = 0; i < 1e6; ++i) {
    q[0] = 0.3 + 1e-7 * (i % 1000);
    solver.solve();
    checksum += qdd[0];
  }
  assert.ok(Number.isFinite(checksum));
  assert.equal(achd.memoryBytes(), bytes);
  q[0] = CASE.q[0];
  solver.solve();
  assert.deepEqual(solver.result(), expected);
  solver.delete();
});
