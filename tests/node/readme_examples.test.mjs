// The READMEs' examples run as written: every ```js block of README.md from the
// repository root and of wasm/README.md (the npm package's) with the package installed
// beside it, taken from the files as they are; every `./build/achd` line of README.md's
// command-line section (its placeholders ROBOT.urdf, R and T read as the KUKA LWR 4) and
// the command-line example of its section on trees (the quadruped, a bash script); and
// every page link of README.md (`#robot=...`) read by the page's own parser
// (web/settings.js) and run as the page runs it, from the robot's start pose in
// robots/index.json, for 60 simulated seconds.
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import { mkdirSync, readFileSync, statSync, symlinkSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { adoptOffer, defaultSettings, parseHash, simulatorOptions } from '../../web/settings.js';
import { moduleOffer } from '../../web/module_offer.js';
import { loadAchd, nativeCli, repo, robots, scratchDir } from './helpers.mjs';

const LINK_SECONDS = 60;

function codeBlocks(file, language) {
  const text = readFileSync(join(repo, file), 'utf8');
  return [...text.matchAll(new RegExp('^```' + language + '\\n([\\s\\S]*?)^```$', 'gm'))].map((m) => m[1]);
}

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

test('README.md\'s JavaScript example runs as written and simulates 60 s', async () => {
  const blocks = codeBlocks('README.md', 'js');
  assert.equal(blocks.length, 3, 'README.md has three JavaScript examples: the quadruped\'s, the LWR\'s, the drivers\'');
  const { code, stdout, stderr } = await runModule(blocks[1], repo);
  assert.equal(stderr, '');
  assert.equal(code, 0);
  const m = stdout.match(/^t = (\S+) s, z held within (\S+) m\n$/);
  assert.ok(m, `unexpected output: ${stdout}`);
  assert.equal(Number(m[1]), 60);
  assert.ok(Number(m[2]) < 1e-6, `z residual ${m[2]}`);
  console.log(`# ${stdout.trim()}`);
});

// The drivers: a prescribed joint, a yielding column, a virtual wrench; the
// simulator's prescribed sine with z held.
test('README.md\'s drivers example (JavaScript) runs as written', async () => {
  const block = codeBlocks('README.md', 'js')[2];
  assert.match(block, /qdd_given/);
  const { code, stdout, stderr } = await runModule(block, repo);
  assert.equal(stderr, '');
  assert.equal(code, 0);
  const m = stdout.match(/^qdd 0\.5, 7 virtual torques\nbase at 0\.3000 rad, z held within (\S+) m\n$/);
  assert.ok(m, `unexpected output: ${stdout}`);
  assert.ok(Number(m[1]) < 1e-6, `z residual ${m[1]}`);
});

// The quadruped's four feet held in 3D: full rank, the legs still, the feet pressing; then
// floating, standing on its held feet under the PD controller.
test('README.md\'s quadruped example (JavaScript) runs as written', async () => {
  const [block] = codeBlocks('README.md', 'js');
  assert.match(block, /quadruped/);
  const { code, stdout, stderr } = await runModule(block, repo);
  assert.equal(stderr, '');
  assert.equal(code, 0);
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
  console.log(`# ${stdout.trim()}`);
});

// The first sh block under README.md's `heading`, run whole by bash in a directory like the
// repository root (build/achd and robots/ linked there): it must exit 0 with nothing on
// stderr; returns the JSON documents it printed, one per command.
async function runReadmeShell(heading, expect) {
  const text = readFileSync(join(repo, 'README.md'), 'utf8');
  const section = text.slice(text.indexOf(`\n${heading}\n`));
  const script = section.match(/^```sh\n([\s\S]*?)^```$/m)[1];
  assert.match(script, expect);
  const scratch = scratchDir();
  try {
    mkdirSync(join(scratch.dir, 'build'));
    symlinkSync(nativeCli(), join(scratch.dir, 'build/achd'));
    symlinkSync(join(repo, 'robots'), join(scratch.dir, 'robots'), 'dir');
    const { code, stdout, stderr } = await run('bash', ['-e', '-c', script], '', scratch.dir);
    assert.equal(stderr, '');
    assert.equal(code, 0);
    return stdout.split(/\n(?=\{)/).map((doc) => JSON.parse(doc));
  } finally {
    scratch.remove();
  }
}

// The sh block of "### Floating base", run whole as the one above: achd info reports the
// free joint; the floating quadruped's feet stay put while its unpowered legs fold and the
// trunk drops faster than g.
test('README.md\'s floating quadruped example (command line) runs as written', async () => {
  const [info, result] = await runReadmeShell('### Floating base', /achd solve robots\/quadruped\.urdf --floating/);
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
});

// The sh block of "## Trees and constraint blocks", run whole by bash in a directory like
// the repository root: every command exits 0 and prints JSON; the solve holds the four feet.
test('README.md\'s quadruped example (command line) runs as written', async () => {
  // The outputs, one JSON document per command: info's, then solve's.
  const [info, result] = await runReadmeShell('## Trees and constraint blocks', /achd solve robots\/quadruped\.urdf/);
  assert.equal(info.joints.length, 12);
  assert.equal(info.tip, null);
  assert.equal(result.nu.length, 12);
  assert.equal(result.constraint_wrenches.length, 4);
  assert.equal(result.rank, 12);
  assert.ok(Math.max(...result.qdd.map(Math.abs)) < 1e-9, `qdd ${result.qdd}`);
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
    const { code, stdout, stderr } = await runModule(blocks[0], scratch.dir);
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
test(`every page link in README.md runs ${LINK_SECONDS} simulated seconds as the page runs it`, async () => {
  const text = readFileSync(join(repo, 'README.md'), 'utf8');
  const links = [...new Set(text.match(/#robot=[^\s`)\]]+/g))];
  assert.ok(links.length >= 1, 'README.md has no page link');
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
      { root: entry.root, tip: entry.tip, floating: Boolean(entry.floating) });
    const sim = robot.createSimulator(simulatorOptions(settings));
    try {
      // As web/simulation.js builds it: the start pose (a floating base raised so that its
      // default links stand at z = 0), its PD controller, the default links held in x, y,
      // z, then the directions of the selected link (link=, else the tip or the first
      // default link).
      let q0 = entry.q0;
      if (robot.floating) {
        q0 = [0, 0, 0, 0, 0, 0, 1, ...entry.q0];
        const feet = robot.forwardKinematics(q0).filter((l) => entry.constraints.includes(l.name));
        q0[2] = -Math.min(...feet.map((l) => l.position[2]));
      }
      sim.reset(q0);
      if (entry.joint_control) sim.setJointControl({ target: q0, ...entry.joint_control });
      const selected = settings.link ?? entry.tip ?? entry.constraints[0];
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

// The lines of the ```sh block under "## Command line" that run ./build/achd.
function commandLines() {
  const text = readFileSync(join(repo, 'README.md'), 'utf8');
  const section = text.slice(text.indexOf('\n## Command line\n'));
  const block = section.match(/^```sh\n([\s\S]*?)^```$/m)[1];
  return block.split('\n').filter((line) => line.startsWith('./build/achd '));
}

test('README.md\'s command lines run, with the LWR for ROBOT.urdf, R and T', async () => {
  const lines = commandLines();
  assert.ok(lines.length >= 6, `only ${lines.length} command lines found`);
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
    for (const written of lines) {
      const line = written.replaceAll('ROBOT.urdf', lwr.urdf).replace('--root R ', `--root ${lwr.root} `)
        .replace('--tip T ', `--tip ${lwr.tip} `);
      const { code, stdout, stderr } = await run('bash', ['-c', line], '', scratch.dir);
      assert.equal(code, 0, `${line}: exit ${code}, ${stderr}`);
      // Runs longer than a second print progress lines on stderr; nothing else may appear.
      const other = stderr.split('\n').filter((l) => l && !/^achd: (simulate|accuracy) .*elapsed$/.test(l));
      assert.deepEqual(other, [], line);
      const result = JSON.parse(stdout);
      assert.equal(typeof result, 'object', line);
      console.log(`# ${written}: exit 0`);
    }
    // The files the lines name were written.
    for (const file of ['traj.csv', 'docs/accuracy/arm7/accuracy.svg']) {
      assert.ok(statSync(join(scratch.dir, file)).size > 0, file);
    }
  } finally {
    scratch.remove();
  }
});
