#!/usr/bin/env bash
# Instructions per solve, counted by callgrind: `achd bench` run with N and 2N iterations
# (each a warm-up round and a timed round of that many solves), the difference divided by
# 2N (the loading and the timing code cancel out). Instruction counts are not time, but
# they do not depend on the machine's load: a refactoring that must not change the solver
# shows the same counts before and after. The solves:
#   nc0, nc6    the KUKA LWR 4 chain without constraints and with its tip held in 6D;
#   quad_feet   the quadruped on a floating base, its four feet held in 3D (m = 12);
#   quad, quad_frames   the quadruped (fixed base, unconstrained), and the same robot with
#               60 massless frames on fixed joints added to its links (what sensor and
#               marker frames cost a solve that does not ask for their accelerations).
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
legs='"lf_haa": 0.1, "lf_hfe": 0.8, "lf_kfe": -1.6, "rf_haa": -0.1, "rf_hfe": 0.8, "rf_kfe": -1.6,
  "lh_haa": 0.1, "lh_hfe": -0.8, "lh_kfe": 1.6, "rh_haa": -0.1, "rh_hfe": -0.8, "rh_kfe": 1.6'
xyz='[[1,0,0,0,0,0],[0,1,0,0,0,0],[0,0,1,0,0,0]]'
echo "{\"q\": {\"trunk\": [0, 0, 0.3, 0, 0, 0.2588190451, 0.9659258263], $legs},
  \"qd\": {\"trunk\": [0.1, 0, -0.2, 0, 0.1, 0.3], \"lf_hfe\": 0.5, \"rh_kfe\": -0.4},
  \"gravity\": [0, 0, -9.81], \"constraints\": [
  {\"link\": \"lf_foot\", \"alpha\": $xyz}, {\"link\": \"rf_foot\", \"alpha\": $xyz},
  {\"link\": \"lh_foot\", \"alpha\": $xyz}, {\"link\": \"rh_foot\", \"alpha\": $xyz}]}" > "$work/quad_feet.json"
echo "{\"q\": {$legs}, \"qd\": {\"lf_hfe\": 0.5, \"rh_kfe\": -0.4, \"lh_haa\": 0.2},
  \"gravity\": [0, 0, -9.81]}" > "$work/quad.json"
cp "$work/quad.json" "$work/quad_frames.json"
# The quadruped with 60 massless frames, each on a fixed joint below one of its links.
{
  sed '/<\/robot>/d' "$root/robots/quadruped.urdf"
  links=(trunk lf_hip lf_thigh lf_shank lf_foot rf_hip rf_thigh rf_shank rf_foot
         lh_hip lh_thigh lh_shank lh_foot rh_hip rh_thigh rh_shank rh_foot)
  for k in $(seq 0 59); do
    echo "  <joint name=\"frame_${k}_joint\" type=\"fixed\"><parent link=\"${links[k % 17]}\"/>"
    echo "    <child link=\"frame_$k\"/><origin xyz=\"0.01 0.0$((k % 10)) -0.02\" rpy=\"0.1 0 0.$k\"/></joint>"
    echo "  <link name=\"frame_$k\"/>"
  done
  echo "</robot>"
} > "$work/quad_frames.urdf"

count() {  # instructions of one bench run of $3 solves of robot $1 on case $2 (then options)
  local urdf=$1 case=$2 iterations=$3
  shift 3
  valgrind --tool=callgrind --callgrind-out-file="$work/out" "$build/achd" bench "$urdf" --case "$case" \
    --iterations "$iterations" --repeats 1 "$@" >/dev/null 2>"$work/log"
  sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$work/log"
}
per_solve() {  # name, robot, case, options
  local name=$1 urdf=$2 case=$3
  shift 3
  a=$(count "$urdf" "$case" "$n" "$@")
  b=$(count "$urdf" "$case" $((2 * n)) "$@")
  echo "$name: $(( (b - a) / (2 * n) )) instructions per solve"
}
lwr=(--root lwr_base_link --tip lwr_link_7)
per_solve nc0 "$root/robots/kuka_lwr4.urdf" "$work/nc0.json" "${lwr[@]}"
per_solve nc6 "$root/robots/kuka_lwr4.urdf" "$work/nc6.json" "${lwr[@]}"
per_solve quad_feet "$root/robots/quadruped.urdf" "$work/quad_feet.json" --floating
per_solve quad "$root/robots/quadruped.urdf" "$work/quad.json"
per_solve quad_frames "$work/quad_frames.urdf" "$work/quad_frames.json"
