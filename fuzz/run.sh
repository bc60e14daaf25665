#!/bin/sh
# Builds the libFuzzer targets (clang, ASan + UBSan) into build-fuzz and runs each for
# SECONDS seconds (default 60) from the committed seed corpus; exits non-zero on any
# crash, sanitizer report or uncaught exception. New inputs go to build-fuzz/corpus/,
# never into the committed seeds. Usage: fuzz/run.sh [SECONDS]
set -eu
seconds=${1:-60}
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build-fuzz
# urdfdom leaks its own graph on cyclic URDFs it then rejects: see the file.
export LSAN_OPTIONS=suppressions=$root/fuzz/urdfdom_leaks.supp
CXX=clang++ cmake -S "$root/fuzz" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j2
for target in fuzz_urdf fuzz_case; do
  seeds=$root/fuzz/corpus/${target#fuzz_}
  work=$build/corpus/${target#fuzz_}
  mkdir -p "$work"
  echo "fuzz: $target for ${seconds}s"
  (cd "$build" && ./$target -max_total_time="$seconds" -max_len=8192 -timeout=10 \
     -rss_limit_mb=2048 -print_final_stats=1 "$work" "$seeds")
done
echo "fuzz: no crash in ${seconds}s per target"
