// The core's layers hold (scripts/check_layers.mjs): no source or public header includes a
// higher layer, every folder of core/src belongs to one layer and holds at most 15 files,
// no core file has more than 500 lines. The checker is first shown to fail on small made-up
// trees that break each rule.
import assert from 'node:assert/strict';
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { test } from 'node:test';

import { checkLayers } from '../../scripts/check_layers.mjs';
import { repo } from './helpers.mjs';

const cmake = `set(ACHD_LAYERS low high)
set(ACHD_LAYER_BELOW_low "")
set(ACHD_LAYER_BELOW_high low)
set(ACHD_PUBLIC_low low.hpp)
set(ACHD_PUBLIC_high high.hpp)
set(ACHD_PUBLIC_umbrella all.hpp)
`;

// A made-up tree: `files` maps paths to their text; core/CMakeLists.txt is `cmake`.
function tree(files) {
  const root = mkdtempSync(join(tmpdir(), 'achd-layers-'));
  const all = {
    'core/CMakeLists.txt': cmake,
    'core/include/achd/low.hpp': '#pragma once\n',
    'core/include/achd/high.hpp': '#pragma once\n#include "achd/low.hpp"\n',
    'core/include/achd/all.hpp': '#include "achd/high.hpp"\n#include "achd/low.hpp"\n',
    'core/src/low/a.cpp': '#include "achd/low.hpp"\n#include "a.hpp"\n#include <vector>\n',
    'core/src/low/a.hpp': '#pragma once\n',
    'core/src/high/b.cpp': '#include "achd/high.hpp"\n#include "a.hpp"\n#include "b.hpp"\n',
    'core/src/high/b.hpp': '#pragma once\n',
    ...files,
  };
  for (const [path, text] of Object.entries(all)) {
    if (text === null) continue;
    mkdirSync(dirname(join(root, path)), { recursive: true });
    writeFileSync(join(root, path), text);
  }
  return root;
}

function problems(files) {
  const root = tree(files);
  try {
    return checkLayers(root);
  } finally {
    rmSync(root, { recursive: true, force: true });
  }
}

test('the checker passes a tree that keeps its layers', () => {
  assert.deepEqual(problems({}), []);
});

test('the checker names each broken rule', () => {
  const cases = [
    [{ 'core/src/low/a.cpp': '#include "b.hpp"\n' }, /core\/src\/low\/a\.cpp: includes b\.hpp of layer high, above its layer low/],
    [{ 'core/src/low/a.cpp': '#include "achd/high.hpp"\n' }, /a\.cpp: includes achd\/high\.hpp of layer high, above/],
    [{ 'core/include/achd/low.hpp': '#include "achd/high.hpp"\n' }, /low\.hpp: includes achd\/high\.hpp of layer high, above its layer low/],
    [{ 'core/include/achd/low.hpp': '#include "a.hpp"\n' }, /low\.hpp: includes "a\.hpp", which is not a public header/],
    [{ 'core/include/achd/stray.hpp': '#pragma once\n' }, /stray\.hpp: a public header of no layer/],
    [{ 'core/src/low/c.cpp': '#include "achd/stray.hpp"\n' }, /c\.cpp: includes achd\/stray\.hpp, a public header of no layer/],
    [{ 'core/src/middle/c.cpp': '\n' }, /c\.cpp: its folder core\/src\/middle is not a layer/],
    [{ 'core/src/high/long.cpp': 'x\n'.repeat(501) }, /long\.cpp: 501 lines, more than 500/],
    [Object.fromEntries(Array.from({ length: 15 }, (_, k) => [`core/src/high/f${k}.cpp`, '\n'])),
      /core\/src\/high: 17 files, more than 15/],
  ];
  for (const [files, expected] of cases) {
    const found = problems(files);
    assert.ok(found.some((p) => expected.test(p)), `${expected}: got ${JSON.stringify(found)}`);
  }
  // At the limits: 500 lines and 15 files pass.
  assert.deepEqual(problems({ 'core/src/high/long.cpp': 'x\n'.repeat(500) }), []);
  assert.deepEqual(problems(Object.fromEntries(Array.from({ length: 13 }, (_, k) => [`core/src/high/f${k}.cpp`, '\n']))), []);
});

test("achd's core keeps its layers", () => {
  assert.deepEqual(checkLayers(repo), []);
});
