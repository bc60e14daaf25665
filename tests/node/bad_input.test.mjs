// The bad-input list through JS: every kind throws an Error whose message names
// the problem (the same list as tests/native/support/bad_input_urdfs.hpp for the C++ API and
// the CLI), massless links load, and NaN/Infinity in every case field name the field.
// No failed load leaks or breaks the module; the wasm loader reads the same
// numbers as the native one; mimic joints load only when asked for.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { before, test } from 'node:test';

import { loadAchd, nativeCli, robots, scratchDir } from './helpers.mjs';

let achd, kuka, entry;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
});

const inertial = (mass = '1', ixx = '1', ixy = '0', izz = '1') =>
  `<inertial><mass value="${mass}"/><inertia ixx="${ixx}" ixy="${ixy}" ixz="0" iyy="1" iyz="0" izz="${izz}"/></inertial>`;
const link = (name, body = inertial()) => `<link name="${name}">${body}</link>`;
// Mass x and principal moments x.
const diagonalInertial = (x) =>
  `<inertial><mass value="${x}"/><inertia ixx="${x}" ixy="0" ixz="0" iyy="${x}" iyz="0" izz="${x}"/></inertial>`;
const limit = '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>';
const joint = (name, type, parent, child, extra = limit) =>
  `<joint name="${name}" type="${type}"><parent link="${parent}"/><child link="${child}"/>` +
  `<origin xyz="0.1 0 0"/>${extra}</joint>`;
const robot = (body) => `<robot name="r">${body}</robot>`;
const ab = link('a') + link('b');
const nested = (depth) => '<x>'.repeat(depth) + '</x>'.repeat(depth);
const continuous = (name, parent, child, origin) =>
  `<joint name="${name}" type="continuous"><parent link="${parent}"/><child link="${child}"/>` +
  `<origin ${origin}/><axis xyz="0 0 1"/></joint>`;

const badUrdfs = [
  ['malformed XML', '<robot name="r"><link name="a">', 'a', 'b', /cannot parse URDF/],
  ['empty document', '', 'a', 'b', /cannot parse URDF.*empty/],
  ['cycle', robot(link('a') + link('b') + link('c') + joint('j1', 'revolute', 'a', 'b') +
    joint('j2', 'revolute', 'b', 'c') + joint('j3', 'revolute', 'c', 'a')), 'a', 'b', /cannot parse URDF.*root/],
  ['cycle below the root', robot(link('r') + link('a') + link('b') + link('c') + joint('j0', 'revolute', 'r', 'a') +
    joint('j1', 'revolute', 'c', 'b') + joint('j2', 'revolute', 'b', 'c')), 'r', 'b',
  /the links form a cycle through link/],
  ['several roots', robot(ab + link('c') + link('d') + joint('j1', 'revolute', 'a', 'b') +
    joint('j2', 'revolute', 'c', 'd')), 'a', 'b', /Two root links.*\[a\].*\[c\]/],
  ['unknown root', robot(ab + joint('j', 'revolute', 'a', 'b')), 'x', 'b', /unknown root link 'x'/],
  ['unknown tip', robot(ab + joint('j', 'revolute', 'a', 'b')), 'a', 'x', /unknown tip link 'x'/],
  ['tip not below root', robot(ab + link('c') + joint('j1', 'revolute', 'a', 'b') + joint('j2', 'revolute', 'a', 'c')),
    'b', 'c', /tip link 'c' is not below root link 'b'/],
  ['negative mass', robot(link('a') + link('b', inertial('-1')) + joint('j', 'revolute', 'a', 'b')), 'a', 'b',
    /link 'b': negative mass/],
  ['inertia not PSD', robot(link('a') + link('b', inertial('1', '1', '2')) + joint('j', 'revolute', 'a', 'b')),
    'a', 'b', /link 'b': spatial inertia is not positive semi-definite/],
  ['NaN mass', robot(link('a') + link('b', inertial('nan')) + joint('j', 'revolute', 'a', 'b')), 'a', 'b',
    /mass \[nan\]/],
  ['Inf inertia', robot(link('a') + link('b', inertial('1', 'inf')) + joint('j', 'revolute', 'a', 'b')), 'a', 'b',
    /ixx/],
  ['a point mass on the joint axis', robot(link('a') + link('b', '<inertial><origin xyz="0 0 0.5"/><mass value="1"/>' +
    '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>') + joint('j', 'revolute', 'a', 'b')), 'a', 'b',
  /joint 'j' moves nothing.*D = S\^T IA S = 0/],
  ['a later coaxial joint frees the motion', robot(link('a') + link('b', '') + link('c') +
    joint('j1', 'revolute', 'a', 'b') +
    '<joint name="j2" type="continuous"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/></joint>'),
  'a', 'c', /joint 'j1' moves nothing/],
  ['floating joint', robot(ab + joint('j', 'floating', 'a', 'b', '')), 'a', 'b',
    /joint 'j': unsupported joint type 'floating'/],
  ['planar joint', robot(ab + joint('j', 'planar', 'a', 'b', '<axis xyz="0 0 1"/>')), 'a', 'b',
    /joint 'j': unsupported joint type 'planar'/],
  ['zero axis', robot(ab + joint('j', 'revolute', 'a', 'b',
    '<axis xyz="0 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>')), 'a', 'b', /joint 'j': axis is zero/],
  ['no movable joint', robot(ab + joint('j', 'fixed', 'a', 'b', '')), 'a', 'b', /no movable joint/],
  ['elements nested too deep', robot(ab + joint('j', 'revolute', 'a', 'b') + nested(100)), 'a', 'b',
    /^URDF: cannot parse URDF: elements nested more than 100 deep \(line 1\)/],
  ['elements nested 50000 deep', robot(ab + joint('j', 'revolute', 'a', 'b') + nested(50000)), 'a', 'b',
    /nested more than 100 deep/],
  ['a later coaxial joint, moved along and turned about the axis', robot(link('a') + link('b', '') + link('c') +
    joint('j1', 'revolute', 'a', 'b') + continuous('j2', 'b', 'c', 'xyz="0 0 0.3" rpy="0 0 0.7"')), 'a', 'c',
  /joint 'j1' moves nothing/],
  ['three parallel joints on one line with massless links between', robot(link('a') + link('b', '') + link('c', '') +
    link('d') + joint('j1', 'revolute', 'a', 'b') + joint('j2', 'revolute', 'b', 'c') + joint('j3', 'revolute', 'c', 'd')),
  'a', 'd', /joint 'j1' moves nothing/],
  ['joints 1e200 m apart', robot(ab + link('c') + joint('j1', 'revolute', 'a', 'b') +
    continuous('j2', 'b', 'c', 'xyz="1e200 0 0"')), 'a', 'c', /joint 'j2': origin overflows.*moved to joint 'j1'/],
  ['positions that add up past the largest double', robot(link('a') + link('b') + link('c') +
    continuous('j1', 'a', 'b', 'xyz="1e308 0 0"') + continuous('j2', 'b', 'c', 'xyz="1e308 0 0"')), 'a', 'c',
  /joint 'j2': origin overflows: its position from the root/],
  ['a link fixed 1e200 m away', robot(ab + link('c') + joint('j', 'revolute', 'a', 'b') +
    '<joint name="f" type="fixed"><parent link="b"/><child link="c"/><origin xyz="1e200 0 0"/></joint>'), 'a', 'c',
  /joint 'f': origin overflows: link 'c' moved by it to joint 'j'/],
  ['fixed origins that add up past the largest double', robot(ab + link('c', '') + link('d', '') +
    joint('j', 'revolute', 'a', 'b') +
    '<joint name="f1" type="fixed"><parent link="b"/><child link="c"/><origin xyz="1e308 0 0"/></joint>' +
    '<joint name="f2" type="fixed"><parent link="c"/><child link="d"/><origin xyz="1e308 0 0"/></joint>'), 'a', 'd',
  /joint 'f2': origin overflows: its position from joint 'j' is not finite/],
  ['an inertial origin 1e200 m away', robot(link('a') + link('b', '<inertial><origin xyz="0 1e200 0"/><mass value="1"/>' +
    '<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>') + joint('j', 'revolute', 'a', 'b')), 'a', 'b',
  /link 'b': <inertial> overflows/],
];

for (const [what, xml, root, tip, message] of badUrdfs) {
  test(`bad URDF: ${what}`, () => {
    assert.throws(() => achd.loadURDF(xml, { root, tip }),
      (e) => e instanceof Error && message.test(e.message), `expected ${message}`);
  });
}

// The text of a 50000-deep URDF is refused before TinyXML sees it: before, each attempt
// overflowed the JS stack inside the parser (RangeError) and leaked the half-built
// document, ~0.5 MB, so that 60 attempts grew the memory from 16 to 48 MB.
test('failed loads of a deeply nested URDF leave the memory as it was and the module usable', () => {
  const deep = robot(ab + joint('j', 'revolute', 'a', 'b') + nested(50000));
  const attempt = () => assert.throws(() => achd.loadURDF(deep, { root: 'a', tip: 'b' }),
    (e) => e instanceof Error && !(e instanceof RangeError) && /nested more than 100 deep/.test(e.message));
  attempt();
  const bytes = achd.memoryBytes();
  for (let k = 0; k < 60; ++k) attempt();
  assert.equal(achd.memoryBytes(), bytes);
  const r = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
  assert.ok(Array.from(r.solve({ q: entry.q0, gravity: [0, 0, -9.81] }).qdd).every(Number.isFinite));
  r.delete();
});

// Every other failed load frees what it built: each bad URDF carries a 512 KB comment
// (kept in TinyXML's document), so that anything left behind by 4 rounds of the list
// (~40 MB) would have to grow the memory.
test('no failed load leaks', () => {
  const padding = `<!--${'x'.repeat(1 << 19)}-->`;
  const round = () => {
    for (const [, xml, root, tip] of badUrdfs)
      assert.throws(() => achd.loadURDF(padding + xml, { root, tip }), Error);
  };
  round();
  const bytes = achd.memoryBytes();
  for (let k = 0; k < 4; ++k) round();
  assert.equal(achd.memoryBytes(), bytes);
});

// The wasm build parsed numbers with libc++, which refuses an underflow (4e-320, a
// denormal; 1e-400) and accepts nan, inf and hex floats, unlike the native urdfdom.
test('the wasm loader reads the same numbers as the native one', () => {
  const cli = nativeCli();
  const scratch = scratchDir();
  try {
    const c = scratch.write('case.json', '{"q": [0.3], "gravity": [0, 0, -9.81]}');
    for (const x of ['4e-320', '1e-400', '-1e-400', '2.2250738585072014e-308', ' 1', '+1', '1.', '.5', '1e',
      'nan', 'inf', '-inf', '0x1p3', '1,5', '1e400']) {
      const xml = robot(link('a') + link('b', diagonalInertial(x)) + joint('j', 'revolute', 'a', 'b'));
      let native;
      try {
        execFileSync(cli, ['solve', scratch.write('r.urdf', xml), '--root', 'a', '--tip', 'b', '--case', c],
          { stdio: 'pipe' });
        native = 'loads';
      } catch (e) {
        native = /cannot parse URDF/.test(e.stderr.toString()) ? 'parse error' : 'loads';
      }
      let wasm;
      try {
        achd.loadURDF(xml, { root: 'a', tip: 'b' }).delete();
        wasm = 'loads';
      } catch (e) {
        wasm = /cannot parse URDF/.test(e.message) ? 'parse error' : 'loads';
      }
      assert.equal(wasm, native, `mass and inertia ${x}`);
    }
  } finally {
    scratch.remove();
  }
});

test('a denormal mass loads, and solving it gives finite numbers or an Error naming a joint', () => {
  const r = achd.loadURDF(robot(link('a') + link('b', diagonalInertial('4e-320')) + joint('j', 'revolute', 'a', 'b')),
    { root: 'a', tip: 'b' });
  try {
    const out = r.solve({ q: [0.3], gravity: [0, 0, -9.81] });
    assert.ok(Array.from(out.qdd).every(Number.isFinite));
  } catch (e) {
    assert.ok(e instanceof Error && /joint 'j'/.test(e.message), e.message);
  } finally {
    r.delete();
  }
});

test('mimic joints are coupled by default, refused with mimic: \'error\', independent on request', () => {
  const body = ab + link('c') + joint('j1', 'revolute', 'a', 'b');
  const xml = robot(body + joint('j2', 'revolute', 'b', 'c', `${limit}<mimic joint="j1" multiplier="-1"/>`));
  const coupled = achd.loadURDF(xml, { root: 'a', tip: 'c' });
  assert.deepEqual(coupled.couplings, [{ joint: 'j2', leader: 'j1', multiplier: -1, offset: 0 }]);
  const r = coupled.solve({ q: [0.2, -0.2], gravity: [0, 0, -9.81] });
  assert.ok(Math.abs(r.qdd[1] + r.qdd[0]) <= 1e-12 * Math.abs(r.qdd[0]), `qdd ${r.qdd}`);
  assert.deepEqual(r.nu_owners, ['coupling j2']);
  coupled.delete();
  assert.throws(() => achd.loadURDF(xml, { root: 'a', tip: 'c', mimic: 'error' }), /joint 'j2': <mimic> of joint 'j1'/);
  assert.throws(() => achd.loadURDF(xml, { root: 'a', tip: 'c', mimic: 'fold' }),
    /loadURDF: options.mimic: expected 'error' or 'independent' or 'couple', got 'fold'/);
  const m = achd.loadURDF(xml, { root: 'a', tip: 'c', mimic: 'independent' });
  const plain = achd.loadURDF(robot(body + joint('j2', 'revolute', 'b', 'c')), { root: 'a', tip: 'c' });
  const c = { q: [0.2, -0.4], gravity: [0, 0, -9.81] };
  assert.deepEqual(Array.from(m.solve(c).qdd), Array.from(plain.solve(c).qdd));
  m.delete();
  plain.delete();
});

test('an axis of length 1e200 is the same axis as one of length 1', () => {
  const withAxis = (axis) => achd.loadURDF(robot(ab + joint('j', 'continuous', 'a', 'b', `<axis xyz="${axis}"/>`)),
    { root: 'a', tip: 'b' });
  const huge = withAxis('1e200 0 0'), unit = withAxis('1 0 0');
  assert.deepEqual(huge.forwardKinematics([0.7]), unit.forwardKinematics([0.7]));
  huge.delete();
  unit.delete();
});

test('massless links in the middle of a chain are valid', () => {
  const m = achd.loadURDF(robot(link('a') + link('b', '') + link('c') + joint('j1', 'revolute', 'a', 'b') +
    '<joint name="j2" type="continuous"><parent link="b"/><child link="c"/><origin xyz="0.2 0 0"/>' +
    '<axis xyz="0 1 0"/></joint>'), { root: 'a', tip: 'c' });
  const r = m.solve({ q: [0.1, 0.2], gravity: [0, 0, -9.81] });
  assert.ok(Array.from(r.qdd).every(Number.isFinite));
});

test('NaN, Infinity and -Infinity in every case field name the field and index', () => {
  const good = () => ({
    q: [...entry.q0], qd: Array(7).fill(0), ff_torques: Array(7).fill(0), gravity: [0, 0, -9.81],
    alpha: [[1, 0, 0, 0, 0, 0], [0, 0, 0, 0, 1, 0]], beta: [0, 0], f_ext: Array.from({ length: 7 }, () => Array(6).fill(0)),
  });
  const fields = [
    [(c, x) => { c.q[3] = x; }, /^q\[3\] is not finite$/],
    [(c, x) => { c.qd[6] = x; }, /^qd\[6\] is not finite$/],
    [(c, x) => { c.ff_torques[0] = x; }, /^ff_torques\[0\] is not finite$/],
    [(c, x) => { c.gravity[2] = x; }, /^gravity\[2\] is not finite$/],
    [(c, x) => { c.alpha[1][5] = x; }, /^alpha\[1\]\[5\] is not finite$/],
    [(c, x) => { c.beta[1] = x; }, /^beta\[1\] is not finite$/],
    [(c, x) => { c.f_ext[2][4] = x; }, /^f_ext\[2\]\[4\] is not finite$/],
  ];
  kuka.solve(good());
  for (const [set, message] of fields) {
    for (const x of [NaN, Infinity, -Infinity]) {
      const c = good();
      set(c, x);
      assert.throws(() => kuka.solve(c), (e) => e instanceof Error && message.test(e.message), `${message} ${x}`);
    }
  }
});

test('seven or more constraints and bad solver options are refused', () => {
  const c = { q: entry.q0, gravity: [0, 0, -9.81] };
  for (const n of [7, 12]) {
    assert.throws(() => kuka.solve({ ...c, alpha: Array(n).fill([1, 0, 0, 0, 0, 0]), beta: Array(n).fill(0) }),
      new RegExp(`alpha: at most 6 constraints, got ${n}`));
  }
  for (const x of [NaN, Infinity, -1]) {
    assert.throws(() => kuka.solve(c, { tolerance: x }), /tolerance/);
    assert.throws(() => kuka.solve(c, { policy: 'damped', damping: x }), /damping/);
  }
  assert.throws(() => kuka.solve(c, { policy: 'damped', damping: 0 }), /options\.damping must be a finite number > 0, got 0$/);
});
