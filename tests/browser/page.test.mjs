// The demo page in Debian's Chromium: it starts stepping the default robot, holds tip
// directions to within 1e-6 while the free joints move, survives a broken URDF with a
// message on the page, and simulates the 7-DoF arm faster than real time with every
// effect on and all six directions held.
import assert from 'node:assert/strict';
import { mkdir, readFile } from 'node:fs/promises';
import test from 'node:test';
import { openPage } from './launch.mjs';
import { loadAchd } from '../node/helpers.mjs';

const achd = await loadAchd();
const index = JSON.parse(await readFile(new URL('../../robots/index.json', import.meta.url), 'utf8'));
const SCREENSHOT = new URL('../../build/browser/page.png', import.meta.url);
const BROKEN_XML = '<robot name="broken"><link name="base"/><joint name="j" type="revolute">';
const UNKNOWN_TIP = `<robot name="two">
  <link name="base"/>
  <link name="arm"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/></joint>
</robot>`;

const state = (page) => page.evaluate(() => window.achdDemo.state());

// Tries achdDemo.loadURDF and returns how it failed (or null if it did not).
const loadFailure = (page, text, root, tip) =>
  page.evaluate(async ([text, root, tip]) => {
    try {
      await window.achdDemo.loadURDF(text, root, tip);
      return null;
    } catch (err) {
      return { isError: err instanceof Error, message: err.message };
    }
  }, [text, root, tip]);

test('the demo page in Chromium', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    await t.test('opens on the default robot, stepping within a second of load, no console errors', async () => {
      const s = await state(page);
      assert.equal(s.robot, index.default);
      assert.ok(s.t > 0, `t = ${s.t}`);
      // "Within a second of load": from the load event (the page and its modules are in)
      // to the first step; the time from navigation start is printed as well.
      const { stepping, loaded } = await page.evaluate(() => ({
        stepping: performance.getEntriesByName('achd:stepping')[0].startTime,
        loaded: performance.getEntriesByType('navigation')[0].loadEventStart,
      }));
      console.log(`# stepping ${stepping.toFixed(0)} ms after navigation start, ` +
        `${(stepping - loaded).toFixed(0)} ms after the load event`);
      assert.ok(loaded > 0, 'no load event');
      assert.ok(stepping - loaded < 1000, `stepping ${stepping - loaded} ms after the load event`);
      for (const d of ['x', 'y', 'z', 'rx', 'ry', 'rz']) assert.equal(s.directions[d], 'free');
      // The page's defaults are the simulator's (dormand_prince at rtol 1e-9, variable_damping).
      const defaults = achd.constants.simulator_options;
      assert.equal(await page.locator('#integrator').inputValue(), defaults.integrator);
      assert.ok(await page.locator('#rtol').isVisible());
      assert.equal(Number(await page.locator('#rtol').inputValue()), defaults.rtol);
      assert.equal(await page.locator('#policy').inputValue(), defaults.solver.policy);
      assert.equal(await page.locator('#dt').inputValue(), '0.001');
      assert.equal(await page.locator('#limits').inputValue(), defaults.limits);
      assert.ok(await page.locator('input[data-effect="damping"]').isChecked());
      assert.deepEqual(consoleErrors, []);
    });

    await t.test('the joint-limit control: clamp, in the hash, puts a joint set past its limit back on it', async () => {
      const source = await page.evaluate(() => window.achdDemo.robotSource());
      const robot = achd.loadURDF(source.text, { root: source.root, tip: source.tip });
      const j = robot.limits.findIndex((l) => Number.isFinite(l.upper));
      const upper = robot.limits[j].upper;
      robot.delete();
      const past = [...source.q0];
      past[j] = upper + 0.1;
      for (const [limits, within] of [['report', false], ['clamp', true]]) {
        await page.selectOption('#limits', limits);
        if (limits === 'clamp') assert.match(await page.evaluate(() => location.hash), /[#&]limits=clamp(&|$)/);
        await page.evaluate((q) => window.achdDemo.setPose(q), past);
        await page.evaluate(() => window.achdDemo.step(1));
        const q = (await state(page)).q[j];
        console.log(`# limits ${limits}: joint ${j} at ${q.toFixed(4)} (upper limit ${upper})`);
        assert.equal(q <= upper + 1e-9, within, `${limits}: q = ${q}, upper ${upper}`);
      }
      await page.selectOption('#limits', achd.constants.simulator_options.limits);
    });

    await t.test('pause stops time; holding z and rx keeps them within 1e-6 over 2000 steps', async () => {
      await page.evaluate(() => window.achdDemo.pause());
      const paused = await state(page);
      await page.waitForTimeout(300);
      assert.equal((await state(page)).t, paused.t, 'time advanced while paused');

      await page.evaluate(() => {
        window.achdDemo.setDirection('z', 'hold');
        window.achdDemo.setDirection('rx', 'hold');
      });
      const before = await state(page);
      await page.evaluate(() => window.achdDemo.step(2000));
      const after = await state(page);
      assert.ok(Math.abs(after.t - before.t - 2.0) < 1e-9, `t advanced by ${after.t - before.t}`);
      assert.ok(Math.abs(after.residuals.z) < 1e-6, `z residual ${after.residuals.z}`);
      assert.ok(Math.abs(after.residuals.rx) < 1e-6, `rx residual ${after.residuals.rx}`);
      for (const d of ['x', 'y', 'ry', 'rz']) assert.equal(after.residuals[d], null);
      assert.ok(Array.isArray(after.q) && Array.isArray(after.qd));
      const moved = Math.max(...after.q.map((q, i) => Math.abs(q - before.q[i])));
      assert.ok(moved > 0.01, `the free joints moved only ${moved} rad`);
      assert.ok(typeof after.stepMicros === 'number' && after.stepMicros > 0);
      assert.match(await page.evaluate(() => location.hash), /dirs=z:hold,rx:hold/);
      assert.deepEqual(consoleErrors, []);
    });

    await t.test('the direction toggles on the page drive the simulator', async () => {
      await page.locator('button[data-direction="x"][data-mode="hold"]').click();
      assert.equal((await state(page)).directions.x, 'hold');
      await page.locator('button[data-direction="x"][data-mode="free"]').click();
      assert.equal((await state(page)).directions.x, 'free');
    });

    await t.test('a broken URDF is rejected with a message on the page; the robot keeps running', async () => {
      for (const [text, root, tip, expected] of [
        [BROKEN_XML, 'base', 'arm', null],
        [UNKNOWN_TIP, 'base', 'no_such_link', /no_such_link/],
      ]) {
        const failure = await loadFailure(page, text, root, tip);
        assert.ok(failure?.isError, `loadURDF did not reject with an Error: ${JSON.stringify(failure)}`);
        if (expected) assert.match(failure.message, expected);
        const shown = page.locator('#page-error');
        assert.ok(await shown.isVisible(), 'no error on the page');
        assert.ok((await shown.textContent()).includes(failure.message.split('\n')[0]));
        const before = await state(page);
        assert.equal(before.robot, index.default);
        await page.evaluate(() => window.achdDemo.step(10));
        const after = await state(page);
        assert.ok(Math.abs(after.t - before.t - 0.01) < 1e-9, `t advanced by ${after.t - before.t}`);
      }
      assert.deepEqual(consoleErrors, []);
    });

    await t.test('faster than real time on the 7-DoF arm, every effect on, 6 directions held, dt = 1 ms', async () => {
      assert.equal((await state(page)).robot, 'kuka_lwr4');
      for (const box of await page.locator('input[data-effect]').all()) assert.ok(await box.isChecked());
      // From the start pose: where the arm has swung to while the page played depends on
      // how long the earlier subtests took, and near the hanging, stretched pose (its wrist
      // nearly singular) variable_damping rightly releases one of six held directions.
      await page.evaluate(() => window.achdDemo.pause());
      await page.locator('#btn-reset').click();
      const factor = await page.evaluate(() => {
        const demo = window.achdDemo;
        for (const d of ['x', 'y', 'z', 'rx', 'ry', 'rz']) demo.setDirection(d, 'hold');
        demo.step(2000);  // lets the wasm code tier up before timing
        const steps = 5000;
        const start = performance.now();
        demo.step(steps);
        return (steps * 0.001) / ((performance.now() - start) / 1000);
      });
      const s = await state(page);
      const integrator = await page.locator('#integrator').inputValue();
      console.log(`# real-time factor: ${factor.toFixed(1)} simulated s per wall s ` +
        `(kuka_lwr4, all effects, 6 held, ${integrator}, dt = 1 ms); page shows ${s.stepMicros.toFixed(1)} µs per step`);
      assert.ok(factor >= 1, `only ${factor} simulated s per wall s`);
      for (const d of ['x', 'y', 'z', 'rx', 'ry', 'rz']) assert.ok(Math.abs(s.residuals[d]) < 1e-6, `${d}: ${s.residuals[d]}`);
    });

    await t.test('an own URDF from the file picker loads with the root and tip chosen on the page', async () => {
      await page.locator('#urdf-file').setInputFiles(new URL('../../robots/planar2.urdf', import.meta.url).pathname);
      await page.locator('#urdf-chain').waitFor({ state: 'visible', timeout: 5000 });
      assert.equal(await page.locator('#urdf-root').inputValue(), 'base_link');
      assert.equal(await page.locator('#urdf-tip').inputValue(), 'link2');
      await page.locator('#urdf-chain button[type="submit"]').click();
      const s = await state(page);
      assert.equal(s.robot, 'custom');
      assert.equal(s.q.length, 2);
      assert.ok(await page.locator('#page-error').isHidden());
      assert.deepEqual(consoleErrors, []);
    });

    // The hash below uses the previous release's words (semi-implicit, velocity): links
    // shared before keep working, read as the current names.
    await t.test('a shared URL hash restores robot and toggles', async () => {
      await page.evaluate(() => window.achdDemo.play());
      await page.waitForTimeout(500);
      await mkdir(new URL('.', SCREENSHOT), { recursive: true });
      await page.screenshot({ path: SCREENSHOT.pathname });

      // Through about:blank: a hash-only change would be a same-document navigation.
      await page.goto('about:blank');
      await page.goto(session.url + '#robot=ur5&integrator=semi-implicit&dt=0.0005&effects=gravity,velocity&dirs=y:hold,rz:0.5');
      await page.evaluate(() => window.achdDemo.ready);
      const s = await state(page);
      assert.equal(s.robot, 'ur5');
      assert.equal(s.directions.y, 'hold');
      assert.equal(s.directions.rz, 0.5);
      assert.equal(await page.locator('#integrator').inputValue(), 'semi_implicit_euler');
      assert.equal(await page.locator('#dt').inputValue(), '0.0005');
      assert.ok(!(await page.locator('input[data-effect="damping"]').isChecked()));
      assert.ok(await page.locator('input[data-effect="velocityProducts"]').isChecked());
      assert.deepEqual(consoleErrors, []);
    });
  } finally {
    await session.close();
  }
});
