#!/usr/bin/env bash
# Builds and runs every test of achd on a fresh Debian machine: native GoogleTest suites
# (Release), the same suites under ASan+UBSan, the wasm module with its Node tests, the
# page in Chromium, and the fuzzers for a fixed time. Installs what is missing first.
#
#   bash scripts/test.sh               every stage, in the order below (what CI runs)
#   bash scripts/test.sh STAGE...      only those stages, each with what it needs first
#
# Stages (each installs missing dependencies first; nothing runs twice in one call):
#   native    native Release build (build/) and its ctest suites
#   wasm      the wasm module (build-wasm/ -> web/dist/achd.mjs, wasm/dist/)
#   node      Node tests, wasm against the native CLI (builds build/achd and the module)
#   browser   the page in Chromium (builds the module)
#   sanitize  native build under ASan + UBSan (build-asan/) and its ctest suites
#   fuzz      the libFuzzer targets and the JS boundary's property test (builds the
#             module), ACHD_FUZZ_SECONDS (default 30) each
# Environment: ACHD_JOBS (parallel jobs, default 2), ACHD_FUZZ_SECONDS.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${ACHD_JOBS:-2}
fuzz_seconds=${ACHD_FUZZ_SECONDS:-30}
stage() { printf '\n=== %s ===\n' "$*"; }
all_stages=(native wasm node browser sanitize fuzz)

# Each step runs at most once per call (a stage asked for twice, or one another needs).
declare -A done_steps=()
once() { [ -n "${done_steps[$1]:-}" ] && return 1; done_steps[$1]=1; }

dependencies() {
  once dependencies || return 0
  stage "dependencies"
  bash scripts/install-deps.sh
}

native_configure() {
  once native_configure || return 0
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
}

native() {
  once native || return 0
  stage "native Release build and tests"
  native_configure
  cmake --build build -j"$jobs"
  ctest --test-dir build --output-on-failure -j"$jobs"
}

# The native CLI alone (and the writer of the random trees they share with the C++
# suites), for the Node tests when the native stage did not run.
native_cli() {
  [ -n "${done_steps[native]:-}" ] && return 0
  once native_cli || return 0
  stage "native achd CLI (for the Node tests)"
  native_configure
  cmake --build build -j"$jobs" --target achd_cli random_tree_files
}

wasm() {
  once wasm || return 0
  stage "wasm module"
  cmake --preset wasm
  cmake --build --preset wasm
}

node_tests() {
  once node || return 0
  stage "Node tests (wasm == native)"
  ACHD_CLI="$PWD/build/achd" node --test tests/node/
}

browser() {
  once browser || return 0
  stage "browser test (Chromium)"
  node --test tests/browser/
}

sanitize() {
  once sanitize || return 0
  stage "native tests under ASan + UBSan"
  cmake --preset debug-sanitize
  cmake --build build-asan -j"$jobs"
  ctest --test-dir build-asan --output-on-failure -j"$jobs"
}

fuzz() {
  once fuzz || return 0
  stage "fuzzing (${fuzz_seconds} s per target)"
  bash fuzz/run.sh "$fuzz_seconds"
  # The JS boundary (views, callbacks, inputs read once) for twice that time (60 s by
  # default: random create/delete/view/step sequences need the length); the Node stage
  # runs it for its default few seconds.
  wasm
  ACHD_FUZZ_SECONDS="$((2 * fuzz_seconds))" node --test tests/node/boundary_property.test.mjs
}

# One stage asked for by name, after what it needs.
run_stage() {
  dependencies
  case $1 in
    native) native ;;
    wasm) wasm ;;
    node) native_cli; wasm; node_tests ;;
    browser) wasm; browser ;;
    sanitize) sanitize ;;
    fuzz) fuzz ;;
  esac
}

usage() {
  echo "usage: bash scripts/test.sh [STAGE...]   (no stage: all of them, in this order)"
  echo "stages: ${all_stages[*]}"
}

for arg in "$@"; do
  case $arg in
    -h | --help) usage; exit 0 ;;
    native | wasm | node | browser | sanitize | fuzz) ;;
    *) echo "test.sh: unknown stage '$arg'" >&2; usage >&2; exit 2 ;;
  esac
done

if (($# == 0)); then
  # Every stage in this order: the native build first, so that the Node tests find
  # build/achd, and the wasm module before the Node and browser tests that load it.
  dependencies
  native
  wasm
  node_tests
  browser
  sanitize
  fuzz
  stage "all tests passed"
else
  for arg in "$@"; do run_stage "$arg"; done
  stage "passed: $*"
fi
