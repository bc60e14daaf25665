// An own floating robot with meshes, in Chromium, from a folder as a user has it
// (tests/fixtures/make_solo_meshes.mjs: solo_description with two URDFs, an SRDF and STL
// meshes named by package://): solo12 picked among the folder's URDFs loads whole on a
// floating base in its SRDF pose, every one of its visuals read from the folder's meshes
// (no stick figure note), and stands under the page's default controller: its four feet
// held within 1e-6 m and its trunk within 2 cm over 3 s. The page's picture is written to
// the temporary folder (its path is a diagnostic) to look at.
import assert from 'node:assert/strict';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, test } from 'node:test';
import { writeSoloFolder } from '../fixtures/make_solo_meshes.mjs';
import { openPage } from './launch.mjs';

const FEET = ['FL_FOOT', 'FR_FOOT', 'HL_FOOT', 'HR_FOOT'];
const SECONDS = 3;
const HELD_TOLERANCE = 1e-6;
const TRUNK_TOLERANCE = 0.02;

const dir = mkdtempSync(join(tmpdir(), 'achd-own-meshes-'));
after(() => rmSync(dir, { recursive: true, force: true }));
const FOLDER = writeSoloFolder(dir);

const state = (page) => page.evaluate(() => window.achdDemo.state());
const linkPositions = (page, links) => page.evaluate((names) => names.map((n) => window.achdDemo.linkPosition(n)), links);

test('an own floating robot with meshes loads from a folder of several URDFs and an SRDF, and stands', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    await page.locator('#urdf-folder').setInputFiles(FOLDER);
    await page.locator('#urdf-chain').waitFor({ state: 'visible' });
    const urdfs = await page.locator('#urdf-pick option').allTextContents();
    assert.deepEqual(urdfs.filter((p) => p.endsWith('.urdf')).map((p) => p.split('/').pop()).sort(),
      ['solo.urdf', 'solo12.urdf'], `the folder's URDFs: ${urdfs}`);
    await page.locator('#urdf-pick').selectOption({ index: urdfs.findIndex((p) => p.endsWith('solo12.urdf')) });
    await page.waitForFunction(() => document.getElementById('urdf-chain-file').textContent.includes('solo12.urdf'));
    await page.locator('#urdf-base').selectOption('floating');
    await page.locator('#urdf-chain button[type=submit]').click();
    await page.locator('#urdf-chain').waitFor({ state: 'hidden' });
    await page.waitForFunction(() => {
      const s = window.achdDemo.state();
      return s.robot === 'custom' && s.share && s.look.meshes !== null;
    });
    await page.evaluate(() => window.achdDemo.pause());
    const s0 = await state(page);
    assert.equal(s0.error, null);
    assert.equal(s0.q.length, 7 + 12, 'whole, on a floating base');
    assert.equal(s0.pose, 'standing', 'in the SRDF\'s first pose');

    // Every visual of solo12 (17) is drawn from the folder's meshes.
    const visuals = (readFileSync(join(FOLDER, 'robots/solo12.urdf'), 'utf8').match(/<visual>/g) ?? []).length;
    assert.equal(visuals, 17);
    assert.equal(s0.look.meshes.length, visuals);
    for (const m of s0.look.meshes) assert.equal(m.status, 'loaded', `${m.filename} on ${m.link}: ${m.status}`);
    assert.deepEqual(s0.look.problems, []);
    assert.ok(await page.locator('#view-note').isHidden(), 'a note shows though every mesh loaded');
    await page.waitForTimeout(300);  // frames render the meshes
    const picture = join(tmpdir(), 'achd-own-meshes.png');
    await page.screenshot({ path: picture });
    t.diagnostic(`the page: ${picture}`);

    // It stands: the feet held where they started, the trunk within 2 cm.
    assert.deepEqual(Object.keys(s0.links).sort(), FEET, 'the four feet are held, and only they');
    const feet0 = await linkPositions(page, FEET);
    for (let k = 0; k < SECONDS * 10; k++) await page.evaluate(() => window.achdDemo.step(100));
    const s1 = await state(page);
    assert.equal(s1.error, null);
    assert.ok(s1.t - s0.t >= SECONDS - 1e-9, `${s1.t - s0.t} s stepped`);
    const feet1 = await linkPositions(page, FEET);
    const drift = Math.max(...feet1.map((p, k) => Math.hypot(...p.map((x, i) => x - feet0[k][i]))));
    const trunk = Math.hypot(...s1.q.slice(0, 3).map((x, i) => x - s0.q[i]));
    t.diagnostic(`after ${(s1.t - s0.t).toFixed(3)} s the feet moved ${drift.toExponential(2)} m, the trunk ${(1000 * trunk).toFixed(3)} mm`);
    assert.ok(drift <= HELD_TOLERANCE, `a foot moved ${drift} m`);
    assert.ok(trunk <= TRUNK_TOLERANCE, `the trunk moved ${trunk} m`);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});
