// Callbacks cannot pull the object out from under the call that runs them: a
// Simulator.step whose onProgress deletes or resets the simulator stops with an Error
// saying what the callback did (and never runs the freed pointer, so a simulator created
// in the callback is not stepped by the old run); a nested step() is refused; changing
// directions or creating other objects in the callback is fine. The same holds for the
// caller's code that reading an input runs (a Proxy's trap): an object deleted by it is
// reported as deleted, never used.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAchd, robots } from './helpers.mjs';

let achd, entry, robot;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  robot = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
});

function started() {
  const sim = robot.createSimulator();
  sim.reset(entry.q0);
  return sim;
}

test('deleting the simulator in onProgress stops step() with an Error; a simulator made there is not stepped', () => {
  const sim = started();
  let other = null;
  assert.throws(() => sim.step(50, 1e-3, { progressInterval: 10, onProgress: () => {
    sim.delete();
    other = started();  // may take the freed memory
  } }), /^Error: Simulator\.step: the onProgress callback deleted the simulator \(after 10 of 50 steps\)$/);
  assert.equal(sim.deleted, true);
  assert.equal(other.t, 0, 'the new simulator was never stepped by the old run');
  assert.equal(other.stepsTaken, 0);
  assert.deepEqual(Array.from(other.q), entry.q0);
  other.delete();
});

test('resetting the simulator in onProgress stops step() with an Error; the reset state stays', () => {
  const sim = started();
  assert.throws(() => sim.step(50, 1e-3, { progressInterval: 10, onProgress: (done) => {
    if (done === 20) sim.reset(entry.q0);
  } }), /the onProgress callback reset the simulator \(after 20 of 50 steps\); the run stops there/);
  assert.equal(sim.t, 0);
  assert.equal(sim.stepsTaken, 0);
  assert.equal(sim.step(5), 5, 'the simulator steps again afterwards');
  sim.delete();
});

test('step() inside its own onProgress is refused', () => {
  const sim = started();
  assert.throws(() => sim.step(20, 1e-3, { progressInterval: 10, onProgress: () => { sim.step(1); } }),
    /Simulator\.step: called from its own onProgress callback/);
  assert.equal(sim.stepsTaken, 10, 'the outer run stopped where the callback threw');
  assert.equal(sim.step(3), 3, 'and the simulator is not left marked as stepping');
  sim.delete();
});

test('creating, using and deleting other objects in onProgress leaves the run as without them', () => {
  const plain = started();
  plain.step(40);
  const expected = Array.from(plain.q);
  plain.delete();
  const sim = started();
  const done = sim.step(40, 1e-3, { progressInterval: 10, onProgress: () => {
    const r = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
    const s = r.createSimulator();
    s.step(3);
    const view = s.q;
    s.delete();
    view[0] = 1e300;  // a stale view of the other simulator: harmless
    r.delete();
  } });
  assert.equal(done, 40);
  assert.deepEqual(Array.from(sim.q), expected);
  sim.delete();
});

test('a direction changed in onProgress takes effect in the rest of the run', () => {
  const sim = started();
  sim.step(20, 1e-3, { progressInterval: 10, onProgress: (d) => { if (d === 10) sim.setDirection('z', 'hold'); } });
  assert.equal(sim.directionMode('z'), 'hold');
  assert.equal(sim.stepsTaken, 20);
  sim.delete();
});

test('an input whose Proxy trap deletes the object gives "has been deleted", not a freed pointer', () => {
  const sim = started();
  const q = new Proxy(entry.q0.slice(), {
    getOwnPropertyDescriptor(target, key) {
      if (key === '3' && !sim.deleted) sim.delete();
      return Reflect.getOwnPropertyDescriptor(target, key);
    },
  });
  assert.throws(() => sim.reset(q), /^Error: Simulator has been deleted$/);
  const r = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
  const c = { q: new Proxy(entry.q0.slice(), { getOwnPropertyDescriptor(target, key) {
    if (key === '2' && !r.deleted) r.delete();
    return Reflect.getOwnPropertyDescriptor(target, key);
  } }), gravity: [0, 0, -9.81] };
  assert.throws(() => r.solve(c), /^Error: Robot has been deleted$/);
  // and the module goes on
  assert.equal(robot.solve({ q: entry.q0, gravity: [0, 0, -9.81] }).qdd.length, 7);
});
