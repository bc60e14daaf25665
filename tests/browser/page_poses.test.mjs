// An own robot's SRDF poses after loading, and its link with every loader option, in
// Chromium. solo12 is loaded whole from example-robot-data's folder on a floating base: the
// pose list (#pose-select) offers the SRDF's group_states and shows the one it started
// from; choosing another starts again from it as a load in that pose would: the joints
// are the SRDF's values as achd reads them (robot.poses), the feet the lowest leaves there,
// on the ground and held, time back at 0, and the PD controller's target and hold torques
// that pose's, so that it stands there (feet within 1e-6 m, trunk within 2 cm over 2 s).
// A robot of the list without an SRDF has no pose list. The link of an own robot loaded
// with options other than the form's first ones (floating, mimic independent, inertia
// repair, the second pose) reopens, in a browser profile that never saw it, with the same
// options, the same SRDF poses and the same start pose; a pose chosen after loading goes
// into the link too.
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { fileURLToPath } from 'node:url';
import { loadAchd } from '../node/helpers.mjs';
import { openPage } from './launch.mjs';

const FOLDER = new URL('../../robots/example-robot-data/solo_description/', import.meta.url);
const FEET = ['FL_FOOT', 'FR_FOOT', 'HL_FOOT', 'HR_FOOT'];
const SECONDS = 2;
const HELD_TOLERANCE = 1e-6;
const TRUNK_TOLERANCE = 0.02;

const state = (page) => page.evaluate(() => window.achdDemo.state());
const linkPositions = (page, links) => page.evaluate((names) => names.map((n) => window.achdDemo.linkPosition(n)), links);

// solo12's SRDF poses as achd reads them: {name: q}.
async function soloPoses() {
  const achd = await loadAchd();
  const robot = achd.loadURDF(await readFile(new URL('robots/solo12.urdf', FOLDER), 'utf8'), {
    floating: true, srdf: await readFile(new URL('srdf/solo.srdf', FOLDER), 'utf8') });
  const poses = structuredClone(robot.poses);
  robot.delete();
  return poses;
}

// Picks solo_description's folder and loads solo12 whole with the form's `choices`
// ({base, mimic, inertia, pose}: option values and the pose's name).
async function loadSolo(page, { base = 'floating', mimic, inertia, pose } = {}) {
  await page.locator('#urdf-folder').setInputFiles(fileURLToPath(FOLDER));
  await page.locator('#urdf-chain').waitFor({ state: 'visible' });
  const urdfs = await page.locator('#urdf-pick option').allTextContents();
  await page.locator('#urdf-pick').selectOption({ index: urdfs.findIndex((p) => p.endsWith('solo12.urdf')) });
  await page.waitForFunction(() => document.getElementById('urdf-chain-file').textContent.includes('solo12.urdf'));
  await page.locator('#urdf-base').selectOption(base);
  if (mimic) await page.locator('#urdf-mimic').selectOption(mimic);
  if (inertia) await page.locator('#urdf-inertia').selectOption(inertia);
  if (pose) await page.locator('#urdf-pose').selectOption({ label: pose });
  await page.locator('#urdf-chain button[type=submit]').click();
  await page.locator('#urdf-chain').waitFor({ state: 'hidden' });
  await page.waitForFunction(() => window.achdDemo.state().share);
}

function assertJoints(q, want, what) {
  assert.equal(q.length, want.length);
  q.slice(7).forEach((v, j) => assert.ok(Math.abs(v - want[7 + j]) < 1e-12, `${what}, joint ${j}: ${v}, the SRDF says ${want[7 + j]}`));
}

test('the pose list offers the SRDF\'s poses after loading and starts again from the one chosen', async (t) => {
  const poses = await soloPoses();
  assert.deepEqual(Object.keys(poses), ['standing', 'straight_standing']);
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    assert.equal(await page.locator('#pose-select-label').isVisible(), false, 'the LWR has no SRDF: no pose list');
    await loadSolo(page);
    assert.equal(await page.locator('#pose-select-label').isVisible(), true);
    const offered = await page.locator('#pose-select option').evaluateAll((os) => os.map((o) => o.value));
    assert.deepEqual(offered, ['', 'standing', 'straight_standing'], 'none, then the SRDF\'s poses');
    assert.equal(await page.locator('#pose-select').inputValue(), 'standing', 'the pose it was loaded in');
    assert.equal((await state(page)).pose, 'standing');

    for (const name of ['straight_standing', 'standing']) {
      await page.evaluate(() => window.achdDemo.step(300));
      await page.evaluate(() => window.achdDemo.setDirection('rz', 'hold'));
      // (paused first: a playing page plays on from the pose chosen, before it is read)
      await page.evaluate(() => window.achdDemo.pause());
      await page.locator('#pose-select').selectOption(name);
      const s0 = await state(page);
      assert.equal(s0.error, null);
      assert.equal(s0.pose, name);
      assert.equal(s0.t, 0, 'the time starts again');
      assertJoints(s0.q, poses[name], name);
      assert.ok(s0.qd.every((v) => v === 0), 'at rest');
      assert.deepEqual(Object.keys(s0.links).sort(), FEET, 'the four feet are held, and only they');
      for (const foot of FEET) {
        assert.deepEqual(Object.entries(s0.links[foot].directions).filter(([, m]) => m === 'hold').map(([d]) => d),
          ['x', 'y', 'z'], `${foot}: the default directions again`);
      }
      const feet0 = await linkPositions(page, FEET);
      for (const p of feet0) assert.ok(Math.abs(p[2]) < 1e-12, `${name}: a foot starts at z = ${p[2]}`);
      assert.equal((await page.evaluate(() => window.achdDemo.robotSource())).pose, name);
      assert.match(await page.evaluate(() => location.hash), new RegExp(`[#&]pose=${name}(&|$)`));
      assert.equal(await page.locator('#pose-select').inputValue(), name);
      // Start pose is the chosen pose now.
      await page.evaluate(() => window.achdDemo.setPose(window.achdDemo.state().q.map((v, i) => (i === 9 ? v + 0.2 : v))));
      await page.locator('#btn-start-pose').click();
      assertJoints((await state(page)).q, poses[name], `${name} after Start pose`);

      // The PD controller holds this pose: it stands.
      for (let k = 0; k < SECONDS * 10; k++) await page.evaluate(() => window.achdDemo.step(100));
      const s1 = await state(page);
      assert.equal(s1.error, null);
      const feet1 = await linkPositions(page, FEET);
      const drift = Math.max(...feet1.map((p, k) => Math.hypot(...p.map((x, i) => x - feet0[k][i]))));
      const trunk = Math.hypot(...s1.q.slice(0, 3).map((x, i) => x - s0.q[i]));
      const joints = Math.max(...s1.q.slice(7).map((v, j) => Math.abs(v - poses[name][7 + j])));
      t.diagnostic(`${name}: after ${SECONDS} s the feet moved ${drift.toExponential(2)} m, the trunk ` +
        `${(1000 * trunk).toFixed(3)} mm, the joints at most ${joints.toExponential(2)} rad from the pose`);
      assert.ok(drift <= HELD_TOLERANCE, `${name}: a foot moved ${drift} m`);
      assert.ok(trunk <= TRUNK_TOLERANCE, `${name}: the trunk moved ${trunk} m`);
    }

    // None: the loader's default pose, which the list's pose field then names.
    await page.locator('#pose-select').selectOption('');
    const none = await state(page);
    assert.equal(none.pose, null);
    assert.doesNotMatch(await page.evaluate(() => location.hash), /[#&]pose=/);
    // A robot of the list has no SRDF: the list goes.
    await page.selectOption('#robot-select', 'quadruped');
    await page.waitForFunction(() => window.achdDemo.state().robot === 'quadruped');
    assert.equal(await page.locator('#pose-select-label').isVisible(), false);
    await assert.rejects(page.evaluate(() => window.achdDemo.choosePose('standing')), /no pose "standing"/);
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});

test('the link of an own robot reopens it with every loader option and pose', async () => {
  const poses = await soloPoses();
  const session = await openPage();
  const { page, consoleErrors } = session;
  const others = [];
  try {
    await loadSolo(page, { mimic: 'independent', inertia: 'repair', pose: 'straight_standing' });
    const here = await page.evaluate(() => ({ state: window.achdDemo.state(), source: window.achdDemo.robotSource() }));
    assert.equal(here.state.share.form, 'link');
    assert.equal(here.state.share.srdf.form, 'link', 'the SRDF\'s poses travel in the link too');
    assert.deepEqual([here.source.floating, here.source.mimic, here.source.inertia, here.source.pose],
      [true, 'independent', 'repair', 'straight_standing']);
    const link = new URL(page.url()).hash;
    for (const part of ['base=floating', 'mimic=independent', 'inertia=repair', 'srdf=deflate:', 'pose=straight_standing']) {
      assert.ok(link.includes(part), `the link has ${part}: ${link.slice(0, 200)}`);
    }

    // Another browser profile: nothing in its storage.
    const reopened = async (hash) => {
      const other = await openPage({ hash });
      others.push(other);
      await other.page.waitForFunction(() => window.achdDemo.state().share);
      return {
        other,
        ...(await other.page.evaluate(() => ({ state: window.achdDemo.state(), source: window.achdDemo.robotSource(),
          error: document.getElementById('page-error').hidden ? null : document.getElementById('page-error-text').textContent,
          poses: [...document.querySelectorAll('#pose-select option')].map((o) => o.value),
          pose: document.getElementById('pose-select').value }))),
      };
    };
    const there = await reopened(link);
    assert.equal(there.error, null);
    assert.equal(there.state.robot, 'custom');
    for (const key of ['text', 'root', 'tip', 'floating', 'mimic', 'inertia', 'pose']) {
      assert.deepEqual(there.source[key], here.source[key], `${key} comes back`);
    }
    assert.deepEqual(there.state.warnings, here.state.warnings, 'the inertias repaired alike');
    assert.deepEqual(there.poses, ['', 'standing', 'straight_standing'], 'the same poses to choose from');
    assert.equal(there.pose, 'straight_standing');
    assertJoints(there.source.q0, poses.straight_standing, 'reopened');
    assert.deepEqual(there.source.q0, here.source.q0, 'the same start pose, base included');
    assert.deepEqual(Object.keys(there.state.links).sort(), FEET);
    assert.equal(new URL(there.other.page.url()).hash, link, 'the reopened page writes the same link');

    // A pose chosen after loading is in the link, and comes back.
    await page.locator('#pose-select').selectOption('standing');
    const chosen = new URL(page.url()).hash;
    assert.ok(chosen.includes('pose=standing'), chosen.slice(0, 200));
    const again = await reopened(chosen);
    assert.equal(again.error, null);
    assert.equal(again.source.pose, 'standing');
    assertJoints(again.source.q0, poses.standing, 'reopened after choosing');
    assert.deepEqual(consoleErrors, []);
    for (const o of others) assert.deepEqual(o.consoleErrors, []);
  } finally {
    for (const o of others) await o.close();
    await session.close();
  }
});
