// wasm/achd.d.ts type-checks, and the type tests in types/usage.ts hold: tsc --noEmit
// (TypeScript pinned in package.json) exits 0. usage.ts uses the API as a user would and
// marks misuse with @ts-expect-error, which tsc reports when the misuse compiles.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';

import { repo } from './helpers.mjs';

test('tsc --noEmit over achd.d.ts and the type tests', () => {
  const tsc = join(repo, 'node_modules/.bin/tsc');
  assert.ok(existsSync(tsc), `${tsc} is missing: run npm ci (scripts/install-deps.sh does)`);
  const run = spawnSync(tsc, ['-p', join(repo, 'tests/node/types/tsconfig.json')], { encoding: 'utf8' });
  assert.equal(run.status, 0, `tsc failed:\n${run.stdout}${run.stderr}`);
  assert.equal(run.stdout + run.stderr, '');
});
