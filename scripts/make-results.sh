#!/usr/bin/env bash
# Regenerates docs/results/ (the grids, scanline plots and metric tables docs/results.md shows)
# with the built phongsim. Usage: scripts/make-results.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-${BUILD_DIR:-$root/build}}
out="$root/docs/results"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

render() {  # render NAME ARGS...: keep the grid, the scanline plot and the metrics table
  local name=$1
  shift
  "$build/phongsim" render --quiet --out "$work/$name" "$@" >"$work/$name.log"
  local scene
  scene=$(basename "$(ls "$work/$name/"*_grid.png)" _grid.png)
  cp "$work/$name/${scene}_grid.png" "$out/$name-grid.png"
  cp "$work/$name/${scene}_scanline.png" "$out/$name-scanline.png"
  cp "$work/$name/${scene}_metrics.md" "$out/$name-metrics.md"
  echo "$name: phongsim render $*"
}

render shinyballs --scene shinyballs
render triangle --scene triangle --method flat,gouraud,gouraud4,quadratic,lyon-k2,kb-onevec
render teapot --scene teapot --method flat,gouraud,gouraud4,quadratic,lyon-k2,kb-onevec
render kbsphere32 --scene kbsphere32 --method gouraud,kb-exact,kb-decomp,kb-onevec,lyon-k2
render kbsphere512 --scene kbsphere512 --method gouraud,kb-exact,kb-decomp,kb-onevec,lyon-k2
render machband --scene "$root/data/scenes/kbsphere512-diffuse.toml" --method kb-exact,kb-onevec
render dodecahedron --scene dodecahedron --method gouraud,gouraud4,quadratic,kb-onevec
render sphere40 --scene sphere40 --method gouraud,gouraud4,quadratic,kb-onevec
