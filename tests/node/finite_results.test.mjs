// Every number the JS API returns is finite, or the call throws an Error naming the cause,
// and the module keeps working: finite inputs whose solve overflows (joint velocities of
// 1e155, torques of 1e308) through robot.solve and the zero-copy solver; constraint
// columns of any scale; sigma_min of columns whose coupling is beyond a double.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAchd, relativeError, robots } from './helpers.mjs';

let achd, entry, kuka, reference;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
  reference = kuka.solve(goodCase());
});

const goodCase = () => ({ q: entry.q0, gravity: [0, 0, -9.81], alpha: [[0, 0, 1, 0, 0, 0]], beta: [0.2] });

function allFinite(result) {
  const numbers = [...result.qdd, ...result.nu, ...result.joint_torques, ...result.constraint_torques,
    ...result.total_torques, ...result.constraint_wrench, ...result.link_accelerations.flat(), result.sigma_min];
  return numbers.every(Number.isFinite);
}

// Before: NaN and Infinity in every result array, no error.
test('overflowing solves throw an Error naming the joint, then the module works', () => {
  const overflowing = [
    { ...goodCase(), qd: [1e155, 0, 0, 0, 0, 0, 1e155] },
    { ...goodCase(), qd: [1e200, 0, 0, 0, 0, 0, 0] },
    { ...goodCase(), ff_torques: [1e308, 1e308, 0, 0, 0, 0, -1e308] },
  ];
  for (const c of overflowing) {
    assert.throws(() => kuka.solve(c), (e) => e instanceof Error && /the solve overflows: joint 'lwr_joint_\d'/.test(e.message));
    assert.deepEqual(kuka.solve(goodCase()), reference);
  }
  // Huge but representable: finite numbers.
  assert.ok(allFinite(kuka.solve({ ...goodCase(), qd: Array(7).fill(1e50), ff_torques: Array(7).fill(1e300) })));
});

test('the zero-copy solver throws on overflow and solves again afterwards', () => {
  const solver = kuka.createSolver({ maxConstraints: 1 });
  solver.q.set(entry.q0);
  solver.numConstraints = 1;
  solver.alpha.set([0, 0, 1, 0, 0, 0]);
  solver.beta.set([0.2]);
  solver.qd.set([1e155, 0, 0, 0, 0, 0, 1e155]);
  assert.throws(() => solver.solve(), /the solve overflows/);
  solver.qd.fill(0);
  solver.solve();
  assert.deepEqual(solver.result(), reference);
  solver.delete();
});

// Before: a column of 1e-160 gave NaN everywhere, 1e-200 dropped the constraint (rank 0).
test('a constraint column of any scale gives the same motion, its nu scaled', () => {
  for (const s of [1e-160, 1e-200, 2 ** -700, 1e150]) {
    const r = kuka.solve({ ...goodCase(), alpha: [[0, 0, s, 0, 0, 0]], beta: [0.2 * s] });
    assert.equal(r.rank, 1, `scale ${s}`);
    assert.ok(relativeError(r.qdd, reference.qdd) <= 1e-12, `scale ${s}: qdd`);
    assert.ok(relativeError([r.nu[0] * s], reference.nu) <= 1e-12, `scale ${s}: nu`);
    if (s === 2 ** -700) assert.deepEqual(r.qdd, reference.qdd, 'a power of two: the same bits');
  }
});

test('sigma_min of columns whose coupling is beyond a double is an Error, not Infinity', () => {
  const c = { ...goodCase(), alpha: [[0, 0, 1e160, 0, 0, 0]], beta: [0] };
  assert.throws(() => kuka.solve(c), /sigma_min: the coupling matrix K/);
  const solver = kuka.createSolver({ maxConstraints: 1 });
  solver.q.set(entry.q0);
  solver.numConstraints = 1;
  solver.alpha.set(c.alpha[0]);
  solver.solve();  // the solve itself is fine: nu ~ 1e-160
  assert.ok(Number.isFinite(solver.nu[0]));
  assert.throws(() => solver.sigma_min, /sigma_min/);
  solver.delete();
  assert.deepEqual(kuka.solve(goodCase()), reference);
});
