// The bad-input list through JS: every kind throws an Error whose message names
// the problem (the same list as tests/native/bad_input_urdfs.hpp for the C++ API and
// the CLI), massless links load, and NaN/Infinity in every case field name the field.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAchd, robots } from './helpers.mjs';

let achd, kuka, entry;
before(async () => {
  achd = await loadAchd();
  entry = robots().find((r) => r.name === 'kuka_lwr4');
  kuka = achd.loadURDF(entry.text, { root: entry.root, tip: entry.tip });
});

const inertial = (mass = '1', ixx = '1', ixy = '0', izz = '1') =>
  `<inertial><mass value="${mass}"/><inertia ixx="${ixx}" ixy="${ixy}" ixz="0" iyy="1" iyz="0" izz="${izz}"/></inertial>`;
const link = (name, body = inertial()) => `<link name="${name}">${body}</link>`;
const limit = '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>';
const joint = (name, type, parent, child, extra = limit) =>
  `<joint name="${name}" type="${type}"><parent link="${parent}"/><child link="${child}"/>` +
  `<origin xyz="0.1 0 0"/>${extra}</joint>`;
const robot = (body) => `<robot name="r">${body}</robot>`;
const ab = link('a') + link('b');

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
    'a', 'b', /link 'b': inertia is not positive semi-definite/],
  ['triangle inequality', robot(link('a') + link('b', inertial('1', '1', '0', '2.00000001')) +
    joint('j', 'revolute', 'a', 'b')), 'a', 'b', /link 'b': inertia violates the triangle inequality/],
  ['NaN mass', robot(link('a') + link('b', inertial('nan')) + joint('j', 'revolute', 'a', 'b')), 'a', 'b',
    /mass \[nan\]/],
  ['Inf inertia', robot(link('a') + link('b', inertial('1', 'inf')) + joint('j', 'revolute', 'a', 'b')), 'a', 'b',
    /ixx/],
  ['moving a massless link', robot(link('a') + link('b', '') + joint('j', 'revolute', 'a', 'b')), 'a', 'b',
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
];

for (const [what, xml, root, tip, message] of badUrdfs) {
  test(`bad URDF: ${what}`, () => {
    assert.throws(() => achd.loadURDF(xml, { root, tip }),
      (e) => e instanceof Error && message.test(e.message), `expected ${message}`);
  });
}

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
