// Seeing forces on the page, in Chromium: the arrow at the tip is the constraint
// wrench alpha nu of the simulator's last solve (checked against the identity
// joint_torques = ff - J^T alpha nu with the module's tip Jacobian, ff = 0 and no damping
// or friction), drawn from the tip at the robot's scale (reach / 2 per weight, reach and
// weight from the URDF and forward kinematics), in its colour on the canvas, its length
// following nu when nu changes and gone when every direction is free; hovering it shows
// its numbers; the torque bars turn red past a URDF effort limit (a UR5 given a 5 N m
// limit at the shoulder) and have no scale where the URDF gives none; no console errors.
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import test from 'node:test';
import { loadAchd } from '../node/helpers.mjs';
import { openPage } from './launch.mjs';

const achd = await loadAchd();
const index = JSON.parse(await readFile(new URL('../../robots/index.json', import.meta.url), 'utf8'));
const ur5 = index.robots.find((r) => r.name === 'ur5');
const ur5Text = await readFile(new URL(`../../${ur5.urdf}`, import.meta.url), 'utf8');
// Gravity and velocity products only: joint_torques = ff - J^T alpha nu holds with ff = 0.
const HASH = '#robot=ur5&integrator=rk4&dt=0.001&effects=gravity,velocity_products&dirs=z:hold,rx:hold';
const FORCE_RGB = [0xc2, 0x18, 0x5b];
const G = 9.81;

const close = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol * Math.max(1, Math.abs(b)), `${what}: ${a} vs ${b}`);
const frames = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

// One step from a known q, paused: nu and joint_torques are of the solve at that q.
async function stepFrom(page) {
  const before = await page.evaluate(() => {
    window.achdDemo.pause();
    return window.achdDemo.state().q;
  });
  await page.evaluate(() => window.achdDemo.step(1));
  await frames(page);
  const now = await page.evaluate(() => ({ s: window.achdDemo.state(), f: window.achdDemo.forces(), camera: window.achdDemo.camera() }));
  return { q: before, ...now };
}

// The mass of the chain's links (root included) read from the URDF's <inertial> blocks.
function chainMass(text, links) {
  let mass = 0;
  for (const name of links) {
    const block = text.match(new RegExp(`<link name="${name}">([\\s\\S]*?)</link>`))?.[1] ?? '';
    mass += Number(block.match(/<mass value="([^"]+)"/)?.[1] ?? 0);
  }
  return mass;
}

function project(camera, p) {
  const mul = (m, v) => [0, 1, 2, 3].map((i) => m[i] * v[0] + m[4 + i] * v[1] + m[8 + i] * v[2] + m[12 + i] * v[3]);
  const clip = mul(camera.projection, mul(camera.worldInverse, [...p, 1]));
  const { left, top, width, height } = camera.rect;
  return [left + ((clip[0] / clip[3] + 1) / 2) * width, top + ((1 - clip[1] / clip[3]) / 2) * height];
}

// The most pixels of the canvas within `radius` CSS pixels of any of the world points ps'
// projections whose colour is within 40 of rgb, at least `enough` of them if a frame
// within about a second has them. Several points along an arrow, not one: a direction
// glyph drawn at the same link may cover any one of them. Each look waits two animation
// frames, then reads the camera and the pixels in one task, so the projection is that of
// the frame read (the page may reframe the robot and rebuild its view as the meshes
// arrive, which a loaded machine delays).
function colourCount(page, ps, rgb, enough, radius = 4) {
  return page.evaluate(async ({ ps, rgb, enough, radius }) => {
    const mul = (m, v) => [0, 1, 2, 3].map((i) => m[i] * v[0] + m[4 + i] * v[1] + m[8 + i] * v[2] + m[12 + i] * v[3]);
    let n = 0;
    for (let look = 0; look < 30 && n < enough; look++) {
      await new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
      const camera = window.achdDemo.camera();
      const canvas = document.querySelector('#view canvas');
      const rect = canvas.getBoundingClientRect();
      const scale = canvas.width / rect.width;
      const copy = document.createElement('canvas');
      copy.width = canvas.width;
      copy.height = canvas.height;
      const ctx = copy.getContext('2d');
      ctx.drawImage(canvas, 0, 0);
      n = 0;
      for (const p of ps) {
        const clip = mul(camera.projection, mul(camera.worldInverse, [...p, 1]));
        const x = camera.rect.left + ((clip[0] / clip[3] + 1) / 2) * camera.rect.width;
        const y = camera.rect.top + ((1 - clip[1] / clip[3]) / 2) * camera.rect.height;
        const cx = Math.round((x - rect.left) * scale), cy = Math.round((y - rect.top) * scale), r = Math.round(radius * scale);
        const { data } = ctx.getImageData(cx - r, cy - r, 2 * r + 1, 2 * r + 1);
        let here = 0;
        for (let i = 0; i < data.length; i += 4) {
          if (Math.hypot(data[i] - rgb[0], data[i + 1] - rgb[1], data[i + 2] - rgb[2]) < 40) here++;
        }
        n = Math.max(n, here);
      }
    }
    return n;
  }, { ps, rgb, enough, radius });
}

test('the constraint wrench arrow and the joint torque bars', async (t) => {
  const session = await openPage({ hash: HASH });
  const { page, consoleErrors } = session;
  const robot = achd.loadURDF(ur5Text, { root: ur5.root, tip: ur5.tip });
  try {
    let held;
    await t.test('the arrow is alpha nu of the last solve, from the tip, at the robot\'s scale, drawn in its colour', async () => {
      // From the start pose at rest: where the page had got to when the test paused it
      // depends on the machine's load (0.09 s to 0.56 s of simulated time).
      await page.evaluate((q0) => window.achdDemo.setPose(q0), ur5.q0);
      held = await stepFrom(page);
      const { q, s, f, camera } = held;
      assert.equal(s.nu.length, 2);
      assert.deepEqual(f.wrench, [0, 0, s.nu[0], s.nu[1], 0, 0]);
      // joint_torques = ff - J^T (alpha nu), ff = 0: the drawn wrench is the constraint's.
      const J = robot.tipJacobian(q);
      s.joint_torques.forEach((tau, j) => {
        const expected = -J.reduce((sum, row, r) => sum + row[j] * f.wrench[r], 0);
        close(tau, expected, 1e-9, `joint ${j} torque`);
      });
      // Scale: half the reach (farthest link origin at the start pose) per weight.
      const reach = Math.max(0.2, ...robot.forwardKinematics(ur5.q0).map((l) => Math.hypot(...l.position)));
      const weight = G * chainMass(ur5Text, [ur5.root, ...robot.linkNames]);
      close(f.metersPerNewton, reach / (2 * weight), 1e-12, 'm per N');
      close(f.metersPerNewtonMeter, 1 / (2 * weight), 1e-12, 'm per N m');
      const tip = robot.forwardKinematics(s.q).at(-1).position;
      assert.ok(f.force.shown && f.moment.shown);
      for (let i = 0; i < 3; i++) {
        close(f.force.from[i], tip[i], 1e-9, `force arrow start ${i}`);
        close(f.force.to[i], tip[i] + f.wrench[i] * f.metersPerNewton, 1e-9, `force arrow end ${i}`);
        close(f.moment.to[i], tip[i] + f.wrench[3 + i] * f.metersPerNewtonMeter, 1e-9, `moment arrow end ${i}`);
      }
      close(f.force.length, Math.abs(s.nu[0]) * f.metersPerNewton, 1e-9, 'force arrow length');
      // On the canvas: the arrow's colour along its shaft (it is drawn over the robot; the
      // head takes at most half the length, so 10% to 50% of the way is shaft).
      const along = [0.1, 0.2, 0.3, 0.4, 0.5].map((s) => f.force.from.map((v, i) => v + s * (f.force.to[i] - v)));
      const count = await colourCount(page, along, FORCE_RGB, 10);
      assert.ok(count >= 10, `${count} force-coloured pixels around the arrow's shaft, at best`);
    });

    await t.test('its length follows nu; with every direction free there is none', async () => {
      await page.evaluate(() => window.achdDemo.setDirection('z', 4));
      const pushed = await stepFrom(page);
      close(pushed.f.force.length, Math.abs(pushed.s.nu[0]) * pushed.f.metersPerNewton, 1e-9, 'length under a 4 m/s² setpoint');
      close(pushed.f.force.length / held.f.force.length, Math.abs(pushed.s.nu[0] / held.s.nu[0]), 1e-9, 'length ratio = nu ratio');
      assert.ok(Math.abs(pushed.f.force.length - held.f.force.length) > 1e-3, 'the setpoint changed the arrow');
      await page.evaluate(() => {
        for (const d of ['x', 'y', 'z', 'rx', 'ry', 'rz']) window.achdDemo.setDirection(d, 'free');
      });
      const free = await stepFrom(page);
      assert.deepEqual(free.s.nu, []);
      assert.deepEqual(free.f.wrench, [0, 0, 0, 0, 0, 0]);
      assert.equal(free.f.force.shown, false);
      assert.equal(free.f.moment.shown, false);
    });

    await t.test('hovering the arrow shows its numbers', async () => {
      await page.evaluate(() => window.achdDemo.setDirection('z', 'hold'));
      const { s, f, camera } = await stepFrom(page);
      const middle = f.force.from.map((v, i) => (v + f.force.to[i]) / 2);
      const [x, y] = project(camera, middle);
      await page.mouse.move(x, y);
      const label = page.locator('#link-label');
      await label.waitFor({ state: 'visible' });
      const text = await label.textContent();
      assert.match(text, /constraint wrench α ν at wrist_3_link/);
      assert.ok(text.includes(`|f| = ${Math.abs(s.nu[0]).toPrecision(3)} N`), text);
      await page.mouse.move(5, 5);
    });

    await t.test('torque bars: red past a URDF effort limit, no scale without one', async () => {
      // The UR5 with a 5 N m limit at the shoulder lift and none at the last wrist joint.
      const text = ur5Text
        .replace(/(<joint name="shoulder_lift_joint"[\s\S]*?effort=")150"/, '$15"')
        .replace(/(<joint name="wrist_3_joint"[\s\S]*?effort=")28"/, '$10"');
      await page.evaluate(([text, root, tip]) => window.achdDemo.loadURDF(text, root, tip), [text, ur5.root, ur5.tip]);
      // At the index's pose (an own URDF starts elsewhere): the shoulder lifts about 36 N m.
      await page.evaluate((q0) => {
        window.achdDemo.setPose(q0);
        window.achdDemo.setDirection('z', 'hold');
        window.achdDemo.setDirection('rx', 'hold');
      }, ur5.q0);
      const { s, f } = await stepFrom(page);
      const bars = Object.fromEntries(f.torques.map((b) => [b.joint, b]));
      f.torques.forEach((b, j) => assert.equal(b.torque, s.joint_torques[j], b.joint));
      assert.equal(bars.shoulder_lift_joint.effort, 5);
      assert.ok(Math.abs(s.joint_torques[1]) > 5, `shoulder lift torque ${s.joint_torques[1]}`);
      assert.ok(Math.abs(s.joint_torques[2]) < 150, `elbow torque ${s.joint_torques[2]}`);
      const row = (joint) => page.locator(`.torque-row[data-joint="${joint}"]`);
      await frames(page);
      const look = (joint) => row(joint).evaluate((r) => ({
        over: r.classList.contains('torque-over'),
        bar: r.querySelector('.torque-bar') && getComputedStyle(r.querySelector('.torque-bar')).backgroundColor,
        transform: r.querySelector('.torque-bar')?.style.transform ?? null,
        unscaled: r.querySelector('.torque-track').classList.contains('torque-unscaled'),
      }));
      const shoulder = await look('shoulder_lift_joint');
      assert.equal(shoulder.over, true);
      assert.equal(shoulder.bar, 'rgb(217, 48, 42)');
      assert.equal(shoulder.transform, `scaleX(${Math.sign(s.joint_torques[1])})`, 'drawn to the end of the track');
      const elbow = await look('elbow_joint');
      assert.equal(elbow.over, false);
      assert.equal(elbow.bar, 'rgb(47, 111, 223)');
      close(Number(elbow.transform.match(/scaleX\((.*)\)/)[1]), s.joint_torques[2] / 150 / 1.1, 1e-6, 'elbow bar');
      const wrist = await look('wrist_3_joint');
      assert.equal(wrist.bar, null);
      assert.equal(wrist.unscaled, true);
      assert.equal(bars.wrist_3_joint.fraction, null);
    });

    assert.deepEqual(consoleErrors, []);
  } finally {
    robot.delete();
    await session.close();
  }
});
