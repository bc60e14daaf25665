// Own URDFs first class (issue 17), in Chromium: an own URDF picked with the file input
// travels in the page's link compressed and reopens, with the link's held direction, in
// a browser profile that never saw it, and in an open page whose address is set to it; one too long for a link (the 200-joint chain) is
// kept in the browser's storage under its SHA-256, and its link reopens it in a new page
// of that browser and explains itself in another; the page says which form each link
// has; no console errors.
import assert from 'node:assert/strict';
import { createHash } from 'node:crypto';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
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

      const second = await page.context().newPage();
      second.on('console', (msg) => msg.type() === 'error' && consoleErrors.push(msg.text()));
      second.on('pageerror', (err) => consoleErrors.push(`page error: ${err.message}`));
      await second.goto(page.url());
      await second.evaluate(() => window.achdDemo.ready);
      await waitForShare(second);
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
