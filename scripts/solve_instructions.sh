#!/usr/bin/env bash
# Instructions per solve of the KUKA LWR 4 chain, without constraints and with its tip
# held in 6D, counted by callgrind: `achd bench` run with N and 2N iterations (each a
# warm-up round and a timed round of that many solves), the difference divided by 2N (the
# loading and the timing code cancel out). Instruction counts are not
# time, but they do not depend on the machine's load: a refactoring that must not change
# the solver shows the same counts before and after.
#
#   bash scripts/solve_instructions.sh [BUILD_DIR] [N]     (default build, 2000)
set -euo pipefail
build=${1:-build}
n=${2:-2000}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
q='[0.3, 0.6, -0.2, -1.2, 0.4, 0.8, 0.1]'
qd='[0.1, -0.2, 0.3, -0.1, 0.2, -0.3, 0.1]'
echo "{\"q\": $q, \"qd\": $qd, \"gravity\": [0, 0, -9.81]}" > "$work/nc0.json"
echo "{\"q\": $q, \"qd\": $qd, \"gravity\": [0, 0, -9.81],
  \"alpha\": [[1,0,0,0,0,0],[0,1,0,0,0,0],[0,0,1,0,0,0],[0,0,0,1,0,0],[0,0,0,0,1,0],[0,0,0,0,0,1]],
  \"beta\": [0, 0, 0, 0, 0, 0]}" > "$work/nc6.json"

count() {  # instructions of one bench run of $2 solves on case $1
  valgrind --tool=callgrind --callgrind-out-file="$work/out" "$build/achd" bench \
    "$root/robots/kuka_lwr4.urdf" --root lwr_base_link --tip lwr_link_7 --case "$1" \
    --iterations "$2" --repeats 1 >/dev/null 2>"$work/log"
  sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$work/log"
}
for c in nc0 nc6; do
  a=$(count "$work/$c.json" "$n")
  b=$(count "$work/$c.json" $((2 * n)))
  echo "$c: $(( (b - a) / (2 * n) )) instructions per solve"
done
