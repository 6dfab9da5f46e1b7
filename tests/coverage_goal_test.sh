#!/usr/bin/env bash
# The coverage goal of issue 17 (docs/verification.md, "RTL coverage") on every configuration
# of a pipeline:
#   tests/coverage_goal_test.sh BUILD_DIR CONFIGS_DIR PIPELINE VECTORS
# Each configs/PIPELINE/*.toml is co-simulated (VECTORS random vectors after the directed ones;
# lyon/wide's compare.just_above needs more than 2000) over the matrix of four source and four sink
# stall patterns with a line-coverage build of its plugin (--no-toggle-coverage: the goal is
# about lines, and toggle points make the build several times slower), into a DIR of its own,
# and must hit 100 % of its declared coverpoints and at least 95 % of the RTL line points not
# waived. Prints one line per configuration (the figures of docs/verification.md's table).
set -uo pipefail
phongsim="$1/phongsim"
configs=$2
p=$3
vectors=$4
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-coverage-goal.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() { echo "coverage_goal_test $p: $*"; exit 1; }
shopt -s nullglob
files=("$configs/$p"/*.toml)
[ ${#files[@]} -gt 0 ] || fail "no configuration in $configs/$p"
for f in "${files[@]}"; do
  name=$(basename "$f" .toml)
  "$phongsim" cosim --config "$f" --coverage "$tmp/$name" --no-toggle-coverage --vectors "$vectors" \
    --json "$tmp/$name.json" --source-idle none,periodic:1110,random:0.3,long:64:200 \
    --backpressure none,random:0.5,periodic:0001,long:100:300 >"$tmp/out" 2>&1 ||
    fail "$name: $(cat "$tmp/out")"
  python3 - "$tmp/$name.json" "$p/$name" <<'EOT' || fail "$name: $(grep -v '^PASS' "$tmp/out")"
import json, sys
doc = json.load(open(sys.argv[1]))
c = doc["coverage"]
assert doc["passed"] and doc["runs_passed"] == 16, "a run failed"
p, l = c["coverpoints"], c["lines"]
assert c["toggle_percent"] is None and c["toggles"] is None, c
assert l["total"] > 0 and p["total"] > 0, c
# Every waived line point is listed with its instance and a reason.
assert len(l["waivers"]) == l["waived"], l
assert all(w["file"].endswith(".sv") and w["instance"] and w["reason"] for w in l["waivers"]), l
print(f"{sys.argv[2]}: coverpoints {p['hit']} of {p['total']} ({len(p['waivers'])} waived), "
      f"lines {c['line_percent']:.1f} % ({l['hit']} of {l['total']}; {l['waived']} waived)")
assert p["hit"] == p["total"] and not p["holes"], ("coverpoints below 100 %", p["holes"])
assert c["line_percent"] >= 95, ("RTL lines below 95 %", c["line_percent"], l)
EOT
done
