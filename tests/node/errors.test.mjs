// Bad input from JS throws an Error naming the problem, and the module keeps working:
// the next valid call gives the same answer as before the error.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAchd, robots } from './helpers.mjs';

let achd, kuka, entry, reference;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
  reference = kuka.solve(goodCase());
});

const goodCase = () => ({ q: entry.q0, gravity: [0, 0, -9.81], alpha: [[0, 0, 1, 0, 0, 0]], beta: [0.2] });

// fn throws an Error whose message matches `message`; then a valid solve is unchanged.
function throwsThenRecovers(fn, message) {
  assert.throws(fn, (e) => e instanceof Error && message.test(e.message), `expected ${message}`);
  assert.deepEqual(kuka.solve(goodCase()), reference);
}

test('broken URDF text and unknown links', () => {
  throwsThenRecovers(() => achd.loadURDF('<robot name="x"><link name="a"></robot>', { root: 'a', tip: 'b' }),
    /cannot parse URDF/);
  throwsThenRecovers(() => achd.loadURDF(entry.text, { root: 'nope', tip: entry.tip }), /unknown root link 'nope'/);
  throwsThenRecovers(() => achd.loadURDF(entry.text, { root: entry.root, tip: 'tool0' }), /unknown tip link 'tool0'/);
  throwsThenRecovers(() => achd.loadURDF(entry.text, { root: entry.tip, tip: entry.root }), /is not below root link/);
  // Without a tip the whole tree loads (trees.test.mjs); a tip that is not a name is refused.
  throwsThenRecovers(() => achd.loadURDF(entry.text, { root: entry.root, tip: 7 }), /options\.tip must be a link name/);
  throwsThenRecovers(() => achd.loadURDF(42, { root: 'a', tip: 'b' }), /URDF must be a string/);
});

test('wrong lengths, NaN, Infinity, wrong types and unknown fields name the field and index', () => {
  const bad = (patch) => () => kuka.solve({ ...goodCase(), ...patch });
  throwsThenRecovers(bad({ q: [1, 2, 3] }), /^q: expected 7 values, got 3$/);
  throwsThenRecovers(bad({ qd: new Float64Array(8) }), /^qd: expected 7 values, got 8$/);
  throwsThenRecovers(bad({ q: [0, 0, 0, NaN, 0, 0, 0] }), /^q\[3\] is not finite$/);
  throwsThenRecovers(bad({ ff_torques: [0, 0, 0, 0, 0, 0, Infinity] }), /^ff_torques\[6\] is not finite$/);
  throwsThenRecovers(bad({ gravity: [0, '0', -9.81] }), /^gravity\[1\] must be a number$/);
  throwsThenRecovers(bad({ alpha: [[0, 0, 1, 0, 0]] }), /^alpha\[0\]: expected 6 values, got 5$/);
  throwsThenRecovers(bad({ alpha: [[0, 0, 1, 0, 0, 0], [0, NaN, 0, 0, 0, 0]], beta: [0, 0] }), /^alpha\[1\]\[1\] is not finite$/);
  throwsThenRecovers(bad({ beta: [1, 2] }), /^beta: expected 1 values \(one per alpha column\), got 2$/);
  throwsThenRecovers(bad({ alpha: Array(7).fill([1, 0, 0, 0, 0, 0]) }), /^alpha: at most 6 constraints, got 7$/);
  throwsThenRecovers(bad({ f_ext: [[0, 0, 0, 0, 0, 0]] }), /^f_ext: expected 7 wrenches \(one per link after the root\), got 1$/);
  throwsThenRecovers(bad({ torques: [0] }), /^unknown field 'torques'$/);
  throwsThenRecovers(() => kuka.solve({ q: entry.q0 }), /^missing required field 'gravity'$/);
  throwsThenRecovers(() => kuka.solve(goodCase(), { convention: 'mks' }), /options\.convention: expected 'physical' or 'kdl', got 'mks'/);
  throwsThenRecovers(() => kuka.solve(goodCase(), { tolerance: -1 }), /options\.tolerance must be a finite number >= 0/);
  throwsThenRecovers(() => kuka.solve(goodCase(), { effects: { gravitation: false } }), /options\.effects: unknown field 'gravitation'/);
  throwsThenRecovers(() => kuka.forwardKinematics([0, 0]), /^q: expected 7 values, got 2$/);
  throwsThenRecovers(() => kuka.rnea(entry.q0, entry.q0, [0, 0, 0, 0, 0, 0, NaN]), /^qdd\[6\] is not finite$/);
});

test('errors thrown inside C++ reach JS with their message (zero-copy solver)', () => {
  const solver = kuka.createSolver({ maxConstraints: 2 });
  solver.q.set(entry.q0);
  solver.q[4] = NaN;
  throwsThenRecovers(() => solver.solve(), /^q\[4\] is not finite$/);
  throwsThenRecovers(() => { solver.numConstraints = 3; }, /numConstraints must be an integer in \[0, 2\]/);
  throwsThenRecovers(() => kuka.createSolver({ maxConstraints: 7 }), /maxConstraints must be an integer in \[0, 6\], got 7/);
  solver.q.set(entry.q0);
  solver.solve();
  assert.deepEqual(Array.from(solver.qdd), kuka.solve({ q: entry.q0, gravity: [0, 0, -9.81] }).qdd);
  solver.delete();
});

test('a deleted object throws on every call; the others keep working', () => {
  const robot = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
  const solver = robot.createSolver();
  robot.delete();
  // A solver keeps its own reference to the model: it outlives the robot.
  solver.q.set(entry.q0);
  solver.solve();
  assert.deepEqual(Array.from(solver.qdd), kuka.solve({ q: entry.q0, gravity: [0, 0, -9.81] }).qdd);
  throwsThenRecovers(() => robot.solve(goodCase()), /^Robot has been deleted$/);
  throwsThenRecovers(() => robot.forwardKinematics(entry.q0), /^Robot has been deleted$/);
  throwsThenRecovers(() => robot.createSolver(), /^Robot has been deleted$/);
  throwsThenRecovers(() => robot.delete(), /^Robot has been deleted$/);
  solver.delete();
  assert.equal(solver.deleted, true);
  throwsThenRecovers(() => solver.solve(), /^Solver has been deleted$/);
  throwsThenRecovers(() => solver.q, /^Solver has been deleted$/);
  throwsThenRecovers(() => solver.rank, /^Solver has been deleted$/);
});
