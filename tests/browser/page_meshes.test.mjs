// The robot as it looks, in Chromium: tests/fixtures/mesh_robot/ (an STL in millimetres
// named by package://, a COLLADA file in centimetres named by a relative path) loaded
// through the folder picker shows both meshes where the URDF puts them: the coloured
// pixels' bounding box on the canvas is the box of the meshes' corners projected by the
// page's camera at the link poses achd's forward kinematics gives (in Node, apart from
// the page), and not the stick figure's; so it is for the chain ending at the arm, the
// hand drawn on it through the locked elbow. A URDF whose meshes are missing loads with a
// note naming them and the stick figure through the link origins; a broken URDF is
// explained while the robot keeps stepping; an OBJ mesh picked with its URDF loads, and a
// visual that cannot be read is named; the fixture's files dropped loose on the page load
// with their meshes; a COLLADA texture given with the files is drawn, one missing named.
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { fileURLToPath } from 'node:url';
import {
  ARM_VERTICES, binaryStl, collada, ELBOW_XYZ, files as fixtureFiles, HAND_VERTICES, MESH_FILES, png, urdf, VISUALS,
} from '../fixtures/make_mesh_robot.mjs';
import { loadAchd } from '../node/helpers.mjs';
import { openPage } from './launch.mjs';

const FOLDER = new URL('../fixtures/mesh_robot/', import.meta.url);
// Rasterising puts a pixel's centre inside a triangle: the drawn box is within a pixel of
// the projected one; antialiased edge pixels, too pale to count, take one more.
const PIXELS = 2;

const achd = await loadAchd();
const state = (page) => page.evaluate(() => window.achdDemo.state());

// Loads files given to an <input> and submits the chain form with its preselected chain
// (or the tip given).
async function loadThrough(page, input, files, tip) {
  await page.locator(input).setInputFiles(files);
  await page.locator('#urdf-chain').waitFor({ state: 'visible' });
  if (tip) await page.locator('#urdf-tip').selectOption(tip);
  await page.locator('#urdf-chain button[type=submit]').click();
  // The form hides once the robot is in (its meshes then start loading).
  await page.locator('#urdf-chain').waitFor({ state: 'hidden' });
  await page.waitForFunction(() => {
    const s = window.achdDemo.state();
    return s.robot === 'custom' && s.look.meshes !== null;
  });
}

// p_world = T_link (T(xyz) R(rpy) (scale p_file)), R(rpy) = Rz(y) Ry(p) Rx(r).
function visualToWorld(visual, link, p) {
  const [r, pi, y] = visual.rpy;
  const [cr, sr, cp, sp, cy, sy] = [Math.cos(r), Math.sin(r), Math.cos(pi), Math.sin(pi), Math.cos(y), Math.sin(y)];
  const R = [
    [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
    [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
    [-sp, cp * sr, cp * cr],
  ];
  const s = p.map((v) => v * visual.scale);
  const inLink = R.map((row, i) => row[0] * s[0] + row[1] * s[1] + row[2] * s[2] + visual.xyz[i]);
  const L = link.rotation;
  return [0, 1, 2].map((i) => L[3 * i] * inLink[0] + L[3 * i + 1] * inLink[1] + L[3 * i + 2] * inLink[2] + link.position[i]);
}

// A world point to CSS pixels on the page, with three's column-major matrices.
function project(camera, p) {
  const mul = (m, v) => [0, 1, 2, 3].map((i) => m[i] * v[0] + m[4 + i] * v[1] + m[8 + i] * v[2] + m[12 + i] * v[3]);
  const clip = mul(camera.projection, mul(camera.worldInverse, [...p, 1]));
  const { left, top, width, height } = camera.rect;
  return [left + ((clip[0] / clip[3] + 1) / 2) * width, top + ((1 - clip[1] / clip[3]) / 2) * height];
}

function boxOf(points) {
  const xs = points.map((p) => p[0]);
  const ys = points.map((p) => p[1]);
  return { left: Math.min(...xs), right: Math.max(...xs), top: Math.min(...ys), bottom: Math.max(...ys) };
}

// Hue windows (degrees) of the meshes' colours: the arm's magenta (URDF material) and the
// hand's yellow (the COLLADA file's own); lighting changes their brightness, not their
// hue. Grey base, grid and the tip axes' red, green and blue are out.
const MESH_HUES = [[285, 335], [35, 65]];
// The stick figure's orange links (web/chain_view.js, #e8a33d).
const STICK_HUES = [[25, 45]];

// The box (CSS pixels) of the canvas's saturated pixels whose hue is in one of the windows.
function pixelsBox(hues) {
  const canvas = document.querySelector('#view canvas');
  const copy = document.createElement('canvas');
  copy.width = canvas.width;
  copy.height = canvas.height;
  const ctx = copy.getContext('2d');
  ctx.drawImage(canvas, 0, 0);
  const { data } = ctx.getImageData(0, 0, copy.width, copy.height);
  const rect = canvas.getBoundingClientRect();
  const box = { left: Infinity, right: -Infinity, top: Infinity, bottom: -Infinity, count: 0 };
  for (let j = 0; j < copy.height; j++) {
    for (let i = 0; i < copy.width; i++) {
      const k = 4 * (j * copy.width + i);
      const [r, g, b] = [data[k], data[k + 1], data[k + 2]];
      const max = Math.max(r, g, b);
      const min = Math.min(r, g, b);
      if (max < 40 || (max - min) / max < 0.45) continue;
      let hue = max === r ? (60 * (g - b)) / (max - min) : max === g ? 120 + (60 * (b - r)) / (max - min) : 240 + (60 * (r - g)) / (max - min);
      if (hue < 0) hue += 360;
      if (!hues.some(([lo, hi]) => hue > lo && hue < hi)) continue;
      const x = rect.left + ((i + 0.5) * rect.width) / copy.width;
      const y = rect.top + ((j + 0.5) * rect.height) / copy.height;
      box.left = Math.min(box.left, x);
      box.right = Math.max(box.right, x);
      box.top = Math.min(box.top, y);
      box.bottom = Math.max(box.bottom, y);
      box.count++;
    }
  }
  return box;
}

const SIDES = ['left', 'right', 'top', 'bottom'];

// Pauses the page and checks the box of the mesh pixels drawn against the meshes' corners
// projected at the poses achd gives the chain base -> tip; a hand beyond the tip is placed
// on the arm through the elbow at its locked value.
async function drawnAndProjected(page, tip) {
  await page.evaluate(() => window.achdDemo.pause());
  await page.waitForTimeout(300);  // frames render the paused pose
  const drawn = await page.evaluate(pixelsBox, MESH_HUES);
  const { q, camera } = await page.evaluate(() => ({ q: window.achdDemo.state().q, camera: window.achdDemo.camera() }));
  const robot = achd.loadURDF(urdf(), { root: 'base', tip });
  const links = Object.fromEntries(robot.forwardKinematics(q).map((l) => [l.name, l]));
  const locked = robot.lockedJoints;
  robot.delete();
  if (!links.hand) {
    assert.deepEqual(locked.map((j) => j.name), ['elbow']);
    const [c, s] = [Math.cos(locked[0].value), Math.sin(locked[0].value)];
    const R = links.arm.rotation;
    const Ry = [c, 0, s, 0, 1, 0, -s, 0, c];
    links.hand = {
      position: [0, 1, 2].map((i) => links.arm.position[i] + R[3 * i] * ELBOW_XYZ[0] + R[3 * i + 1] * ELBOW_XYZ[1] + R[3 * i + 2] * ELBOW_XYZ[2]),
      rotation: [0, 1, 2].flatMap((i) => [0, 1, 2].map((k) => R[3 * i] * Ry[k] + R[3 * i + 1] * Ry[3 + k] + R[3 * i + 2] * Ry[6 + k])),
    };
  }
  const corners = VISUALS.flatMap((v) => v.vertices.map((p) => project(camera, visualToWorld(v, links[v.link], p))));
  const expected = boxOf(corners);
  console.log(`# tip ${tip}: drawn ${JSON.stringify(drawn)}\n# projected ${JSON.stringify(expected)}`);
  assert.ok(drawn.count > 500, `${drawn.count} mesh pixels`);
  for (const side of SIDES) {
    assert.ok(Math.abs(drawn[side] - expected[side]) <= PIXELS, `${side}: drawn ${drawn[side]}, projected ${expected[side]}`);
  }
  return { drawn, expected, camera, links };
}

test('the robot as it looks: meshes from a folder', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    await t.test('the fixture on disk is what tests/fixtures/make_mesh_robot.mjs writes', async () => {
      for (const [path, contents] of Object.entries(fixtureFiles())) {
        assert.deepEqual(await readFile(new URL(path, FOLDER)), Buffer.from(contents), path);
      }
    });

    await t.test('the folder picker loads the robot and every mesh', async () => {
      await loadThrough(page, '#urdf-folder', fileURLToPath(FOLDER));
      const s = await state(page);
      assert.deepEqual(s.look.meshes.map((m) => [m.filename, m.link, m.status]),
        [[MESH_FILES[0], 'arm', 'loaded'], [MESH_FILES[1], 'hand', 'loaded']]);
      assert.deepEqual(s.look.problems, []);
      assert.ok(await page.locator('#view-note').isHidden(), 'a note shows though every mesh loaded');
    });

    await t.test('the drawn meshes cover their projected corners, not the stick figure', async () => {
      const { drawn, expected, camera, links } = await drawnAndProjected(page, 'hand');
      // The stick figure runs through the link origins: its box is far from the meshes'.
      const base = { position: [0, 0, 0] };
      const stick = boxOf([base, links.arm, links.hand].map((l) => project(camera, l.position)));
      const apart = Math.max(...SIDES.map((side) => Math.abs(stick[side] - expected[side])));
      assert.ok(apart > 20 * PIXELS, `the stick figure's box is within ${apart} px of the meshes' (drawn ${JSON.stringify(drawn)})`);
      await page.evaluate(() => window.achdDemo.play());
    });

    await t.test('a chain ending at the arm: the hand hangs on it at the locked elbow', async () => {
      await loadThrough(page, '#urdf-folder', fileURLToPath(FOLDER), 'arm');
      const s = await state(page);
      assert.deepEqual(s.look.meshes.map((m) => m.status), ['loaded', 'loaded']);
      await drawnAndProjected(page, 'arm');
      await page.evaluate(() => window.achdDemo.play());
    });

    await t.test('a URDF whose meshes are missing loads with a note naming them', async () => {
      await loadThrough(page, '#urdf-file', { name: 'mesh_robot.urdf', mimeType: 'application/xml', buffer: Buffer.from(urdf()) });
      const s = await state(page);
      assert.deepEqual(s.look.meshes.map((m) => m.status), ['missing', 'missing']);
      const note = await page.locator('#view-note').textContent();
      assert.ok(await page.locator('#view-note').isVisible());
      for (const file of MESH_FILES) assert.ok(note.includes(file), `note "${note}" does not name ${file}`);
      assert.match(note, /stick figure/);
      const t0 = s.t;
      await page.waitForTimeout(300);
      assert.ok((await state(page)).t > t0, 'the robot with missing meshes does not step');
      // The stick figure stands in: an orange segment from the arm's origin to the hand's.
      await page.evaluate(() => window.achdDemo.pause());
      await page.waitForTimeout(300);
      const stick = await page.evaluate(pixelsBox, STICK_HUES);
      const { q, camera } = await page.evaluate(() => ({ q: window.achdDemo.state().q, camera: window.achdDemo.camera() }));
      const robot = achd.loadURDF(urdf(), { root: 'base', tip: 'hand' });
      const ends = robot.forwardKinematics(q).map((l) => project(camera, l.position));
      robot.delete();
      assert.ok(stick.count > 100, `${stick.count} stick pixels`);
      for (const [x, y] of ends) {
        assert.ok(x >= stick.left - PIXELS && x <= stick.right + PIXELS && y >= stick.top - PIXELS && y <= stick.bottom + PIXELS,
          `link origin (${x}, ${y}) is off the stick figure ${JSON.stringify(stick)}`);
      }
      await page.evaluate(() => window.achdDemo.play());
    });

    await t.test('a broken URDF is explained while the robot keeps stepping', async () => {
      const before = await state(page);
      await page.locator('#urdf-file').setInputFiles({
        name: 'broken.urdf', mimeType: 'application/xml', buffer: Buffer.from('<robot name="broken"><link name="a">'),
      });
      await page.locator('#page-error').waitFor({ state: 'visible' });
      const message = await page.locator('#page-error-text').textContent();
      assert.match(message, /broken\.urdf: not a URDF file/);
      await page.waitForTimeout(300);
      const after = await state(page);
      assert.equal(after.robot, before.robot);
      assert.ok(after.t > before.t, 'the robot stopped stepping');
      // The robot's own note stays: its meshes are still missing.
      assert.ok(await page.locator('#view-note').isVisible());
    });

    await t.test('a URDF picked with its OBJ file: the mesh loads; a visual that cannot be read is named', async () => {
      // A unit cube, 8 corners and 12 triangles, written here.
      const obj = ['v 0 0 0', 'v 1 0 0', 'v 1 1 0', 'v 0 1 0', 'v 0 0 1', 'v 1 0 1', 'v 1 1 1', 'v 0 1 1',
        'f 1 3 2', 'f 1 4 3', 'f 5 6 7', 'f 5 7 8', 'f 1 2 6', 'f 1 6 5', 'f 2 3 7', 'f 2 7 6',
        'f 3 4 8', 'f 3 8 7', 'f 4 1 5', 'f 4 5 8', ''].join('\n');
      const text = `<robot name="cube">
  <link name="base"><visual><geometry><sphere radius="0.05"/></geometry></visual></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <link name="arm">
    <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><mesh filename="package://cube/meshes/cube.obj" scale="0.1 0.1 0.3"/></geometry></visual>
    <visual><geometry><cylinder radius="-0.02" length="0.1"/></geometry></visual>
    <visual><origin xyz="0 0 0.3"/><geometry><cylinder radius="0.02" length="0.1"/></geometry></visual>
  </link>
</robot>`;
      await loadThrough(page, '#urdf-file', [
        { name: 'cube.urdf', mimeType: 'application/xml', buffer: Buffer.from(text) },
        { name: 'cube.obj', mimeType: 'text/plain', buffer: Buffer.from(obj) },
      ]);
      const s = await state(page);
      assert.deepEqual(s.look.meshes.map((m) => [m.filename, m.status]), [['package://cube/meshes/cube.obj', 'loaded']]);
      // urdfdom takes a negative radius; the page leaves that visual out and says so.
      assert.deepEqual(s.look.problems, ['link "arm", visual 2: cylinder radius "-0.02" is not a positive number']);
      assert.match(await page.locator('#view-note').textContent(), /Visual left out: link "arm", visual 2: cylinder radius/);
    });

    await t.test('the URDF and its meshes dropped together as loose files: the meshes resolve by name', async () => {
      const loose = Object.entries(fixtureFiles())
        .filter(([path]) => path !== 'package.xml')
        .map(([path, contents]) => [path.split('/').pop(), Buffer.from(contents).toString('base64')]);
      await page.evaluate((files) => {
        const drop = new DataTransfer();
        for (const [name, base64] of files) {
          drop.items.add(new File([Uint8Array.from(atob(base64), (c) => c.charCodeAt(0))], name));
        }
        document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: drop, bubbles: true, cancelable: true }));
      }, loose);
      await page.locator('#urdf-chain').waitFor({ state: 'visible' });
      await page.locator('#urdf-chain button[type=submit]').click();
      await page.locator('#urdf-chain').waitFor({ state: 'hidden' });
      await page.waitForFunction(() => window.achdDemo.state().look.meshes !== null);
      const s = await state(page);
      assert.deepEqual(s.look.meshes.map((m) => [m.filename, m.status]), [[MESH_FILES[0], 'loaded'], [MESH_FILES[1], 'loaded']]);
      assert.ok(await page.locator('#view-note').isHidden());
    });

    await t.test('a COLLADA texture is read from the files given; one not given is named, nothing fetched', async () => {
      // The hand's COLLADA file with a texture of one colour, teal (hue 187), next to it.
      const TEAL = [30, 190, 210];
      const given = [
        { name: 'mesh_robot.urdf', mimeType: 'application/xml', buffer: Buffer.from(urdf()) },
        { name: 'arm.stl', mimeType: 'model/stl', buffer: binaryStl(ARM_VERTICES) },
        { name: 'hand.dae', mimeType: 'model/vnd.collada+xml', buffer: Buffer.from(collada(HAND_VERTICES, 'textures/skin.png')) },
      ];
      await loadThrough(page, '#urdf-file', [...given, { name: 'skin.png', mimeType: 'image/png', buffer: png(4, 4, TEAL) }]);
      let s = await state(page);
      assert.deepEqual(s.look.meshes.map((m) => [m.status, m.texturesMissing]), [['loaded', []], ['loaded', []]]);
      assert.ok(await page.locator('#view-note').isHidden());
      await page.evaluate(() => window.achdDemo.pause());
      await page.waitForTimeout(500);  // the image decodes, then frames draw it
      const teal = await page.evaluate(pixelsBox, [[175, 200]]);
      console.log(`# ${teal.count} pixels in the texture's colour`);
      assert.ok(teal.count > 1000, `${teal.count} pixels in the texture's colour`);
      await page.evaluate(() => window.achdDemo.play());

      await loadThrough(page, '#urdf-file', given);
      s = await state(page);
      assert.deepEqual(s.look.meshes.map((m) => [m.status, m.texturesMissing]), [['loaded', []], ['loaded', ['textures/skin.png']]]);
      assert.match(await page.locator('#view-note').textContent(), /Textures of \.\.\/meshes\/hand\.dae not found \(drawn without\): textures\/skin\.png/);
    });

    await t.test('no console errors', () => {
      assert.deepEqual(consoleErrors, []);
    });
  } finally {
    await session.close();
  }
});
