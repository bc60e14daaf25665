// The camera frames any robot, in Chromium: solo12 (a 0.4 m quadruped, floating, in its
// SRDF's standing pose), Talos (a 1.7 m humanoid, floating, half sitting), both from
// example-robot-data without their meshes (stick figures), and the 50-link chain of the
// list. At the pose the camera framed (the start pose, set again paused), the box it
// framed (achdDemo.camera().box) holds every link origin, and projected through the
// camera's matrices it lies fully inside the canvas and spans 30% to 90% of its width or
// height (the larger of the two); the link origins alone lie inside it too and span at
// least 20% of it. The
// view never depends on the robot's size: the two robots, 4x apart, fill it alike.
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { openPage } from './launch.mjs';

const ERD = new URL('../../robots/example-robot-data/', import.meta.url);
const read = (path) => readFile(new URL(path, ERD), 'utf8');
const MIN_FILL = 0.3;
const MAX_FILL = 0.9;
const MIN_ORIGINS_FILL = 0.2;

// p' = P V p for column-major 4x4 matrices; -> [x, y] in CSS pixels of the canvas.
function project({ projection: P, worldInverse: V, rect }, p) {
  const apply = (M, v) => [0, 1, 2, 3].map((r) => M[r] * v[0] + M[4 + r] * v[1] + M[8 + r] * v[2] + M[12 + r] * v[3]);
  const c = apply(P, apply(V, [...p, 1]));
  assert.ok(c[3] > 0, `a point behind the camera: ${p}`);
  return [(c[0] / c[3] + 1) / 2 * rect.width, (1 - c[1] / c[3]) / 2 * rect.height];
}

// The pixel box [minX, minY, maxX, maxY] of points projected.
function pixelBox(camera, points) {
  const xy = points.map((p) => project(camera, p));
  return [Math.min(...xy.map((p) => p[0])), Math.min(...xy.map((p) => p[1])),
    Math.max(...xy.map((p) => p[0])), Math.max(...xy.map((p) => p[1]))];
}

// The camera, the box it framed and every link origin, at the start pose, paused.
async function framed(page, urdf) {
  await page.waitForFunction(() => window.achdDemo.state().look.meshes !== null);
  await page.evaluate(() => {
    window.achdDemo.pause();
    window.achdDemo.setPose(window.achdDemo.robotSource().q0);
  });
  const names = [...urdf.matchAll(/<link\s+name="([^"]+)"/g)].map((m) => m[1]);
  return page.evaluate((links) => ({
    camera: window.achdDemo.camera(),
    origins: links.flatMap((name) => {
      try {
        return [window.achdDemo.linkPosition(name)];
      } catch {
        return [];  // the root of a fixed base, or a link the loader merged
      }
    }),
  }), names);
}

function checkFraming(t, what, { camera, origins }) {
  const { box, rect } = camera;
  assert.ok(box, 'the camera framed a box');
  assert.ok(origins.length > 5, `${what}: link origins found`);
  for (const p of origins) {
    p.forEach((x, i) => assert.ok(x >= box.min[i] - 1e-9 && x <= box.max[i] + 1e-9, `${what}: a link origin ${p} outside the box`));
  }
  const corners = [0, 1, 2, 3, 4, 5, 6, 7].map((k) => [k & 1 ? box.max[0] : box.min[0], k & 2 ? box.max[1] : box.min[1],
    k & 4 ? box.max[2] : box.min[2]]);
  const [x0, y0, x1, y1] = pixelBox(camera, corners);
  const fill = Math.max((x1 - x0) / rect.width, (y1 - y0) / rect.height);
  const [ox0, oy0, ox1, oy1] = pixelBox(camera, origins);
  const originsFill = Math.max((ox1 - ox0) / rect.width, (oy1 - oy0) / rect.height);
  const size = box.max.map((x, i) => x - box.min[i]);
  t.diagnostic(`${what}: box ${size.map((x) => x.toFixed(2)).join(' x ')} m fills ${(100 * fill).toFixed(0)}% of the ` +
    `canvas (${rect.width} x ${rect.height} px), its link origins ${(100 * originsFill).toFixed(0)}%`);
  assert.ok(x0 >= 0 && y0 >= 0 && x1 <= rect.width && y1 <= rect.height,
    `${what}: the box projects to ${[x0, y0, x1, y1].map((v) => v.toFixed(0))}, outside the canvas`);
  assert.ok(fill >= MIN_FILL && fill <= MAX_FILL, `${what}: the box fills ${fill} of the canvas`);
  assert.ok(ox0 >= 0 && oy0 >= 0 && ox1 <= rect.width && oy1 <= rect.height,
    `${what}: the link origins project to ${[ox0, oy0, ox1, oy1].map((v) => v.toFixed(0))}, outside the canvas`);
  assert.ok(originsFill >= MIN_ORIGINS_FILL, `${what}: the link origins fill ${originsFill} of the canvas`);
  return fill;
}

test('the camera frames a small and a large robot and a long chain', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    const solo = await read('solo_description/robots/solo12.urdf');
    await page.evaluate(([text, srdf]) => window.achdDemo.loadURDF(text, 'base_link', null,
      { floating: true, srdf, pose: 'standing' }), [solo, await read('solo_description/srdf/solo.srdf')]);
    const small = checkFraming(t, 'solo12', await framed(page, solo));

    const talos = await read('talos_data/robots/talos_reduced.urdf');
    await page.evaluate(([text, srdf]) => window.achdDemo.loadURDF(text, 'base_link', null,
      { floating: true, srdf, pose: 'half_sitting' }), [talos, await read('talos_data/srdf/talos.srdf')]);
    const large = checkFraming(t, 'talos', await framed(page, talos));
    const sizes = await page.evaluate(() => window.achdDemo.camera().box);
    assert.ok(sizes.max[2] - sizes.min[2] > 1, 'Talos is over a metre tall');
    assert.ok(Math.abs(small - large) < 0.25, `the small robot fills ${small}, the large one ${large}`);

    await page.selectOption('#robot-select', 'chain50');
    await page.waitForFunction(() => window.achdDemo.state().robot === 'chain50');
    checkFraming(t, 'chain50', await framed(page, await readFile(new URL('../../robots/chain50.urdf', import.meta.url), 'utf8')));
    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});
