#!/usr/bin/env bash
# The main job: install, build, then co-simulate the default LIRP configuration (Lyon Fig. 7a
# widths) against its model: 10^6 random vectors plus directed corners, random source idles and
# sink backpressure. Prints a one-line summary; exit 0 only if every output matched.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
"$root/scripts/build.sh"
"$build/phongsim" cosim --pipeline lirp --config "$root/configs/lirp/default.toml" \
  --vectors 1000000 --seed 1 --source-idle random:0.2 --backpressure random:0.5 \
  --json "$build/main-job.json"
