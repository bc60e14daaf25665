// Relative constraint blocks (link_b, point_b: alpha^T (a_P - a_Q) = beta between two
// links) through the module: wasm equals the native CLI to the bit on the quadruped
// (its front feet held together in 3D, fixed and floating), on the dual-arm torso (the hands
// held together in 6D) and on random columns; the pair of forces cancels where the motion
// needs none (the floating quadruped falling at rest, its front feet held together); a
// bad second link gets the CLI's message word for word.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';

import { assertSameResult, loadAchd, nativeCli, nativeError, nativeSolve, pool, repo, scratchDir } from './helpers.mjs';
import { rng } from './random_chain.mjs';

const QUADRUPED = join(repo, 'robots/quadruped.urdf');
const TORSO = join(repo, 'robots/dual_arm_torso.urdf');
const GRAVITY = [0, 0, -9.81];
const UNIT = [0, 1, 2, 3, 4, 5].map((k) => [0, 1, 2, 3, 4, 5].map((r) => (r === k ? 1 : 0)));

let achd, cli, scratch;
before(async () => {
  achd = await loadAchd();
  cli = nativeCli();
  scratch = scratchDir();
});
after(() => scratch.remove());

function withRobot(path, load, f) {
  const robot = achd.loadURDF(readFileSync(path, 'utf8'), load);
  try {
    return f(robot);
  } finally {
    robot.delete();
  }
}

test('wasm equals native on relative blocks (quadruped fixed and floating, torso, random columns)', async () => {
  const random = rng(2711);
  const r = () => 2 * random() - 1;
  const column = () => {
    const c = [r(), r(), r(), r(), r(), r()];
    const n = Math.hypot(...c);
    return c.map((x) => x / n);
  };
  const jobs = [];
  for (const floating of [false, true]) {
    const load = floating ? { floating: true } : {};
    const n = withRobot(QUADRUPED, load, (robot) => robot.numRates);
    const positions = withRobot(QUADRUPED, load, (robot) => robot.numPositions);
    const q = Array.from({ length: positions }, (_, i) => (floating && i < 7 ? [0, 0, 0.5, 0, 0, 0, 1][i] : 0.3 * r()));
    const qd = Array.from({ length: n }, () => 0.5 * r());
    jobs.push({ urdf: QUADRUPED, load, what: `quadruped${floating ? ' floating' : ''}: front feet together in 3D`,
      c: { q, qd, gravity: GRAVITY, constraints: [{ link: 'lf_foot', link_b: 'rf_foot', alpha: UNIT.slice(0, 3) }] } });
    jobs.push({ urdf: QUADRUPED, load, what: `quadruped${floating ? ' floating' : ''}: random columns, mixed blocks`,
      c: { q, qd, gravity: GRAVITY, constraints: [
        { link: 'lh_shank', point: [0.01, 0, -0.1], link_b: 'rf_thigh', point_b: [0, 0.02, -0.05],
          alpha: [column(), column()], beta: [r(), r()] },
        { link: 'rh_foot', alpha: [column()], beta: [r()] }] } });
  }
  jobs.push({ urdf: TORSO, load: {}, what: 'torso: the hands together in 6D',
    c: { q: Array(withRobot(TORSO, {}, (robot) => robot.numRates)).fill(0.2), gravity: GRAVITY,
      constraints: [{ link: 'left_hand', link_b: 'right_hand', point_b: [0, 0, 0.1], alpha: UNIT }] } });
  const natives = await pool(jobs.map((j) => () => nativeSolve(cli, scratch, j.urdf, j.load, j.c)));
  jobs.forEach((j, i) => withRobot(j.urdf, j.load, (robot) => {
    const wasm = robot.solve(j.c);
    assertSameResult(wasm, natives[i], j.what);
    assert.ok(wasm.nu.some((x) => x !== 0), `${j.what}: the block acted`);
  }));
});

test('the floating quadruped falling at rest, its front feet held together, needs no force to hold them', () => {
  withRobot(QUADRUPED, { floating: true }, (robot) => {
    const q = Array.from({ length: robot.numPositions }, (_, i) => [0, 0, 0.5, 0, 0, 0, 1][i] ?? 0.2);
    const free = robot.solve({ q, gravity: GRAVITY });
    const held = robot.solve({ q, gravity: GRAVITY, constraints: [{ link: 'lf_foot', link_b: 'rf_foot', alpha: UNIT.slice(0, 3) }] });
    // Falling freely, the robot is rigid and every point falls alike: a_P - a_Q = 0 already,
    // so the pair of forces is zero and nothing changes.
    const scale = Math.max(...held.qdd.map(Math.abs), 1);
    for (let i = 0; i < free.qdd.length; ++i) assert.ok(Math.abs(held.qdd[i] - free.qdd[i]) <= 1e-12 * scale, `qdd[${i}]`);
    for (const x of held.nu) assert.ok(Math.abs(x) <= 1e-9, `nu ${held.nu}`);
  });
});

test('a bad second link or point gets the CLI\'s message, word for word', async () => {
  const q = Array(12).fill(0);
  const bad = [
    { link: 'lf_foot', link_b: 'nowhere', alpha: [UNIT[2]] },
    { link: 'lf_foot', link_b: 'lf_foot', alpha: [UNIT[2]] },
    { link: 'lf_foot', link_b: 7, alpha: [UNIT[2]] },
    { link: 'lf_foot', point_b: [0, 0, 1], alpha: [UNIT[2]] },
    { link: 'lf_foot', link_b: 'rf_foot', point_b: [0, 1], alpha: [UNIT[2]] },
  ];
  const natives = await pool(bad.map((b) => () => nativeError(cli, scratch, QUADRUPED, {}, { q, gravity: GRAVITY, constraints: [b] })));
  withRobot(QUADRUPED, {}, (robot) => bad.forEach((b, i) => {
    assert.throws(() => robot.solve({ q, gravity: GRAVITY, constraints: [b] }), (e) => {
      assert.equal(e.message, natives[i]);
      return true;
    });
    assert.ok(natives[i].includes('link_b') || natives[i].includes('point_b'), natives[i]);
  }));
});
