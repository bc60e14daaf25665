// The page's URL hash (web/settings.js) speaks the scene files' words: it writes
// semi_implicit_euler and velocity_products, reads them back, and still reads the
// previous release's words (semi-implicit, euler, velocity, push) as those names.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { EFFECTS, INTEGRATORS, defaultSettings, formatHash, parseHash } from '../../web/settings.js';

test('the hash writes the scene names and reads them back', () => {
  const s = defaultSettings('ur5');
  s.integrator = 'semi_implicit_euler';
  s.effects.friction = false;
  s.directions.z = 'hold';
  const hash = formatHash(s);
  assert.equal(hash,
    '#robot=ur5&integrator=semi_implicit_euler&dt=0.001&effects=gravity,velocity_products,damping,external_wrenches&dirs=z:hold');
  assert.deepEqual(parseHash(hash, defaultSettings('kuka_lwr4')), { settings: s, problems: [] });
  assert.deepEqual(INTEGRATORS.slice().sort(), ['explicit_euler', 'rk4', 'semi_implicit_euler']);
});

test('hashes with the previous release\'s words still parse, as the current names', () => {
  for (const [old, now] of [['semi-implicit', 'semi_implicit_euler'], ['euler', 'explicit_euler']]) {
    const { settings, problems } = parseHash(`#integrator=${old}`, defaultSettings('ur5'));
    assert.deepEqual(problems, []);
    assert.equal(settings.integrator, now);
  }
  const { settings, problems } = parseHash('#effects=velocity,push', defaultSettings('ur5'));
  assert.deepEqual(problems, []);
  assert.deepEqual(settings.effects, Object.fromEntries(EFFECTS.map((e) =>
    [e.key, e.key === 'velocityProducts' || e.key === 'externalWrenches'])));
  assert.deepEqual(parseHash('#integrator=verlet', defaultSettings('ur5')).problems, ['unknown integrator "verlet"']);
  assert.deepEqual(parseHash('#integrator=toString', defaultSettings('ur5')).problems, ['unknown integrator "toString"']);
});
