// Inputs that used to take the page down, in Chromium:
//   - a share link whose urdf=deflate: text expands past the 64 MiB limit of a URDF file
//     (here a 200 MB one, about 200 KB of link) is refused within 2 s with a message
//     naming the limit, and after a forced garbage collection the page's JS heap is
//     within 20 MB of its size before (before: the whole text was decompressed, 100 MB in
//     27 s, and the heap kept hundreds of MB);
//   - an OBJ mesh whose vertices are NaN, infinite or kilometres away is refused per
//     mesh: it is reported 'failed' with the reason, its link keeps the stick figure, the
//     camera's matrices stay finite and the robot keeps stepping (before: the mesh was
//     reported loaded and the camera's matrices became NaN).
import assert from 'node:assert/strict';
import test from 'node:test';
import { deflateRawSync } from 'node:zlib';
import { openPage } from './launch.mjs';

const LIMIT_MIB = 64;

// The page's JS heap after a forced garbage collection, in bytes (DevTools protocol).
async function heapAfterGc(cdp) {
  await cdp.send('HeapProfiler.collectGarbage');
  await cdp.send('HeapProfiler.collectGarbage');
  return (await cdp.send('Runtime.getHeapUsage')).usedSize;
}

const errorShown = (page) => page.evaluate(() =>
  (document.getElementById('page-error').hidden ? null : document.getElementById('page-error-text').textContent));

test('a deflate link that expands past the URDF limit is refused quickly, its memory given back', async () => {
  // 200 MB of spaces inside a comment: a valid URDF's worth of bytes, were it read whole.
  const text = Buffer.concat([Buffer.from('<robot name="bomb"><!--'), Buffer.alloc(200 * 1024 * 1024, 0x20),
    Buffer.from('--><link name="a"/></robot>')]);
  const packed = deflateRawSync(text, { level: 9 }).toString('base64url');
  assert.ok(packed.length < 400 * 1024, `${packed.length} characters`);
  const session = await openPage();
  const { page } = session;
  try {
    const cdp = await page.context().newCDPSession(page);
    const before = await heapAfterGc(cdp);
    const started = Date.now();
    await page.evaluate((hash) => { location.hash = hash; }, `#robot=custom&urdf=deflate:${packed}&root=a&tip=a`);
    await page.waitForFunction(() => !document.getElementById('page-error').hidden, null, { timeout: 10000 });
    const seconds = (Date.now() - started) / 1000;
    const message = await errorShown(page);
    assert.match(message, new RegExp(`expands past the ${LIMIT_MIB} MiB limit of a URDF file`), message);
    assert.ok(seconds < 2, `refused after ${seconds} s`);
    const after = await heapAfterGc(cdp);
    const grown = (after - before) / (1024 * 1024);
    console.log(`deflate link of ${packed.length} characters refused after ${seconds.toFixed(2)} s; ` +
      `heap ${(before / 1048576).toFixed(1)} MB before, ${(after / 1048576).toFixed(1)} MB after (+${grown.toFixed(1)} MB)`);
    assert.ok(grown < 20, `the heap grew by ${grown.toFixed(1)} MB`);
    // The page still works: the robot it had keeps stepping.
    const t0 = await page.evaluate(() => window.achdDemo.state().t);
    await page.waitForFunction((t) => window.achdDemo.state().t > t, t0);
    assert.deepEqual(session.consoleErrors, []);
  } finally {
    await session.close();
  }
});

test('an OBJ mesh with NaN, infinite or absurd vertices is refused per mesh; the view stays drawable', async () => {
  const cube = (first) => [first, 'v 1 0 0', 'v 1 1 0', 'v 0 1 0', 'v 0 0 1', 'v 1 0 1', 'v 1 1 1', 'v 0 1 1',
    'f 1 3 2', 'f 1 4 3', 'f 5 6 7', 'f 5 7 8', 'f 1 2 6', 'f 1 6 5', 'f 2 3 7', 'f 2 7 6',
    'f 3 4 8', 'f 3 8 7', 'f 4 1 5', 'f 4 5 8', ''].join('\n');
  const meshes = { 'nan.obj': cube('v nan 0 0'), 'inf.obj': cube('v 1e39 0 0'), 'far.obj': cube('v 1e7 0 0'),
    'good.obj': cube('v 0 0 0') };
  const inertial = '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>';
  const names = Object.keys(meshes);
  const links = names.map((file, i) => `<link name="l${i}">${inertial}
    <visual><geometry><mesh filename="package://m/${file}" scale="0.1 0.1 0.1"/></geometry></visual></link>`);
  const joints = names.map((_, i) => `<joint name="j${i}" type="revolute"><parent link="${i ? `l${i - 1}` : 'base'}"/>
    <child link="l${i}"/><origin xyz="0 0 0.2"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>`);
  const urdf = `<robot name="meshes"><link name="base"/>${links.join('')}${joints.join('')}</robot>`;
  const session = await openPage();
  const { page } = session;
  try {
    await page.locator('#urdf-file').setInputFiles([
      { name: 'meshes.urdf', mimeType: 'application/xml', buffer: Buffer.from(urdf) },
      ...names.map((name) => ({ name, mimeType: 'text/plain', buffer: Buffer.from(meshes[name]) })),
    ]);
    await page.locator('#urdf-chain').waitFor({ state: 'visible' });
    await page.locator('#urdf-tip').selectOption('l3');
    await page.locator('#urdf-chain button[type=submit]').click();
    await page.locator('#urdf-chain').waitFor({ state: 'hidden' });
    await page.waitForFunction(() => window.achdDemo.state().look.meshes !== null);
    const s = await page.evaluate(() => window.achdDemo.state());
    const byFile = Object.fromEntries(s.look.meshes.map((m) => [m.filename.split('/').pop(), m]));
    assert.equal(byFile['good.obj'].status, 'loaded');
    assert.equal(byFile['nan.obj'].status, 'failed');
    assert.match(byFile['nan.obj'].message, /vertex 1 has a coordinate that is not a finite number \(NaN\)/);
    assert.equal(byFile['inf.obj'].status, 'failed');
    assert.match(byFile['inf.obj'].message, /not a finite number \(Infinity\)/);
    assert.equal(byFile['far.obj'].status, 'failed');
    assert.match(byFile['far.obj'].message, /1\.00e\+6 m from the visual's origin, more than the 1000 m/);
    const note = await page.locator('#view-note').textContent();
    for (const file of ['nan.obj', 'inf.obj', 'far.obj']) assert.match(note, new RegExp(`Mesh package://m/${file} of link l\\d not shown`));
    const camera = await page.evaluate(() => window.achdDemo.camera());
    assert.ok([...camera.projection, ...camera.worldInverse].every(Number.isFinite), JSON.stringify(camera));
    const t0 = s.t;
    await page.waitForFunction((t) => window.achdDemo.state().t > t, t0);
    assert.deepEqual(session.consoleErrors, []);
  } finally {
    await session.close();
  }
});
