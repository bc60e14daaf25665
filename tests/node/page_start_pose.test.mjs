// The pose the page starts an own URDF from (web/start_pose.js): inside the joint limits
// and away from a singularity of the tip Jacobian, on the real module's robots. The plain
// choice it replaces (0, or the middle of the limits) is singular on the KUKA LWR 4 (it
// stands straight up and loses three tip directions) and on the UR5.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { MIN_SCORE, startPose } from '../../web/start_pose.js';
import { singularValues } from '../../web/singular_values.js';
import { loadAchd, robots } from './helpers.mjs';

const achd = await loadAchd();

// Singular values of the whole tip Jacobian (6 rows), largest first.
const sigmas = (robot, q) => singularValues(robot.tipJacobian(q));

test('singular values of small matrices', () => {
  assert.deepEqual(singularValues([[3, 0], [0, -2], [0, 0]]), [3, 2]);
  // [[1, 1], [1, 1]] has singular values 2 and 0; a 2x3 matrix of rank 1 has its Frobenius
  // norm and 0.
  const [a, b] = singularValues([[1, 1], [1, 1]]);
  assert.ok(Math.abs(a - 2) < 1e-15 && b < 1e-7, `${a} ${b}`);
  const wide = singularValues([[1, 2, 2], [2, 4, 4]]);
  assert.ok(Math.abs(wide[0] - 45 ** 0.5) < 1e-14 && wide[1] < 1e-7, `${wide}`);
  // A rotation times diag(5, 1, 0.001) keeps those values.
  const c = Math.cos(0.3), s = Math.sin(0.3);
  const m = [[5 * c, -1 * s, 0], [5 * s, 1 * c, 0], [0, 0, 0.001]];
  const got = singularValues(m);
  [5, 1, 0.001].forEach((v, i) => assert.ok(Math.abs(got[i] - v) < 1e-14, `${got}`));
});

test('every robot starts inside its limits, away from a singularity', () => {
  for (const entry of robots()) {
    const robot = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
    const { q, score } = startPose(robot);
    assert.equal(q.length, robot.numRates);
    robot.limits.forEach((l, j) => {
      const margin = Number.isFinite(l.upper - l.lower) ? 0.05 * (l.upper - l.lower) : 0;
      assert.ok(q[j] >= l.lower + margin - 1e-12 && q[j] <= l.upper - margin + 1e-12,
        `${entry.name} ${robot.jointNames[j]}: ${q[j]} outside [${l.lower}, ${l.upper}] less 5%`);
    });
    assert.ok(score >= MIN_SCORE, `${entry.name}: score ${score}`);
    // The same URDF always starts from the same pose.
    assert.deepEqual(startPose(robot).q, q);
    console.log(`# ${entry.name}: score ${score.toFixed(3)}, sigma_min/sigma_max of J ` +
      `${(sigmas(robot, q).at(-1) / sigmas(robot, q)[0]).toExponential(1)}`);
    robot.delete();
  }
});

// The listed robots start from their q0 on the page: those must be good start poses too.
test('every q0 of robots/index.json is inside the limits and away from a singularity', () => {
  for (const entry of robots()) {
    const robot = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
    robot.limits.forEach((l, j) => assert.ok(entry.q0[j] > l.lower && entry.q0[j] < l.upper,
      `${entry.name} ${robot.jointNames[j]}: ${entry.q0[j]} outside (${l.lower}, ${l.upper})`));
    const s = sigmas(robot, entry.q0);
    assert.ok(s.at(-1) >= MIN_SCORE * s[0], `${entry.name}: sigma ${s}`);
    robot.delete();
  }
});

test('the LWR and the UR5, whose plain pose is singular, are moved away from it', () => {
  for (const name of ['kuka_lwr4', 'ur5']) {
    const entry = robots().find((r) => r.name === name);
    const robot = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
    const plain = robot.limits.map((l) => (l.lower <= 0 && 0 <= l.upper ? 0 : (l.lower + l.upper) / 2));
    const before = sigmas(robot, plain);
    const { q } = startPose(robot);
    const after = sigmas(robot, q);
    console.log(`# ${name}: sigma_min/sigma_max ${(before.at(-1) / before[0]).toExponential(1)} at the plain pose, ` +
      `${(after.at(-1) / after[0]).toExponential(2)} at the start pose`);
    assert.ok(before.at(-1) < 1e-9 * before[0], `${name}: the plain pose is not singular (${before})`);
    assert.ok(after.at(-1) >= MIN_SCORE * after[0], `${name}: ${after}`);
    // A simulator from there holds z and rx and accelerates x for 2 s (from the plain pose
    // the LWR fails this at step 17: the acceleration to enforce along x is not finite).
    const sim = robot.createSimulator();
    sim.reset(q);
    sim.setDirection('z', 'hold');
    sim.setDirection('rx', 'hold');
    sim.setDirection('x', 0.1);
    sim.step(2000, 0.001);
    assert.ok(Math.abs(sim.residuals().z) < 1e-6, `${name}: z residual ${sim.residuals().z}`);
    sim.delete();
    robot.delete();
  }
});
