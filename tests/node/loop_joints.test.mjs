// Loop joints (loadURDF's options.loops) through the module: the four-bar's loop keeps the
// same directions as `achd info --loops` finds, its solves (at rest, moving, with a
// loop_beta) equal the native CLI's to the bit, its simulation ends where `achd simulate`
// of the same scene ends with the loop closed, bad loops get the CLI's messages, and a loop
// that cannot close has the CLI's events, naming the loop.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';

import { assertSameResult, loadAchd, nativeCli, nativeSolve, pool, relativeError, repo, runCli, scratchDir } from './helpers.mjs';

const URDF = join(repo, 'robots/four_bar.urdf');
const LOOPS_FILE = join(repo, 'robots/four_bar.loops.json');
const SCENE = join(repo, 'robots/scenes/four_bar_swing.json');
const LOOPS = JSON.parse(readFileSync(LOOPS_FILE, 'utf8')).loops;
const scene = JSON.parse(readFileSync(SCENE, 'utf8'));

let achd, cli, scratch, robot;
before(async () => {
  achd = await loadAchd();
  cli = nativeCli();
  scratch = scratchDir();
  robot = achd.loadURDF(readFileSync(URDF, 'utf8'), { loops: LOOPS });
});
after(() => {
  robot.delete();
  scratch.remove();
});

test('robot.loops lists what achd info --loops lists', async () => {
  const info = JSON.parse(await runCli(cli, ['info', URDF, '--loops', LOOPS_FILE]));
  assert.deepEqual(robot.loops, info.loops);
  assert.deepEqual(robot.loops[0].directions, ['x', 'y']);
  assert.deepEqual(robot.loops[0].dropped, ['z', 'rx', 'ry']);
});

test('four-bar solves equal the native CLI to the bit (at rest, moving, with loop_beta)', async () => {
  const q0 = scene.q0;
  const cases = [
    { q: q0, gravity: [0, 0, -9.81] },
    { q: q0, qd: [3, -1.2, 0.7], gravity: [0, 0, -9.81] },
    { q: [0.3, 2.1, -0.4], qd: [-2, 0.5, 1], gravity: [0, 0, -9.81], loop_beta: [0.25, -1.5] },
  ];
  const natives = await pool(cases.map((c) => () => nativeSolve(cli, scratch, URDF, { loops: LOOPS }, c)));
  cases.forEach((c, i) => {
    const wasm = robot.solve(c);
    assertSameResult(wasm, natives[i], `case ${i}`);
    assert.equal(wasm.nu.length, 2, 'the loop adds its two columns to nu');
  });
});

test('the four-bar scene in wasm ends where achd simulate ends, the loop closed', async () => {
  const sim = robot.createSimulator();
  try {
    sim.reset(scene.q0);
    const steps = Math.round(scene.duration / scene.dt);
    sim.step(steps, scene.dt);
    const csv = join(scratch.dir, 'four_bar.csv');
    const summary = JSON.parse(await runCli(cli, ['simulate', SCENE, '--out', csv]));
    const last = readFileSync(csv, 'utf8').trim().split('\n').at(-1).split(',').map(Number);
    assert.equal(sim.t, last[0]);
    assert.ok(relativeError(Array.from(sim.q), last.slice(1, 4)) <= 1e-9);
    assert.ok(relativeError(Array.from(sim.qd), last.slice(4, 7)) <= 1e-9);
    const drift = sim.loopDrift();
    assert.deepEqual(Object.keys(drift), ['coupler_rocker']);
    assert.ok(drift.coupler_rocker.max < 1e-9, `loop drift ${drift.coupler_rocker.max}`);
    assert.ok(drift.coupler_rocker.now <= drift.coupler_rocker.max);
    assert.ok(summary.loop_drift.coupler_rocker < 1e-9);
    assert.equal(sim.substeps, summary.substeps);
  } finally {
    sim.delete();
  }
});

test('bad loops: the CLI\'s message after the field, the module usable after', async () => {
  const text = readFileSync(URDF, 'utf8');
  const bad = [
    [{ name: 'a', link_a: 'coupler', link_b: 'nope', type: 'revolute' }, "loop 'a': link_b: no link 'nope' in the model"],
    [{ name: 'a', link_a: 'coupler', link_b: 'rocker', type: 'hinge' }, "[0].type: unknown loop joint type 'hinge'"],
    [{ name: 'a', link_a: 'coupler', link_b: 'rocker', type: 'revolute', axis: [0, 0, 0] }, "loop 'a': axis must be finite and not zero"],
    [{ name: 'a', link_a: 'coupler', link_b: 'rocker', type: 'spherical', directions: ['rx'] }, "'rx' is not a direction a spherical loop holds"],
    [{ name: 'a', link_a: 'coupler', type: 'fixed' }, "[0]: missing required field 'link_b'"],
    [{ name: 'a', link_a: 'coupler', link_b: 'rocker', type: 'fixed', origin_a: { xyz: [1, NaN, 0] } }, '[0].origin_a.xyz[1] is not finite', 'JS only: JSON has no NaN'],
  ];
  for (const [loop, words, jsOnly] of bad) {
    assert.throws(() => achd.loadURDF(text, { loops: [loop] }), (e) => e.message.includes(words), words);
    if (jsOnly) continue;
    const file = scratch.write('bad_loops.json', JSON.stringify({ loops: [loop] }));
    await assert.rejects(runCli(cli, ['info', URDF, '--loops', file]), (e) => e.message.includes(words), words);
  }
  assert.throws(() => achd.loadURDF(text, { loops: {} }), /options\.loops must be an array of loop joints/);
  assert.equal(achd.loadURDF(text, { loops: LOOPS }).delete(), undefined);
});

test('a loop the arm cannot close: sim.events() name the loop as the CLI summary does', async () => {
  const pin = [{ name: 'pin', link_a: 'link2', origin_a: { xyz: [1, 0, 0] }, link_b: 'base_link',
    origin_b: { xyz: [0, 0, -2.2] }, type: 'spherical' }];
  const planar2 = join(repo, 'robots/planar2.urdf');
  const path = scratch.write('pin.json', JSON.stringify({ urdf: planar2, root: 'base_link', q0: [0.3, -0.6],
    loops: pin, dt: 0.001, duration: 2 }));
  const summary = JSON.parse(await runCli(cli, ['simulate', path]));
  const arm = achd.loadURDF(readFileSync(planar2, 'utf8'), { loops: pin });
  const sim = arm.createSimulator();
  try {
    sim.reset([0.3, -0.6]);
    assert.equal(sim.step(2000, 1e-3), 2000);
    const events = sim.events();
    assert.ok(events.some((e) => e.kind === 'released'), JSON.stringify(events));
    assert.equal(events.length, summary.events.length);
    for (const [i, e] of events.entries()) {
      assert.deepEqual(Object.keys(e), ['t', 'step', 'loop', 'direction', 'kind', 'sigma_min', 'unmet', 'effort_ratio']);
      const c = summary.events[i];
      assert.deepEqual([e.t, e.loop, e.direction, e.kind], [c.t, c.loop, c.direction, c.kind], `event ${i}`);
    }
    const released = sim.loopReleasedSeconds().pin;
    for (const [direction, seconds] of Object.entries(released)) {
      assert.ok(Math.abs(seconds - (summary.loop_released_s.pin[direction] ?? 0)) <= 1e-12, `${direction}: ${seconds}`);
    }
    assert.ok(Object.values(released).some((s) => s > 0));
  } finally {
    sim.delete();
    arm.delete();
  }
});
