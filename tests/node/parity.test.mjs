// robot.solve in wasm equals the native `achd solve` (the Release build) to the bit on
// every output (the CLI prints 17 significant digits, which parse back to the same
// double), for every robot in robots/ and for a few hundred random cases on random
// chains of up to 50 joints with well-conditioned constraints (coupling matrix condition
// number < 1e4): the documented claim (docs/design.md) for joint angles below 1e5 rad. Beyond 1e5 rad achd's
// sin_cos hands over to the C library's sin and cos, which differ between glibc and musl
// in the last bit: there the two agree to 1e-12. Fixtures are written by the native CLI
// during the run.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';

import { cliOptionFlags, loadAchd, nativeCli, pool, relativeError, robots, runCli, scratchDir } from './helpers.mjs';
import { conditionNumber, couplingMatrix } from './linear_algebra.mjs';
import { randomCase, randomChain, rng } from './random_chain.mjs';

// Relative error allowed between wasm and native: none where achd's own sin_cos runs.
const EXACT = 0;
const LIBM_TOLERANCE = 1e-12;
const VECTOR_OUTPUTS = ['qdd', 'constraint_torques', 'total_torques', 'nu', 'joint_torques', 'constraint_wrench'];

let achd, cli, scratch;
before(async () => {
  achd = await loadAchd();
  cli = nativeCli();
  scratch = scratchDir();
});
after(() => scratch.remove());

// Every output of the wasm result against the native one, within `tolerance` (relative);
// returns the worst error.
function assertSameResult(wasm, native, what, tolerance) {
  let worst = 0;
  for (const key of VECTOR_OUTPUTS) {
    assert.equal(wasm[key].length, native[key].length, `${what}: ${key} length`);
    const e = relativeError(wasm[key], native[key]);
    assert.ok(e <= tolerance, `${what}: ${key} relative error ${e}`);
    worst = Math.max(worst, e);
  }
  assert.equal(wasm.link_accelerations.length, native.link_accelerations.length, `${what}: link count`);
  const e = relativeError(wasm.link_accelerations.flat(), native.link_accelerations.flat());
  assert.ok(e <= tolerance, `${what}: link_accelerations relative error ${e}`);
  assert.equal(wasm.rank, native.rank, `${what}: rank`);
  const es = relativeError([wasm.sigma_min], [native.sigma_min]);
  assert.ok(es <= tolerance, `${what}: sigma_min relative error ${es}`);
  assert.equal(wasm.dropped.length, native.dropped.length, `${what}: dropped directions`);
  const ed = relativeError(wasm.dropped.flat(), native.dropped.flat());
  assert.ok(ed <= tolerance, `${what}: dropped relative error ${ed}`);
  assert.deepEqual(Object.keys(wasm).sort(), Object.keys(native).sort(), `${what}: field names`);
  return Math.max(worst, e, es, ed);
}

// Each job: a URDF file, root, tip, case, options -> compare in wasm and native.
async function runParity(jobs, tolerance = EXACT) {
  const natives = await pool(jobs.map((j, i) => () => {
    const casePath = scratch.write(`case${i}.json`, JSON.stringify(j.c));
    return runCli(cli, ['solve', j.urdf, '--root', j.root, '--tip', j.tip, '--case', casePath,
      ...cliOptionFlags(j.options)]);
  }));
  let worst = 0;
  jobs.forEach((j, i) => {
    const wasm = j.robot.solve(j.c, j.options);
    worst = Math.max(worst, assertSameResult(wasm, JSON.parse(natives[i]), j.what, tolerance));
  });
  return worst;
}

// Random alpha until K's condition number is below 1e4 (null if none in 20 tries).
function wellConditionedCase(r, robot, nc) {
  for (let attempt = 0; attempt < 20; ++attempt) {
    const c = randomCase(r, robot.numRates, robot.numLinks, nc);
    if (nc === 0) return c;
    const { cond } = conditionNumber(couplingMatrix(robot, c.q, c.alpha));
    if (cond < 1e4) return c;
  }
  return null;
}

const OPTION_SETS = [undefined, { convention: 'kdl' }, { policy: 'damped', damping: 1e-6 }];

// The chains (robots() lists them); the trees are compared in trees.test.mjs, with
// constraint blocks in place of the tip's alpha.
test('every chain robot in robots/index.json: wasm == native', async () => {
  const r = rng(7);
  const jobs = [];
  for (const entry of robots()) {
    const robot = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
    const base = { robot, urdf: entry.path, root: entry.root, tip: entry.tip };
    jobs.push({ ...base, c: { q: entry.q0, gravity: [0, 0, -9.81] }, what: `${entry.name} q0` });
    for (let nc = 0; nc <= Math.min(6, robot.numRates); ++nc) {
      const c = wellConditionedCase(r, robot, nc);
      if (c) jobs.push({ ...base, c, options: OPTION_SETS[nc % 3], what: `${entry.name} nc=${nc}` });
    }
  }
  const worst = await runParity(jobs);
  console.log(`robots: ${jobs.length} cases, worst relative error ${worst}`);
});

test('random chains up to 50 joints, a few hundred cases: wasm == native', async () => {
  const jobs = [];
  let rejected = 0;
  for (let seed = 1; seed <= 60; ++seed) {
    const r = rng(1000 + seed);
    const nj = seed <= 10 ? seed : 1 + Math.floor(r() * 50);
    const chain = randomChain(seed, nj);
    const robot = achd.loadURDF(chain.text, { root: chain.root, tip: chain.tip });
    assert.equal(robot.numRates, nj);
    const urdf = scratch.write(`chain${seed}.urdf`, chain.text);
    for (let k = 0; k < 5; ++k) {
      const nc = Math.floor(r() * (Math.min(6, nj) + 1));
      const c = wellConditionedCase(r, robot, nc);
      if (!c) { ++rejected; continue; }
      jobs.push({ robot, urdf, root: chain.root, tip: chain.tip, c, options: OPTION_SETS[k % 3],
        what: `chain seed ${seed} (${nj} joints) case ${k} nc=${nc}` });
    }
  }
  assert.ok(jobs.length >= 250, `only ${jobs.length} well-conditioned cases (${rejected} rejected)`);
  const worst = await runParity(jobs);
  console.log(`random chains: ${jobs.length} cases (${rejected} rejected), worst relative error ${worst}`);
});

test('joint angles beyond 1e5 rad (the C library\'s sin and cos): wasm within 1e-12 of native', async () => {
  const entry = robots().find((e) => e.name === 'kuka_lwr4');
  const robot = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
  const base = { robot, urdf: entry.path, root: entry.root, tip: entry.tip };
  const r = rng(31);
  const jobs = [];
  for (const scale of [1e5, 1e7, 1e9]) {
    const q = entry.q0.map((x) => x + scale * (1 + r()));
    jobs.push({ ...base, c: { q, gravity: [0, 0, -9.81], alpha: [[0, 0, 1, 0, 0, 0]], beta: [0] },
      what: `kuka_lwr4 |q| ~ ${scale}` });
  }
  const worst = await runParity(jobs, LIBM_TOLERANCE);
  console.log(`angles beyond 1e5 rad: worst relative error ${worst}`);
});

test('the coupling matrix the solver reports matches an independent J M^-1 J^T', () => {
  // sigma_min of the solver's K against the smallest eigenvalue of alpha^T J M^-1 J^T alpha.
  const r = rng(99);
  for (let seed = 200; seed < 210; ++seed) {
    const chain = randomChain(seed, 6 + (seed % 7));
    const robot = achd.loadURDF(chain.text, { root: chain.root, tip: chain.tip });
    const c = wellConditionedCase(r, robot, 3);
    assert.ok(c, `seed ${seed}: a well-conditioned case`);
    const { min } = conditionNumber(couplingMatrix(robot, c.q, c.alpha));
    const result = robot.solve(c);
    assert.ok(Math.abs(result.sigma_min - min) <= 1e-9 * Math.max(1, min), `seed ${seed}: ${result.sigma_min} vs ${min}`);
    robot.delete();
  }
});
