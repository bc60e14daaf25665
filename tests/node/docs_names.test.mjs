// The documents name only what exists. In README.md, docs/**/*.md, web/README.md and
// wasm/README.md, every name in backticks that looks like code is checked against the
// tree git tracks:
// - a file name or path (`free_motions.cpp`, `robots/index.json`, `wasm/js`,
//   `tests/fixtures/mesh_robot/`):
//   a path must be a tracked file or folder (from the repository root, or the tail of a
//   tracked path at a folder boundary, as `achd/pv_reference.hpp` or a robot's path under
//   robots/example-robot-data/); a bare file name must be tracked somewhere. Paths under
//   the build's output folders (what .gitignore ignores: build/, web/dist/, ...), absolute
//   paths and placeholders in capitals (`ROBOT.urdf`) are not files of the tree;
// - an identifier (`hybrid_dynamics`, `Model::num_joints`, `joint_moving_nothing()`,
//   `sim.setDirection`, `Effects.SkipsEqualTheComputedPath`): each of its parts must occur
//   as a word in a tracked source file (core/, tools/, wasm/, web/, tests/, bench/, fuzz/,
//   scripts/, cmake/, the root's build files; never a markdown file). Math symbols written
//   as code (`D_i`, `E_0`, `alpha_k`) are not names: a short symbol with a subscript, or a
//   Greek letter with one, is skipped when the source does not have it;
// - a long command-line option (`--floating`): it occurs in a tracked source file;
// - a quoted value or field (`"joint_control"`, `'rk4'`): the word occurs in a source or a
//   data file (robots/ too).
// Not checked: anything with a space (prose, commands, formulas), numbers, JSON and other
// fragments, compiler flags (`-msimd128`), the few names of other projects listed in
// FOREIGN, and table columns that hold other projects' or the book's symbols (headed KDL,
// Featherstone, Pinocchio, PV_tree, spatial_v2, or "here").
// It also checks that every relative link resolves (the file, and a heading for an
// anchor), and that docs/design.md's test table (section 11) lists every test suite: each
// program the CMakeLists.txt files of tests/native/ register, each tests/node/*.test.mjs
// and each tests/browser/*.test.mjs. Every problem is listed with its file and line. Its own cases run the checker on made-up texts to show that
// it fails.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { basename, dirname, join, normalize } from 'node:path';
import { test } from 'node:test';

import { repo } from './helpers.mjs';

const SELF = 'tests/node/docs_names.test.mjs';

// Names of other projects that the documents compare achd with, where no column says so.
const FOREIGN = new Set([
  'segment_info', 'getTransformedLinkAcceleration', // KDL
  'implicitfast', // MuJoCo
  'HD.m', 'ABA.m', 'PV_tree.m', // spatial_v2 and its PV_tree extension
  'pv.hxx', 'pinocchio/algorithm/pv.hxx', 'par_cons_ind', // Pinocchio
]);

// Table columns whose cells are other projects' or the book's symbols.
const FOREIGN_COLUMN = /^(kdl|featherstone|pinocchio|pv_tree|spatial_v2|here)\b/i;

const GREEK = 'alpha|beta|gamma|delta|eps|epsilon|zeta|eta|theta|kappa|lambda|mu|nu|xi|pi|rho|sigma|tau|phi|chi|psi|omega';
const MATH_SYMBOL = new RegExp(`^([A-Za-z]{1,3}[0-9]?|${GREEK})(_[A-Za-z0-9]{1,3})?$`);
const FILE = /^[\w.\/@+-]*[\w-]\.(cpp|hpp|h|mjs|js|ts|json|md|urdf|srdf|xml|sh|txt|html|css|cmake|in|supp|svg|png|csv|stl|dae|obj)$/;
const SOURCE_ROOTS = ['core/', 'tools/', 'wasm/', 'web/', 'tests/', 'bench/', 'fuzz/', 'scripts/', 'cmake/', '.ci/'];
const SOURCE_FILE = /\.(cpp|hpp|h|mjs|js|ts|sh|cmake|txt|json|in|html|css|supp)$|(^|\/)run$/;
const DATA_ROOTS = ['robots/'];
const DATA_FILE = /\.(json|urdf|srdf|xml)$/;
const WORD = /[A-Za-z_][A-Za-z0-9_]*/g;

// What the checks compare with: the tracked files and folders, the words of the source
// files, the words of the data files, and which paths git ignores (the build's outputs).
export function treeIndex(root = repo) {
  const git = (args, input) => execFileSync('git', args, { cwd: root, encoding: 'utf8', input });
  const files = git(['ls-files']).split('\n').filter(Boolean);
  const dirs = new Set();
  for (const f of files) for (let d = dirname(f); d !== '.'; d = dirname(d)) dirs.add(d);
  const words = new Set();
  const dataWords = new Set();
  const read = (f) => {
    try {
      return readFileSync(join(root, f), 'utf8');
    } catch {
      return '';  // a file git tracks but the checkout lacks
    }
  };
  const isSource = (f) => f !== SELF && (SOURCE_ROOTS.some((r) => f.startsWith(r)) || !f.includes('/')) &&
    SOURCE_FILE.test(f);
  const isData = (f) => DATA_ROOTS.some((r) => f.startsWith(r)) && DATA_FILE.test(f);
  const sources = files.filter(isSource);
  for (const f of sources) for (const w of read(f).match(WORD) ?? []) words.add(w);
  for (const f of files.filter(isData)) for (const w of read(f).match(WORD) ?? []) dataWords.add(w);
  const sourceText = sources.map(read).join('\n');
  // The build's own files, which name what it writes.
  const buildText = files.filter((f) => /(^|\/)CMakeLists\.txt$|\.cmake$|^CMakePresets\.json$|^scripts\/.*\.sh$/.test(f))
    .map(read).join('\n');
  const ignoredCache = new Map();
  const ignored = (path) => {
    if (!ignoredCache.has(path)) {
      let answer = false;
      try {
        git(['check-ignore', '-q', '--no-index', path]);  // (a folder: with its trailing slash)
        answer = true;
      } catch {
        answer = false;
      }
      ignoredCache.set(path, answer);
    }
    return ignoredCache.get(path);
  };
  return {
    files: new Set(files), dirs, basenames: new Set(files.map((f) => basename(f))),
    dirNames: new Set([...dirs].map((d) => basename(d))), words, dataWords, sourceText, buildText, ignored,
    suites: testSuites(root, files),
  };
}

// The test suites the test table must list: the programs that the CMakeLists.txt files
// of tests/native/ register with achd_gtest (their source files), tests/node/*.test.mjs,
// tests/browser/*.test.mjs.
function testSuites(root, files) {
  const native = files.filter((f) => /^tests\/native\/(.*\/)?CMakeLists\.txt$/.test(f)).flatMap((f) =>
    [...readFileSync(join(root, f), 'utf8').matchAll(/^\s*achd_gtest\(\s*\w+\s+(\S+\.cpp)/gm)]
      .map((m) => join(dirname(f), m[1])));
  const js = files.filter((f) => /^tests\/(node|browser)\/[^/]+\.test\.mjs$/.test(f));
  return [...native, ...js];
}

// The inline code spans of a markdown text outside fenced blocks, with their line and
// whether they stand in a foreign table column: [{line, token, foreign}].
export function codeSpans(text) {
  const spans = [];
  let fence = false;
  let header = null;
  text.split('\n').forEach((line, k) => {
    if (/^\s*```/.test(line)) {
      fence = !fence;
      return;
    }
    if (fence) return;
    const row = /^\s*\|/.test(line);
    if (!row) header = null;
    let cells = null;
    if (row) {
      cells = line.trim().replace(/^\||\|$/g, '').split(/(?<!\\)\|/);
      if (header === null) header = cells.map((c) => c.replace(/`/g, '').trim());
    }
    if (row && cells.every((c) => /^\s*:?-+:?\s*$/.test(c))) return;  // the separator row
    const cellOf = (index) => (cells ? line.slice(0, index).split(/(?<!\\)\|/).length - 2 : -1);
    for (const m of line.matchAll(/(`+)(.+?)\1/g)) {
      const column = cellOf(m.index);
      const foreign = row && header !== null && column >= 0 && FOREIGN_COLUMN.test(header[column] ?? '');
      spans.push({ line: k + 1, token: m[2].trim(), foreign });
    }
  });
  return spans;
}

// Why `token` names nothing in the tree, or null when it does (or is no name).
export function brokenName(token, index) {
  if (!token || /\s/.test(token) || FOREIGN.has(token)) return null;
  // a quoted value or field
  const quoted = token.match(/^(["'])([A-Za-z_][\w-]*)\1$/);
  if (quoted) {
    const words = quoted[2].split('-');
    return words.every((w) => index.words.has(w) || index.dataWords.has(w))
      ? null : `no source or data file has the word '${quoted[2]}'`;
  }
  // a long option
  const option = token.match(/^--[a-z][a-z0-9-]*/);
  if (option) return index.sourceText.includes(option[0]) ? null : `no source file has the option ${option[0]}`;
  if (token.startsWith('-')) return null;  // compiler flags, negative numbers
  // a path or file name
  const path = token.replace(/^\.\//, '');
  if (path.includes('*')) {
    if (!path.includes('/') && !FILE.test(path)) return null;
    const glob = new RegExp(`(^|/)${path.replace(/[.+^${}()|[\]\\]/g, '\\$&').replace(/\*/g, '[^/]*')}$`);
    return [...index.files].some((f) => glob.test(f)) ? null : 'no tracked file matches';
  }
  const isDir = /^[\w.\/-]+\/$/.test(path) && /[A-Za-z]/.test(path);
  // a/b with a first folder of the tree's (tests/..., not dq/dt): a file or a folder
  const isPath = /^[\w.-]+(\/[\w.-]+)+$/.test(path) && (index.dirs.has(path.split('/')[0]) || index.ignored(`${path.split('/')[0]}/`));
  if (FILE.test(path) || isDir || isPath) {
    if (path.startsWith('/') || index.ignored(path)) return null;
    const name = basename(path);
    if (/^[A-Z][A-Z0-9_]*\.[a-z]+$/.test(name) || name === '.' || name === '..') return null;  // ROBOT.urdf
    const clean = path.replace(/\/$/, '');
    if (clean.includes('/')) {
      const exists = (p) => index.files.has(p) || index.dirs.has(p);
      if (exists(clean)) return null;
      const tail = `/${clean}`;
      if ([...index.files, ...index.dirs].some((f) => f.endsWith(tail))) return null;
      return `no tracked ${isDir ? 'folder' : isPath && !FILE.test(path) ? 'file or folder' : 'file'} ${clean}`;
    }
    if ((isDir ? index.dirNames : index.basenames).has(clean)) return null;
    if (!isDir && index.buildText.includes(clean)) return null;  // a file the build writes (achd.mjs)
    return `no tracked ${isDir ? 'folder' : 'file'} named ${clean}`;
  }
  // an identifier: calls, template arguments, indices and braces dropped
  const name = token.replace(/\((?:[^()]*)\)/g, '').replace(/<[^<>]*>/g, '').replace(/\[[^\]]*\]/g, '').replace(/\{\}$/, '');
  if (!/^~?[A-Za-z_]\w*(?:(?:::|\.)~?[A-Za-z_]\w*)*$/.test(name)) return null;  // not code: values, formulas, JSON
  const parts = name.split(/::|\./).map((p) => p.replace(/^~/, ''));
  const missing = parts.filter((p) => !index.words.has(p));
  if (missing.length === 0) return null;
  if (parts.length === 1 && MATH_SYMBOL.test(name)) return null;  // D_i, E_0, alpha_k
  return `no source file has the word${missing.length > 1 ? 's' : ''} ${missing.join(', ')}`;
}

// GitHub's anchor for a heading.
function anchorOf(heading) {
  return heading.trim().toLowerCase().replace(/[^\p{L}\p{N}_\- ]/gu, '').replace(/ /g, '-');
}

function headings(text) {
  const out = new Set();
  let fence = false;
  const seen = new Map();
  for (const line of text.split('\n')) {
    if (/^\s*```/.test(line)) fence = !fence;
    const m = !fence && line.match(/^#{1,6} (.*)$/);
    if (!m) continue;
    const base = anchorOf(m[1]);
    const n = seen.get(base) ?? 0;
    seen.set(base, n + 1);
    out.add(n ? `${base}-${n}` : base);
  }
  return out;
}

// The problems of the documents `docs` ([{path, text}]) against `index`: names that do not
// exist, links that do not resolve, and, when docs/design.md is among them, suites its test
// table misses. Each problem is 'file:line: ...'.
export function checkDocs(docs, index) {
  const problems = [];
  const byPath = new Map(docs.map((d) => [d.path, d.text]));
  for (const { path, text } of docs) {
    for (const { line, token, foreign } of codeSpans(text)) {
      if (foreign) continue;
      const why = brokenName(token, index);
      if (why) problems.push(`${path}:${line}: \`${token}\`: ${why}`);
    }
    // relative links [text](target) and images
    let fence = false;
    text.split('\n').forEach((line, k) => {
      if (/^\s*```/.test(line)) fence = !fence;
      if (fence) return;
      for (const m of line.replace(/`[^`]*`/g, '').matchAll(/\]\(([^)\s]+)\)/g)) {
        const target = m[1];
        if (/^[a-z]+:/.test(target)) continue;  // http:, mailto:
        const [file, anchor] = target.split('#');
        const resolved = file ? normalize(join(dirname(path), file)).replace(/\/$/, '') : path;
        if (file && !index.files.has(resolved) && !index.dirs.has(resolved) && !byPath.has(resolved)) {
          problems.push(`${path}:${k + 1}: link ${target}: no file ${resolved}`);
        } else if (anchor && resolved.endsWith('.md')) {
          const targetText = byPath.get(resolved) ?? readFileSync(join(repo, resolved), 'utf8');
          if (!headings(targetText).has(anchor)) problems.push(`${path}:${k + 1}: link ${target}: no heading #${anchor} in ${resolved}`);
        }
      }
    });
  }
  const design = byPath.get('docs/design.md');
  if (design !== undefined) problems.push(...missingSuites(design, index.suites));
  return problems;
}

// The suites docs/design.md's test table does not list: its section "Tests" has a table
// whose first column names the suites (by path or file name) and whose second says what
// each proves.
export function missingSuites(design, suites) {
  const section = design.match(/^## (?:\d+\. )?Tests\n([\s\S]*?)(?=^## |(?![\s\S]))/m);
  if (!section) return ['docs/design.md: no section "Tests"'];
  const listed = new Set();
  for (const line of section[1].split('\n')) {
    const cells = line.trim().replace(/^\||\|$/g, '').split(/(?<!\\)\|/);
    if (!line.trim().startsWith('|') || cells.length < 2 || !cells[1].trim() || /^\s*:?-+/.test(cells[0])) continue;
    for (const m of cells[0].matchAll(/`([^`]+)`/g)) listed.add(basename(m[1]));
  }
  return suites.filter((s) => !listed.has(basename(s)))
    .map((s) => `docs/design.md: the test table (section Tests) does not list ${s}`);
}

// The documents the rules hold for.
function documents() {
  const files = execFileSync('git', ['ls-files', 'README.md', 'docs', 'web/README.md', 'wasm/README.md'],
    { cwd: repo, encoding: 'utf8' }).split('\n').filter((f) => f.endsWith('.md'));
  // new, not yet tracked guides count too
  const untracked = execFileSync('git', ['ls-files', '--others', '--exclude-standard', 'docs'],
    { cwd: repo, encoding: 'utf8' }).split('\n').filter((f) => f.endsWith('.md'));
  return [...new Set([...files, ...untracked])].map((path) => ({ path, text: readFileSync(join(repo, path), 'utf8') }));
}

const index = treeIndex();

test('the checker finds a file, a path, a function, a type and an option that do not exist', () => {
  const text = [
    '# Made up',
    '',
    'The sweep is in `no_such_sweep.cpp`, beside `core/src/no_such_folder/kinematics.cpp`.',
    'It calls `constraint_forces_at_tip()` and fills `Data::no_such_member`;',
    'the CLI takes `--no-such-option`, and scenes the field `"no_such_field"`; see `tests/no_such_folder/thing`.',
    'See [the guide](no_such_guide.md) and [a heading](#no-such-heading).',
  ].join('\n');
  const problems = checkDocs([{ path: 'docs/made_up.md', text }], index);
  assert.deepEqual(problems, [
    'docs/made_up.md:3: `no_such_sweep.cpp`: no tracked file named no_such_sweep.cpp',
    'docs/made_up.md:3: `core/src/no_such_folder/kinematics.cpp`: no tracked file core/src/no_such_folder/kinematics.cpp',
    'docs/made_up.md:4: `constraint_forces_at_tip()`: no source file has the word constraint_forces_at_tip',
    'docs/made_up.md:4: `Data::no_such_member`: no source file has the word no_such_member',
    'docs/made_up.md:5: `--no-such-option`: no source file has the option --no-such-option',
    'docs/made_up.md:5: `"no_such_field"`: no source or data file has the word \'no_such_field\'',
    'docs/made_up.md:5: `tests/no_such_folder/thing`: no tracked file or folder tests/no_such_folder/thing',
    'docs/made_up.md:6: link no_such_guide.md: no file docs/no_such_guide.md',
    'docs/made_up.md:6: link #no-such-heading: no heading #no-such-heading in docs/made_up.md',
  ]);
});

test('the checker passes names that exist, and what is not a name', () => {
  const text = [
    '# Made up',
    '',
    '`hybrid_dynamics()` in `hybrid_dynamics.cpp`, `Model::num_joints`, `achd::Simulator`,',
    '`sim.setDirection`, `Effects.SkipsEqualTheComputedPath`, `UnitConstraintForces<NC>`,',
    '`tests/node/helpers.mjs`, `achd/pv_reference.hpp`, `tests/fixtures/mesh_robot/`, `robots/scenes/*_stand.json`, `wasm/js`,',
    '`--floating`, `"joint_control"`, `\'rk4\'`, `build/achd`, `web/dist/achd.mjs`, `ROBOT.urdf`,',
    'math `D_i`, `E_0`, `alpha_k`, `dq/dt`, values `1e-9`, `[0, 0, -9.81]`, `-msimd128`, `q[3] is not finite`.',
    'See [the heading](#made-up).',
    '',
    '| quantity | KDL | achd |',
    '|---|---|---|',
    '| unit constraint forces | `E_tilde` | `Data::E` |',
  ].join('\n');
  assert.deepEqual(checkDocs([{ path: 'docs/made_up.md', text }], index), []);
});

test('the checker finds a suite missing from the test table', () => {
  const suites = ['tests/native/gauss_principle.cpp', 'tests/node/parity.test.mjs', 'tests/browser/page.test.mjs'];
  const table = (rows) => ['# Design', '', '## 11. Tests', '', '| suite | proves |', '|---|---|', ...rows, '', '## 12. Next'].join('\n');
  const all = table([
    '| `gauss_principle.cpp` | the KKT solution |',
    '| `tests/node/parity.test.mjs` | wasm equals native |',
    '| `tests/browser/page.test.mjs` | the page |',
  ]);
  assert.deepEqual(missingSuites(all, suites), []);
  const without = table(['| `gauss_principle.cpp` | the KKT solution |', '| `tests/browser/page.test.mjs` | the page |']);
  assert.deepEqual(missingSuites(without, suites),
    ['docs/design.md: the test table (section Tests) does not list tests/node/parity.test.mjs']);
  // a suite named outside the table does not count
  const prose = table(['| `gauss_principle.cpp` | the KKT solution |']) + '\n`parity.test.mjs` and `page.test.mjs` exist.\n';
  assert.equal(missingSuites(prose, suites).length, 2);
});

test('every name, path and link in README.md, docs/, web/README.md and wasm/README.md exists, and the test table lists every suite', () => {
  const docs = documents();
  assert.ok(docs.some((d) => d.path === 'docs/design.md') && docs.some((d) => d.path === 'README.md'));
  assert.ok(index.suites.length > 60, `only ${index.suites.length} suites found`);
  const problems = checkDocs(docs, index);
  assert.deepEqual(problems, [], `\n${problems.join('\n')}\n`);
});
