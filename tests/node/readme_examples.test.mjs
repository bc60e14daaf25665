// The documents' examples run as written, wherever they stand: README.md and the user
// guides (docs/guide/*.md) are read as one set.
// - Every ```js block of the set runs from the repository root (as a file saved there),
//   and every ```js block of wasm/README.md (the npm package's) with the package
//   installed beside it; each must exit 0 with nothing on stderr, and each is one of the
//   known examples below, whose output is checked (a new example needs its check here).
// - Every `./build/achd` line of the set's ```sh blocks runs in a directory like the
//   repository root (build/achd and robots/ linked there), one line at a time; a block
//   with a here-document runs whole, as one bash script. The placeholders ROBOT.urdf, R
//   and T read as the KUKA LWR 4, and case.json holds its start pose with the tip height
//   held. Each must exit 0 and print JSON; the files its `--out` names are written.
// - Every page link of the set (`#robot=...`) is read by the page's own parser
//   (web/settings.js) and run as the page runs it, from the robot's start pose in
//   robots/index.json, for 60 simulated seconds.
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdirSync, readdirSync, readFileSync, statSync, symlinkSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { adoptOffer, defaultSettings, parseHash, simulatorOptions } from '../../web/settings.js';
import { moduleOffer } from '../../web/module_offer.js';
import { loadAchd, nativeCli, repo, robots, scratchDir } from './helpers.mjs';

const LINK_SECONDS = 60;

// README.md and the user guides, the files whose examples run from the repository root.
function documents() {
  const guides = readdirSync(join(repo, 'docs/guide')).filter((f) => f.endsWith('.md')).sort();
  return ['README.md', ...guides.map((f) => `docs/guide/${f}`)];
}

// The ```language blocks of `file`: [{where: 'file:line', text}].
function codeBlocks(file, language) {
  const text = readFileSync(join(repo, file), 'utf8');
  return [...text.matchAll(new RegExp('^```' + language + '\\n([\\s\\S]*?)^```$', 'gm'))].map((m) => ({
    where: `${file}:${text.slice(0, m.index).split('\n').length}`, text: m[1],
  }));
}

const blocksOf = (files, language) => files.flatMap((file) => codeBlocks(file, language));

// Runs `program args...` with `input` on stdin in `cwd`; resolves to {code, stdout, stderr}.
function run(program, args, input, cwd) {
  return new Promise((resolve, reject) => {
    const child = spawn(program, args, { cwd, stdio: ['pipe', 'pipe', 'pipe'] });
    let stdout = '';
    let stderr = '';
    child.stdout.on('data', (d) => (stdout += d));
    child.stderr.on('data', (d) => (stderr += d));
    child.on('error', reject);
    child.on('close', (code) => resolve({ code, stdout, stderr }));
    child.stdin.end(input);
  });
}

// Runs an ES module given as text in `cwd` (imports resolve from there, as for a file
// saved there).
const runModule = (source, cwd) => run(process.execPath, ['--input-type=module'], source, cwd);

// The JavaScript examples of the set, each found by what its source says, with a check of
// what it prints.
const JS_EXAMPLES = [
  {
    name: 'the quick start (the LWR: a solve with the tip height held, then 1 s held)',
    signature: /rank \$\{r\.rank\}, nu /,
    check(stdout) {
      const m = stdout.match(/^rank 1, nu (\S+) N\nt = 1 s, z held within (\S+) m\n$/);
      assert.ok(m, `unexpected output: ${stdout}`);
      assert.ok(Number.isFinite(Number(m[1])) && Number(m[1]) !== 0, `nu ${m[1]}`);
      assert.ok(Number(m[2]) < 1e-6, `z residual ${m[2]}`);
    },
  },
  {
    name: 'the LWR simulated for 60 s',
    signature: /sim\.step\(59000, 0\.001/,
    check(stdout) {
      const m = stdout.match(/^t = (\S+) s, z held within (\S+) m\n$/);
      assert.ok(m, `unexpected output: ${stdout}`);
      assert.equal(Number(m[1]), 60);
      assert.ok(Number(m[2]) < 1e-6, `z residual ${m[2]}`);
    },
  },
  {
    // A prescribed joint, a yielding column, a virtual wrench; the simulator's
    // prescribed sine with z held.
    name: 'the drivers',
    signature: /qdd_given/,
    check(stdout) {
      const m = stdout.match(/^qdd 0\.5, 7 virtual torques\nbase at 0\.3000 rad, z held within (\S+) m\n$/);
      assert.ok(m, `unexpected output: ${stdout}`);
      assert.ok(Number(m[1]) < 1e-6, `z residual ${m[1]}`);
    },
  },
  {
    // The quadruped's four feet held in 3D: full rank, the legs still, the feet pressing;
    // then floating, standing on its held feet under the PD controller.
    name: 'the quadruped',
    signature: /robots\/quadruped\.urdf/,
    check(stdout) {
      const m = stdout.match(/^rank (\d+), max \|qdd\| (\S+), foot z forces (\S+) (\S+) (\S+) (\S+) N\n/);
      assert.ok(m, `unexpected output: ${stdout}`);
      assert.equal(Number(m[1]), 12);
      assert.ok(Number(m[2]) < 1e-9, `max |qdd| ${m[2]}`);
      for (const f of m.slice(3)) assert.ok(Number.isFinite(Number(f)) && Number(f) !== 0, `foot force ${f}`);
      // then floating, standing on its held feet: the trunk within 1 cm of 0.3 m, the foot held
      const stand = stdout.slice(m[0].length).match(/^trunk at (\S+) m, lf_foot held within (\S+) m\n$/);
      assert.ok(stand, `unexpected output: ${stdout}`);
      assert.ok(Math.abs(Number(stand[1]) - 0.3) < 0.01, `trunk at ${stand[1]} m`);
      assert.ok(Number(stand[2]) < 1e-9, `foot residual ${stand[2]}`);
    },
  },
  {
    // The four-bar closed by its loop joint: the loop keeps its two in-plane directions,
    // and after 1 s from its crank straight up the crank is where the independent
    // reference puts it (-1.2470 rad, support/four_bar_reference.hpp) with the loop closed.
    name: 'the four-bar loop',
    signature: /loopDrift\(\)/,
    check(stdout) {
      const m = stdout.match(/^coupler_rocker: holds x y\ncrank at (\S+) rad, loop closed within (\S+) m\n$/);
      assert.ok(m, `unexpected output: ${stdout}`);
      assert.ok(Math.abs(Number(m[1]) - -1.2470) <= 1e-4, `crank at ${m[1]}`);
      assert.ok(Number(m[2]) < 1e-9, `loop drift ${m[2]}`);
    },
  },
];

// The example of JS_EXAMPLES a block is; fails unless exactly one matches.
function exampleOf(block) {
  const found = JS_EXAMPLES.filter((e) => e.signature.test(block.text));
  assert.equal(found.length, 1,
    `${block.where}: a JavaScript example must be exactly one of the known ones (found ${found.length}): add its check to JS_EXAMPLES`);
  return found[0];
}

for (const example of JS_EXAMPLES) {
  test(`the JavaScript example of ${example.name} runs as written`, async () => {
    const blocks = blocksOf(documents(), 'js').filter((b) => example.signature.test(b.text));
    assert.equal(blocks.length, 1, `${example.name}: expected once in ${documents().join(', ')}, found ${blocks.length}`);
    const [block] = blocks;
    const { code, stdout, stderr } = await runModule(block.text, repo);
    assert.equal(stderr, '', block.where);
    assert.equal(code, 0, block.where);
    example.check(stdout);
    console.log(`# ${block.where}: ${stdout.trim().replaceAll('\n', '; ')}`);
  });
}

test('every JavaScript block of README.md and the guides is a known example', () => {
  const blocks = blocksOf(documents(), 'js');
  assert.ok(blocks.length >= JS_EXAMPLES.length, `only ${blocks.length} JavaScript blocks`);
  for (const block of blocks) exampleOf(block);
});

test('wasm/README.md\'s example runs as written with the npm package installed', async () => {
  const blocks = codeBlocks('wasm/README.md', 'js');
  assert.equal(blocks.length, 1, 'wasm/README.md has one JavaScript example');
  const scratch = scratchDir();
  try {
    // What a user of the package has: node_modules/achd (the package wasm/dist/ holds) and
    // the robot's URDF in the working directory.
    mkdirSync(join(scratch.dir, 'node_modules'));
    symlinkSync(join(repo, 'wasm/dist'), join(scratch.dir, 'node_modules/achd'), 'dir');
    symlinkSync(join(repo, 'robots/kuka_lwr4.urdf'), join(scratch.dir, 'kuka_lwr4.urdf'));
    const { code, stdout, stderr } = await runModule(blocks[0].text, scratch.dir);
    assert.equal(stderr, '');
    assert.equal(code, 0);
    const m = stdout.match(/^t = (\S+) s, z held within (\S+) m\n$/);
    assert.ok(m, `unexpected output: ${stdout}`);
    assert.ok(Number(m[1]) >= 1, `t = ${m[1]}`);
    assert.ok(Number(m[2]) < 1e-6, `z residual ${m[2]}`);
    console.log(`# ${stdout.trim()}`);
  } finally {
    scratch.remove();
  }
});

// The UR5 link (z and rx held, y accelerated at 0.5 m/s²) runs on the simulator's
// variable_damping policy and fixed physics defaults: before them it stopped
// at t = 2.183 s, "the acceleration to enforce along direction y is not finite".
test(`every page link in README.md and the guides runs ${LINK_SECONDS} simulated seconds as the page runs it`, async () => {
  const links = [...new Set(documents().flatMap((file) =>
    readFileSync(join(repo, file), 'utf8').match(/#robot=[^\s`)\]]+/g) ?? []))];
  assert.ok(links.length >= 2, `only ${links.length} page links`);
  const achd = await loadAchd();
  const offer = moduleOffer(achd);
  adoptOffer(offer);  // as the page does once its module has loaded
  const index = JSON.parse(readFileSync(join(repo, 'robots/index.json'), 'utf8'));
  const failures = [];
  for (const link of links) {
    const { settings, problems } = parseHash(link, defaultSettings(index.default, offer), offer);
    assert.deepEqual(problems, [], `${link}: the page would ignore parts of it`);
    const entry = index.robots.find((r) => r.name === settings.robot);
    assert.ok(entry, `${link}: robot ${settings.robot} is not in robots/index.json`);
    const robot = achd.loadURDF(readFileSync(join(repo, entry.urdf), 'utf8'),
      { root: entry.root, tip: entry.tip, floating: Boolean(entry.floating),
        loops: entry.loops ? JSON.parse(readFileSync(join(repo, entry.loops), 'utf8')).loops : [] });
    const sim = robot.createSimulator(simulatorOptions(settings));
    try {
      // As web/simulation.js builds it: the start pose (a floating base raised so that its
      // default links stand at z = 0), its PD controller, the default links held in x, y,
      // z, then the directions of the selected link (link=, else the tip, the first
      // default link or the last link).
      let q0 = entry.q0;
      if (robot.floating) {
        q0 = [0, 0, 0, 0, 0, 0, 1, ...entry.q0];
        const feet = robot.forwardKinematics(q0).filter((l) => entry.constraints.includes(l.name));
        q0[2] = -Math.min(...feet.map((l) => l.position[2]));
      }
      sim.reset(q0);
      if (entry.joint_control) sim.setJointControl({ target: q0, ...entry.joint_control });
      const selected = settings.link ?? entry.tip ?? entry.constraints?.[0] ?? robot.linkNames.at(-1);
      for (const held of entry.constraints ?? []) {
        if (held !== selected) for (const d of ['x', 'y', 'z']) sim.setDirection(d, 'hold', held);
      }
      for (const [name, mode] of Object.entries(settings.directions)) sim.setDirection(name, mode, selected);
      const steps = Math.round(LINK_SECONDS / settings.dt);
      try {
        sim.step(steps, settings.dt);
        assert.equal(sim.t, steps * settings.dt);
        assert.ok(Array.from(sim.q).every(Number.isFinite));
        console.log(`# ${link}: t = ${sim.t} s, ${sim.events().length} direction events`);
      } catch (err) {
        failures.push(`${link}: ${err.message}`);
      }
    } finally {
      sim.delete();
      robot.delete();
    }
  }
  assert.deepEqual(failures, []);
});

// The shell examples of the set: a block with a here-document is one script; otherwise
// each `./build/achd` line is one. [{where, script}], placeholders still in.
function shellScripts() {
  const scripts = [];
  for (const block of blocksOf(documents(), 'sh')) {
    if (!/^\.\/build\/achd /m.test(block.text)) continue;
    if (/<<'?EOF'?/.test(block.text)) {
      scripts.push({ where: block.where, script: block.text });
    } else {
      const [file, line] = block.where.split(':');
      block.text.split('\n').forEach((text, k) => {
        if (text.startsWith('./build/achd ')) scripts.push({ where: `${file}:${Number(line) + 1 + k}`, script: text });
      });
    }
  }
  return scripts;
}

// Checks of the shell examples whose output says more than "JSON", by what they run.
const SHELL_CHECKS = [
  {
    // The four-bar's loop joint: info lists it with its held and dropped directions; the
    // scene keeps it closed and the energy constant.
    signature: /achd info robots\/four_bar\.urdf --loops/,
    check([info]) {
      assert.deepEqual(info.loops.map((l) => [l.name, l.directions, l.dropped]),
        [['coupler_rocker', ['x', 'y'], ['z', 'rx', 'ry']]]);
    },
  },
  {
    signature: /achd simulate robots\/scenes\/four_bar_swing\.json/,
    check([summary]) {
      assert.ok(summary.loop_drift.coupler_rocker < 1e-9, `loop drift ${summary.loop_drift.coupler_rocker}`);
      assert.ok(summary.energy_drift < 1e-8, `energy drift ${summary.energy_drift}`);
    },
  },
  {
    // achd info reports the free joint; the floating quadruped's feet stay put while its
    // unpowered legs fold and the trunk drops faster than g.
    signature: /achd solve robots\/quadruped\.urdf --floating/,
    check([info, result]) {
      assert.equal(info.floating, true);
      assert.equal(info.joints[0].type, 'floating');
      assert.equal(result.joints[0], 'trunk');
      assert.equal(result.qdd.length, 18);
      assert.equal(result.rank, 12);
      assert.ok(result.qdd[2] < -9.81, `the trunk drops at ${result.qdd[2]} m/s^2`);
      // the feet (links lf_foot ...): their linear accelerations held at 0
      for (const foot of ['lf_foot', 'rf_foot', 'lh_foot', 'rh_foot']) {
        const a = result.link_accelerations[result.links.indexOf(foot)];
        assert.ok(Math.hypot(a[0], a[1], a[2]) < 1e-9, `${foot}: ${a}`);
      }
    },
  },
  {
    // The fixed-base quadruped: the solve holds the four feet, the legs still.
    signature: /achd info robots\/quadruped\.urdf\n\.\/build\/achd solve robots\/quadruped\.urdf --case -/,
    check([info, result]) {
      assert.equal(info.joints.length, 12);
      assert.equal(info.tip, null);
      assert.equal(result.nu.length, 12);
      assert.equal(result.constraint_wrenches.length, 4);
      assert.equal(result.rank, 12);
      assert.ok(Math.max(...result.qdd.map(Math.abs)) < 1e-9, `qdd ${result.qdd}`);
    },
  },
  {
    // The relative block: the two front feet keep together (equal accelerations) while the
    // legs move, held by one pair of forces.
    signature: /"link_b": "rf_foot"/,
    check([result]) {
      assert.equal(result.rank, 3);
      assert.equal(result.nu.length, 3);
      assert.equal(result.constraint_wrenches.length, 1);
      const a = (foot) => result.link_accelerations[result.links.indexOf(foot)];
      const lf = a('lf_foot'), rf = a('rf_foot');
      assert.ok(Math.hypot(lf[0] - rf[0], lf[1] - rf[1], lf[2] - rf[2]) < 1e-9, `${lf} vs ${rf}`);
      assert.ok(Math.hypot(lf[0], lf[1], lf[2]) > 0.1, `the feet move together: ${lf}`);
    },
  },
  {
    // The quick start's solve: the tip's height held by one constraint force.
    signature: /achd solve robots\/kuka_lwr4\.urdf --root lwr_base_link --tip lwr_link_7 --case - <</,
    check([result]) {
      assert.equal(result.rank, 1);
      assert.equal(result.nu.length, 1);
      assert.ok(Math.abs(result.link_accelerations.at(-1)[2]) < 1e-9, `tip z ${result.link_accelerations.at(-1)}`);
    },
  },
];

test('every ./build/achd line of README.md and the guides runs, with the LWR for ROBOT.urdf, R and T', async () => {
  const scripts = shellScripts();
  assert.ok(scripts.length >= 8, `only ${scripts.length} command lines found`);
  for (const { signature } of SHELL_CHECKS) {
    assert.equal(scripts.filter((s) => signature.test(s.script)).length, 1, `expected one example running ${signature}`);
  }
  const lwr = robots().find((r) => r.name === 'kuka_lwr4');
  const scratch = scratchDir();
  try {
    // A working directory like the repository root: build/achd, robots/, and the case.json
    // the lines read (the LWR at its start pose, tip height held).
    mkdirSync(join(scratch.dir, 'build'));
    symlinkSync(nativeCli(), join(scratch.dir, 'build/achd'));
    symlinkSync(join(repo, 'robots'), join(scratch.dir, 'robots'), 'dir');
    mkdirSync(join(scratch.dir, 'docs/accuracy'), { recursive: true });
    writeFileSync(join(scratch.dir, 'case.json'),
      JSON.stringify({ q: lwr.q0, gravity: [0, 0, -9.81], alpha: [[0, 0, 1, 0, 0, 0]], beta: [0] }));
    for (const { where, script: written } of scripts) {
      const script = written.replaceAll('ROBOT.urdf', lwr.urdf).replaceAll('--root R ', `--root ${lwr.root} `)
        .replaceAll('--tip T ', `--tip ${lwr.tip} `);
      const { code, stdout, stderr } = await run('bash', ['-e', '-c', script], '', scratch.dir);
      assert.equal(code, 0, `${where}: exit ${code}, ${stderr}`);
      // Runs longer than a second print progress lines on stderr, and a URDF with odd
      // inertias loads with warnings there; nothing else may appear.
      const other = stderr.split('\n')
        .filter((l) => l && !/^achd: (simulate|accuracy) .*elapsed$/.test(l) && !l.startsWith('achd: warning: '));
      assert.deepEqual(other, [], where);
      // One JSON document per command.
      const outputs = stdout.split(/\n(?=\{)/).map((doc) => JSON.parse(doc));
      for (const output of outputs) assert.equal(typeof output, 'object', where);
      for (const { signature, check } of SHELL_CHECKS) if (signature.test(written)) check(outputs);
      // The files the commands write.
      for (const [, out] of written.matchAll(/--out (\S+)/g)) {
        if (out === '-') continue;
        const file = out.endsWith('.csv') ? out : join(out, 'accuracy.svg');
        assert.ok(statSync(join(scratch.dir, file)).size > 0, `${where}: ${file}`);
      }
      console.log(`# ${where}: exit 0`);
    }
  } finally {
    scratch.remove();
  }
});
