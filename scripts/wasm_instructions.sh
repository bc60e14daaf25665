#!/usr/bin/env bash
# Instructions per solve of the wasm module's zero-copy solver in Node, counted by callgrind
# (the x86 instructions of V8's compiled wasm, not wasm instructions): Node runs W warm-up
# solves and then N, and again W and 2N; the difference of the two counts divided by N
# (Node's start, V8's compilation and the warm-up cancel out). V8 compiles the wasm with
# TurboFan from the start (--no-liftoff: no tier-up whose moment depends on timing) on
# one thread (--single-threaded). The case is the benchmark's: the KUKA LWR 4 at its q0
# with nonzero qd and ff_torques, without constraints (nc0) and with its tip held in 6D
# (nc6).
#
# Two counts per case: `wasm`, the instructions in the module's compiled functions alone
# (V8's --perf-basic-prof map says which addresses are whose), which is exact: two runs of
# one build give the same number to the instruction; and `all`, every instruction of the
# process, which also holds V8's JIT compiler and JS glue and moves by 1-2% from run to
# run (what the compiler does during the N extra solves differs), so compare builds by
# `wasm`. With a symbol map next to the module (MODULE.symbols: link with
# --emit-symbol-map) it also names the functions that cost the most per solve.
#
#   bash scripts/wasm_instructions.sh [MODULE.mjs] [N]   (default web/dist/achd.mjs, 10000)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
module=$(realpath "${1:-$root/web/dist/achd.mjs}")
n=${2:-10000}
warmup=3000
driver="
import { readFileSync } from 'node:fs';
const [module, nc, count] = process.argv.slice(1);
const { default: createAchd } = await import(module);
const achd = await createAchd();
const index = JSON.parse(readFileSync('$root/robots/index.json', 'utf8'));
const e = index.robots.find((r) => r.name === 'kuka_lwr4');
const robot = achd.loadURDF(readFileSync('$root/' + e.urdf, 'utf8'), { root: e.root, tip: e.tip });
const s = robot.createSolver({ maxConstraints: 6 });
const nj = e.q0.length;
s.q.set(e.q0);
s.qd.set(Array.from({ length: nj }, (_, i) => 0.3 * Math.sin(i + 1)));
s.ff_torques.set(Array.from({ length: nj }, (_, i) => 0.5 * Math.cos(i + 1)));
s.gravity.set([0, 0, -9.81]);
const m = Number(nc), total = Number(count);
s.numConstraints = m;
for (let k = 0; k < m; ++k) s.alpha[7 * k] = 1;  // column k: unit row k
for (let k = 0; k < m; ++k) s.beta[k] = 0.1 * (k + 1);
for (let i = 0; i < total; ++i) s.solve();
"
attribute="
import { readFileSync } from 'node:fs';
// per wasm function index, the instructions callgrind counted at its addresses
const [cg, map] = process.argv.slice(1);
const entries = [];
for (const line of readFileSync(map, 'utf8').split('\\n')) {
  const m = /^([0-9a-f]+) ([0-9a-f]+) .*wasm-function\\[(\\d+)\\]/.exec(line);
  if (m) entries.push([parseInt(m[1], 16), parseInt(m[2], 16), Number(m[3])]);
}
entries.sort((a, b) => a[0] - b[0]);
const cost = new Map();
let inclusive = false;  // the line after calls= is a call's inclusive cost: not this code's
for (const line of readFileSync(cg, 'utf8').split('\\n')) {
  if (line.startsWith('calls=')) { inclusive = true; continue; }
  if (!line.startsWith('0x')) continue;
  if (inclusive) { inclusive = false; continue; }
  const [position, , count] = line.split(' ');
  const address = parseInt(position, 16);
  let lo = 0, hi = entries.length - 1, i = -1;
  while (lo <= hi) {
    const mid = (lo + hi) >> 1;
    if (entries[mid][0] <= address) { i = mid; lo = mid + 1; } else hi = mid - 1;
  }
  if (i < 0 || address >= entries[i][0] + entries[i][1]) continue;
  cost.set(entries[i][2], (cost.get(entries[i][2]) ?? 0) + Number(count));
}
for (const [f, c] of cost) console.log(f, c);
"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"  # where V8's --perf-basic-prof leaves its isolate logs
count() {  # one Node run of $2 solves with $1 constraints: its total, then per wasm function
  local out=$work/$1-$2
  valgrind --tool=callgrind --smc-check=all --dump-instr=yes --compress-pos=no --compress-strings=no \
    --callgrind-out-file="$out.cg" \
    node --no-liftoff --single-threaded --perf-basic-prof --input-type=module -e "$driver" "$module" "$1" "$2" \
    2>"$out.log" >/dev/null &
  local pid=$!  # valgrind runs node in its own process: the map is /tmp/perf-<pid>.map
  wait $pid
  mv "/tmp/perf-$pid.map" "$out.map"
  sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$out.log" > "$out.total"
  node --input-type=module -e "$attribute" "$out.cg" "$out.map" > "$out.functions"
  rm "$out.cg"
}
symbols=$module.symbols
for nc in 0 6; do
  a=$((warmup + n)) b=$((warmup + 2 * n))
  count "$nc" $a &  # the two runs side by side
  count "$nc" $b
  wait
  node --input-type=module -e "
import { readFileSync, existsSync } from 'node:fs';
const [work, nc, a, b, n, symbols] = process.argv.slice(1);
const read = (runs) => new Map(readFileSync(work + '/' + nc + '-' + runs + '.functions', 'utf8').trim().split('\\n')
  .map((l) => l.split(' ').map(Number)));
const total = (runs) => Number(readFileSync(work + '/' + nc + '-' + runs + '.total', 'utf8'));
const fa = read(a), fb = read(b);
const per = [...fb].map(([f, c]) => [f, (c - (fa.get(f) ?? 0)) / n]).filter(([, c]) => c > 0);
const wasm = per.reduce((s, [, c]) => s + c, 0);
console.log('nc' + nc + ': wasm ' + Math.round(wasm) + ', all ' + Math.round((total(b) - total(a)) / n) +
            ' instructions per solve');
if (existsSync(symbols)) {
  const names = new Map(readFileSync(symbols, 'utf8').trim().split('\\n').map((l) => {
    const k = l.indexOf(':');
    let name = l.slice(k + 1);
    try { name = decodeURIComponent(name.replace(/\\\\/g, '%')); } catch {}  // \\20: a space
    return [Number(l.slice(0, k)), name.slice(0, 100)];
  }));
  for (const [f, c] of per.sort((x, y) => y[1] - x[1]).slice(0, 8))
    console.log('  ' + String(Math.round(c)).padStart(6) + '  ' + (names.get(f) ?? 'function ' + f));
}
" "$work" "$nc" $a $b "$n" "$symbols"
done
