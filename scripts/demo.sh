#!/usr/bin/env bash
# Builds the wasm module and serves the repository root; open the printed URL.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset wasm
cmake --build --preset wasm
exec node scripts/serve.mjs "$@"
