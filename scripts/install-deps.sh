#!/usr/bin/env bash
# Installs what building, testing and serving achd need, from Debian's packages and npm,
# skipping whatever is already there. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ clang libclang-rt-14-dev pkg-config dpkg-dev   # toolchains, libFuzzer, apt-get source
  libeigen3-dev liburdfdom-dev liburdfdom-headers-dev libtinyxml-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev               # tests and benchmarks
  liborocos-kdl-dev libkdl-parser-dev                      # the parity reference
  emscripten chromium                                      # wasm build, browser test
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}"
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
command -v node >/dev/null || { echo "install-deps: Node.js 20 is required (node not found)" >&2; exit 1; }
# npm packages pinned by package-lock.json (three for the page, playwright-core for the
# browser test, typescript for the type tests).
if [ -f package-lock.json ] && ! npm ls --silent >/dev/null 2>&1; then
  npm ci --no-audit --no-fund
fi
