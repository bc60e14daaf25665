// One source per fact across the wasm boundary: a case is parsed by the C++ case parser
// alone (wasm/js holds none of its forms or messages), what JSON cannot hold is refused
// with a named error before it could be silently changed on the way, the robot's joints
// and links come from C++ as the native CLI's `achd info` gives them, and the page reads
// them from the module instead of parsing the URDF itself (only the URDF picker, which
// offers names before anything is loaded, reads XML).
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { before, test } from 'node:test';

import { loadAchd, nativeCli, repo, robots, scratchDir } from './helpers.mjs';

let achd, entry, kuka;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
});

const GOOD = () => ({ q: [...entry.q0], gravity: [0, 0, -9.81] });

function throwsMessage(fn, message) {
  assert.throws(fn, (e) => {
    assert.equal(e.constructor, Error, `a named Error, not ${e.constructor.name}: ${e.message}`);
    assert.match(e.message, message);
    return true;
  });
}

test('what a JSON round trip would change is a named error naming the field and index', () => {
  class Pose { constructor() { this.lwr_joint_1 = 1; } }
  const cyclic = [0, 0, 0, 0, 0, 0];
  cyclic[5] = cyclic;
  const deep = [];  // 100,000 arrays deep: no stack overflow, the parser sees a marked value at depth 32
  let at = deep;
  for (let k = 0; k < 100000; ++k) at = at[0] = [];
  const cases = [
    [{ q: new Map([['lwr_joint_1', 1]]) }, /^q must be an array of 7 numbers or an object \{joint name: value\}, got a Map$/],
    [{ q: new Set([1]) }, /^q must be an array .*, got a Set$/],
    [{ q: new DataView(new ArrayBuffer(56)) }, /^q must be an array .*, got a DataView$/],
    [{ q: new Pose() }, /^q must be an array .*, got a class instance \(not a plain object\)$/],
    [{ q: new BigInt64Array(7) }, /^q must be an array .*, got a BigInt typed array$/],
    [{ q: [0, undefined, 0, 0, 0, 0, 0] }, /^q\[1\] must be a number, got undefined$/],
    [{ q: [0, 1n, 0, 0, 0, 0, 0] }, /^q\[1\] must be a number, got 1n \(a BigInt\)$/],
    [{ q: [0, 0, () => 0, 0, 0, 0, 0] }, /^q\[2\] must be a number, got a function$/],
    [{ q: [0, 0, 0, Symbol('s'), 0, 0, 0] }, /^q\[3\] must be a number, got a symbol$/],
    [{ q: [0, 0, 0, 0, NaN, 0, 0] }, /^q\[4\] is not finite$/],
    [{ q: [0, 0, 0, 0, 0, -Infinity, 0] }, /^q\[5\] is not finite$/],
    [{ q: { lwr_joint_2: undefined } }, /^q\['lwr_joint_2'\] must be a number, got undefined$/],
    [{ qdd_given: [null, undefined, null, null, null, null, null] }, /^qdd_given\[1\] \(joint 'lwr_joint_2'\) must be a number, got undefined$/],
    [{ f_ext: { lwr_link_3: cyclic } }, /^f_ext\['lwr_link_3'\]\[5\] must be a number, got a value that contains itself$/],
    [{ alpha: [deep] }, /^alpha\[0\]: expected 6 values, got 1$/],
    [{ alpha: [[deep, 0, 0, 0, 0, 0]], beta: [0] }, /^alpha\[0\]\[0\] must be a number$/],
    [{ constraints: [{ link: new Map(), alpha: [] }] }, /^constraints\[0\]\.link must be a link name, got a Map$/],
    [{ constraints: [{ link: entry.tip, alpha: undefined }] }, /^constraints\[0\]\.alpha must be an array of 6-element columns, got undefined$/],
  ];
  for (const [patch, message] of cases) throwsMessage(() => kuka.solve({ ...GOOD(), ...patch }), message);
  // An optional field given undefined is absent, as in JS (and as the previous release read it).
  assert.deepEqual(kuka.solve({ ...GOOD(), qd: undefined, alpha: undefined, f_ext: undefined }), kuka.solve(GOOD()));
  // The same words for the other calls that take a case's forms.
  throwsMessage(() => kuka.forwardKinematics(new Map()), /^q must be an array of 7 numbers or an object \{joint name: value\}, got a Map$/);
  throwsMessage(() => kuka.rnea(entry.q0, entry.q0, entry.q0, { f_ext: [new Set()] }), /^f_ext: expected 7 wrenches/);
  throwsMessage(() => kuka.rnea(entry.q0, entry.q0, entry.q0, { f_ext: { lwr_link_2: [0, 0, NaN, 0, 0, 0] } }),
    /^f_ext\['lwr_link_2'\]\[2\] is not finite$/);
  const solver = kuka.createSolver();
  throwsMessage(() => solver.setConstraints([{ link: entry.tip, alpha: [[0, 0, 1, 0, 0, Infinity]] }]),
    /^constraints\[0\]\.alpha\[0\]\[5\] is not finite$/);
  throwsMessage(() => solver.setConstraints(new Set()), /^constraints must be an array of blocks \{link, alpha, beta, point, link_b, point_b\}, got a Set$/);
  throwsMessage(() => solver.setPrescribed(['nope']), /^setPrescribed: no movable joint 'nope' between the root and the tip$/);
  solver.delete();
});

test('typed arrays are read as arrays of their numbers, and -0 keeps its sign', () => {
  const plain = kuka.solve({ ...GOOD(), qd: [0.1, 0, 0, 0, 0, 0, 0.2], alpha: [[0, 0, 1, 0, 0, 0]] });
  const typed = kuka.solve({ q: Float32Array.from(GOOD().q.map(Math.fround)), gravity: new Float64Array([0, 0, -9.81]),
    qd: new Float64Array([0.1, 0, 0, 0, 0, 0, 0.2]), alpha: [new Int8Array([0, 0, 1, 0, 0, 0])] });
  const rounded = kuka.solve({ q: GOOD().q.map(Math.fround), gravity: [0, 0, -9.81], qd: [0.1, 0, 0, 0, 0, 0, 0.2],
    alpha: [[0, 0, 1, 0, 0, 0]] });
  assert.deepEqual(typed, rounded);
  assert.notDeepEqual(plain.qdd, typed.qdd, 'float32 q is its own numbers');
  // A wrench with -0 in it: the C++ side sees -0 (a JSON '-0' would read as the integer 0).
  const fk = kuka.forwardKinematics([-0, 0, 0, 0, 0, 0, 0]);
  assert.deepEqual(fk, kuka.forwardKinematics(new Float64Array([-0, 0, 0, 0, 0, 0, 0])));
});

test('wasm/js holds no case parsing: none of the case parser\'s messages or result names are there', () => {
  const dir = join(repo, 'wasm', 'js');
  for (const file of readdirSync(dir).filter((f) => f.endsWith('.mjs') || f.endsWith('.js'))) {
    const text = readFileSync(join(dir, file), 'utf8');
    for (const words of ['missing required field', 'one per link after the root', 'no movable joint', '{joint name: value}',
      'one per alpha column', 'null where not prescribed', "'coupling "])
      assert.ok(!text.includes(words), `wasm/js/${file} has "${words}": the case parser is tools/case_json.cpp`);
  }
});

test('robot.joints and robot.links are the loader\'s, as `achd info` gives them', async () => {
  const cli = nativeCli();
  const scratch = scratchDir();
  try {
    const tree = robots().length && JSON.parse(readFileSync(join(repo, 'robots/index.json'), 'utf8')).robots.find((r) => !r.tip);
    const loads = [
      { path: entry.path, args: ['--root', entry.root, '--tip', entry.tip], options: { root: entry.root, tip: entry.tip } },
      { path: join(repo, tree.urdf), args: ['--floating'], options: { floating: true } },
    ];
    for (const l of loads) {
      const info = JSON.parse(execFileSync(cli, ['info', l.path, ...l.args], { encoding: 'utf8' }));
      const robot = achd.loadURDF(readFileSync(l.path, 'utf8'), l.options);
      const model = robot.links.filter((link) => link.offset === null);
      assert.deepEqual(model.map((link) => [link.name, link.body, link.mass]),
        info.links.map((link) => [link.name, link.body, link.mass]), l.path);
      assert.deepEqual(model.map((link) => link.frame), model.map((_, i) => i));
      assert.deepEqual(robot.joints.map((j) => [j.name, j.type]), info.joints.map((j) => [j.name, j.type]));
      // Rates and positions: consecutive, the free joint's 6 and 7 first.
      let rate = 0, position = 0;
      for (const j of robot.joints) {
        assert.deepEqual([j.rateIndex, j.positionIndex], [rate, position], j.name);
        assert.deepEqual([j.rateCount, j.positionCount], j.type === 'floating' ? [6, 7] : [1, 1]);
        rate += j.rateCount;
        position += j.positionCount;
      }
      assert.deepEqual([rate, position], [robot.numRates, robot.numPositions]);
      // Every link but the root names its URDF parent and joint.
      for (const link of robot.links.slice(1)) assert.ok(link.parent && link.joint, link.name);
      robot.delete();
    }
  } finally {
    scratch.remove();
  }
});

// A chain a-b with a side branch b-c (a locked revolute joint at 0.5 rad about z, c 1 m
// out along x), each link with a visual.
const SIDE_URDF = `<robot name="side">
  <material name="red"><color rgba="1 0 0 1"/></material>
  <link name="a"><visual><geometry><box size="0.1 0.2 0.3"/></geometry></visual></link>
  <link name="b"><inertial><mass value="2"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><origin xyz="0 0 0.5"/><geometry><cylinder radius="0.05" length="1"/></geometry><material name="red"/></visual></link>
  <link name="c"><inertial><mass value="0.5"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial>
    <visual><geometry><mesh filename="package://x/hand.stl" scale="2 2 2"/></geometry></visual></link>
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="side" type="revolute"><parent link="b"/><child link="c"/><origin xyz="1 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>`;

test('a chain\'s side link rides on its host at its locked value, with its visuals and mass', () => {
  const robot = achd.loadURDF(SIDE_URDF, { root: 'a', tip: 'b', locked: { side: 0.5 } });
  try {
    assert.deepEqual(robot.links.map((l) => [l.name, l.frame, l.parent, l.joint?.name ?? null, l.body, l.mass]),
      [['a', 0, null, null, null, 0], ['b', 1, 'a', 'j', 'j', 2], ['c', 1, 'b', 'side', 'j', 0.5]]);
    const c = robot.links[2];
    assert.deepEqual(c.offset.position, [1, 0, 0]);
    const [cos, sin] = [Math.cos(0.5), Math.sin(0.5)];
    c.offset.rotation.forEach((x, k) => assert.ok(Math.abs(x - [cos, -sin, 0, sin, cos, 0, 0, 0, 1][k]) < 1e-15, `${k}`));
    assert.deepEqual(robot.links[0].visuals[0].geometry, { type: 'box', size: [0.1, 0.2, 0.3] });
    assert.deepEqual(robot.links[0].visuals[0].color, null);
    assert.deepEqual(robot.links[1].visuals[0].geometry, { type: 'cylinder', radius: 0.05, length: 1 });
    assert.deepEqual(robot.links[1].visuals[0].position, [0, 0, 0.5]);
    assert.deepEqual(robot.links[1].visuals[0].color, [1, 0, 0, 1]);
    assert.deepEqual(c.visuals[0].geometry, { type: 'mesh', filename: 'package://x/hand.stl', scale: [2, 2, 2] });
    assert.ok(Object.isFrozen(robot.links) && Object.isFrozen(robot.links[2].offset));
  } finally {
    robot.delete();
  }
});

test('the page parses no URDF beyond the picker: DOMParser only in modules the picker alone imports', () => {
  const web = join(repo, 'web');
  const files = readdirSync(web).filter((f) => f.endsWith('.js'));
  const parsing = files.filter((f) => readFileSync(join(web, f), 'utf8').includes('DOMParser'));
  const PICKER = 'urdf_upload.js';
  const imports = (f) => [...readFileSync(join(web, f), 'utf8').matchAll(/from '\.\/([\w.]+\.js)'/g)].map((m) => m[1]);
  for (const f of parsing) {
    if (f === PICKER) continue;
    const importers = files.filter((g) => imports(g).includes(f));
    assert.deepEqual(importers, [PICKER], `web/${f} parses XML and is imported by ${importers.join(', ') || 'nothing'}`);
  }
  assert.ok(parsing.includes(PICKER), 'the picker reads names before loading');
  // The page's view and simulation read the module's links, not the URDF text.
  for (const f of ['simulation.js', 'main.js', 'chain_view.js', 'robot_feet.js'])
    assert.doesNotMatch(readFileSync(join(web, f), 'utf8'), /urdf_tree\.js|urdfTree|DOMParser/, `web/${f}`);
});
