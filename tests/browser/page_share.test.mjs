// Own URDFs first class, in Chromium: an own URDF picked with the file input
// travels in the page's link compressed and reopens, with the link's held direction, in
// a browser profile that never saw it, and in an open page whose address is set to it; one too long for a link (the 200-joint chain) is
// kept in the browser's storage under its SHA-256, and its link reopens it in a new page
// of that browser and explains itself in another; the page says which form each link
// has. The mesh robot of tests/fixtures/mesh_robot/ loaded from its folder keeps its
// mesh files in the browser's IndexedDB under the URDF's key: its link reopens it with
// every mesh loaded in a new page of that browser, and with a stick figure and a note
// naming the missing meshes in another; loaded again without its folder, its link
// reopens it without meshes there too; no console errors.
import assert from 'node:assert/strict';
import { createHash } from 'node:crypto';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { fileURLToPath } from 'node:url';
import { MESH_FILES, files as fixtureFiles, urdf as meshUrdf } from '../fixtures/make_mesh_robot.mjs';
import { openPage } from './launch.mjs';

const read = (path) => readFile(new URL(`../../${path}`, import.meta.url), 'utf8');
const index = JSON.parse(await read('robots/index.json'));
// An own UR5: the index's URDF under another robot name, so that it is not the list's.
const ownText = (await read('robots/ur5.urdf')).replace(/<robot name="[^"]*"/, '<robot name="my_arm"');
const longText = await read('robots/chain200.urdf');

const state = (page) => page.evaluate(() => window.achdDemo.state());
const shown = (page) => page.evaluate(() => ({
  state: window.achdDemo.state(),
  source: window.achdDemo.robotSource(),
  note: document.getElementById('share-note').hidden ? null : document.getElementById('share-note').textContent,
  error: document.getElementById('page-error').hidden ? null : document.getElementById('page-error-text').textContent,
  select: document.getElementById('robot-select').value,
}));
const waitForShare = (page) => page.waitForFunction(() => window.achdDemo.state().share);

// The page's link opened in a new page of the same browser, its console errors and page
// errors going into `errors`, once it has loaded and worked out its share.
async function reopen(page, errors) {
  const other = await page.context().newPage();
  other.on('console', (msg) => msg.type() === 'error' && errors.push(msg.text()));
  other.on('pageerror', (err) => errors.push(`page error: ${err.message}`));
  await other.goto(page.url());
  await other.evaluate(() => window.achdDemo.ready);
  await waitForShare(other);
  return other;
}

test('a share link restores an own URDF', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  const others = [];
  try {
    await t.test('a short URDF travels in the link and opens in another browser profile', async () => {
      assert.ok(ownText.includes('<robot name="my_arm"'));
      await page.setInputFiles('#urdf-file', { name: 'my_arm.urdf', mimeType: 'application/xml', buffer: Buffer.from(ownText) });
      await page.locator('#urdf-chain button[type="submit"]').click();
      await waitForShare(page);
      await page.evaluate(() => window.achdDemo.setDirection('z', 'hold'));
      const here = await shown(page);
      assert.equal(here.state.robot, 'custom');
      assert.equal(here.state.share.form, 'link');
      assert.equal(here.source.text, ownText);
      assert.match(here.note, /^my_arm\.urdf travels in this page's link \(\d+ characters, compressed\)/);
      const hash = await page.evaluate(() => location.hash);
      assert.ok(hash.startsWith(`#robot=custom&urdf=deflate:`), hash.slice(0, 60));
      assert.match(hash, /&dirs=z:hold/);

      const other = await openPage({ hash });
      others.push(other);
      await waitForShare(other.page);
      const there = await shown(other.page);
      assert.equal(there.error, null);
      assert.equal(there.select, 'custom');
      assert.equal(there.source.text, ownText);
      assert.equal(there.source.root, here.source.root);
      assert.equal(there.source.tip, here.source.tip);
      assert.equal(there.state.directions.z, 'hold');
      assert.match(there.note, /travels in this page's link/);
      await other.page.waitForFunction(() => window.achdDemo.state().t > 0.2);
      assert.deepEqual(other.consoleErrors, []);
    });

    await t.test('the link put in the address of an open page opens it there, without a reload', async () => {
      const ownHash = await page.evaluate(() => location.hash);
      await page.selectOption('#robot-select', 'ur5');
      await page.waitForFunction(() => window.achdDemo.state().robot === 'ur5');
      assert.doesNotMatch(await page.evaluate(() => location.hash), /urdf=/);
      await page.evaluate((hash) => {
        window.achdMarker = true;  // gone if the page reloaded
        location.hash = hash;
      }, ownHash);
      await page.waitForFunction(() => window.achdDemo.state().robot === 'custom');
      const back = await shown(page);
      assert.equal(back.source.text, ownText);
      assert.equal(back.state.directions.z, 'hold');
      assert.equal(await page.evaluate(() => window.achdMarker), true);
      await waitForShare(page);
      assert.equal(await page.evaluate(() => location.hash), ownHash);
    });

    let localHash;
    await t.test('a long URDF is kept in the browser\'s storage and its link reopens it in a new page', async () => {
      await page.evaluate((text) => window.achdDemo.loadURDF(text, 'link0', 'link200'), longText);
      await waitForShare(page);
      const here = await shown(page);
      assert.equal(here.state.share.form, 'local');
      const key = createHash('sha256').update(longText).digest('hex').slice(0, 16);
      assert.equal(here.state.share.ref, `local:${key}`);
      assert.ok(here.state.share.characters > 8000, `${here.state.share.characters} characters compressed`);
      assert.match(here.note, new RegExp(`kept in this browser's storage and this page's link names it \\(local:${key}\\)`));
      localHash = await page.evaluate(() => location.hash);
      assert.ok(localHash.startsWith(`#robot=custom&urdf=local:${key}&root=link0&tip=link200&`), localHash);

      const second = await reopen(page, consoleErrors);
      const there = await shown(second);
      assert.equal(there.error, null);
      assert.equal(there.state.robot, 'custom');
      assert.equal(there.source.text, longText);
      assert.equal(there.source.tip, 'link200');
      assert.equal(there.state.q.length, 200);
      assert.match(there.note, /kept in this browser's storage/);
      await second.close();
    });

    await t.test('in a browser that does not keep it, the local link says so and shows the default robot', async () => {
      const other = await openPage({ hash: localHash });
      others.push(other);
      const there = await shown(other.page);
      assert.equal(there.state.robot, index.default);
      assert.match(there.error, /not in this browser's storage: such a link reopens a URDF only in the browser that loaded it/);
      assert.deepEqual(other.consoleErrors, []);
    });

    assert.deepEqual(consoleErrors, []);
  } finally {
    for (const other of others) await other.close();
    await session.close();
  }
});

test('a share link restores an own URDF\'s meshes in the browser that loaded them', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  const others = [];
  // Every mesh of the fixture: its STL and its COLLADA file, both loaded.
  const allLoaded = (s) => JSON.stringify(s.look.meshes?.map((m) => [m.filename, m.status])) ===
    JSON.stringify(MESH_FILES.map((f) => [f, 'loaded']));
  try {
    const text = meshUrdf();
    const key = createHash('sha256').update(text).digest('hex').slice(0, 16);
    const meshBytes = Object.entries(fixtureFiles()).filter(([path]) => path.startsWith('meshes/'))
      .reduce((sum, [, contents]) => sum + Buffer.from(contents).length, 0);
    let hash;
    await t.test('the robot loaded from its folder keeps its two mesh files with its link', async () => {
      await page.locator('#urdf-folder').setInputFiles(fileURLToPath(new URL('../fixtures/mesh_robot/', import.meta.url)));
      await page.locator('#urdf-chain button[type=submit]').click();
      await page.waitForFunction(() => window.achdDemo.state().robot === 'custom');
      await waitForShare(page);
      const here = await shown(page);
      assert.ok(allLoaded(here.state), JSON.stringify(here.state.look.meshes));
      assert.equal(here.source.text, text);
      assert.equal(here.state.share.form, 'link');
      assert.equal(here.state.share.key, key);
      assert.deepEqual(here.state.share.meshes, { named: 2, files: 2, bytes: meshBytes, error: null });
      assert.match(here.note, new RegExp(`^mesh_robot/urdf/mesh_robot\\.urdf travels in this page's link \\(\\d+ characters, compressed\\): ` +
        `the address opens it in any browser\\. Its 2 mesh files \\(${(meshBytes / 1024).toFixed(1)} kB\\) are kept in this browser's ` +
        `storage \\(IndexedDB, key ${key}\\): the link shows them in this browser only, another draws a stick figure instead\\.$`));
      hash = await page.evaluate(() => location.hash);
      assert.ok(hash.startsWith('#robot=custom&urdf=deflate:'), hash.slice(0, 40));
    });

    await t.test('its link reopens it with every mesh in a new page of that browser', async () => {
      const second = await reopen(page, consoleErrors);
      const there = await shown(second);
      assert.equal(there.error, null);
      assert.equal(there.state.robot, 'custom');
      assert.equal(there.source.text, text);
      assert.ok(allLoaded(there.state), JSON.stringify(there.state.look.meshes));
      assert.ok(await second.locator('#view-note').isHidden(), 'a note shows though every mesh loaded');
      // Reopened, it keeps the same files under the same key.
      assert.deepEqual(there.state.share.meshes, { named: 2, files: 2, bytes: meshBytes, error: null });
      await second.close();
    });

    await t.test('in another browser the link opens the URDF with a stick figure and names the meshes', async () => {
      const other = await openPage({ hash });
      others.push(other);
      await waitForShare(other.page);
      const there = await shown(other.page);
      assert.equal(there.error, null);
      assert.equal(there.source.text, text);
      assert.deepEqual(there.state.look.meshes.map((m) => m.status), ['missing', 'missing']);
      const note = await other.page.locator('#view-note').textContent();
      for (const file of MESH_FILES) assert.ok(note.includes(file), `note "${note}" does not name ${file}`);
      assert.match(there.note, /None of its mesh files was read here, so the link reopens it without them/);
      assert.deepEqual(other.consoleErrors, []);
    });

    await t.test('the same URDF loaded alone: its link shows what the page shows, no meshes', async () => {
      await page.setInputFiles('#urdf-file', { name: 'mesh_robot.urdf', mimeType: 'application/xml', buffer: Buffer.from(text) });
      await page.locator('#urdf-chain button[type=submit]').click();
      await page.waitForFunction(() => window.achdDemo.state().look.meshes?.every((m) => m.status === 'missing'));
      await waitForShare(page);
      const here = await shown(page);
      assert.deepEqual(here.state.share.meshes, { named: 2, files: 0, bytes: 0, error: null });
      assert.match(here.note, /None of its mesh files was read here, so the link reopens it without them/);
      assert.equal(await page.evaluate(() => location.hash), hash);
      const third = await reopen(page, consoleErrors);
      assert.deepEqual((await shown(third)).state.look.meshes.map((m) => m.status), ['missing', 'missing']);
      await third.close();
    });

    assert.deepEqual(consoleErrors, []);
  } finally {
    for (const other of others) await other.close();
    await session.close();
  }
});
