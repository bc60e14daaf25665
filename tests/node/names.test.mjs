// One spelling per name: JS takes the scene files' values (explicit_euler,
// semi_implicit_euler, rk4), still takes the previous release's spellings with one
// console.warn each, names results as the solver does (joint_torques), and refuses
// options C++ would refuse, under their JS names.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAchd, robots } from './helpers.mjs';

let achd, kuka, entry;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
});

// assert.throws matching the Error's message alone (a regex given to assert.throws is
// matched against "Error: message").
function throwsMessage(fn, message) {
  assert.throws(fn, (e) => e instanceof Error && message.test(e.message), `expected ${message}`);
}

// Runs fn with console.warn recorded; returns the warnings.
function warnings(fn) {
  const seen = [], warn = console.warn;
  console.warn = (...args) => seen.push(args.join(' '));
  try {
    fn();
  } finally {
    console.warn = warn;
  }
  return seen;
}

// q after 20 steps of 1 ms from q0 with this integrator.
function run(integrator) {
  const sim = kuka.createSimulator({ integrator });
  sim.reset(entry.q0);
  sim.step(20);
  const q = Array.from(sim.q);
  sim.delete();
  return q;
}

test('the scene files\' integrator names are accepted, and give different runs', () => {
  const runs = {};
  const seen = warnings(() => {
    for (const name of ['explicit_euler', 'semi_implicit_euler', 'rk4']) runs[name] = run(name);
  });
  assert.deepEqual(seen, []);
  assert.notDeepEqual(runs.explicit_euler, runs.semi_implicit_euler);
  assert.notDeepEqual(runs.semi_implicit_euler, runs.rk4);
});

test('the old integrator spellings run the same integrator, with one deprecation warning each', () => {
  for (const [old, now] of [['euler', 'explicit_euler'], ['semi-implicit', 'semi_implicit_euler']]) {
    let q;
    const first = warnings(() => { q = run(old); });
    assert.equal(first.length, 1, old);
    assert.match(first[0], new RegExp(`integrator '${old}' is deprecated.*use '${now}'`));
    assert.deepEqual(q, run(now), `${old} runs ${now}`);
    assert.deepEqual(warnings(() => run(old)), [], `${old}: warned once only`);
  }
  throwsMessage(() => kuka.createSimulator({ integrator: 'toString' }),
    /^options\.integrator: expected 'explicit_euler' or 'semi_implicit_euler' or 'rk4' or 'dormand_prince' or 'implicit_euler', got 'toString'$/);
});

test('Simulator.joint_torques() is the result; jointTorques() is its deprecated alias', () => {
  const sim = kuka.createSimulator();
  sim.reset(entry.q0);
  sim.setDirection('z', 'hold');  // joint_torques = ff - J^T alpha nu: nonzero when held
  sim.step(2);
  const torques = sim.joint_torques();
  assert.equal(torques.length, 7);
  assert.ok(torques.some((x) => x !== 0));
  let alias;
  const seen = warnings(() => { alias = sim.jointTorques(); sim.jointTorques(); });
  assert.deepEqual(alias, torques);
  assert.equal(seen.length, 1);
  assert.match(seen[0], /Simulator\.jointTorques\(\) is deprecated.*Simulator\.joint_torques\(\)/);
  sim.delete();
});

test('options C++ refuses are refused by JS under the JS name (damping and frictionVelocity > 0)', () => {
  const c = { q: entry.q0, gravity: [0, 0, -9.81] };
  throwsMessage(() => kuka.solve(c, { policy: 'damped', damping: 0 }), /^options\.damping must be a finite number > 0, got 0$/);
  throwsMessage(() => kuka.solve(c, { frictionVelocity: 0 }), /^options\.frictionVelocity must be a finite number > 0, got 0$/);
  throwsMessage(() => kuka.createSolver({ damping: 0 }), /^options\.damping must be a finite number > 0, got 0$/);
  throwsMessage(() => kuka.rnea(entry.q0, entry.q0, entry.q0, { frictionVelocity: 0 }),
    /^options\.frictionVelocity must be a finite number > 0, got 0$/);
});
