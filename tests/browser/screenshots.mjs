// Writes the documents' screenshots of the demo page, from Debian's Chromium:
//   docs/screenshots/default.png  the default robot as the page opens, swinging under gravity
//   docs/screenshots/held.png     the same robot with x, z, rx and ry held: the tip keeps its
//                                 height and tilt while gravity swings it along y
//   docs/screenshots/boundary.png README.md's UR5 link (z and rx held, y accelerated at
//                                 0.5 m/s²) after 12 simulated seconds: the tip has reached
//                                 the workspace boundary, the events notice says what the
//                                 simulator did about y
//   docs/screenshots/robot.png    the UR5 at its start pose, drawn from its URDF's visuals
//   docs/screenshots/sliders.png  the LWR posed with the joint sliders, paused, the pointer on a
//                                 link naming it
//   docs/screenshots/forces.png   the LWR with its tip held in place (x, y, z, rx, ry) and pushed
//                                 sideways at its elbow: the constraint force and moment arrows
//                                 at the tip (the pointer on the force showing its numbers) and
//                                 the joint torque bars against the URDF's effort limits
//   docs/screenshots/quadruped.png the floating quadruped standing on its four held feet under its
//                                 PD controller, pushed sideways at a hip: each foot's
//                                 constraint force arrow, the torque bars
//   docs/screenshots/humanoid.png  the floating humanoid standing on its two soles held in 6D under
//                                 the 5 Hz hold controller, after 3 simulated seconds
//   docs/screenshots/four_bar.png  the four-bar linkage of the list swinging on its loop joint
//                                 (coupler to rocker: the cyan ring and dot) after 0.6 simulated
//                                 seconds, the panel scrolled to the loops card
//   docs/screenshots/own_robot.png solo12 loaded whole from example-robot-data's solo_description
//                                 folder (two URDFs, an SRDF), floating, in the SRDF's standing
//                                 pose, on its four held feet (no meshes in that copy: stick
//                                 figure, the note names them); own_robot_form.png its load
//                                 form; own_robot_pose.png the same robot started again from
//                                 the SRDF's straight_standing pose with the pose list
// Usage: node tests/browser/screenshots.mjs [name...]   (after the wasm build; names: the
// files' without .png, all of them when none is given)
import { mkdir } from 'node:fs/promises';
import { fileURLToPath } from 'node:url';
import { openPage } from './launch.mjs';

const out = new URL('../../docs/screenshots/', import.meta.url);
await mkdir(out, { recursive: true });
const wanted = process.argv.slice(2);
const SHOTS = ['default', 'boundary', 'robot', 'sliders', 'forces', 'quadruped', 'humanoid', 'four_bar', 'own_robot'];
for (const name of wanted) {
  if (!SHOTS.includes(name) && name !== 'held') throw new Error(`no screenshot "${name}" (${[...SHOTS, 'held'].join(', ')})`);
}
// default.png and held.png come from one session.
const want = (name) => !wanted.length || wanted.includes(name) || (name === 'default' && wanted.includes('held'));

if (want('default')) {
const session = await openPage({ viewport: { width: 1400, height: 1000 } });
try {
  const { page } = session;
  await page.waitForTimeout(1500);
  await page.screenshot({ path: new URL('default.png', out).pathname });

  await page.evaluate(() => {
    const demo = window.achdDemo;
    demo.setDirection('x', 'hold');
    demo.setDirection('z', 'hold');
    demo.setDirection('rx', 'hold');
    demo.setDirection('ry', 'hold');
  });
  await page.waitForTimeout(2500);
  await page.screenshot({ path: new URL('held.png', out).pathname });
  if (session.consoleErrors.length) throw new Error(`console errors: ${session.consoleErrors.join('\n')}`);
} finally {
  await session.close();
}
}

if (want('boundary')) {
const boundary = await openPage({
  viewport: { width: 1400, height: 1000 },
  hash: '#robot=ur5&integrator=rk4&dt=0.001&effects=gravity,velocity_products,damping,friction,external_wrenches' +
    '&dirs=z:hold,rx:hold,y:0.5',
});
try {
  const { page } = boundary;
  // 12 s at once (a step that fails is shown on the page, and so is in the picture).
  await page.evaluate(() => {
    window.achdDemo.pause();
    try {
      window.achdDemo.step(12000);
    } catch {
      return;
    }
    window.achdDemo.play();
  });
  await page.waitForTimeout(1500);
  await page.screenshot({ path: new URL('boundary.png', out).pathname });
  if (boundary.consoleErrors.length) throw new Error(`console errors: ${boundary.consoleErrors.join('\n')}`);
} finally {
  await boundary.close();
}
}

if (want('robot')) {
const look = await openPage({ viewport: { width: 1400, height: 1000 }, hash: '#robot=ur5' });
try {
  const { page } = look;
  await page.evaluate(() => {
    window.achdDemo.pause();
    document.getElementById('btn-start-pose').click();
  });
  await page.waitForTimeout(800);
  await page.screenshot({ path: new URL('robot.png', out).pathname });
  if (look.consoleErrors.length) throw new Error(`console errors: ${look.consoleErrors.join('\n')}`);
} finally {
  await look.close();
}
}

if (want('sliders')) {
const posed = await openPage({ viewport: { width: 1400, height: 1000 } });
try {
  const { page } = posed;
  for (const [joint, value] of [['lwr_joint_1', '0.8'], ['lwr_joint_2', '0.9'], ['lwr_joint_4', '-1.4'], ['lwr_joint_6', '1.1']]) {
    await page.locator(`#joint-sliders input[data-joint="${joint}"]`).fill(value);
  }
  await page.waitForTimeout(500);
  // The pointer on the robot's middle link: the page names it.
  const box = await page.locator('#view').boundingBox();
  for (let y = box.y + box.height * 0.3; y < box.y + box.height * 0.8; y += 8) {
    await page.mouse.move(box.x + box.width / 2, y);
    if (await page.locator('#link-label').isVisible()) break;
  }
  await page.waitForTimeout(300);
  await page.screenshot({ path: new URL('sliders.png', out).pathname });
  if (posed.consoleErrors.length) throw new Error(`console errors: ${posed.consoleErrors.join('\n')}`);
} finally {
  await posed.close();
}
}

if (want('forces')) {
  const held = await openPage({
    viewport: { width: 1400, height: 1000 },
    hash: '#robot=kuka_lwr4&integrator=rk4&dt=0.001&dirs=x:hold,y:hold,z:hold,rx:hold,ry:hold',
  });
  try {
    const { page } = held;
    await page.evaluate(() => window.achdDemo.push('lwr_link_4', [0, 150, 0, 0, 0, 0]));
    await page.waitForTimeout(1500);
    const { f, camera } = await page.evaluate(() => {
      window.achdDemo.pause();
      return { f: window.achdDemo.forces(), camera: window.achdDemo.camera() };
    });
    // The pointer on the force arrow's middle: the page shows its numbers.
    const mul = (m, v) => [0, 1, 2, 3].map((i) => m[i] * v[0] + m[4 + i] * v[1] + m[8 + i] * v[2] + m[12 + i] * v[3]);
    const clip = mul(camera.projection, mul(camera.worldInverse, [...f.force.from.map((v, i) => (v + f.force.to[i]) / 2), 1]));
    const { left, top, width, height } = camera.rect;
    await page.mouse.move(left + ((clip[0] / clip[3] + 1) / 2) * width, top + ((1 - clip[1] / clip[3]) / 2) * height);
    await page.waitForTimeout(300);
    await page.screenshot({ path: new URL('forces.png', out).pathname });
    if (held.consoleErrors.length) throw new Error(`console errors: ${held.consoleErrors.join('\n')}`);
  } finally {
    await held.close();
  }
}

if (want('quadruped')) {
  const standing = await openPage({ viewport: { width: 1400, height: 1000 }, hash: '#robot=quadruped&integrator=rk4&dt=0.001' });
  try {
    const { page } = standing;
    await page.evaluate(() => window.achdDemo.push('lf_hip', [0, 8, 0, 0, 0, 0]));
    await page.waitForTimeout(1500);
    await page.evaluate(() => window.achdDemo.pause());
    await page.screenshot({ path: new URL('quadruped.png', out).pathname });
    if (standing.consoleErrors.length) throw new Error(`console errors: ${standing.consoleErrors.join('\n')}`);
  } finally {
    await standing.close();
  }
}

if (want('humanoid')) {
  const standing = await openPage({ viewport: { width: 1400, height: 1000 }, hash: '#robot=humanoid' });
  try {
    const { page } = standing;
    await page.evaluate(() => {
      window.achdDemo.pause();
      window.achdDemo.step(3000);
      window.achdDemo.play();
    });
    await page.waitForTimeout(1000);
    await page.evaluate(() => window.achdDemo.pause());
    await page.screenshot({ path: new URL('humanoid.png', out).pathname });
    if (standing.consoleErrors.length) throw new Error(`console errors: ${standing.consoleErrors.join('\n')}`);
  } finally {
    await standing.close();
  }
}

if (want('four_bar')) {
  const linkage = await openPage({ viewport: { width: 1400, height: 1000 }, hash: '#robot=four_bar' });
  try {
    const { page } = linkage;
    await page.evaluate(() => {
      window.achdDemo.pause();
      window.achdDemo.step(600);
    });
    // The panel scrolled to the loops card, beside the view.
    await page.waitForTimeout(500);
    await page.locator('#loop-list').scrollIntoViewIfNeeded();
    await page.screenshot({ path: new URL('four_bar.png', out).pathname });
    if (linkage.consoleErrors.length) throw new Error(`console errors: ${linkage.consoleErrors.join('\n')}`);
  } finally {
    await linkage.close();
  }
}

if (want('own_robot')) {
  const own = await openPage({ viewport: { width: 1400, height: 1000 } });
  try {
    const { page } = own;
    const folder = new URL('../../robots/example-robot-data/solo_description/', import.meta.url);
    await page.locator('#urdf-folder').setInputFiles(fileURLToPath(folder));
    await page.locator('#urdf-chain').waitFor({ state: 'visible' });
    const urdfs = await page.locator('#urdf-pick option').allTextContents();
    await page.locator('#urdf-pick').selectOption({ index: urdfs.findIndex((p) => p.endsWith('solo12.urdf')) });
    await page.waitForFunction(() => document.getElementById('urdf-chain-file').textContent.includes('solo12.urdf'));
    await page.locator('#urdf-base').selectOption('floating');
    // The form as filled in, then the robot standing.
    await page.screenshot({ path: new URL('own_robot_form.png', out).pathname, clip: { x: 0, y: 0, width: 1400, height: 200 } });
    await page.locator('#urdf-chain button[type=submit]').click();
    await page.locator('#urdf-chain').waitFor({ state: 'hidden' });
    await page.waitForTimeout(2500);
    await page.evaluate(() => window.achdDemo.pause());
    await page.screenshot({ path: new URL('own_robot.png', out).pathname });
    // Then started again from the SRDF's other pose with the pose list, the list in view.
    await page.locator('#pose-select').selectOption('straight_standing');
    await page.evaluate(() => window.achdDemo.play());
    await page.waitForTimeout(1500);
    await page.evaluate(() => window.achdDemo.pause());
    await page.locator('#pose-select').scrollIntoViewIfNeeded();
    await page.waitForTimeout(300);
    await page.screenshot({ path: new URL('own_robot_pose.png', out).pathname });
    if (own.consoleErrors.length) throw new Error(`console errors: ${own.consoleErrors.join('\n')}`);
  } finally {
    await own.close();
  }
}
