// Every JS input is read once into a copy that is checked and then written: an array
// Proxy that reports more elements on a second read (of its length or its descriptors)
// changes nothing, for every array input of robot.solve, the zero-copy solver, reset,
// the direction setters, the joint control and rnea. What is not an array, a typed array
// or a plain {name: value} object (a Map, a DataView, a class instance), a getter, a
// number given as a string and a null options object are errors that name the input
// (with the CLI's words where the CLI has the same error; kinds JSON cannot hold are
// named: ", got a Map");
// numbers in messages are printed as given; a link named '__proto__' keeps its key.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAchd, robots } from './helpers.mjs';

let achd, entry, robot;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  robot = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
});

// An array Proxy that tells the truth on its first read of the length and then claims
// 5000 elements of 1e300 (through both `get` and its own-property descriptors): code that
// checks the length and then copies the array again writes far past its buffer.
function growing(values) {
  let lengthReads = 0;
  const grown = () => lengthReads > 1;
  return new Proxy(values.slice(), {
    get(target, key, receiver) {
      if (key === 'length') return ++lengthReads > 1 ? 5000 : target.length;
      if (typeof key === 'string' && /^\d+$/.test(key) && grown() && Number(key) >= target.length) return 1e300;
      return Reflect.get(target, key, receiver);
    },
    getOwnPropertyDescriptor(target, key) {
      const d = Reflect.getOwnPropertyDescriptor(target, key);
      if (key === 'length') return { ...d, value: ++lengthReads > 1 ? 5000 : target.length };
      if (d === undefined && /^\d+$/.test(key) && grown())
        return { value: 1e300, writable: true, enumerable: true, configurable: true };
      return d;
    },
  });
}

function throwsMessage(fn, message) {
  assert.throws(fn, (e) => {
    assert.equal(e.constructor, Error, `a named Error, not ${e.constructor.name}: ${e.message}`);
    assert.match(e.message, message);
    return true;
  });
}

const N = 7;
const CASE = {
  q: [0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1],
  qd: [0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.7],
  ff_torques: [1, -2, 0.5, 3, -0.1, 0.2, 0.05],
  gravity: [0.5, 0, -9.81],
  alpha: [[1, 0, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0]],
  beta: [0.1, -0.3],
  w_fext: [1, 0.5],
  w_ff: [0.25, 1],
  f_ext: Array.from({ length: N }, (_, i) => [i, -1, 0.5, 0.1 * i, 0, -0.2]),
  f_virtual: Array.from({ length: N }, (_, i) => [0, 0.1 * i, 0, 0, 0.2, 0]),
  qdd_given: [null, null, 0.5, null, null, null, null],
  constraints: [{ link: 'lwr_link_5', alpha: [[0, 1, 0, 0, 0, 0]], beta: [0.2], point: [0, 0, 0.1], w_fext: [1], w_ff: [1] }],
};

test('robot.solve: a growing Proxy as any array input gives the plain arrays\' answer', () => {
  const expected = robot.solve(CASE);
  const inputs = [['q'], ['qd'], ['ff_torques'], ['gravity'], ['alpha'], ['alpha', 0], ['beta'], ['w_fext'], ['w_ff'],
    ['f_ext'], ['f_ext', 3], ['f_virtual'], ['f_virtual', 6], ['qdd_given'], ['constraints'],
    ['constraints', 0, 'alpha'], ['constraints', 0, 'alpha', 0], ['constraints', 0, 'beta'], ['constraints', 0, 'point'],
    ['constraints', 0, 'w_fext'], ['constraints', 0, 'w_ff']];
  for (const path of inputs) {
    const c = structuredClone(CASE);
    let parent = c;
    for (const key of path.slice(0, -1)) parent = parent[key];
    parent[path.at(-1)] = growing(parent[path.at(-1)]);
    assert.deepEqual(robot.solve(c), expected, path.join('.'));
  }
  assert.deepEqual(robot.solve(CASE), expected, 'and the solver is unharmed');
});

test('the zero-copy solver, reset, the direction setters and the joint control read a growing Proxy once', () => {
  const solver = robot.createSolver();
  solver.q.set(CASE.q);
  solver.gravity.set(CASE.gravity);
  solver.setConstraints(CASE.constraints);
  solver.setPrescribed(['lwr_joint_2']);
  solver.solve();
  const expected = Array.from(solver.qdd);
  const blocks = [{ ...CASE.constraints[0], alpha: growing(CASE.constraints[0].alpha), point: growing([0, 0, 0.1]) }];
  solver.setConstraints(growing(blocks));
  solver.setPrescribed(growing(['lwr_joint_2']));
  solver.solve();
  assert.deepEqual(Array.from(solver.qdd), expected);
  solver.delete();

  const sim = robot.createSimulator();
  sim.reset(growing(entry.q0), growing(new Array(N).fill(0)));
  sim.setDirectionPoint(entry.tip, growing([0, 0, 0.05]));
  sim.setDirection('z', 'hold');
  sim.setJointControl({ target: growing(entry.q0), kp: growing(new Array(N).fill(10)), kd: growing(new Array(N).fill(1)) });
  sim.setExternalWrench(2, growing([1, 0, 0, 0, 0, 0]));
  sim.step(10);
  const q = Array.from(sim.q);
  const plain = robot.createSimulator();
  plain.reset(entry.q0);
  plain.setDirectionPoint(entry.tip, [0, 0, 0.05]);
  plain.setDirection('z', 'hold');
  plain.setJointControl({ target: entry.q0, kp: 10, kd: 1 });
  plain.setExternalWrench(2, [1, 0, 0, 0, 0, 0]);
  plain.step(10);
  assert.deepEqual(q, Array.from(plain.q));
  sim.delete();
  plain.delete();

  const torques = robot.rnea(CASE.q, CASE.qd, CASE.ff_torques, { gravity: CASE.gravity, f_ext: CASE.f_ext });
  assert.deepEqual(robot.rnea(growing(CASE.q), growing(CASE.qd), growing(CASE.ff_torques),
    { gravity: growing(CASE.gravity), f_ext: growing(CASE.f_ext) }), torques);
  assert.deepEqual(robot.massMatrix(growing(CASE.q)), robot.massMatrix(CASE.q));
  assert.deepEqual(robot.forwardKinematics(growing(CASE.q)), robot.forwardKinematics(CASE.q));
});

test('Map, DataView, Set, class instances and BigInt arrays are named errors, not read as empty objects', () => {
  class Pose { constructor() { this.lwr_joint_1 = 1; } }
  const bad = [[new Map([['lwr_joint_1', 1]]), /a Map/], [new DataView(new ArrayBuffer(56)), /a DataView/],
    [new Set([1]), /a Set/], [new Pose(), /a class instance/], [new BigInt64Array(7), /BigInt/], ['1,2,3', /\{joint name: value\}$/]];
  for (const [value, kind] of bad) {
    throwsMessage(() => robot.solve({ q: value, gravity: [0, 0, -9.81] }), new RegExp(`^q must be an array.*${kind.source}`));
    throwsMessage(() => robot.forwardKinematics(value), /^q must be an array/);
  }
  throwsMessage(() => robot.solve({ q: CASE.q, gravity: new Map() }), /^gravity must be an array of 3 numbers, got a Map$/);
  throwsMessage(() => robot.solve(new Map()), /^the case must be a JSON object, got a Map$/);
  throwsMessage(() => robot.solve({ q: CASE.q, gravity: [0, 0, -9.81], f_ext: new Map() }), /^f_ext must be an array.*got a Map$/);
  const sim = robot.createSimulator();
  throwsMessage(() => sim.reset(new DataView(new ArrayBuffer(56))), /^q must be an array of 7 numbers, got a DataView$/);
  throwsMessage(() => sim.setJointControl(new Map()), /setJointControl: the control \{target, kp, kd\} or \{target, frequency, dampingRatio, feedforward\} must be an object, got a Map/);
  sim.delete();
});

test('getters are refused, on array elements and on object properties', () => {
  const q = CASE.q.slice();
  Object.defineProperty(q, 2, { get: () => 0.5, enumerable: true });
  throwsMessage(() => robot.solve({ q, gravity: [0, 0, -9.81] }), /^q\[2\] must be a number, got a getter \(give plain values\)$/);
  throwsMessage(() => robot.solve({ q: { get lwr_joint_1() { return 1; } }, gravity: [0, 0, -9.81] }),
    /^q\['lwr_joint_1'\] must be a number, got a getter/);
  throwsMessage(() => robot.solve({ get q() { return CASE.q; }, gravity: [0, 0, -9.81] }),
    /^q must be an array of 7 numbers or an object \{joint name: value\}, got a getter/);
  const sim = robot.createSimulator();
  throwsMessage(() => sim.setDirectionWeights('z', { get wFext() { return 0.5; } }), /wFext is a getter/);
  throwsMessage(() => sim.step(10, 1e-3, { get onProgress() { return () => {}; } }), /step options\.onProgress is a getter/);
  sim.delete();
});

test('numbers must be numbers: a string weight, gain or position is an error', () => {
  const sim = robot.createSimulator();
  throwsMessage(() => sim.setDirectionWeights('z', { wFext: '0.5' }), /^setDirectionWeights: wFext must be a number in \[0, 1\], got '0\.5'$/);
  throwsMessage(() => sim.setDirectionWeights('z', { wFf: [0.5] }), /wFf must be a number.*got an array/);
  throwsMessage(() => sim.setJointControl({ target: entry.q0, kp: '10' }), /^setJointControl: kp must be an array of 7 numbers$/);
  throwsMessage(() => sim.reset(entry.q0.map(String)), /^q\[0\] must be a number$/);
  sim.delete();
  throwsMessage(() => robot.solve({ ...CASE, w_fext: ['1', 1] }), /^w_fext\[0\] must be a number$/);
  throwsMessage(() => robot.solve({ ...CASE, qd: { lwr_joint_1: '0.5' } }), /^qd\['lwr_joint_1'\] must be a number$/);
});

test('null where an options object goes is a named error', () => {
  const sim = robot.createSimulator();
  throwsMessage(() => sim.setDirectionWeights('z', null), /^setDirectionWeights: weights \{wFext, wFf\} must be an object$/);
  throwsMessage(() => sim.setJointControl(null), /^setJointControl: the control \{target, kp, kd\} or \{target, frequency, dampingRatio, feedforward\} must be an object$/);
  throwsMessage(() => sim.prescribe(1, null), /^prescribe: motion must be an object$/);
  throwsMessage(() => robot.massMatrix(CASE.q, null), /^options must be an object$/);
  throwsMessage(() => robot.rnea(CASE.q, CASE.qd, CASE.ff_torques, null), /^options must be an object$/);
  throwsMessage(() => robot.createSimulator({ jointControl: null }), /^options\.jointControl must be an object$/);
  throwsMessage(() => robot.createSimulator(null), /must be an object/);
  throwsMessage(() => robot.createSolver(null), /must be an object/);
  throwsMessage(() => robot.solve(CASE, null), /^options must be an object$/);
  throwsMessage(() => sim.step(1, 1e-3, null), /^step options must be an object$/);
  throwsMessage(() => achd.loadURDF(entry.text, null), /^loadURDF options must be an object$/);
  sim.setDirectionWeights('z');  // omitted: the defaults
  sim.delete();
});

test('numbers in messages are printed as given (no int32 wrap)', () => {
  throwsMessage(() => robot.createSolver({ maxConstraints: 2 ** 31 }), /^options\.maxConstraints must be an integer in \[0, 6\], got 2147483648$/);
  throwsMessage(() => robot.createSolver({ maxConstraints: 2 ** 32 + 1 }), /got 4294967297$/);
  const solver = robot.createSolver();
  throwsMessage(() => { solver.numConstraints = 2 ** 31; }, /got 2147483648$/);
  throwsMessage(() => { solver.numConstraints = -(2 ** 32); }, /got -4294967296$/);
  solver.delete();
  const sim = robot.createSimulator();
  throwsMessage(() => sim.setDirection('z', Symbol('x')), /mode must be 'hold', 'free' or a finite number, got a symbol/);
  throwsMessage(() => sim.setDirection('z', 'hold', 2n), /unknown link 2n \(a BigInt\)/);
  sim.delete();
});

// A tree whose second link is named '__proto__' (held at a point off the hinge axis).
const PROTO_URDF = `<robot name="proto">
  <link name="base"/>
  <link name="__proto__"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>
    <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="hinge" type="revolute"><parent link="base"/><child link="__proto__"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="100" velocity="10"/></joint>
</robot>`;

test('constraintWrenches keeps a link named __proto__ as a key', () => {
  const tree = achd.loadURDF(PROTO_URDF);
  const sim = tree.createSimulator();
  sim.setDirectionPoint('__proto__', [1, 0, 0]);
  sim.setDirection('z', 'hold', '__proto__');
  sim.step(1);
  const wrenches = sim.constraintWrenches();
  assert.deepEqual(Object.keys(wrenches), ['__proto__']);
  assert.equal(Object.getPrototypeOf(wrenches), Object.prototype);
  assert.equal(wrenches.__proto__.length, 6);
  assert.ok(Math.abs(wrenches.__proto__[2]) > 1, `the held point carries about half the weight: ${wrenches.__proto__}`);
  // and as an input key: a wrench by link name '__proto__'
  const r = tree.solve({ q: [0], gravity: [0, 0, -9.81], f_ext: { ["__proto__"]: [0, 5, 0, 0, 5, 0] } });
  const r0 = tree.solve({ q: [0], gravity: [0, 0, -9.81] });
  assert.notDeepEqual(r.qdd, r0.qdd);
  sim.delete();
  tree.delete();
});
