// Poses on the page, in Chromium: one slider per joint over its URDF limits (a continuous
// joint over a full turn); moving one pauses and sets that joint's q and no other, the
// clock kept; "Start pose" puts back robots/index.json's q0; the link under the pointer
// is named beside it.
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { loadAchd } from '../node/helpers.mjs';
import { openPage } from './launch.mjs';

const achd = await loadAchd();
const index = JSON.parse(await readFile(new URL('../../robots/index.json', import.meta.url), 'utf8'));
const state = (page) => page.evaluate(() => window.achdDemo.state());

async function loadRobot(name) {
  const entry = index.robots.find((r) => r.name === name);
  const text = await readFile(new URL(`../../${entry.urdf}`, import.meta.url), 'utf8');
  return { entry, robot: achd.loadURDF(text, { root: entry.root, tip: entry.tip }) };
}

const sliderRange = (page, joint) =>
  page.locator(`#joint-sliders input[data-joint="${joint}"]`).evaluate((e) => [Number(e.min), Number(e.max), Number(e.step)]);

test('joint sliders and link names on the page', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  const { entry, robot } = await loadRobot(index.default);
  try {
    await t.test('one slider per joint, over the URDF limits', async () => {
      assert.equal(await page.locator('#joint-sliders input[type=range]').count(), robot.numRates);
      for (const [j, name] of robot.jointNames.entries()) {
        const [min, max] = await sliderRange(page, name);
        assert.equal(min, robot.limits[j].lower, name);
        assert.equal(max, robot.limits[j].upper, name);
      }
    });

    await t.test('moving a slider pauses and sets that joint, the others and the clock kept', async () => {
      await page.evaluate(() => window.achdDemo.pause());
      const before = await state(page);
      const j = 3;
      const slider = page.locator(`#joint-sliders input[data-joint="${robot.jointNames[j]}"]`);
      await page.evaluate(() => window.achdDemo.play());
      await slider.fill('-1');
      const after = await state(page);
      const [, , step] = await sliderRange(page, robot.jointNames[j]);
      assert.equal(after.playing, false);
      assert.equal(after.q[j], Number(await slider.inputValue()));
      assert.ok(Math.abs(after.q[j] + 1) <= step / 2, `q[${j}] = ${after.q[j]}`);
      assert.deepEqual(after.qd, after.qd.map(() => 0));
      assert.ok(after.t >= before.t, `t went back from ${before.t} to ${after.t}`);
      // Whatever the few steps before the move did to the other joints, the move left them.
      const moved = await page.evaluate(() => window.achdDemo.state().q);
      await slider.fill('-0.5');
      const again = await state(page);
      again.q.forEach((q, k) => {
        if (k !== j) assert.equal(q, moved[k], `joint ${k} moved with joint ${j}`);
      });
      await page.evaluate(() => window.achdDemo.step(10));
      assert.notEqual((await state(page)).q[j], again.q[j], 'the simulation does not go on from the pose set');
    });

    await t.test('"Start pose" puts back the start pose, at rest', async () => {
      await page.locator('#btn-start-pose').click();
      const s = await state(page);
      assert.deepEqual(s.q, entry.q0);
      assert.deepEqual(s.qd, s.qd.map(() => 0));
      assert.equal(s.playing, false);
    });

    await t.test('hovering a link names it', async () => {
      // The middle of lwr_link_3's body: 0.1 m along its z axis. The view in sight first
      // (filling a slider scrolled the page to it).
      const camera = await page.evaluate(() => {
        window.scrollTo(0, 0);
        return window.achdDemo.camera();
      });
      const link = robot.forwardKinematics(entry.q0).find((l) => l.name === 'lwr_link_3');
      const r = link.rotation;
      const p = [0, 1, 2].map((i) => link.position[i] + 0.1 * r[3 * i + 2]);
      const m = (M, v) => [0, 1, 2, 3].map((i) => M[i] * v[0] + M[4 + i] * v[1] + M[8 + i] * v[2] + M[12 + i] * v[3]);
      const clip = m(camera.projection, m(camera.worldInverse, [...p, 1]));
      const x = camera.rect.left + ((clip[0] / clip[3] + 1) / 2) * camera.rect.width;
      const y = camera.rect.top + ((1 - clip[1] / clip[3]) / 2) * camera.rect.height;
      await page.mouse.move(x, y);
      await page.locator('#link-label').waitFor({ state: 'visible' });
      assert.equal(await page.locator('#link-label').textContent(), 'lwr_link_3');
      await page.mouse.move(camera.rect.left + 5, camera.rect.top + 5);
      await page.locator('#link-label').waitFor({ state: 'hidden' });
    });

    await t.test('a continuous joint slides over a full turn', async () => {
      await page.locator('#robot-select').selectOption('mixed_chain');
      await page.waitForFunction(() => window.achdDemo.state().robot === 'mixed_chain');
      const { robot: mixed } = await loadRobot('mixed_chain');
      const j = mixed.jointTypes.indexOf('continuous');
      assert.ok(j >= 0);
      const [min, max] = await sliderRange(page, mixed.jointNames[j]);
      assert.deepEqual([min, max], [-Math.PI, Math.PI]);
      mixed.delete();
    });

    await t.test('no console errors', () => {
      assert.deepEqual(consoleErrors, []);
    });
  } finally {
    robot.delete();
    await session.close();
  }
});
