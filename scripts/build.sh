#!/usr/bin/env bash
# Installs dependencies (scripts/setup.sh), then configures and builds phongsim in $BUILD_DIR
# (default: build/), Release, with Ninja: the targets given (e.g. `phongsim`: the program alone,
# plugins Verilated when a command first needs them), else everything (every test and every
# built-in configuration's plugin).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
"$root/scripts/setup.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build "$build" --parallel "$(nproc)" "${targets[@]}"
