// The accuracy panel studies an own URDF, in Chromium: a three-joint arm
// written here, picked with the file input, is studied by the panel: every run has a
// finite cost (positive for a stable run: its timing is not lost below the timer's
// resolution, where a cost of 0 once sent the plot's log axis looping from -Infinity),
// every stable run a finite error, RK4's error falls as its step shrinks,
// the reference's self-check is finite and below RK4's smallest-step error; no console
// errors. The study runs while the page gets no animation frames (as a hidden page
// does), and the page steps on once they are back.
import assert from 'node:assert/strict';
import test from 'node:test';
import { openPage } from './launch.mjs';

// A three-joint arm (not a robot of robots/): a yaw joint, then two pitch joints, 0.4 m
// and 0.3 m links of 2 kg and 1 kg, joint damping, Coulomb friction on the last joint.
const link = (name, mass, length) => `
  <link name="${name}">
    <inertial><origin xyz="0 0 ${length / 2}"/><mass value="${mass}"/>
      <inertia ixx="${(mass * length * length) / 12}" iyy="${(mass * length * length) / 12}" izz="0.002" ixy="0" ixz="0" iyz="0"/></inertial>
  </link>`;
const joint = (name, parent, child, axis, z, friction) => `
  <joint name="${name}" type="revolute"><parent link="${parent}"/><child link="${child}"/>
    <origin xyz="0 0 ${z}"/><axis xyz="${axis}"/>
    <limit lower="-2.5" upper="2.5" effort="50" velocity="3"/><dynamics damping="0.1" friction="${friction}"/></joint>`;
const OWN_URDF = `<?xml version="1.0"?>
<robot name="three_joint_arm">
  <link name="base"/>${link('turret', 3, 0.1)}${link('upper', 2, 0.4)}${link('fore', 1, 0.3)}
  ${joint('yaw', 'base', 'turret', '0 0 1', 0, 0)}
  ${joint('shoulder', 'turret', 'upper', '0 1 0', 0.1, 0)}
  ${joint('elbow', 'upper', 'fore', '0 1 0', 0.4, 0.05)}
</robot>
`;

// The panel's table of runs: [{integrator, step, error (rad, Infinity when unstable),
// usPerStep, cost}], and its status line.
const studied = (page) => page.evaluate(() => ({
  status: document.querySelector('.accuracy-status').textContent,
  circles: document.querySelectorAll('.accuracy-live svg circle').length,
  runs: [...document.querySelectorAll('.accuracy-live-table tr')].slice(1).map((tr) => {
    const [integrator, step, error, usPerStep, cost] = [...tr.cells].map((c) => c.textContent);
    return { integrator, step, error: error === 'unstable' ? Infinity : Number(error), usPerStep: Number(usPerStep), cost: Number(cost) };
  }),
}));

async function runStudy(page) {
  await page.locator('.accuracy-run').click();
  await page.waitForFunction(() => {
    const status = document.querySelector('.accuracy-status').textContent;
    return status && !/…$/.test(status);
  }, null, { polling: 100, timeout: 120000 });
  return studied(page);
}

test('the accuracy panel studies an own URDF', async (t) => {
  const session = await openPage();
  const { page, consoleErrors } = session;
  try {
    await page.setInputFiles('#urdf-file', { name: 'three_joint_arm.urdf', mimeType: 'application/xml', buffer: Buffer.from(OWN_URDF) });
    await page.locator('#urdf-chain button[type="submit"]').click();
    await page.waitForFunction(() => window.achdDemo.state().robot === 'custom');
    const source = await page.evaluate(() => window.achdDemo.robotSource());
    assert.equal(source.text, OWN_URDF);
    assert.equal(source.tip, 'fore');

    await t.test('with no animation frame (a hidden page gets none), every run is finite, RK4 converges', async () => {
      // Frames are withheld from the page, the page's own loop included, and given back after.
      await page.evaluate(() => {
        const withheld = [];
        window.achdFrames = { request: window.requestAnimationFrame, withheld };
        window.requestAnimationFrame = (callback) => withheld.push(callback);
      });
      const { status, circles, runs } = await runStudy(page);
      const withheld = await page.evaluate(() => {
        const { request, withheld } = window.achdFrames;
        window.requestAnimationFrame = request;
        for (const callback of withheld) request(callback);
        return withheld.length;
      });
      assert.ok(withheld >= 1, 'no frame was asked for while they were withheld');
      assert.match(status, /^three_joint_arm\.urdf: reference self-check \(halving its step\) (\S+) rad; unstable: .*; study took/);
      const selfError = Number(/self-check \(halving its step\) (\S+) rad/.exec(status)[1]);
      assert.ok(Number.isFinite(selfError) && selfError >= 0, `self-check ${selfError}`);
      const integrators = await page.evaluate(() => [...document.getElementById('integrator').options].map((o) => o.value));
      // 5 steps per fixed-step integrator, 4 tolerances for the adaptive one.
      assert.equal(runs.length, integrators.filter((n) => n !== 'dormand_prince').length * 5 + 4);
      for (const r of runs) {
        // A diverged run's time per step taken may be below the timer's resolution.
        const least = Number.isFinite(r.error) ? Number.MIN_VALUE : 0;
        assert.ok(Number.isFinite(r.cost) && r.cost >= least, `${r.integrator} at ${r.step}: cost ${r.cost}`);
        assert.ok(Number.isFinite(r.usPerStep) && r.usPerStep >= 0, `${r.integrator} at ${r.step}: ${r.usPerStep} µs/step`);
        assert.ok(r.error === Infinity || (Number.isFinite(r.error) && r.error >= 0), `${r.integrator} at ${r.step}: error ${r.error}`);
      }
      const rk4 = runs.filter((r) => r.integrator === 'RK4');
      assert.deepEqual(rk4.map((r) => r.step), ['10 ms', '5 ms', '2 ms', '1 ms', '0.5 ms']);
      for (let i = 1; i < rk4.length; i++) {
        assert.ok(rk4[i].error < rk4[i - 1].error, `RK4 error at ${rk4[i].step} ${rk4[i].error}, at ${rk4[i - 1].step} ${rk4[i - 1].error}`);
      }
      assert.ok(selfError < rk4.at(-1).error, `self-check ${selfError} against RK4 at 0.5 ms ${rk4.at(-1).error}`);
      assert.ok(circles >= runs.filter((r) => Number.isFinite(r.error)).length, `${circles} points plotted`);
      t.diagnostic(status);
      t.diagnostic(`RK4 errors ${rk4.map((r) => `${r.step}: ${r.error}`).join(', ')}; self-check ${selfError}`);
    });

    await t.test('with its frames back, the page steps on', async () => {
      const t0 = (await page.evaluate(() => window.achdDemo.state())).t;
      await page.waitForFunction((t0) => window.achdDemo.state().t > t0 + 0.1, t0);
    });

    assert.deepEqual(consoleErrors, []);
  } finally {
    await session.close();
  }
});
