#!/usr/bin/env node
// ns per hybrid-dynamics solve: the zero-copy solver of the wasm module in Node against
// the native CLI's `achd bench` on the same robot and case, in the same run. Both sides do
// the same work: the zero-copy solver writes every link's acceleration (its
// link_accelerations view), so the native side runs with `--link-outputs`, which computes
// them too (`achd bench` alone computes none, Data::set_link_outputs({})).
//
//   node bench/wasm_vs_native.mjs          (native CLI: $ACHD_CLI, else build/achd)
//
// The cases: the KUKA LWR 4 without constraints and with its tip held in 6D, the 50-link
// chain with its tip held in 6D, and the quadruped on a floating base holding its four
// feet in 3D (m = 12).
//
// Prints {"cases": [{"name", "wasm_ns", "native_ns", "ratio"}]}, ratio = wasm / native.
// wasm: 2e4 warm-up calls (V8 tiers wasm up late). Then REPEATS rounds, each timing
// ~10 ms of wasm solves and one `achd bench --clock wall` round of the same length, one
// after the other, so that the shared machine's load changes hit both alike. Both sides
// use the wall clock (Node has no per-thread CPU clock, and process.cpuUsage also counts
// V8's compiler and GC threads). Reported: the medians of each side and the median of
// the per-round ratios.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';

import { loadAchd, nativeCli, repo, robots, scratchDir } from '../tests/node/helpers.mjs';

const WARMUP = 2e4;
const REPEATS = 31;
const TARGET_NS_PER_REPEAT = 1e7;  // ~10 ms per timed repeat

// Six independent constraints: the tip's full acceleration is prescribed.
const ALL_SIX = [0, 1, 2, 3, 4, 5].map((k) => [0, 1, 2, 3, 4, 5].map((r) => (r === k ? 1 : 0)));

const XYZ = ALL_SIX.slice(0, 3);

// nc columns on a chain's tip, or on a floating base (entry.floating) its 3D blocks on the
// links of entry.constraints, the root 0.3 m up.
function benchCase(entry, nc) {
  const nj = entry.q0.length + (entry.floating ? 6 : 0);
  const c = {
    q: entry.floating ? [0, 0, 0.3, 0, 0, 0, 1, ...entry.q0] : entry.q0,
    qd: Array.from({ length: nj }, (_, i) => 0.3 * Math.sin(i + 1)),
    ff_torques: Array.from({ length: nj }, (_, i) => 0.5 * Math.cos(i + 1)),
    gravity: [0, 0, -9.81],
  };
  if (entry.floating) {
    c.constraints = entry.constraints.map((link) => ({ link, alpha: XYZ }));
  } else if (nc > 0) {
    c.alpha = ALL_SIX.slice(0, nc);
    c.beta = Array.from({ length: nc }, (_, k) => 0.1 * (k + 1));
  }
  return c;
}

function median(xs) {
  const s = xs.slice().sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}

// The zero-copy solver on the case, warmed up.
function wasmSolver(achd, entry, c) {
  const robot = achd.loadURDF(entry.text, entry.floating ? { root: entry.root, floating: true }
                                                      : { root: entry.root, tip: entry.tip });
  const solver = robot.createSolver({ maxConstraints: entry.floating ? 0 : 6 });
  solver.q.set(c.q);
  solver.qd.set(c.qd);
  solver.ff_torques.set(c.ff_torques);
  solver.gravity.set(c.gravity);
  const nc = c.alpha ? c.alpha.length : 0;
  solver.numConstraints = nc;
  for (let k = 0; k < nc; ++k) solver.alpha.set(c.alpha[k], 6 * k);
  if (nc) solver.beta.set(c.beta);
  if (c.constraints) solver.setConstraints(c.constraints);
  for (let i = 0; i < WARMUP; ++i) solver.solve();
  return { robot, solver };
}

// Wall-clock ns per call of fn over n calls.
function nsPerCall(fn, n) {
  const t0 = process.hrtime.bigint();
  for (let i = 0; i < n; ++i) fn();
  return Number(process.hrtime.bigint() - t0) / n;
}

// One native round: `achd bench --link-outputs` (every link's acceleration, as the wasm
// solver computes them) with a fixed count (its own warm-up round, then one timed round
// on the wall clock).
function nativeRound(cli, entry, casePath, iterations) {
  const model = entry.floating ? ['--floating'] : ['--tip', entry.tip];
  const out = execFileSync(cli, ['bench', entry.path, '--root', entry.root, ...model,
    '--case', casePath, '--iterations', String(iterations), '--repeats', '1', '--clock', 'wall', '--link-outputs'],
    { encoding: 'utf8' });
  return JSON.parse(out).achd_ns;
}

function measure(achd, cli, entry, c, casePath) {
  const { robot, solver } = wasmSolver(achd, entry, c);
  const solve = () => solver.solve();
  const wasmN = Math.max(1000, Math.round(TARGET_NS_PER_REPEAT / nsPerCall(solve, 5000)));
  const nativeN = Math.max(1000, Math.round(TARGET_NS_PER_REPEAT / nativeRound(cli, entry, casePath, 1000)));
  const wasm = [], native = [], ratios = [];
  for (let r = 0; r < REPEATS; ++r) {
    wasm.push(nsPerCall(solve, wasmN));
    native.push(nativeRound(cli, entry, casePath, nativeN));
    ratios.push(wasm[r] / native[r]);
  }
  solver.delete();
  robot.delete();
  return { wasm_ns: median(wasm), native_ns: median(native), ratio: median(ratios) };
}

const achd = await loadAchd();
const cli = nativeCli();
const scratch = scratchDir();
const byName = Object.fromEntries(robots().map((r) => [r.name, r]));
const quadruped = JSON.parse(readFileSync(join(repo, 'robots/index.json'), 'utf8')).robots.find((r) => r.name === 'quadruped');
byName.quadruped = { ...quadruped, path: join(repo, quadruped.urdf), text: readFileSync(join(repo, quadruped.urdf), 'utf8') };
const cases = [['kuka_lwr4_nc0', 'kuka_lwr4', 0], ['kuka_lwr4_nc6', 'kuka_lwr4', 6], ['chain50_nc6', 'chain50', 6],
  ['quadruped_floating_feet', 'quadruped', 12]];
const results = [];
try {
  for (const [name, robotName, nc] of cases) {
    const entry = byName[robotName];
    const c = benchCase(entry, nc);
    const casePath = scratch.write(`${name}.json`, JSON.stringify(c));
    const m = measure(achd, cli, entry, c, casePath);
    results.push({ name, wasm_ns: Number(m.wasm_ns.toFixed(1)), native_ns: Number(m.native_ns.toFixed(1)),
                   ratio: Number(m.ratio.toFixed(3)) });
  }
} finally {
  scratch.remove();
}
console.log(JSON.stringify({ cases: results }, null, 2));
