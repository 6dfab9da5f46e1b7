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

# Vlasic's Table 6.1 layout from the metrics CSVs of the renders NAME...: one row per render,
# one column per method (colour correctness).
pivot() {
  local header=1 name
  for name in "$@"; do
    awk -F, -v name="$name" -v header=$header '
      NR > 1 { m[NR - 1] = $1; c[NR - 1] = sprintf("%.4f", $3); n = NR - 1 }
      END {
        if (header) {
          h = "| render |"; r = "|---|"
          for (i = 1; i <= n; i++) { h = h " " m[i] " |"; r = r "---|" }
          print h; print r
        }
        l = "| " name " |"
        for (i = 1; i <= n; i++) l = l " " c[i] " |"
        print l
      }' "$work/$name/"*_metrics.csv
    header=0
  done
}

render shinyballs --scene shinyballs
render triangle --scene triangle --method flat,gouraud,gouraud4,quadratic,lyon-k2,kb-onevec
render teapot --scene teapot --method flat,gouraud,gouraud4,quadratic,lyon-k2,kb-onevec
render kbsphere32 --scene kbsphere32 --method gouraud,kb-exact,kb-decomp,kb-onevec,lyon-k2
render kbsphere512 --scene kbsphere512 --method gouraud,kb-exact,kb-decomp,kb-onevec,lyon-k2
render machband --scene "$root/data/scenes/kbsphere512-diffuse.toml" --method kb-exact,kb-onevec
render dodecahedron --scene dodecahedron --method gouraud,gouraud4,quadratic,kb-onevec
render sphere40 --scene sphere40 --method gouraud,gouraud4,quadratic,kb-onevec

# Every seed method side by side (docs/methods.md), full colour against Phong and, as Vlasic's
# Table 6.1 compares them, specular only against Phong shading with Blinn's model.
seed_methods=gouraud,gouraud4,quadratic,env-map,blinn-map,quad-blinn-map,fast-phong,fence,highlight-track
for scene in triangle teapot; do
  render "methods-$scene" --scene $scene --method $seed_methods
  render "methods-$scene-specular" --scene $scene --method $seed_methods --terms specular \
    --reference blinn
done
pivot methods-triangle methods-teapot methods-triangle-specular methods-teapot-specular \
  >"$out/methods-table.md"
echo "methods-table: colour correctness of each render above, one row each"

# How often each claim holds over 200 random scenes (phongsim study; docs/results.md).
"$build/phongsim" study --quiet --out "$work/study" >"$work/study.log"
cp "$work/study/study.md" "$out/study-table.md"
cp "$work/study/study.png" "$out/study.png"
echo "study: phongsim study (200 random scenes, seed 1)"
