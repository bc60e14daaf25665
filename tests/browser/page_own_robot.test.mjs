// An own robot loaded whole from a picked folder, in Chromium: example-robot-data's
// solo_description (two URDFs, solo.urdf and solo12.urdf, and srdf/solo.srdf). The load form
// lists both URDFs instead of picking one, offers the SRDF's poses, and loads solo12 as a
// whole robot (not a chain) on a floating base in the SRDF's "standing" pose: its four feet
// (the leaf links lowest at that pose) start at z = 0, are held in x, y, z, and over 5
// simulated seconds under the 5 Hz hold controller they stay within 1e-6 m and the trunk
// within 2 cm. The loader's warnings (robot.warnings) are shown under the robot list: a
// URDF whose link inertia violates the triangle inequality loads with the default inertia
// option and the note names that link.
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { fileURLToPath } from 'node:url';
import { loadAchd } from '../node/helpers.mjs';
import { openPage } from './launch.mjs';

const FOLDER = new URL('../../robots/example-robot-data/solo_description/', import.meta.url);
const FEET = ['FL_FOOT', 'FR_FOOT', 'HL_FOOT', 'HR_FOOT'];
const SECONDS = 5;
const HELD_TOLERANCE = 1e-6;
const TRUNK_TOLERANCE = 0.02;

const state = (page) => page.evaluate(() => window.achdDemo.state());
const linkPositions = (page, links) => page.evaluate((names) => names.map((n) => window.achdDemo.linkPosition(n)), links);

// solo12's joint values in the SRDF's standing pose, as achd reads them.
async function standingJoints() {
  const achd = await loadAchd();
  const robot = achd.loadURDF(await readFile(new URL('robots/solo12.urdf', FOLDER), 'utf8'), {
    floating: true, srdf: await readFile(new URL('srdf/solo.srdf', FOLDER), 'utf8'), pose: 'standing' });
  const q = robot.startPose.slice(7);
  robot.delete();
  return q;
}

test('an own floating robot from a folder of several URDFs and an SRDF stands on its feet', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    await page.locator('#urdf-folder').setInputFiles(fileURLToPath(FOLDER));
    await page.locator('#urdf-chain').waitFor({ state: 'visible' });
    const urdfs = await page.locator('#urdf-pick option').allTextContents();
    assert.deepEqual(urdfs.map((p) => p.split('/').at(-1)), ['solo.urdf', 'solo12.urdf'], 'both URDFs are offered');
    assert.equal(await page.locator('#urdf-pick-label').isVisible(), true);
    await page.locator('#urdf-pick').selectOption({ index: urdfs.findIndex((p) => p.endsWith('solo12.urdf')) });
    await page.waitForFunction(() => document.getElementById('urdf-chain-file').textContent.includes('solo12.urdf'));
    assert.equal(await page.locator('#urdf-whole').inputValue(), 'tree', 'a branching robot is offered whole');
    assert.equal(await page.locator('#urdf-tip').isVisible(), false, 'no tip for the whole robot');
    const poses = await page.locator('#urdf-pose option').allTextContents();
    assert.deepEqual(poses.slice(1), ['standing', 'straight_standing'], 'the SRDF\'s poses');
    assert.equal(await page.locator('#urdf-pose option:checked').textContent(), 'standing');
    await page.locator('#urdf-base').selectOption('floating');
    await page.locator('#urdf-chain button[type=submit]').click();
    await page.locator('#urdf-chain').waitFor({ state: 'hidden' });
    await page.evaluate(() => window.achdDemo.pause());

    const s0 = await state(page);
    assert.equal(s0.error, null);
    assert.equal(s0.robot, 'custom');
    assert.equal(s0.floating, true);
    const source = await page.evaluate(() => window.achdDemo.robotSource());
    assert.equal(source.tip, null, 'loaded whole');
    assert.equal(s0.q.length, 7 + 12);
    const want = await standingJoints();
    s0.q.slice(7).forEach((q, j) => assert.ok(Math.abs(q - want[j]) < 1e-12, `joint ${j}: ${q}, the SRDF says ${want[j]}`));
    assert.deepEqual(Object.keys(s0.links).sort(), FEET, 'the four feet are held');
    for (const foot of FEET) {
      assert.deepEqual(Object.entries(s0.links[foot].directions).filter(([, m]) => m === 'hold').map(([d]) => d), ['x', 'y', 'z']);
    }
    const feet0 = await linkPositions(page, FEET);
    for (const p of feet0) assert.ok(Math.abs(p[2]) < 1e-12, `a foot starts at z = ${p[2]}`);
    const warnings = await page.locator('#robot-warnings');
    assert.equal(await warnings.isHidden(), !s0.warnings.length, 'the warnings note shows when there are warnings');
    if (s0.warnings.length) assert.match(await warnings.textContent(), new RegExp(`${s0.warnings.length} warning`));

    const start = Date.now();
    for (let k = 0; k < SECONDS * 10; k++) await page.evaluate(() => window.achdDemo.step(100));
    const s1 = await state(page);
    assert.equal(s1.error, null);
    const feet1 = await linkPositions(page, FEET);
    const drift = Math.max(...feet1.map((p, k) => Math.hypot(...p.map((x, i) => x - feet0[k][i]))));
    const trunk = Math.hypot(...s1.q.slice(0, 3).map((x, i) => x - s0.q[i]));
    t.diagnostic(`solo12 from its folder: ${SECONDS} s in ${((Date.now() - start) / 1000).toFixed(1)} s wall; feet moved ` +
      `${drift.toExponential(2)} m, the trunk ${(1000 * trunk).toFixed(3)} mm; trunk at z = ${s0.q[2].toFixed(4)} m; ` +
      `${s0.warnings.length} loader warning(s)`);
    assert.ok(drift <= HELD_TOLERANCE, `a foot moved ${drift} m`);
    assert.ok(trunk <= TRUNK_TOLERANCE, `the trunk moved ${trunk} m`);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});

// Two links: `odd` has principal moments 1, 1, 3 (1 + 1 < 3).
const ODD_INERTIA = `<robot name="odd">
  <link name="base"/>
  <joint name="j" type="revolute"><parent link="base"/><child link="odd"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="1"/></joint>
  <link name="odd"><inertial><mass value="1"/><origin xyz="0.1 0 0"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="3"/></inertial></link>
</robot>`;

test('the loader\'s warnings about an own URDF are shown on the page', async () => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    await page.evaluate((text) => window.achdDemo.loadURDF(text, 'base', 'odd'), ODD_INERTIA);
    const s = await state(page);
    assert.equal(s.error, null);
    assert.ok(s.warnings.length >= 1, 'the loader warns about the odd inertia');
    const note = page.locator('#robot-warnings');
    assert.equal(await note.isVisible(), true);
    assert.match(await note.textContent(), /odd/);
    // A robot without warnings hides the note again.
    await page.selectOption('#robot-select', 'ur5');
    await page.waitForFunction(() => window.achdDemo.state().robot === 'ur5');
    assert.equal(await note.isHidden(), true);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});
