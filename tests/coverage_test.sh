#!/usr/bin/env bash
# RTL code coverage (`cosim --coverage DIR`, docs/verification.md):
#   tests/coverage_test.sh BUILD_DIR PIPELINE
# Two co-simulations of the pipeline's default configuration into one DIR: the first writes
# DIR/coverage.info and DIR/html with line and toggle percentages in (0, 100] in its JSON; the
# second (other seed, random stalls) merges with the first (more data files, no fewer points hit).
# A run of a single vector into a DIR of its own reaches fewer toggles and fewer functional
# coverpoints than the two together: the percentages measure the vectors. Coverpoints: hit and
# total are numbers, DIR/coverpoints.txt holds them, and the second run keeps every point hit.
# --no-toggle-coverage: only with --coverage; its build has line points and no toggle points.
# The goal (100 % of the coverpoints, 95 % of the lines) on every configuration is
# tests/coverage_goal_test.sh's.
set -uo pipefail
phongsim="$1/phongsim"
p=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-coverage-test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() { echo "coverage_test $p: $*"; exit 1; }
"$phongsim" cosim "$p" --coverage "$tmp/cov" --vectors 1000 --json "$tmp/a.json" >"$tmp/out" 2>&1 ||
  fail "first run: $(cat "$tmp/out")"
cat "$tmp/out"
grep -q "^coverage (.* data files\? in $tmp/cov/data): lines .* %" "$tmp/out" || fail "no coverage line"
grep -q "^coverpoints: [0-9]* of [0-9]* hit (.* %); $tmp/cov/coverpoints.txt" "$tmp/out" ||
  fail "no coverpoints line"
[ -s "$tmp/cov/coverpoints.txt" ] || fail "no coverpoints.txt"
[ -s "$tmp/cov/coverage.info" ] && [ -s "$tmp/cov/html/index.html" ] || fail "no coverage.info or html"
"$phongsim" cosim "$p" --coverage "$tmp/cov" --vectors 1000 --seed 2 --backpressure random:0.5 \
  --json "$tmp/b.json" >"$tmp/out" 2>&1 || fail "second run: $(cat "$tmp/out")"
cat "$tmp/out"
"$phongsim" cosim "$p" --coverage "$tmp/one" --vector-index 0 --json "$tmp/c.json" >"$tmp/out" 2>&1 ||
  fail "one vector: $(cat "$tmp/out")"
cat "$tmp/out"
"$phongsim" cosim "$p" --no-toggle-coverage --vectors 10 >"$tmp/out" 2>&1 &&
  fail "--no-toggle-coverage without --coverage was taken"
grep -q "^phongsim: error: --no-toggle-coverage goes with --coverage DIR$" "$tmp/out" ||
  fail "--no-toggle-coverage without --coverage: $(cat "$tmp/out")"
"$phongsim" cosim "$p" --coverage "$tmp/line" --no-toggle-coverage --vectors 1000 \
  --json "$tmp/line.json" >"$tmp/out" 2>&1 || fail "line coverage: $(cat "$tmp/out")"
cat "$tmp/out"
grep -q "line coverage)$" "$tmp/out" || fail "the verdict does not name the line-coverage build"
grep -q "toggles not measured (--no-toggle-coverage)" "$tmp/out" || fail "line coverage: toggles"
python3 - "$tmp" <<'EOT' || fail "JSON"
import json, sys
a, b, c, line = (json.load(open(f"{sys.argv[1]}/{n}.json"))["coverage"] for n in ("a", "b", "c", "line"))
# The line-only build: the same line points as the full one, the same vectors reaching them.
assert line["toggles"] is None and line["toggle_percent"] is None, line
assert line["lines"] == a["lines"], (line, a)
for x in (a, b, c):
    assert 0 < x["line_percent"] <= 100 and 0 < x["toggle_percent"] <= 100, x
    assert x["lines"]["total"] > 0 and x["toggles"]["total"] > 0, x
    p = x["coverpoints"]
    assert type(p["hit"]) is int and type(p["total"]) is int and 0 < p["hit"] <= p["total"], p
    assert len(p["holes"]) == p["total"] - p["hit"], p
assert b["data_files"] > a["data_files"] and b["lines"]["total"] == a["lines"]["total"], (a, b)
assert b["lines"]["hit"] >= a["lines"]["hit"] and b["toggles"]["hit"] >= a["toggles"]["hit"], (a, b)
assert c["toggles"]["hit"] < b["toggles"]["hit"], (c, b)
assert b["coverpoints"]["hit"] >= a["coverpoints"]["hit"], (a, b)
assert b["coverpoints"]["total"] == a["coverpoints"]["total"], (a, b)
assert c["coverpoints"]["hit"] < b["coverpoints"]["hit"], (c, b)
print("coverpoints", a["coverpoints"]["hit"], b["coverpoints"]["hit"], c["coverpoints"]["hit"],
      "of", b["coverpoints"]["total"], "lines", a["line_percent"], b["line_percent"], c["line_percent"],
      "toggles", a["toggle_percent"], b["toggle_percent"], c["toggle_percent"])
EOT
