// Loop joints on the page, in Chromium:
// - the four-bar of the robot list comes with its loops file's loop joint (coupler to
//   rocker), listed in the loops card; while it swings for 5 s under gravity, the loop
//   stays closed within 1e-6 m and the readout shows its closure error;
// - two Alt-clicks on the LWR's links 4 and 6 close a fixed loop joint between them as they
//   are then: the page goes on from the same state (q, qd, time), the loop stays closed
//   within 1e-6 (once the links' relative velocity at the click is taken out, 0.5 s) over
//   5 s while the arm moves under gravity, and Open removes it again;
// - a closed loop is part of the page's link (closed=): the link opens the robot with the
//   same loop joint, which the stabilisation closes from the link's start pose; Open takes
//   it out of the link; a closed= the page cannot read is named and the robot runs on;
// - a loop between two links on the ends of fixed joints (the mixed chain's link_c and
//   spacer2), whose every direction the tree holds already: the loader's message is shown
//   in the page's error area and the robot runs on without it.
import assert from 'node:assert/strict';
import test from 'node:test';
import { openPage } from './launch.mjs';

const CLOSURE = 1e-6;
const state = (page) => page.evaluate(() => window.achdDemo.state());
const drift = (page) => page.evaluate(() => window.achdDemo.loopDrift());

// Where a world point is on the screen (CSS pixels), from the page's camera.
async function screenOf(page, p) {
  return page.evaluate((w) => {
    const { projection: P, worldInverse: V, rect } = window.achdDemo.camera();
    const mul = (m, v) => [0, 1, 2, 3].map((r) => m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3]);
    const c = mul(P, mul(V, [...w, 1]));
    return { x: rect.left + ((c[0] / c[3] + 1) / 2) * rect.width, y: rect.top + ((1 - c[1] / c[3]) / 2) * rect.height };
  }, p);
}

// A screen point over `link`: along the line from its origin toward another link's origin
// (at these fractions of the way: negative ones lead away from it), the first that the
// page names `link` under the pointer.
async function pointOver(page, link, toward, fractions = [0.5, 0.35, 0.65, 0.2, 0.8, 0.1, 0.9]) {
  const [a, b] = await page.evaluate(([l, n]) => [window.achdDemo.linkPosition(l), window.achdDemo.linkPosition(n)],
    [link, toward]);
  for (const f of fractions) {
    const at = await screenOf(page, a.map((x, i) => x + f * (b[i] - x)));
    await page.mouse.move(at.x, at.y);
    const label = page.locator('#link-label');
    if (!(await label.isHidden()) && (await label.textContent()) === link) return at;
  }
  throw new Error(`no point over ${link} found on the line from its origin to ${toward}'s`);
}

async function altClick(page, at) {
  await page.keyboard.down('Alt');
  await page.mouse.click(at.x, at.y);
  await page.keyboard.up('Alt');
}

test('the four-bar of the robot list swings with its loop closed', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    await page.selectOption('#robot-select', 'four_bar');
    await page.waitForFunction(() => window.achdDemo.state().robot === 'four_bar');
    await page.evaluate(() => window.achdDemo.pause());
    const s0 = await state(page);
    assert.equal(s0.error, null);
    assert.deepEqual(s0.loops.map((l) => [l.name, l.type, l.link_a, l.link_b, l.directions, l.picked]),
      [['coupler_rocker', 'revolute', 'coupler', 'rocker', ['x', 'y'], false]]);
    assert.match(await page.locator('#loop-list li').textContent(), /coupler_rocker: revolute, coupler to rocker/);
    assert.equal(await page.locator('#loop-list button').count(), 0, 'a loop of the robot cannot be opened');
    let worst = 0;
    for (let k = 0; k < 50; k++) {
      await page.evaluate(() => window.achdDemo.step(100));
      worst = Math.max(worst, (await drift(page)).coupler_rocker.now);
    }
    const s1 = await state(page);
    assert.equal(s1.error, null);
    assert.ok(Math.abs(s1.t - s0.t - 5) < 1e-9, `t from ${s0.t} to ${s1.t}`);
    const crank = Math.abs(s1.q[0] - s0.q[0]);
    const { max } = (await drift(page)).coupler_rocker;
    t.diagnostic(`four-bar: the crank turned ${crank.toFixed(3)} rad in 5 s, the loop's largest closure error ${max.toExponential(2)} m`);
    assert.ok(crank > 0.1, `the crank turned ${crank} rad`);
    assert.ok(worst <= CLOSURE && max <= CLOSURE, `closure error ${worst}, largest ${max}`);
    // The readout (refreshed every 200 ms while frames run) names the loop.
    await page.waitForFunction(() => document.querySelector('#numbers').textContent.includes('coupler_rocker:'));
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});

test('two Alt-clicks close a loop between two links of the LWR, Open opens it', async (t) => {
  const session = await openPage({ hash: '#robot=kuka_lwr4&integrator=rk4&dt=0.001' });
  const { page, consoleErrors } = session;
  try {
    await page.evaluate(() => window.achdDemo.pause());
    await page.evaluate(() => window.achdDemo.step(200));  // moving: the loop must keep qd
    const first = await pointOver(page, 'lwr_link_4', 'lwr_link_5');
    // The wrist (link 6) hides the flange (link 7) when the arm hangs: link 6, by the tip.
    const second = await pointOver(page, 'lwr_link_6', 'lwr_link_7', [0.5, 0.3, 0.7, 0, 0.9]);
    const before = await state(page);
    await altClick(page, first);
    assert.equal((await state(page)).loopPick, 'lwr_link_4');
    assert.match(await page.locator('#loop-pick').textContent(), /from lwr_link_4/);
    await altClick(page, second);
    const s0 = await state(page);
    assert.equal(s0.error, null);
    assert.equal(s0.loopPick, null);
    assert.equal(await page.locator('#page-error').isHidden(), true);
    assert.deepEqual(s0.loops.map((l) => [l.name, l.type, l.link_a, l.link_b, l.picked]),
      [['lwr_link_4-lwr_link_6', 'fixed', 'lwr_link_4', 'lwr_link_6', true]]);
    assert.equal(s0.link, before.link, 'the selected link is kept');
    assert.deepEqual(s0.q, before.q, 'q is kept');
    assert.deepEqual(s0.qd, before.qd, 'qd is kept');
    assert.equal(s0.t, before.t, 'the time is kept');
    assert.ok((await drift(page))['lwr_link_4-lwr_link_6'].now < 1e-12, 'closed where it was picked');
    // The links were moving apart when the loop closed: the simulator's stabilization
    // takes that out within the first 0.5 s; from then on the loop stays closed.
    const joints = async () => page.evaluate(() => ['lwr_link_4', 'lwr_link_6'].map((l) => window.achdDemo.linkPosition(l)));
    const distance = (e) => Math.hypot(...e[1].map((x, i) => x - e[0][i]));
    await page.evaluate(() => window.achdDemo.step(500));
    const d0 = distance(await joints());
    let worst = 0;
    for (let k = 0; k < 45; k++) {
      await page.evaluate(() => window.achdDemo.step(100));
      worst = Math.max(worst, (await drift(page))['lwr_link_4-lwr_link_6'].now);
    }
    const s1 = await state(page);
    assert.equal(s1.error, null);
    assert.ok(Math.abs(s1.t - s0.t - 5) < 1e-9, `t from ${s0.t} to ${s1.t}`);
    const { max } = (await drift(page))['lwr_link_4-lwr_link_6'];
    const moved = Math.max(...s1.q.map((q, j) => Math.abs(q - s0.q[j])));
    const change = Math.abs(distance(await joints()) - d0);
    t.diagnostic(`LWR, link 4 to link 6: 5 s, the largest joint moved ${moved.toFixed(3)} rad; closure error ` +
      `${worst.toExponential(2)} from 0.5 s on (${max.toExponential(2)} in the first steps, the links' velocities ` +
      `taken out); the links' distance changed by ${change.toExponential(2)} m`);
    assert.ok(worst <= CLOSURE, `closure error ${worst}`);
    assert.ok(change <= CLOSURE, `the links' distance changed by ${change} m`);
    assert.ok(moved > 0.05, `the arm moved ${moved} rad`);
    // Open: the robot goes on without the loop, from the same state.
    await page.click('#loop-list button[data-open="lwr_link_4-lwr_link_6"]');
    const s2 = await state(page);
    assert.deepEqual(s2.loops, []);
    assert.deepEqual(s2.q, s1.q);
    assert.deepEqual(await drift(page), {});
    assert.equal(await page.locator('#loops-none').isHidden(), false);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});

test('a loop whose every direction the tree holds is refused, the robot runs on', async () => {
  const session = await openPage({ hash: '#robot=mixed_chain' });
  const { page, consoleErrors } = session;
  try {
    const t0 = (await state(page)).t;
    await assert.rejects(page.evaluate(() => window.achdDemo.closeLoop('link_c', 'spacer2')),
      /the tree already holds every direction of the loop/);
    assert.equal(await page.locator('#page-error').isHidden(), false);
    assert.match(await page.locator('#page-error-text').textContent(),
      /could not close a loop between link_c and spacer2: .*the tree already holds every direction of the loop/);
    const s = await state(page);
    assert.deepEqual(s.loops, []);
    assert.equal(s.error, null);
    assert.equal(s.playing, true);
    await page.waitForFunction((t) => window.achdDemo.state().t > t + 0.2, t0);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});

test('a loop closed on the page is in its link, and the link opens the robot with it', async () => {
  const first = await openPage({ hash: '#robot=kuka_lwr4&integrator=rk4&dt=0.001' });
  let hash, loops;
  try {
    await first.page.evaluate(() => window.achdDemo.pause());
    await first.page.evaluate(() => window.achdDemo.step(300));
    await first.page.evaluate(() => window.achdDemo.closeLoop('lwr_link_4', 'lwr_link_6'));
    hash = await first.page.evaluate(() => location.hash);
    loops = (await first.page.evaluate(() => window.achdDemo.robotSource())).loops;
    assert.match(hash, /&closed=/);
    assert.equal(loops.length, 1);
    assert.deepEqual(first.consoleErrors, []);
  } finally {
    await first.close();
  }
  const second = await openPage({ hash });
  const { page, consoleErrors } = second;
  try {
    await page.evaluate(() => window.achdDemo.pause());
    assert.deepEqual((await page.evaluate(() => window.achdDemo.robotSource())).loops, loops);
    const s0 = await state(page);
    assert.equal(s0.error, null);
    assert.deepEqual(s0.loops.map((l) => [l.name, l.picked]), [['lwr_link_4-lwr_link_6', true]]);
    // The link starts from the robot's start pose, not where the loop was closed: the
    // stabilisation closes it.
    await page.evaluate(() => window.achdDemo.step(1000));
    const { now } = (await drift(page))['lwr_link_4-lwr_link_6'];
    assert.ok(now <= CLOSURE, `closure error ${now} m after 1 s`);
    await page.click('#loop-list button[data-open="lwr_link_4-lwr_link_6"]');
    assert.doesNotMatch(await page.evaluate(() => location.hash), /closed=/);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await second.close();
  }
  const bad = await openPage({ hash: '#robot=kuka_lwr4&closed=[["x","lwr_link_4"]]' });
  try {
    assert.match(await bad.page.locator('#page-error-text').textContent(),
      /ignored in the URL: closed: loop 0: expected \[name, link_a, link_b/);
    const s = await state(bad.page);
    assert.deepEqual(s.loops, []);
    assert.equal(s.robot, 'kuka_lwr4');
  } finally {
    await bad.close();
  }
});
