// The JS wrapper is ES modules by concern (wasm/js/*.mjs) that the build joins into the
// module's --post-js script: each imports on its own in plain Node, with no wasm module
// behind it, and the parts that need none (the checks of user values) work there.
import assert from 'node:assert/strict';
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { repo } from './helpers.mjs';

const jsDir = join(repo, 'wasm', 'js');

test('every module of the wrapper imports on its own', async () => {
  const modules = readdirSync(jsDir).filter((f) => f.endsWith('.mjs') && f !== 'bundle.mjs');
  assert.ok(modules.length >= 8, `modules: ${modules.join(', ')}`);
  for (const file of modules) {
    const m = await import(join(jsDir, file));
    assert.ok(Object.keys(m).length > 0, `${file} exports nothing`);
  }
});

test('the checks of user values work without wasm', async () => {
  const v = await import(join(jsDir, 'validation.mjs'));
  assert.throws(() => v.achdReadNumbers([1, 2], 'q', 3), /^Error: q: expected 3 values, got 2$/);
  assert.throws(() => v.achdReadNumbers([1, NaN, 3], 'q', 3), /^Error: q\[1\] is not finite$/);
  assert.throws(() => v.achdReadNumbers([1, '2', 3], 'q', 3), /^Error: q\[1\] must be a number$/);
  assert.throws(() => v.achdReadNumbers(new Map(), 'q', 3), /^Error: q must be an array of 3 numbers, got a Map$/);
  assert.deepEqual(v.achdReadNumbers(new Int32Array([1, 2, 3]), 'q', 3), new Float64Array([1, 2, 3]));
  assert.throws(() => v.achdCheckObject({ q: 1, x: 2 }, 'the case', ['q']), /the case: unknown field 'x'/);
  assert.equal(v.achdChoice(undefined, ['a', 'b'], 'b', 'o'), 1);
  assert.throws(() => v.achdChoice('c', ['a', 'b'], 'a', 'options.x'), /options.x: expected 'a' or 'b', got 'c'/);
  assert.throws(() => v.achdPositive(0, 1, 'options.damping'), /options.damping must be a finite number > 0, got 0/);
  assert.equal(v.achdNonNegative(undefined, 7, 'x'), 7);
});
