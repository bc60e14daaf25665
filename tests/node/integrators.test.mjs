// The adaptive 'dormand_prince' integrator (the simulator's default) and 'implicit_euler'
// from JS: options rtol and atol, the substep counters, and the same run as the native
// `achd simulate` with the same options (end state and substep counts).
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';

import { loadAchd, nativeCli, relativeError, repo, runCli, scratchDir } from './helpers.mjs';

const SCENE = join(repo, 'robots/scenes/kuka_lwr4_hold_z_rx.json');
const scene = JSON.parse(readFileSync(SCENE, 'utf8'));
const camelCase = (name) => name.replace(/_([a-z])/g, (_, ch) => ch.toUpperCase());

let achd, kuka;
before(async () => {
  achd = await loadAchd();
  kuka = achd.loadURDF(readFileSync(join(repo, scene.urdf), 'utf8'), { root: scene.root, tip: scene.tip });
});
after(() => kuka.delete());

// The damped LWR scene holding z and rx, as the native start_scene sets it up.
function start(options = {}) {
  const effects = Object.fromEntries(Object.entries(scene.effects).map(([k, on]) => [camelCase(k), on]));
  const sim = kuka.createSimulator({ effects, gravity: scene.gravity, ...options });
  sim.reset(scene.q0, scene.qd0);
  for (const [name, mode] of Object.entries(scene.directions)) sim.setDirection(name, mode);
  return sim;
}

test('the defaults: dormand_prince at rtol 1e-9, atol 1e-11, Baumgarte 100 rad/s (from C++)', () => {
  const d = achd.constants.simulator_options;
  assert.equal(d.integrator, 'dormand_prince');
  assert.equal(d.rtol, 1e-9);
  assert.equal(d.atol, 1e-11);
  assert.equal(d.stabilisation_frequency, 100);
  assert.deepEqual(achd.constants.integrators, ['explicit_euler', 'semi_implicit_euler', 'rk4', 'dormand_prince', 'implicit_euler']);
});

test('substeps and rejectedSubsteps count the adaptive work; reset() clears them; a fixed step takes one', () => {
  const sim = start();
  try {
    assert.equal(sim.substeps, 0);
    sim.step(200, 1e-3);
    assert.equal(sim.t, 200 * 1e-3);
    assert.ok(sim.substeps > 200, `${sim.substeps}`);  // stiff friction: more than one per ms
    assert.ok(sim.rejectedSubsteps > 0, `${sim.rejectedSubsteps}`);
    sim.reset(scene.q0);
    assert.equal(sim.substeps, 0);
    assert.equal(sim.rejectedSubsteps, 0);
  } finally {
    sim.delete();
  }
  const implicit = start({ integrator: 'implicit_euler' });
  try {
    implicit.step(200, 1e-3);
    assert.equal(implicit.substeps, 200);
    assert.equal(implicit.rejectedSubsteps, 0);
    for (const v of implicit.q) assert.ok(Number.isFinite(v));
  } finally {
    implicit.delete();
  }
});

test('rtol and atol must be finite and > 0; stabilisationFrequency > 0 (0 no longer means "from dt")', () => {
  for (const [options, pattern] of [[{ rtol: 0 }, /options\.rtol must be/], [{ atol: -1 }, /options\.atol must be/],
    [{ rtol: NaN }, /options\.rtol must be/], [{ stabilisationFrequency: 0 }, /options\.stabilisationFrequency must be/]])
    assert.throws(() => kuka.createSimulator(options), pattern);
});

test('the same run as achd simulate --rtol 1e-6 --atol 1e-8: end state within 1e-9, the same substep counts (stiff ones too: the friction near rest is detected stiff)', async () => {
  const sim = start({ rtol: 1e-6, atol: 1e-8 });
  const tmp = scratchDir();
  try {
    const steps = Math.round(scene.duration / scene.dt);
    sim.step(steps, scene.dt);
    const csv = join(tmp.dir, 'traj.csv');
    const summary = JSON.parse(await runCli(nativeCli(), ['simulate', SCENE, '--out', csv, '--rtol', '1e-6', '--atol', '1e-8']));
    const last = readFileSync(csv, 'utf8').trim().split('\n').at(-1).split(',').map(Number);
    const nj = kuka.numRates;
    assert.equal(sim.t, last[0]);
    assert.ok(relativeError(Array.from(sim.q), last.slice(1, 1 + nj)) <= 1e-9);
    assert.ok(relativeError(Array.from(sim.qd), last.slice(1 + nj, 1 + 2 * nj)) <= 1e-9);
    assert.equal(sim.substeps, summary.substeps);
    assert.equal(sim.rejectedSubsteps, summary.rejected_substeps);
    assert.ok(summary.stiff_substeps > 0);
    assert.equal(sim.stiffSubsteps, summary.stiff_substeps);
  } finally {
    tmp.remove();
    sim.delete();
  }
});
