#!/usr/bin/env bash
# Installs dependencies (scripts/setup.sh), then configures and builds phongsim in $BUILD_DIR
# (default: build/), Release, with Ninja.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
"$root/scripts/setup.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" --parallel "$(nproc)"
