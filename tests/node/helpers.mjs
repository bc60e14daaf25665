// Shared by the Node tests and bench/wasm_vs_native.mjs: the built module, the native
// CLI (the Release build), the relative error (docs/design.md section 4.6), the
// comparison of a wasm result with the CLI's and robots/index.json.
import assert from 'node:assert/strict';
import { execFile, execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

export const repo = resolve(dirname(fileURLToPath(import.meta.url)), '../..');

// web/dist/achd.mjs, built by `cmake --preset wasm && cmake --build --preset wasm`.
export async function loadAchd() {
  const path = join(repo, 'web/dist/achd.mjs');
  if (!existsSync(path))
    throw new Error(`${path} is missing: run cmake --preset wasm && cmake --build --preset wasm`);
  const { default: createAchd } = await import(path);
  return createAchd();
}

// The native `achd` CLI: $ACHD_CLI, else build/achd, built there first if absent.
export function nativeCli() {
  if (process.env.ACHD_CLI) return resolve(process.env.ACHD_CLI);
  const cli = join(repo, 'build/achd');
  if (!existsSync(cli)) {
    const run = (args) => execFileSync('cmake', args, { cwd: repo, stdio: 'inherit' });
    run(['-S', '.', '-B', 'build', '-DCMAKE_BUILD_TYPE=Release']);
    run(['--build', 'build', '--target', 'achd_cli', '-j2']);
  }
  return cli;
}

// The chains of robots/index.json (entries with a tip; a tree entry has none), with their URDF text.
export function robots() {
  const index = JSON.parse(readFileSync(join(repo, 'robots/index.json'), 'utf8'));
  return index.robots.filter((r) => r.tip).map((r) => ({ ...r, path: join(repo, r.urdf), text: readFileSync(join(repo, r.urdf), 'utf8') }));
}

// max|a - b| / max(1, max|b|) over flat arrays of equal length.
export function relativeError(a, b) {
  if (a.length !== b.length) return Infinity;
  let diff = 0, scale = 1;
  for (let i = 0; i < a.length; ++i) {
    diff = Math.max(diff, Math.abs(a[i] - b[i]));
    scale = Math.max(scale, Math.abs(b[i]));
  }
  return diff / scale;
}

export function scratchDir() {
  const dir = mkdtempSync(join(tmpdir(), 'achd-node-'));
  return { dir, write: (name, text) => { const p = join(dir, name); writeFileSync(p, text); return p; },
    remove: () => rmSync(dir, { recursive: true, force: true }) };
}

// CLI flags for the options object robot.solve() takes.
export function cliOptionFlags(options = {}) {
  const flags = [];
  if (options.convention) flags.push('--convention', options.convention);
  if (options.policy) flags.push('--policy', options.policy);
  if (options.tolerance !== undefined) flags.push('--tolerance', String(options.tolerance));
  if (options.damping !== undefined) flags.push('--damping', String(options.damping));
  if (options.absoluteTolerance) flags.push('--absolute-tolerance');
  return flags;
}

// Runs `achd args...`; resolves to stdout, rejects with stderr on a non-zero exit.
export function runCli(cli, args) {
  return new Promise((ok, fail) => {
    execFile(cli, args, { maxBuffer: 1 << 26 }, (error, stdout, stderr) => {
      if (error) fail(new Error(`achd ${args.join(' ')}: ${stderr || error.message}`));
      else ok(stdout);
    });
  });
}

// Runs the async jobs with at most `width` at a time (the machine has 2 cores).
export async function pool(jobs, width = 2) {
  const results = new Array(jobs.length);
  let next = 0;
  const worker = async () => {
    while (next < jobs.length) {
      const i = next++;
      results[i] = await jobs[i]();
    }
  };
  await Promise.all(Array.from({ length: Math.min(width, jobs.length) }, worker));
  return results;
}

// tests/native/random_tree_files (the C++ suites' random trees as files), from the build
// of the native CLI: beside $ACHD_CLI, else in build/, built there first if absent.
export function randomTreeFiles() {
  const cli = nativeCli();
  const tool = join(dirname(cli), 'tests/native/random_tree_files');
  if (!existsSync(tool)) {
    if (process.env.ACHD_CLI) throw new Error(`${tool} is missing: build the target random_tree_files beside ${cli}`);
    execFileSync('cmake', ['--build', 'build', '--target', 'random_tree_files', '-j2'], { cwd: repo, stdio: 'inherit' });
  }
  return tool;
}

// Every field equal: names exactly, numbers to the bit (17 digits in the CLI), nulls
// (prescribed_torques of joints whose torque was given) where the CLI has them.
export function assertSameResult(wasm, native, what) {
  assert.deepEqual(Object.keys(wasm).sort(), Object.keys(native).sort(), `${what}: field names`);
  for (const key of Object.keys(native)) {
    if (key === 'joints' || key === 'links' || key === 'locked_joints' || key === 'nu_owners') {
      assert.deepEqual(wasm[key], native[key], `${what}: ${key}`);
    } else if (Array.isArray(native[key])) {
      const w = wasm[key].flat(), n = native[key].flat();
      assert.equal(w.length, n.length, `${what}: ${key} length`);
      assert.deepEqual(w.map((x) => x === null), n.map((x) => x === null), `${what}: ${key} nulls`);
      assert.equal(relativeError(w.filter((x) => x !== null), n.filter((x) => x !== null)), 0, `${what}: ${key}`);
    } else {
      assert.equal(relativeError([wasm[key]], [native[key]]), 0, `${what}: ${key}`);
    }
  }
}

// The CLI flags of loadURDF's options (options.loops: written as a loops file into
// `scratch`, scratchDir()).
export function loadFlags(load = {}, scratch = null) {
  const flags = [];
  if (load.loops !== undefined) flags.push('--loops', scratch.write(`loops${caseFiles++}.json`, JSON.stringify({ loops: load.loops })));
  if (load.mimic !== undefined) flags.push('--mimic', load.mimic);
  if (load.root !== undefined) flags.push('--root', load.root);
  if (load.tip !== undefined) flags.push('--tip', load.tip);
  for (const [name, value] of Object.entries(load.locked || {})) flags.push('--lock', `${name}=${value}`);
  if (load.sideBranches === 'ignore') flags.push('--convention', 'kdl');
  if (load.floating) flags.push('--floating');
  if (load.inertia !== undefined) flags.push('--inertia', load.inertia);
  return flags;
}

let caseFiles = 0;
// `achd solve` (the native CLI `cli`) of case c, written into `scratch` (scratchDir()), the
// robot loaded as loadURDF(text, load) loads it: the result object.
export async function nativeSolve(cli, scratch, urdf, load, c, options) {
  const casePath = scratch.write(`case${caseFiles++}.json`, JSON.stringify(c));
  return JSON.parse(await runCli(cli, ['solve', urdf, ...loadFlags(load, scratch), '--case', casePath, ...cliOptionFlags(options)]));
}

// The message of the CLI's error on case c, without "achd: error: FILE: "; null if it solved.
export async function nativeError(cli, scratch, urdf, load, c) {
  const casePath = scratch.write(`bad${caseFiles++}.json`, JSON.stringify(c));
  try {
    await runCli(cli, ['solve', urdf, ...loadFlags(load, scratch), '--case', casePath]);
  } catch (e) {
    return e.message.slice(e.message.lastIndexOf(`${casePath}: `) + casePath.length + 2).trim();
  }
  return null;
}
