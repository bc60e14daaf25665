// The repository speaks of the project alone: no file tracked by git (the vendored robot
// descriptions aside) cites a tracker entry by number (the tracker's word for an entry
// followed by a number, with or without "#", also where a comment wraps between the two).
// The patterns are built at run time, so that this file holds no match itself; the
// test's own cases show that they find one.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { repo } from './helpers.mjs';

const word = ['is', 'sue'].join('');
const reference = new RegExp(`\\b${word}s?\\s*(#\\s*)?\\d+`, 'i');
// The word ending a line and the number starting the next after a comment marker (not a
// numbered list's "1.").
const wrapped = new RegExp(`\\b${word}s?[ \\t]*\\n[ \\t]*(//|#|\\*|--)?[ \\t]*(#[ \\t]*)?\\d+\\b(?!\\.)`, 'gi');

test('the pattern finds a tracker reference and passes plain prose', () => {
  for (const text of [`see ${word} 12`, `(${word} 16's drivers)`, `${word.toUpperCase()}S 14/15`, `${word} #3`])
    assert.ok(reference.test(text), text);
  // (a word that merely ends in the tracker's word, before a number, is prose too)
  for (const text of [`an ${word} of the solver`, `${word}s with two robots`, `t${word} ${6 * 2}`])
    assert.ok(!reference.test(text), text);
  for (const text of [`defaults (${word}\n// 14) carry it`, `the ${word}\n# 3 says`, `an ${word}\n * #7`])
    assert.ok(text.match(wrapped), JSON.stringify(text));
  for (const text of [`the ${word}\n1. a list`, `an ${word}\n// of 12 robots`])
    assert.ok(!text.match(wrapped), JSON.stringify(text));
});

test('no tracked file cites a tracker entry by number', () => {
  const files = execFileSync('git', ['ls-files'], { cwd: repo, encoding: 'utf8' }).split('\n')
    .filter((f) => f && !f.startsWith('robots/example-robot-data/') && !/\.(png|wasm|ico)$/.test(f));
  const found = [];
  for (const file of files) {
    let text;
    try {
      text = readFileSync(join(repo, file), 'utf8');
    } catch {
      continue;  // a file git tracks but the checkout lacks
    }
    const lines = text.split('\n');
    lines.forEach((line, k) => {
      if (reference.test(line)) found.push(`${file}:${k + 1}: ${line.trim()}`);
    });
    for (const m of text.matchAll(wrapped)) {
      const k = text.slice(0, m.index).split('\n').length - 1;
      found.push(`${file}:${k + 1}: ${lines[k].trim()} / ${lines[k + 1].trim()}`);
    }
  }
  assert.deepEqual(found, []);
});
