#!/usr/bin/env bash
# Instructions per solve of the wasm module's zero-copy solver in Node, counted by callgrind
# (the x86 instructions of V8's compiled wasm, not wasm instructions): Node runs W warm-up
# solves and then N, and again W and 2N; the difference of the two counts divided by N
# (Node's start, V8's compilation and the warm-up cancel out). V8 compiles the wasm with
# TurboFan from the start (--no-liftoff: no tier-up whose moment depends on timing) on
# one thread (--single-threaded). Unlike `node bench/wasm_vs_native.mjs` this does not
# depend on the machine's load: two builds compare to about 1% (repeated runs of one
# build differ by that much), where wall-clock times on a shared machine swing by tens of
# percent. The case is the benchmark's: the KUKA LWR 4 at its q0 with nonzero qd and
# ff_torques, without constraints (nc0) and with its tip held in 6D (nc6).
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
count() {  # instructions of one Node run of $2 solves with $1 constraints
  valgrind --tool=callgrind --smc-check=all --callgrind-out-file=/dev/null \
    node --no-liftoff --single-threaded --input-type=module -e "$driver" "$module" "$1" "$2" 2>&1 >/dev/null |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for nc in 0 6; do
  count "$nc" $((warmup + n)) > "$work/a" &  # the two runs side by side
  count "$nc" $((warmup + 2 * n)) > "$work/b"
  wait
  a=$(cat "$work/a") b=$(cat "$work/b")
  echo "nc$nc: $(( (b - a) / n )) instructions per solve"
done
