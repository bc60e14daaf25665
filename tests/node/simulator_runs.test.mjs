// Simulator.step on runs that used to go wrong: step counts beyond the wasm
// export's int (2**32 + 3 ran 3 steps, 2**31 none), the progress callback that reports
// and stops a long run, counts that are not safe integers, and a failed step that keeps
// the last good (finite) state and names the step, the time and the directions.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';

import { loadAchd, repo } from './helpers.mjs';

let achd, planar2, ur5;
before(async () => {
  achd = await loadAchd();
  const load = (file, root, tip) => achd.loadURDF(readFileSync(join(repo, 'robots', file), 'utf8'), { root, tip });
  planar2 = load('planar2.urdf', 'base_link', 'link2');
  ur5 = load('ur5.urdf', 'base_link', 'wrist_3_link');
});
after(() => { planar2.delete(); ur5.delete(); });

function swing() {
  const sim = planar2.createSimulator({ integrator: 'semi_implicit_euler' });
  sim.reset([0.4, 0.9]);
  return sim;
}

test('step(2**32 + 3) and step(2**31) run in full: the progress callback sees the whole count and stops them', () => {
  const sim = swing();
  try {
    for (const n of [2 ** 32 + 3, 2 ** 31]) {
      sim.reset([0.4, 0.9]);
      const calls = [];
      const done = sim.step(n, 1e-3, { progressInterval: 1000, onProgress: (stepsDone, total) => {
        calls.push([stepsDone, total]);
        return calls.length < 3;  // stop after the third report
      } });
      assert.deepEqual(calls, [[1000, n], [2000, n], [3000, n]]);
      assert.equal(done, 3000);
      assert.equal(sim.stepsTaken, 3000);
      assert.equal(sim.t, 3000 * 1e-3);
    }
  } finally {
    sim.delete();
  }
});

test('without a callback every step runs; with one it is called after each interval and after the last step', () => {
  const sim = swing();
  try {
    assert.equal(sim.step(2500, 1e-3), 2500);
    assert.equal(sim.stepsTaken, 2500);
    assert.equal(sim.t, 2500 * 1e-3);  // t = steps * dt exactly (a running sum gave 2.4999999999998357)
    const calls = [];
    assert.equal(sim.step(2500, 1e-3, { onProgress: (d, n) => { calls.push(d); } }), 2500);
    assert.deepEqual(calls, [2500]);  // default interval 10000: only the end
    calls.length = 0;
    sim.step(25, 1e-3, { progressInterval: 10, onProgress: (d) => { calls.push(d); } });
    assert.deepEqual(calls, [10, 20, 25]);
    assert.equal(sim.stepsTaken, 5025);
  } finally {
    sim.delete();
  }
});

test('a step count that is not a safe integer >= 0, or bad step options, throw naming the argument', () => {
  const sim = swing();
  try {
    for (const n of [2 ** 53, 1.5, -1, NaN, '10'])
      assert.throws(() => sim.step(n, 1e-3), /step: n must be an integer >= 0 and <= 2\^53 - 1, got /);
    assert.throws(() => sim.step(10, 1e-3, { onProgress: 1 }), /onProgress must be a function/);
    assert.throws(() => sim.step(10, 1e-3, { progressInterval: 0 }), /progressInterval must be an integer >= 1/);
    assert.throws(() => sim.step(10, 1e-3, { every: 5 }), /step options: unknown field 'every'/);
    assert.equal(sim.stepsTaken, 0);
  } finally {
    sim.delete();
  }
});

// The UR5 holding z and rx while its tip accelerates along y at 0.5 m/s^2 blows up at
// t = 2.184 s under the truncate policy (RK4, 1 ms; 2.183 s while friction smoothing was
// raised with dt; the default variable_damping runs on: direction_events.test.mjs).
// Before: Error('beta[0] is not finite').
test('a failed step names step, time, directions and cause; the state stays finite at the last good step', () => {
  const sim = ur5.createSimulator({ integrator: 'rk4', policy: 'truncate' });
  try {
    sim.reset([0.2, -1.0, 1.2, -1.5, -1.4, 0.3]);
    sim.setDirection('z', 'hold');
    sim.setDirection('rx', 'hold');
    sim.setDirection('y', 0.5);
    assert.throws(() => sim.step(5000, 1e-3),
      (e) => e instanceof Error && /^step 2185 from t = 2\.184 s to 2\.185 s \(rk4 stage \d of 4; held: z, rx; accelerated: y = 0\.5 m\/s\^2\) failed: .+; the state stays at t = 2\.184 s$/.test(e.message) &&
        !e.message.includes('beta['));
    assert.equal(sim.stepsTaken, 2184);
    assert.equal(sim.t, 2184 * 1e-3);
    for (const v of [...sim.q, ...sim.qd, ...sim.nu(), ...sim.qdd()]) assert.ok(Number.isFinite(v), `${v}`);
  } finally {
    sim.delete();
  }
});
