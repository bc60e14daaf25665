// Prints what the CLI returns for every robot and scene in robots/, so that a refactoring
// can be shown to change no bit: run it against the build before and after, and diff.
//
//   node scripts/output_digest.mjs BUILD_DIR > before.txt   (then after.txt, diff the two)
//
// For each URDF (ours and example-robot-data's): `achd info` with the default options, and,
// when it loads, three solves of the whole tree at its default pose: free, with a velocity
// and torques, and with a constraint on the last link plus a prescribed joint; each also on
// a floating base. For each scene: `achd simulate` with the trajectory CSV on stdout.
// Errors are printed as their message, so a changed error shows too. Timing fields
// (ns per step, CPU seconds) and progress lines are removed; everything else is printed as the CLI wrote it.
import { execFileSync, spawnSync } from 'node:child_process';
import { mkdtempSync, readdirSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';

const root = resolve(new URL('..', import.meta.url).pathname);
const build = resolve(process.argv[2] ?? join(root, 'build'));
const achd = join(build, 'achd');
const work = mkdtempSync(join(tmpdir(), 'achd-digest-'));

function run(args) {
  const r = spawnSync(achd, args, { encoding: 'utf8', maxBuffer: 1 << 30 });
  return { code: r.status, out: r.stdout, err: r.stderr };
}
function print(label, r) {
  const timeless = r.out.replace(/"(ns_per_step|cpu_seconds|wall_seconds|seconds)"\s*:\s*[-0-9.e+]+/g, '"$1": _');
  const err = r.err.split(work).join('CASE_DIR').replace(/^achd: simulate .* elapsed\n/gm, '');
  process.stdout.write(`== ${label} exit ${r.code}\n${timeless}${err}\n`);
}

const urdfs = [];
for (const f of readdirSync(join(root, 'robots'))) if (f.endsWith('.urdf')) urdfs.push(join(root, 'robots', f));
const erd = join(root, 'robots', 'example-robot-data');
(function walk(dir) {
  for (const e of readdirSync(dir, { withFileTypes: true })) {
    const p = join(dir, e.name);
    if (e.isDirectory()) walk(p);
    else if (e.name.endsWith('.urdf')) urdfs.push(p);
  }
})(erd);
urdfs.sort();

for (const urdf of urdfs) {
  const name = urdf.slice(root.length + 1);
  for (const floating of [false, true]) {
    const base = floating ? [urdf, '--floating'] : [urdf];
    const info = run(['info', ...base]);
    print(`info ${name}${floating ? ' --floating' : ''}`, info);
    if (info.code !== 0) continue;
    const model = JSON.parse(info.out);
    const q = model.default_q;
    const nv = model.joints.length + (floating ? 5 : 0);
    const qd = Array.from({ length: nv }, (_, i) => 0.1 * ((i % 3) - 1));
    const tau = Array.from({ length: nv }, (_, i) => 0.5 * ((i % 5) - 2));
    const last = model.links[model.links.length - 1].name;
    const cases = {
      free: { q, gravity: [0, 0, -9.81] },
      moving: { q, qd, ff_torques: tau, gravity: [0.3, -0.2, -9.81] },
      held: {
        q, qd, gravity: [0, 0, -9.81],
        constraints: [{ link: last, alpha: [[0, 0, 1, 0, 0, 0], [1, 0, 0, 0, 0, 0]], beta: [0.1, -0.2] }],
      },
    };
    for (const [label, c] of Object.entries(cases)) {
      const file = join(work, 'case.json');
      writeFileSync(file, JSON.stringify(c));
      print(`solve ${name}${floating ? ' --floating' : ''} ${label}`, run(['solve', ...base, '--case', file]));
    }
  }
}
for (const f of readdirSync(join(root, 'robots', 'scenes')).sort()) {
  print(`simulate ${f}`, run(['simulate', join(root, 'robots', 'scenes', f), '--out', '-']));
}
execFileSync('rm', ['-rf', work]);
