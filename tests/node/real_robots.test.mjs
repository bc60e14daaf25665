// The robots people have, in JS as in the CLI: every URDF of the example-robot-data
// collection (robots/example-robot-data) loads in wasm exactly when `achd info` loads it,
// with the same joints and the same warnings, or fails with the same message; the
// inertia option does what --inertia does (the default holds a massless finger); the Panda's coupled fingers solve in wasm to
// the bit as natively (nu_owners included); an SRDF pose is the pose `achd info --srdf`
// lists; and Solo12 stands on its held feet under the frequency/hold controller.
import assert from 'node:assert/strict';
import { readFileSync, readdirSync, statSync } from 'node:fs';
import { join, relative } from 'node:path';
import { after, before, test } from 'node:test';

import { assertSameResult, loadAchd, nativeCli, nativeSolve, repo, runCli, scratchDir } from './helpers.mjs';

const CORPUS = join(repo, 'robots/example-robot-data');
const GRAVITY = [0, 0, -9.81];
const XYZ = [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]];

let achd, cli, scratch;
before(async () => {
  achd = await loadAchd();
  cli = nativeCli();
  scratch = scratchDir();
});
after(() => scratch.remove());

function urdfs(dir = CORPUS) {
  return readdirSync(dir).flatMap((name) => {
    const path = join(dir, name);
    if (statSync(path).isDirectory()) return urdfs(path);
    return name.endsWith('.urdf') ? [path] : [];
  }).sort();
}

// `achd info` of a file: its JSON, or {error} with the message after "FILE: ".
async function nativeInfo(path, flags = []) {
  try {
    return JSON.parse(await runCli(cli, ['info', path, ...flags]));
  } catch (e) {
    const at = e.message.lastIndexOf(`${path}: `);
    return { error: e.message.slice(at + path.length + 2).trim() };
  }
}

test('every URDF of the collection loads in wasm exactly as in the CLI', async () => {
  const files = urdfs();
  assert.equal(files.length, 69);
  let loaded = 0;
  for (const path of files) {
    const name = relative(CORPUS, path);
    const native = await nativeInfo(path);
    let robot = null, error = null;
    try {
      robot = achd.loadURDF(readFileSync(path, 'utf8'));
    } catch (e) {
      error = e.message.replace(/^URDF: /, '');
    }
    if (native.error !== undefined) {
      assert.equal(error, native.error, `${name}: the same error`);
      continue;
    }
    assert.equal(error, null, `${name}: loads`);
    assert.deepEqual(robot.jointNames, native.joints.map((j) => j.name), `${name}: joints`);
    assert.deepEqual(robot.warnings, native.warnings, `${name}: warnings`);
    robot.delete();
    ++loaded;
  }
  console.log(`# ${loaded} of ${files.length} load with the defaults in wasm and natively`);
});

test('the inertia option: strict refuses what accept warns about or holds, repair gives a massless finger mass', async () => {
  const talos = readFileSync(join(CORPUS, 'talos_data/robots/talos_reduced.urdf'), 'utf8');
  const accepted = achd.loadURDF(talos);
  assert.ok(accepted.warnings.length > 0 && accepted.warnings.every((w) => /^link '/.test(w)), accepted.warnings.join('\n'));
  accepted.delete();
  assert.throws(() => achd.loadURDF(talos, { inertia: 'strict' }), /^Error: URDF: link '.*': inertia/);
  assert.throws(() => achd.loadURDF(talos, { inertia: 'lenient' }),
    /loadURDF: options.inertia: expected 'accept' or 'strict' or 'repair', got 'lenient'/);
  const gripperPath = join(CORPUS, 'bravo7_description/urdf/bravo7_gripper.urdf');
  const gripper = readFileSync(gripperPath, 'utf8');
  // The default holds both massless fingers, as the CLI does, one warning each.
  const held = achd.loadURDF(gripper);
  assert.deepEqual(held.warnings, (await nativeInfo(gripperPath)).warnings);
  assert.deepEqual(held.warnings.map((w) => w.match(/^joint '(\w+)' moves nothing: .* locked at 0 /)?.[1]),
    ['bravo_finger1_joint', 'bravo_finger2_joint'], held.warnings.join('\n'));
  assert.equal(held.jointNames.length, 6);
  held.delete();
  assert.throws(() => achd.loadURDF(gripper, { inertia: 'strict' }), /moves nothing.*--inertia repair/);
  const repaired = achd.loadURDF(gripper, { inertia: 'repair' });
  const native = await nativeInfo(gripperPath, ['--inertia', 'repair']);
  assert.deepEqual(repaired.warnings, native.warnings);
  assert.ok(repaired.warnings.some((w) => /floor mass/.test(w)), repaired.warnings.join('\n'));
  repaired.delete();
});

test('the Panda\'s coupled fingers solve in wasm to the bit as natively', async () => {
  const path = join(CORPUS, 'panda_description/urdf/panda.urdf');
  const robot = achd.loadURDF(readFileSync(path, 'utf8'));
  assert.deepEqual(robot.couplings, [{ joint: 'panda_finger_joint2', leader: 'panda_finger_joint1', multiplier: 1, offset: 0 }]);
  const q = { panda_joint2: 0.4, panda_joint4: -1.8, panda_joint6: 1.4, panda_finger_joint1: 0.02, panda_finger_joint2: 0.02 };
  for (const constraints of [undefined, [{ link: 'panda_hand', alpha: XYZ, beta: [0.1, 0, 0] }]]) {
    const c = { q, qd: { panda_joint1: 0.3, panda_finger_joint1: 0.1, panda_finger_joint2: 0.1 }, gravity: GRAVITY };
    if (constraints) c.constraints = constraints;
    const wasm = robot.solve(c);
    const native = await nativeSolve(cli, scratch, path, {}, c);
    assertSameResult(wasm, native, constraints ? 'hand held' : 'free');
    assert.deepEqual(wasm.nu_owners, [...(constraints ? ['link panda_hand', 'link panda_hand', 'link panda_hand'] : []),
      'coupling panda_finger_joint2']);
    const f1 = robot.jointNames.indexOf('panda_finger_joint1'), f2 = robot.jointNames.indexOf('panda_finger_joint2');
    assert.ok(Math.abs(wasm.qdd[f2] - wasm.qdd[f1]) <= 1e-12 * (1 + Math.abs(wasm.qdd[f1])));
  }
  robot.delete();
});

test('Solo12 from its SRDF pose stands on its held feet under the frequency/hold controller', async () => {
  const urdfPath = join(CORPUS, 'solo_description/robots/solo12.urdf');
  const srdfPath = join(CORPUS, 'solo_description/srdf/solo.srdf');
  const robot = achd.loadURDF(readFileSync(urdfPath, 'utf8'), { floating: true, srdf: readFileSync(srdfPath, 'utf8'), pose: 'standing' });
  const native = await nativeInfo(urdfPath, ['--floating', '--srdf', srdfPath]);
  const standing = native.poses.find((p) => p.name === 'standing').q;
  assert.deepEqual(robot.startPose, [...standing.base_link, ...robot.jointNames.slice(1).map((j) => standing[j])]);
  assert.deepEqual(Object.keys(robot.poses).sort(), native.poses.map((p) => p.name).sort());
  assert.throws(() => achd.loadURDF(readFileSync(urdfPath, 'utf8'), { floating: true, srdf: '<robot/>', pose: 'standing' }),
    /options.pose: the SRDF has no group_state 'standing' \(it has none\)/);
  const sim = robot.createSimulator();
  sim.reset(robot.startPose);
  for (const foot of ['FL_FOOT', 'FR_FOOT', 'HL_FOOT', 'HR_FOOT'])
    for (const d of ['x', 'y', 'z']) sim.setDirection(d, 'hold', foot);
  sim.setJointControl({ frequency: 5, dampingRatio: 1, feedforward: 'hold' });
  const z0 = sim.q[2];
  let worst = 0, height = 0;
  for (let k = 0; k < 20; ++k) {
    sim.step(100, 1e-3);
    for (const foot of ['FL_FOOT', 'FR_FOOT', 'HL_FOOT', 'HR_FOOT'])
      for (const r of Object.values(sim.residuals(foot))) if (r !== null) worst = Math.max(worst, Math.abs(r));
    height = Math.max(height, Math.abs(sim.q[2] - z0));
  }
  console.log(`# Solo12 2 s: feet residual ${worst.toExponential(2)} m, trunk height change ${height.toExponential(2)} m`);
  assert.ok(worst <= 1e-6, `feet ${worst}`);
  assert.ok(height <= 0.02, `trunk ${height}`);
  sim.delete();
  robot.delete();
});
