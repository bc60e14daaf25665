// Whole robots on the page, in Chromium: the floating quadruped stands on its four feet
// (held in x, y, z by default, the joint PD controller toward its start pose); a click on
// a foot in the 3D view selects it, the controls then show and set that foot's
// directions; held alone while the other legs swing, the foot stays within 1e-6 m over
// 2000 steps; its constraint-wrench arrow is drawn at the foot with a length that follows
// nu; a Shift-click holds a foot at the point clicked; the sliders set a floating robot's
// joints (q behind the free joint's 7 numbers).
// The quadruped on its four feet and the dual-arm torso holding both hands step at real
// time (dt 1 ms, RK4, every effect, rendering on): the test records the real-time factor
// the page shows and how many simulated seconds a wall second can step.
import assert from 'node:assert/strict';
import test from 'node:test';
import { openPage } from './launch.mjs';

const state = (page) => page.evaluate(() => window.achdDemo.state());
const FEET = ['lf_foot', 'rf_foot', 'lh_foot', 'rh_foot'];

// Where a link's origin is on the screen (CSS pixels), from the page's camera.
async function screenPoint(page, link) {
  return page.evaluate((name) => {
    const { projection: P, worldInverse: V, rect } = window.achdDemo.camera();
    const p = [...window.achdDemo.linkPosition(name), 1];
    const mul = (m, v) => [0, 1, 2, 3].map((r) => m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3]);
    const c = mul(P, mul(V, p));
    return { x: rect.left + ((c[0] / c[3] + 1) / 2) * rect.width, y: rect.top + ((1 - c[1] / c[3]) / 2) * rect.height };
  }, link);
}

test('the floating quadruped on the page', async (t) => {
  const session = await openPage({ hash: '#robot=quadruped&integrator=rk4&dt=0.001' });
  const { page, consoleErrors } = session;
  try {
    await t.test('it stands on its four held feet', async () => {
      await page.evaluate(() => window.achdDemo.pause());
      const start = await state(page);
      assert.equal(start.robot, 'quadruped');
      assert.equal(start.link, 'lf_foot');
      assert.deepEqual(Object.keys(start.links), FEET);
      const feet0 = await page.evaluate((feet) => feet.map((f) => window.achdDemo.linkPosition(f)), FEET);
      for (const p of feet0) assert.ok(Math.abs(p[2]) < 1e-9, `a foot starts at z = ${p[2]}, not on the ground`);
      await page.evaluate(() => window.achdDemo.step(2000));
      const after = await state(page);
      assert.equal(after.error, null);
      assert.ok(Math.abs(after.q[2] - start.q[2]) < 0.01, `the trunk moved from ${start.q[2]} to ${after.q[2]} m`);
      for (const foot of FEET) {
        for (const d of ['x', 'y', 'z']) assert.ok(Math.abs(after.links[foot].residuals[d]) < 1e-6, `${foot} ${d}`);
      }
    });

    await t.test('a Shift-click holds a foot at the point clicked', async () => {
      const at = await screenPoint(page, 'rf_foot');
      await page.keyboard.down('Shift');
      await page.mouse.click(at.x + 2, at.y + 2);
      await page.keyboard.up('Shift');
      let s = await state(page);
      assert.equal(s.link, 'rf_foot');
      for (const d of ['x', 'y', 'z']) await page.click(`#directions button[data-direction="${d}"][data-mode="hold"]`);
      s = await state(page);
      const point = s.links.rf_foot.point;
      assert.ok(Math.hypot(...point) > 1e-4 && Math.hypot(...point) < 0.05, `the point clicked: ${point}`);
      const held0 = await page.evaluate(() => window.achdDemo.pointPosition('rf_foot'));
      const origin0 = await page.evaluate(() => window.achdDemo.linkPosition('rf_foot'));
      await page.evaluate(() => window.achdDemo.step(1000));
      s = await state(page);
      const held = await page.evaluate(() => window.achdDemo.pointPosition('rf_foot'));
      const drift = Math.hypot(...held.map((x, i) => x - held0[i]));
      t.diagnostic(`the point clicked on rf_foot, ${point.map((x) => x.toFixed(4))} in its frame, drifted ${drift.toExponential(2)} m`);
      assert.ok(drift < 1e-6, `the held point moved ${drift} m`);
      for (const d of ['x', 'y', 'z']) assert.ok(Math.abs(s.residuals[d]) < 1e-6, d);
      const f = await page.evaluate(() => window.achdDemo.forces());
      assert.ok(Math.hypot(...f.links.rf_foot.force.from.map((x, i) => x - held[i])) < 1e-6, 'the arrow starts at the point');
      const origin = await page.evaluate(() => window.achdDemo.linkPosition('rf_foot'));
      t.diagnostic(`its origin moved ${Math.hypot(...origin.map((x, i) => x - origin0[i])).toExponential(2)} m`);
    });

    await t.test('a click selects a foot; held alone, it stays while the other legs move', async () => {
      // Free the other feet through the controls, link by link.
      for (const foot of ['rf_foot', 'lh_foot', 'rh_foot']) {
        await page.evaluate((f) => window.achdDemo.selectLink(f), foot);
        for (const d of ['x', 'y', 'z']) await page.click(`#directions button[data-direction="${d}"][data-mode="free"]`);
      }
      assert.deepEqual(Object.keys((await state(page)).links), ['lf_foot']);
      const at = await screenPoint(page, 'lf_foot');
      await page.mouse.click(at.x, at.y);
      let s = await state(page);
      assert.equal(s.link, 'lf_foot', `the click at (${at.x}, ${at.y}) selected ${s.link}`);
      assert.equal(await page.locator('#directions-link').textContent(), 'lf_foot');
      // Its directions are the controls': free it and hold it again by the buttons.
      for (const mode of ['free', 'hold']) {
        for (const d of ['x', 'y', 'z']) await page.click(`#directions button[data-direction="${d}"][data-mode="${mode}"]`);
      }
      s = await state(page);
      assert.deepEqual(['x', 'y', 'z'].map((d) => s.directions[d]), ['hold', 'hold', 'hold']);
      const others0 = await page.evaluate(() => ['rf_foot', 'lh_foot', 'rh_foot'].map((f) => window.achdDemo.linkPosition(f)));
      const held0 = await page.evaluate(() => window.achdDemo.linkPosition('lf_foot'));
      let worst = 0;
      for (let k = 0; k < 20; k++) {
        await page.evaluate(() => window.achdDemo.step(100));
        s = await state(page);
        assert.equal(s.error, null);
        for (const d of ['x', 'y', 'z']) worst = Math.max(worst, Math.abs(s.residuals[d]));
      }
      const held = await page.evaluate(() => window.achdDemo.linkPosition('lf_foot'));
      const others = await page.evaluate(() => ['rf_foot', 'lh_foot', 'rh_foot'].map((f) => window.achdDemo.linkPosition(f)));
      const moved = Math.max(...others.map((p, k) => Math.hypot(...p.map((x, i) => x - others0[k][i]))));
      t.diagnostic(`held foot residual ${worst.toExponential(2)} m over 2000 steps; the other feet moved up to ${moved.toFixed(3)} m`);
      assert.ok(worst < 1e-6, `residual ${worst}`);
      assert.ok(Math.hypot(...held.map((x, i) => x - held0[i])) < 1e-6, 'the held foot moved');
      assert.ok(moved > 0.01, `the other legs moved only ${moved} m`);
    });

    await t.test('the held foot\'s arrow is drawn there, its length following nu', async () => {
      await page.evaluate(() => window.achdDemo.step(1));
      const s = await state(page);
      const f = await page.evaluate(() => window.achdDemo.forces());
      const arrow = f.links.lf_foot.force;
      assert.ok(arrow.shown);
      assert.deepEqual(f.force, arrow, 'the selected link\'s arrow is the one forces() reports first');
      const origin = await page.evaluate(() => window.achdDemo.linkPosition('lf_foot'));
      assert.ok(Math.hypot(...arrow.from.map((x, i) => x - origin[i])) < 1e-6, 'the arrow starts at the foot');
      // alpha's columns are x, y, z: the force is nu.
      const force = Math.hypot(...s.nu);
      assert.ok(force > 1, `the foot carries ${force} N`);
      assert.ok(Math.abs(arrow.length - force * f.metersPerNewton) < 1e-6 * arrow.length,
        `arrow ${arrow.length} m for |nu| ${force} N at ${f.metersPerNewton} m/N`);
    });

    await t.test('a slider sets a joint of the floating robot', async () => {
      const slider = page.locator('#joint-sliders input[data-joint="lf_kfe"]');
      assert.equal(await page.locator('#joint-sliders input[type=range]').count(), 12, 'one per joint, none for the free joint');
      await slider.fill('-1.2');
      const s = await state(page);
      const step = await slider.evaluate((e) => Number(e.step));
      assert.ok(Math.abs(s.q[7 + 2] + 1.2) <= step / 2, `lf_kfe is q[9] = ${s.q[9]}`);
      assert.equal(s.q.length, 19);
    });
    await t.test('a link edited into the hash selects that link with its directions', async () => {
      await page.evaluate(() => { location.hash = '#robot=quadruped&integrator=rk4&dt=0.001&link=rh_foot&dirs=z:hold,rz:hold'; });
      await page.waitForFunction(() => window.achdDemo.state().link === 'rh_foot');
      const s = await state(page);
      assert.deepEqual(s.directions, { x: 'free', y: 'free', z: 'hold', rx: 'free', ry: 'free', rz: 'hold' });
      assert.deepEqual(Object.keys(s.links), FEET, 'the other feet held as the robot list holds them');
      assert.equal(await page.locator('#directions-link').textContent(), 'rh_foot');
      assert.match(await page.evaluate(() => location.hash), /link=rh_foot/);
    });
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});

// The page plays in real time: each frame steps the simulated time the wall clock moved
// (at most 1x); the capacity is dt over the measured time per step.
async function realTime(t, robot, held) {
  const session = await openPage({ hash: `#robot=${robot}&integrator=rk4&dt=0.001` });
  const { page, consoleErrors } = session;
  try {
    const s0 = await state(page);
    assert.deepEqual(Object.keys(s0.links), held);
    await page.waitForTimeout(4000);
    const shown = await page.locator('#readout-rtf').textContent();
    const { rtf, micros, error } = await page.evaluate(() => {
      const s = window.achdDemo.state();
      const text = document.getElementById('readout-rtf').textContent;
      return { rtf: Number(text.match(/running at ([\d.]+)×/)?.[1]), micros: s.stepMicros, error: s.error };
    });
    const capacity = 1000 / micros;  // simulated ms per wall ms at dt = 1 ms
    t.diagnostic(`${robot}: ${shown}; one RK4 step ${micros.toFixed(1)} µs, ${capacity.toFixed(1)}x real time possible`);
    assert.equal(error, null);
    assert.ok(rtf >= 0.95, `${robot} ran at ${rtf}x real time`);
    assert.ok(capacity >= 1, `${robot}: a step takes ${micros} µs, more than dt`);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
}

test('the quadruped on four held feet runs at real time (dt 1 ms, RK4)', (t) => realTime(t, 'quadruped', FEET));
test('the dual-arm torso holding both hands runs at real time (dt 1 ms, RK4)', (t) =>
  realTime(t, 'dual_arm_torso', ['left_hand', 'right_hand']));
