// The JS simulator's directions on any links and its joint PD controller: the floating
// quadruped stands on its four feet (each held through setDirection(name, 'hold', foot),
// the PD controller given to createSimulator), its feet carrying its weight (the URDF's
// masses, read here from the file); wasm steps equal the native simulator's (the scene
// test in simulator.test.mjs); bad links, a tree's missing tip and gains on the free joint
// are Errors naming them, and the simulator keeps stepping after each.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { before, test } from 'node:test';

import { loadAchd, repo } from './helpers.mjs';

let achd, quadruped, entry, text;
before(async () => {
  achd = await loadAchd();
  entry = JSON.parse(readFileSync(join(repo, 'robots/index.json'), 'utf8')).robots.find((r) => r.name === 'quadruped');
  text = readFileSync(join(repo, 'robots/quadruped.urdf'), 'utf8');
  quadruped = achd.loadURDF(text, { root: entry.root, floating: true });
});

const FEET = ['lf_foot', 'rf_foot', 'lh_foot', 'rh_foot'];
const standing = () => [0, 0, 0.3, 0, 0, 0, 1, ...entry.q0];

test('the floating quadruped stands 2 s on its held feet under the PD controller', (t) => {
  const sim = quadruped.createSimulator({ integrator: 'rk4', jointControl: { target: standing(), kp: 30, kd: 0.5 } });
  try {
    assert.equal(sim.jointControlOn, true);
    sim.reset(standing());  // keeps the controller
    for (const foot of FEET) for (const d of ['x', 'y', 'z']) sim.setDirection(d, 'hold', foot);
    assert.deepEqual(sim.directionLinks(), FEET.map((link) => ({ link, directions: 3 })));
    assert.equal(sim.directionMode('z', 'rh_foot'), 'hold');
    assert.equal(sim.directionMode('rz', 'rh_foot'), 'free');
    let worst = 0, sag = 0;
    for (let s = 0; s < 2000; ++s) {
      sim.step(1, 1e-3);
      for (const foot of FEET) {
        const r = sim.residuals(foot);
        assert.equal(r.rx, null);
        worst = Math.max(worst, Math.abs(r.x), Math.abs(r.y), Math.abs(r.z));
      }
      sag = Math.max(sag, Math.abs(sim.q[2] - 0.3));
    }
    t.diagnostic(`feet residual ${worst.toExponential(2)} m, trunk height change ${sag.toExponential(2)} m`);
    assert.ok(worst <= 1e-9, `feet residual ${worst}`);
    assert.ok(sag <= 0.01, `trunk height change ${sag}`);
    assert.equal(sim.nu().length, 12);
    // At rest on its feet, they push down on their holds with the robot's weight.
    const mass = [...text.matchAll(/<mass value="([^"]+)"/g)].reduce((m, x) => m + Number(x[1]), 0);
    sim.step(3000, 1e-3);
    const wrenches = sim.constraintWrenches();
    assert.deepEqual(Object.keys(wrenches), FEET);
    const push = FEET.reduce((sum, foot) => sum + wrenches[foot][2], 0);
    assert.ok(Math.abs(push + mass * 9.81) <= 1e-6 * mass * 9.81, `feet push ${push} N, weight ${mass * 9.81} N`);
  } finally {
    sim.delete();
  }
});

test('a held point off a foot and a freed direction: the point stays, the block shrinks', () => {
  const sim = quadruped.createSimulator({ integrator: 'rk4' });
  try {
    sim.reset(standing());
    sim.setJointControl({ kp: 30, kd: 0.5 });  // toward the current q
    sim.setDirectionPoint('lf_foot', [0, 0, -0.02]);
    for (const d of ['x', 'y', 'z']) sim.setDirection(d, 'hold', 'lf_foot');
    sim.setDirection('z', 'hold', 'rh_foot');
    sim.step(500, 1e-3);
    const r = sim.residuals('lf_foot');
    assert.ok(Math.max(Math.abs(r.x), Math.abs(r.y), Math.abs(r.z)) <= 1e-9, JSON.stringify(r));
    sim.setDirection('z', 'free', 'rh_foot');
    assert.deepEqual(sim.directionLinks(), [{ link: 'lf_foot', directions: 3 }, { link: 'rh_foot', directions: 0 }]);
    sim.step(1, 1e-3);
    assert.equal(sim.nu().length, 3);
  } finally {
    sim.delete();
  }
});

test('errors name the link, the tree and the free joint; the simulator keeps stepping', () => {
  const sim = quadruped.createSimulator({ integrator: 'rk4' });
  try {
    sim.reset(standing());
    assert.throws(() => sim.setDirection('z', 'hold'), /the model is a tree \(loaded without a tip\)/);
    assert.throws(() => sim.residuals(), /the model is a tree/);
    assert.throws(() => sim.setDirection('z', 'hold', 'paw'), /setDirection: unknown link "paw"/);
    assert.throws(() => sim.setDirection('w', 'hold', 'lf_foot'), /setDirection: unknown direction 'w'/);
    assert.throws(() => sim.setDirectionPoint('lf_foot', [0, NaN, 0]), /point/);
    const kp = new Array(18).fill(1);
    assert.throws(() => sim.setJointControl({ kp }), /kp\[0\] of joint 'trunk' \(the floating base's free joint, not actuated\) must be 0/);
    assert.throws(() => quadruped.createSimulator({ jointControl: { target: standing(), kp: -1 } }),
      /kp of joint 'lf_haa' must be finite and >= 0, got -1/);
    assert.throws(() => quadruped.createSimulator({ jointControl: { kp: 1 } }), /options.jointControl.target is required/);
    assert.equal(sim.jointControlOn, false);
    sim.step(10, 1e-3);
    assert.ok(Number.isFinite(sim.q[2]) && sim.q[2] < 0.3, 'it falls, unheld');
  } finally {
    sim.delete();
  }
});
