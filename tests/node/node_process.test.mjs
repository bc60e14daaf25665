// Importing achd leaves Node's process alone: no uncaughtException or unhandledRejection
// handler is installed, so a script that imports the module and then throws exits with
// Node's own code 1 and a short message (not Emscripten's exit 7 printing the module's
// megabyte-long source line), and an unhandled rejection ends it the same way.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { test } from 'node:test';

import { loadAchd, repo } from './helpers.mjs';

const moduleUrl = pathToFileURL(join(repo, 'web/dist/achd.mjs')).href;

function runScript(body) {
  const script = `import createAchd from ${JSON.stringify(moduleUrl)};\nconst achd = await createAchd();\n${body}\n`;
  return spawnSync(process.execPath, ['--input-type=module', '-e', script], { encoding: 'utf8', timeout: 60000 });
}

test('creating the module installs no process-level handlers', async () => {
  const before = ['uncaughtException', 'unhandledRejection', 'exit'].map((e) => process.listenerCount(e));
  await loadAchd();
  const after = ['uncaughtException', 'unhandledRejection', 'exit'].map((e) => process.listenerCount(e));
  assert.deepEqual(after, before);
});

test('a script that imports achd and throws exits 1 with a short message', () => {
  const r = runScript("throw new Error('the caller failed');");
  assert.equal(r.status, 1, r.stderr.slice(0, 2000));
  assert.match(r.stderr, /Error: the caller failed/);
  assert.ok(r.stderr.length + r.stdout.length < 10000, `printed ${r.stderr.length + r.stdout.length} bytes`);
});

test('an unhandled rejection after importing achd exits 1 with a short message', () => {
  const r = runScript("Promise.reject(new Error('rejected'));");
  assert.equal(r.status, 1, r.stderr.slice(0, 2000));
  assert.match(r.stderr, /rejected/);
  assert.ok(r.stderr.length + r.stdout.length < 10000, `printed ${r.stderr.length + r.stdout.length} bytes`);
});

test('an uncaught error from achd itself exits 1 with a short message', () => {
  const r = runScript("achd.loadURDF('<robot name=\"x\">');");
  assert.equal(r.status, 1, r.stderr.slice(0, 2000));
  assert.match(r.stderr, /Error: /);
  assert.ok(r.stderr.length + r.stdout.length < 10000, `printed ${r.stderr.length + r.stdout.length} bytes`);
});

test('a script that imports achd and ends normally exits 0', () => {
  const r = runScript("console.log(achd.constants.max_constraints);");
  assert.equal(r.status, 0, r.stderr);
  assert.equal(r.stdout.trim(), '6');
});
