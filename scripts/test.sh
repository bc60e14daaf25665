#!/usr/bin/env bash
# Builds and runs every test of achd on a fresh Debian machine: native GoogleTest suites
# (Release), the same suites under ASan+UBSan, the wasm module with its Node tests, the
# page in Chromium, and the fuzzers for a fixed time. Installs what is missing first.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${ACHD_JOBS:-2}
fuzz_seconds=${ACHD_FUZZ_SECONDS:-30}
stage() { printf '\n=== %s ===\n' "$*"; }

stage "dependencies"
bash scripts/install-deps.sh

stage "native Release build and tests"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

stage "wasm module"
cmake --preset wasm
cmake --build --preset wasm

stage "Node tests (wasm == native)"
ACHD_CLI="$PWD/build/achd" node --test tests/node/

stage "browser test (Chromium)"
node --test tests/browser/

stage "native tests under ASan + UBSan"
cmake --preset debug-sanitize
cmake --build build-asan -j"$jobs"
ctest --test-dir build-asan --output-on-failure -j"$jobs"

stage "fuzzing (${fuzz_seconds} s per target)"
bash fuzz/run.sh "$fuzz_seconds"

stage "all tests passed"
