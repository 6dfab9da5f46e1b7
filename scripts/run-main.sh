#!/usr/bin/env bash
# The main job: install, build the program, then render Lyon's Figure 9 (shinyballs: twelve
# specular models x five shininess values), the rows with a hardware unit through the Verilated
# RTL (the four Lyon plugins it needs Verilated first, in one parallel build), the others in
# float; writes the images, the labelled grid, difference images, a scanline plot and the metrics
# table to render/ (RENDER_DIR overrides) and prints the table. The tests and the other plugins
# are the test command's (scripts/run-tests.sh).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
"$root/scripts/build.sh" phongsim
"$build/phongsim" render --scene shinyballs --out "${RENDER_DIR:-$root/render}" \
  --json "$build/main-job.json"
