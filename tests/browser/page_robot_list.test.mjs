// Every robot of the page's list (robots/index.json), in Chromium: picked from the list, it
// loads without an error or a console error, runs 5 simulated seconds at the page's
// defaults (dormand_prince, 1 ms steps, every effect on) and does what its title says:
// - a chain has as many joints as its title counts, and moves under gravity;
// - a tree holds its default links: each held direction stays within 1e-6 m (rad) of where
//   the link started;
// - the Panda-like arm's fingers move together: the right finger (a <mimic> joint) follows
//   the left one within 1e-9 m over the run (its hand held);
// - a floating robot stands: its feet start at z = 0, stay held within 1e-6, and its trunk
//   (the free joint's x, y, z) stays within 2 cm of where it started; the humanoid's soles
//   are held in 6D and its head stays within 2 cm of its start height (it does not fold);
// - the four-bar swings on its loop joint: the crank turns and the loop stays closed
//   within 1e-6 m over the run.
// Every entry must have its claim here: a new one without fails the test.
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { loadAchd } from '../node/helpers.mjs';
import { openPage } from './launch.mjs';

const achd = await loadAchd();
const index = JSON.parse(await readFile(new URL('../../robots/index.json', import.meta.url), 'utf8'));
const SECONDS = 5;
const DT = 0.001;
const HELD_TOLERANCE = 1e-6;
const TRUNK_TOLERANCE = 0.02;
const COUPLING_TOLERANCE = 1e-9;

const state = (page) => page.evaluate(() => window.achdDemo.state());
const linkPositions = (page, links) => page.evaluate((names) => names.map((n) => window.achdDemo.linkPosition(n)), links);
const distance = (a, b) => Math.hypot(...a.map((x, i) => x - b[i]));

// The number of joints a title counts: "(7-DoF)", "(9-DoF tree", "200 revolute joints",
// "2-link".
function titleJoints(title) {
  const m = title.match(/(\d+)-DoF/) ?? title.match(/(\d+) revolute joints/) ?? title.match(/(\d+)-link/);
  return m ? Number(m[1]) : null;
}

// What each entry's title claims, checked after the run (s0, s1: states before and after;
// feet0/feet1: the held links' positions).
const CLAIMS = {
  chain: async (t, { s0, s1, entry }) => {
    assert.equal(s1.q.length, titleJoints(entry.title), `${entry.name}: joints`);
    const moved = Math.max(...s1.q.map((q, j) => Math.abs(q - s0.q[j])));
    t.diagnostic(`${entry.name}: ${s1.q.length} joints, the largest joint moved ${moved.toFixed(3)} rad under gravity`);
    assert.ok(moved > 0.01, `${entry.name} did not move under gravity (${moved})`);
  },
  held: async (t, { s1, entry, feet0, feet1 }) => {
    const drift = Math.max(...feet1.map((p, k) => distance(p, feet0[k])));
    const residual = Math.max(...Object.values(s1.links).flatMap((l) => Object.values(l.residuals).filter((r) => r !== null))
      .map(Math.abs));
    t.diagnostic(`${entry.name}: held links ${entry.constraints.join(', ')} moved ${drift.toExponential(2)} m, ` +
      `largest residual ${residual.toExponential(2)}`);
    assert.ok(drift <= HELD_TOLERANCE, `${entry.name}: a held link moved ${drift} m`);
    assert.ok(residual <= HELD_TOLERANCE, `${entry.name}: residual ${residual}`);
  },
  loop: async (t, { page, s0, s1, entry }) => {
    const drift = await page.evaluate(() => window.achdDemo.loopDrift());
    const crank = Math.abs(s1.q[0] - s0.q[0]);
    t.diagnostic(`${entry.name}: the crank turned ${crank.toFixed(2)} rad, the loop's largest closure error ` +
      `${Object.entries(drift).map(([name, e]) => `${name} ${e.max.toExponential(2)} m`).join(', ')}`);
    assert.deepEqual(Object.keys(drift), ['coupler_rocker']);
    assert.ok(drift.coupler_rocker.max <= HELD_TOLERANCE, `${entry.name}: closure error ${drift.coupler_rocker.max}`);
    assert.ok(crank > 0.1, `${entry.name}: the crank turned ${crank} rad`);
  },
  standing: async (t, args) => {
    const { s0, s1, entry, feet0 } = args;
    for (const p of feet0) assert.ok(Math.abs(p[2]) < 1e-9, `${entry.name}: a foot starts at z = ${p[2]}`);
    await CLAIMS.held(t, args);
    const trunk = distance(s1.q.slice(0, 3), s0.q.slice(0, 3));
    t.diagnostic(`${entry.name}: the trunk moved ${(1000 * trunk).toFixed(2)} mm in ${SECONDS} s`);
    assert.ok(trunk <= TRUNK_TOLERANCE, `${entry.name}: the trunk moved ${trunk} m`);
  },
};

// Per entry: which claims its title makes.
const ENTRY_CLAIMS = {
  kuka_lwr4: ['chain'], ur5: ['chain'], planar2: ['chain'], mixed_chain: ['chain'], chain50: ['chain'],
  chain200: ['chain'],
  quadruped: ['standing'],
  dual_arm_torso: ['held'],
  panda_fingers: ['held', 'coupled'],
  humanoid: ['standing', 'upright'],
  four_bar: ['loop'],
};

test('every entry of the robot list has a claim to check', () => {
  assert.deepEqual(index.robots.map((r) => r.name).sort(), Object.keys(ENTRY_CLAIMS).sort());
});

test('every robot of the page\'s list loads, runs 5 s and does what its title says', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    for (const entry of index.robots) {
      await t.test(entry.title, async (t) => {
        await page.selectOption('#robot-select', entry.name);
        await page.waitForFunction((name) => window.achdDemo.state().robot === name, entry.name);
        await page.evaluate(() => window.achdDemo.pause());
        await page.evaluate(() => window.achdDemo.setPose(window.achdDemo.robotSource().q0));
        const s0 = await state(page);
        assert.equal(s0.error, null);
        assert.equal(await page.locator('#page-error').isHidden(), true, 'an error is shown');
        const held = entry.constraints ?? [];
        assert.deepEqual(Object.keys(s0.links).sort(), [...held].sort(), 'the default links are held');
        for (const link of held) {
          const want = entry.held ?? ['x', 'y', 'z'];
          assert.deepEqual(Object.entries(s0.links[link].directions).filter(([, m]) => m === 'hold').map(([d]) => d), want, link);
        }
        const feet0 = await linkPositions(page, held);
        // The coupled joints (<mimic>) as achd loads the entry: their places in q.
        const text = await readFile(new URL(`../../${entry.urdf}`, import.meta.url), 'utf8');
        const robot = achd.loadURDF(text, { root: entry.root, tip: entry.tip, floating: Boolean(entry.floating) });
        const free = robot.floating ? 1 : 0;
        const couplings = robot.couplings.map((c) => ({ ...c, at: robot.jointNames.indexOf(c.joint) - free,
          leaderAt: robot.jointNames.indexOf(c.leader) - free }));
        robot.delete();
        if (ENTRY_CLAIMS[entry.name].includes('coupled')) assert.equal(couplings.length, 1, 'one coupled finger');
        const head0 = entry.name === 'humanoid' ? (await linkPositions(page, ['head']))[0] : null;
        const start = Date.now();
        let worstCoupling = 0;
        for (let k = 0; k < SECONDS * 10; k++) {
          await page.evaluate((n) => window.achdDemo.step(n), 0.1 / DT);
          const q = (await state(page)).q;
          for (const c of couplings) {
            worstCoupling = Math.max(worstCoupling, Math.abs(q[c.at] - c.multiplier * q[c.leaderAt] - c.offset));
          }
        }
        const s1 = await state(page);
        t.diagnostic(`${entry.name}: ${SECONDS} s simulated in ${((Date.now() - start) / 1000).toFixed(1)} s wall`);
        assert.equal(s1.error, null);
        assert.ok(Math.abs(s1.t - s0.t - SECONDS) < 1e-9, `t went from ${s0.t} to ${s1.t}`);
        const feet1 = await linkPositions(page, held);
        const args = { page, s0, s1, entry, feet0, feet1 };
        for (const claim of ENTRY_CLAIMS[entry.name]) {
          if (claim === 'coupled') {
            t.diagnostic(`panda_fingers: |q_right - q_left| <= ${worstCoupling.toExponential(2)} m over the run`);
            assert.ok(worstCoupling <= COUPLING_TOLERANCE, `the fingers moved apart by ${worstCoupling} m`);
          } else if (claim === 'upright') {
            const head1 = (await linkPositions(page, ['head']))[0];
            t.diagnostic(`humanoid: the head from z = ${head0[2].toFixed(3)} m to ${head1[2].toFixed(3)} m`);
            assert.ok(head0[2] > 1.3, `the head starts at z = ${head0[2]} m`);
            assert.ok(Math.abs(head1[2] - head0[2]) <= TRUNK_TOLERANCE, `the head moved from z = ${head0[2]} to ${head1[2]}`);
          } else {
            await CLAIMS[claim](t, args);
          }
        }
      });
    }
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});
