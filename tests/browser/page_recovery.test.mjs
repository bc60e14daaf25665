// The demo page recovers from what a person does to it: a failed step is
// shown and Reset runs again from the start pose with clean plots; a newly loaded robot
// plays with every direction free and no trace of the previous one; an own URDF starts
// away from a singularity; the controls offer what the module has; and a direction
// driven into the workspace boundary is reported as an event while the page keeps
// stepping (the simulator's variable_damping policy and sim.events()).
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { openPage } from './launch.mjs';
import { loadAchd } from '../node/helpers.mjs';

const achd = await loadAchd();
const index = JSON.parse(await readFile(new URL('../../robots/index.json', import.meta.url), 'utf8'));
const lwr = index.robots.find((r) => r.name === 'kuka_lwr4');
const lwrText = await readFile(new URL(`../../${lwr.urdf}`, import.meta.url), 'utf8');
// The page link README.md gives as its example: the UR5 holding z and rx while its tip
// accelerates along y at 0.5 m/s², which drives it into the boundary of its workspace.
const BOUNDARY_HASH = '#robot=ur5&integrator=rk4&dt=0.001&effects=gravity,velocity_products,damping,friction,' +
  'external_wrenches&dirs=z:hold,rx:hold,y:0.5';

const state = (page) => page.evaluate(() => window.achdDemo.state());

async function waitFor(page, predicate, what, timeout = 15000) {
  const start = Date.now();
  for (;;) {
    const s = await state(page);
    if (predicate(s)) return s;
    if (Date.now() - start > timeout) throw new Error(`timed out waiting for ${what}; state: ${JSON.stringify({ ...s, q: undefined, qd: undefined })}`);
    await page.waitForTimeout(50);
  }
}

test('the page recovers: Reset after a failure, a new robot, plot axes', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    await t.test('the controls offer the module\'s integrators and policies', async () => {
      const k = achd.constants;
      const offered = await page.locator('#integrator option').evaluateAll((os) => os.map((o) => o.value));
      assert.deepEqual(offered, k.integrators);
      assert.equal(await page.locator('#integrator').inputValue(), k.simulator_options.integrator);
      const policies = await page.locator('#policy option').evaluateAll((os) => os.map((o) => o.value));
      assert.ok(await page.locator('#policy').isVisible());
      assert.deepEqual(policies, k.singularity_policies);
      assert.equal(await page.locator('#policy').inputValue(), k.simulator_options.solver.policy);
      assert.equal(await page.locator('#sim-events-none').textContent(), 'No event since the start or the last Reset.');
    });

    await t.test('a failed step pauses with the error; Reset clears it, plays again from the start pose, plots start afresh', async () => {
      // Explicit Euler at 10 ms is unstable on the damped LWR: joint speeds pass 1e160
      // rad/s and a step fails within 0.2 s. One step per frame, so that the plots
      // sample every step up to the last good one.
      await page.evaluate(() => window.achdDemo.pause());
      await page.selectOption('#integrator', 'explicit_euler');
      await page.selectOption('#dt', '0.01');
      let thrown = null;
      for (let k = 0; k < 100 && !thrown; k++) {
        thrown = await page.evaluate(() => {
          try {
            window.achdDemo.step(1);
            return null;
          } catch (err) {
            return err.message;
          }
        });
        await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
      }
      assert.ok(thrown, 'explicit Euler at 10 ms did not fail within 1 s');
      const failed = await state(page);
      assert.equal(failed.error, `the simulation stopped: ${thrown}`);
      assert.match(failed.error, /the simulation stopped: step \d+ from t = .* failed: .*not finite/);
      assert.equal(failed.playing, false);
      assert.ok(await page.locator('#page-error').isVisible());
      assert.ok(failed.plots.energy.hi > 1e20, `the run to the failure is on the energy plot: ${JSON.stringify(failed.plots.energy)}`);
      // The Step button from the last good state fails the same step again: shown on the
      // page, nothing thrown into the console.
      await page.locator('#btn-step').click();
      const again = await state(page);
      assert.equal(again.t, failed.t);
      assert.equal(again.error, failed.error);
      assert.deepEqual(consoleErrors, []);
      await page.waitForTimeout(300);
      assert.equal((await state(page)).t, failed.t, 'time advanced after the failure');

      // The user picks a stable integrator and step again, then Reset: the page was
      // paused when the step failed, so Reset leaves it paused; Play runs it.
      await page.selectOption('#integrator', 'rk4');
      await page.selectOption('#dt', '0.001');
      await page.locator('#btn-reset').click();
      const reset = await state(page);
      assert.equal(reset.error, null);
      assert.ok(await page.locator('#page-error').isHidden());
      assert.equal(reset.playing, false);
      assert.equal(reset.t, 0);
      assert.ok(reset.plots.energy === null || reset.plots.energy.hi < 100, `energy plot after Reset: ${JSON.stringify(reset.plots.energy)}`);
      await page.locator('#btn-play').click();
      const resumed = await waitFor(page, (s) => s.t > 0.5, 't to pass 0.5 s after Reset');
      // No sample from before Reset is left on the axis: the energy of the LWR swinging
      // under gravity from its start pose (about 64 J, falling as damping takes it).
      const { energy } = resumed.plots;
      assert.ok(Math.abs(energy.hi) < 1e3 && Math.abs(energy.lo) < 1e3, `energy axis ${JSON.stringify(energy)}`);
      assert.ok(await page.locator('#btn-play').textContent() === 'Pause');
      assert.deepEqual(consoleErrors, []);
    });

    await t.test('a step that fails while playing: Reset plays again', async () => {
      await page.selectOption('#integrator', 'explicit_euler');
      await page.selectOption('#dt', '0.01');
      const failed = await waitFor(page, (s) => s.error !== null, 'the step to fail');
      assert.equal(failed.playing, false);
      await page.waitForTimeout(300);
      assert.equal((await state(page)).t, failed.t, 'time advanced after the failure');
      await page.selectOption('#integrator', 'rk4');
      await page.selectOption('#dt', '0.001');
      // The click and the state in one task: no frame steps in between.
      const reset = await page.evaluate(() => {
        document.getElementById('btn-reset').click();
        return window.achdDemo.state();
      });
      assert.equal(reset.error, null);
      assert.equal(reset.playing, true);
      assert.equal(reset.t, 0);
      assert.deepEqual(reset.q, lwr.q0);
      await waitFor(page, (s) => s.t > 0.5 && s.plots.energy?.hi < 100, 't to pass 0.5 s with a fresh energy plot');
      assert.deepEqual(consoleErrors, []);
    });

    await t.test('Reset while paused keeps the page paused', async () => {
      await page.evaluate(() => window.achdDemo.pause());
      await page.locator('#btn-reset').click();
      const s = await state(page);
      assert.equal(s.playing, false);
      assert.equal(s.t, 0);
      assert.deepEqual(s.q, lwr.q0);
      await page.evaluate(() => window.achdDemo.play());
    });

    await t.test('loading a robot frees every direction, clears events and plots, and plays', async () => {
      await page.evaluate(() => {
        window.achdDemo.setDirection('z', 'hold');
        window.achdDemo.setDirection('rx', 'hold');
      });
      const before = await waitFor(page, (s) => s.plots.energy?.samples >= 100, '100 samples on the energy plot');
      await page.selectOption('#robot-select', 'ur5');
      const s = await waitFor(page, (s) => s.robot === 'ur5', 'the UR5 to load');
      for (const d of ['x', 'y', 'z', 'rx', 'ry', 'rz']) assert.equal(s.directions[d], 'free', d);
      assert.equal(s.playing, true);
      assert.deepEqual(s.events, []);
      assert.equal(s.error, null);
      assert.ok(s.plots.energy === null || s.plots.energy.samples < before.plots.energy.samples,
        `energy plot ${JSON.stringify(s.plots.energy)}, before ${JSON.stringify(before.plots.energy)}`);
      assert.equal(s.plots.residuals, null, 'no held direction, no residual plot');
      assert.doesNotMatch(await page.evaluate(() => location.hash), /dirs=/);
      const pressed = await page.locator('button[data-mode="free"][aria-pressed="true"]').count();
      assert.equal(pressed, 6);
      await waitFor(page, (later) => later.t > s.t + 0.1, 'the UR5 to step');
      assert.deepEqual(consoleErrors, []);
    });

    await t.test('an own URDF of the LWR starts away from its upright singular pose and holds z and rx', async () => {
      await page.evaluate(() => window.achdDemo.setDirection('y', 'hold'));
      await waitFor(page, (s) => s.plots.energy?.samples >= 10, 'samples on the energy plot');
      // The load and the state in one task: the plots as the load left them.
      const s = await page.evaluate(async (text) => {
        await window.achdDemo.loadURDF(text, 'lwr_base_link', 'lwr_link_7');
        return window.achdDemo.state();
      }, lwrText);
      assert.equal(s.robot, 'custom');
      assert.equal(s.directions.y, 'free');
      assert.deepEqual(s.plots, { residuals: null, nu: null, torques: null, energy: null, timing: null });
      assert.ok(Math.max(...s.q.map(Math.abs)) > 0.1, `start pose ${s.q}`);
      await page.evaluate(() => {
        window.achdDemo.pause();
        window.achdDemo.setDirection('z', 'hold');
        window.achdDemo.setDirection('rx', 'hold');
        window.achdDemo.setDirection('x', 0.1);
        window.achdDemo.step(1000);
      });
      const after = await state(page);
      assert.equal(after.error, null);
      assert.ok(Math.abs(after.residuals.z) < 1e-6, `z residual ${after.residuals.z}`);
      assert.deepEqual(consoleErrors, []);
    });
  } finally {
    await session.close();
  }
});

// The simulator's default variable_damping policy and its fixed physics defaults (the
// stabilisation frequency and damping ratio) carry it: before them the page stopped at
// t = 2.183 s with "the acceleration to enforce along direction y is not finite".
test('a direction driven into the workspace boundary is reported and the page keeps stepping', async () => {
  const session = await openPage({ hash: BOUNDARY_HASH });
  const { page, consoleErrors } = session;
  try {
    const start = await state(page);
    assert.equal(start.robot, 'ur5');
    assert.equal(start.directions.y, 0.5);
    await page.evaluate(() => window.achdDemo.pause());
    // 12 s of simulated time in 1 s pieces (synchronous steps: no frame in between).
    for (let k = 0; k < 12; k++) {
      await page.evaluate(() => window.achdDemo.step(1000));
    }
    const s = await state(page);
    assert.equal(s.error, null);
    assert.ok(s.t > 10, `t = ${s.t}`);
    const y = s.events.filter((e) => e.direction === 'y');
    assert.ok(y.length > 0, `no event for y: ${JSON.stringify(s.events)}`);
    assert.ok(y.every((e) => ['limited', 'released', 'resumed'].includes(e.kind)), JSON.stringify(y));
    assert.ok(await page.locator('#sim-events-list li[data-direction="y"]').count() > 0, 'the notice names y');
    // The toggle of a direction lost now says so.
    const lostNow = await page.locator('#directions tr.lost').count();
    assert.equal(lostNow, s.lost.length);
    // The held directions the simulator did not release stay held.
    for (const d of ['z', 'rx']) {
      if (!s.lost.includes(d)) assert.ok(Math.abs(s.residuals[d]) < 1e-6, `${d}: ${s.residuals[d]}`);
    }
    // And it keeps stepping in real time.
    await page.evaluate(() => window.achdDemo.play());
    await waitFor(page, (later) => later.t > s.t + 0.5, 'time to advance past the boundary');
    assert.equal((await state(page)).error, null);
    console.log(`# UR5 y at 0.5 m/s²: t = ${s.t} s, events ${JSON.stringify(s.events.slice(0, 4))}`);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});

test('the policy and the adaptive integrator\'s rtol come from the URL hash and go back into it', async () => {
  const session = await openPage({ hash: '#robot=ur5&integrator=dormand_prince&rtol=1e-6&dt=0.001&policy=damped&dirs=z:hold' });
  const { page, consoleErrors } = session;
  try {
    assert.equal(await page.locator('#integrator').inputValue(), 'dormand_prince');
    assert.ok(await page.locator('#rtol').isVisible());
    assert.equal(Number(await page.locator('#rtol').inputValue()), 1e-6);
    assert.equal(await page.locator('#policy').inputValue(), 'damped');
    assert.ok(await page.locator('#page-error').isHidden());
    await page.selectOption('#policy', 'truncate');
    await page.selectOption('#rtol', String(1e-8));
    const hash = await page.evaluate(() => location.hash);
    assert.match(hash, /integrator=dormand_prince&rtol=1e-8&dt=0.001&policy=truncate&/);
    // A fixed-step integrator has no tolerance: the control goes, and so does rtol in the hash.
    await page.selectOption('#integrator', 'rk4');
    assert.ok(await page.locator('#rtol').isHidden());
    assert.doesNotMatch(await page.evaluate(() => location.hash), /rtol/);
    const s = await waitFor(page, (s) => s.t > 0.2, 'the UR5 to step');
    assert.ok(Math.abs(s.residuals.z) < 1e-6, `z residual ${s.residuals.z}`);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});
