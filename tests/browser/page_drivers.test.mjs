// The page's drivers, through its controls in Debian's Chromium: a joint
// switched to a prescribed sine follows it (started where it was, the trajectory the page
// computes in its own time), and a held direction's "yield" switch lets a push move the
// tip along it, where without the switch the push does not.
import assert from 'node:assert/strict';
import test from 'node:test';
import { openPage } from './launch.mjs';

const state = (page) => page.evaluate(() => window.achdDemo.state());

async function waitFor(page, predicate, what, timeout = 20000) {
  const start = Date.now();
  for (;;) {
    const s = await state(page);
    if (predicate(s)) return s;
    if (Date.now() - start > timeout) throw new Error(`timed out waiting for ${what}; t = ${s.t}, error ${s.error}`);
    await page.waitForTimeout(50);
  }
}

test('the page prescribes a joint\'s motion and lets a held direction yield to a push', async (t) => {
  const session = await openPage({ hash: '#robot=kuka_lwr4&integrator=rk4&dt=0.001' });
  const { page, consoleErrors } = session;
  try {
    await t.test('a joint switched to a sine follows it, the tip holding z', async () => {
      await page.locator('#directions button[data-direction="z"][data-mode="hold"]').click();
      // Paused while choosing, so that the position field is where the joint is at Apply.
      await page.evaluate(() => window.achdDemo.pause());
      await page.selectOption('#joint-select', 'lwr_joint_1');
      await page.selectOption('#joint-motion', 'sine');
      assert.ok(await page.locator('#joint-amplitude').isVisible());
      assert.ok(await page.locator('#joint-velocity').isHidden(), 'a sine reads no velocity');
      await page.fill('#joint-amplitude', '0.4');
      await page.fill('#joint-frequency', '0.5');
      const before = await state(page);
      await page.locator('#joint-apply').click();
      assert.match(await page.locator('#joint-summary').textContent(), /lwr_joint_1 \(sine\)/);
      await page.evaluate(() => window.achdDemo.play());
      const s = await waitFor(page, (x) => x.t > before.t + 1.2, '1.2 s of the sine');
      const m = s.prescribed.lwr_joint_1;
      assert.equal(m.motion, 'sine');
      assert.equal(m.amplitude, 0.4);
      // Started where the joint was (the position field is its q when chosen, to 4 digits).
      assert.ok(Math.abs(m.position - before.q[0]) < 1e-3, `centre ${m.position}, q was ${before.q[0]}`);
      const expected = m.position + m.amplitude * Math.sin(2 * Math.PI * m.frequency * s.t + m.phase);
      assert.ok(Math.abs(s.q[0] - expected) < 1e-9, `q[0] ${s.q[0]}, trajectory ${expected} at t = ${s.t}`);
      assert.ok(Math.abs(s.residuals.z) < 1e-6, `z residual ${s.residuals.z}`);
      // Back to free: the joint is torque-driven again.
      await page.selectOption('#joint-motion', 'free');
      await page.locator('#joint-apply').click();
      assert.deepEqual((await state(page)).prescribed, {});
      assert.equal(await page.locator('#joint-summary').textContent(), 'Every joint is driven by its torques.');
      assert.deepEqual(consoleErrors, []);
    });

    await t.test('"yield" on a held z lets a 1 s push move the tip more than 1 cm; without it the push does not', async () => {
      // Hold z and rx from a fresh start; push the tip up with 20 N for a second of
      // simulated time, stepped by hand so that the push lasts exactly that long.
      const run = async (yielding) => {
        await page.evaluate(() => window.achdDemo.pause());
        await page.locator('#btn-reset').click();
        await page.locator('#directions button[data-direction="rx"][data-mode="hold"]').click();
        const box = page.locator('#directions input[data-yield="z"]');
        if ((await box.isChecked()) !== yielding) await box.click();
        assert.equal((await state(page)).yielding.z, yielding);
        await page.evaluate(() => window.achdDemo.push('lwr_link_7', [0, 0, 20, 0, 0, 0]));
        const z0 = await page.evaluate(() => window.achdDemo.tipPosition()[2]);
        await page.evaluate(() => window.achdDemo.step(1000));
        const z1 = await page.evaluate(() => window.achdDemo.tipPosition()[2]);
        await page.evaluate(() => window.achdDemo.push(null));
        const s = await state(page);
        return { moved: z1 - z0, s };
      };
      const yielded = await run(true);
      assert.ok(yielded.moved > 0.01, `with yield the tip rose ${yielded.moved} m`);
      assert.ok(Math.abs(yielded.s.residuals.rx) < 1e-6, `rx residual ${yielded.s.residuals.rx}`);
      assert.match(await page.evaluate(() => location.hash), /yield=z/);
      const held = await run(false);
      assert.ok(Math.abs(held.moved) < 1e-5, `without yield the tip moved ${held.moved} m`);
      assert.ok(Math.abs(held.s.residuals.z) < 1e-6, `z residual ${held.s.residuals.z}`);
      assert.deepEqual(consoleErrors, []);
    });
  } finally {
    await session.close();
  }
});
