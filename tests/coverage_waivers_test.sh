#!/usr/bin/env bash
# Coverage a user can act on (docs/cosim.md, "RTL code coverage"), on a copy of
# examples/your-rtl/my_lirp.sv in a temporary folder:
#   tests/coverage_waivers_test.sh BUILD_DIR
# - the baseline: the JSON lists the generate-block signals Verilator counts no toggles of, and
#   the HTML report's Branches row is the command's line figure, its Functions row the toggles;
# - a waiver file (a /regex/ waiver, a line waiver narrowed to an instance, comments) leaves two
#   line points out: the totals drop by two, the hits stay, each waived point is in the report
#   (one line per waiver with its reason) and in the JSON (reason, waiver FILE:LINE), and the
#   HTML's Branches row follows;
# - a stale waiver (its regex on no line, its line on no point), a waiver file without a reason
#   and a waived point that is reached are one-line errors naming the waiver file and line,
#   exit 2, the first three before any run (no data file, no JSON);
# - /*verilator coverage_off*/ around the rounding `case` removes its three points.
# One coverage build of the copy (and one of the coverage_off copy); every run is short.
source "$(dirname "$0")/cli_common.sh" "$1" coverage-waivers
rtl="$tmp/rtl"
mkdir -p "$rtl"
cp "$src/examples/your-rtl/my_lirp.sv" "$rtl/my_lirp.sv"
run() {  # run DIR JSON [ARGS...]: a coverage run of the copy
  local dir=$1 json=$2
  shift 2
  "$phongsim" cosim lirp --rtl "$rtl/my_lirp.sv" --top my_lirp --coverage "$dir" --vectors 300 \
    --json "$json" "$@"
}
run "$tmp/base" "$tmp/base.json" >"$tmp/out" 2>&1 || fail "baseline: $(cat "$tmp/out")"
cat "$tmp/out"
grep -q "^not toggle-counted, in a generate or named block (12 signals, 423 bits): top.my_lirp.g_component\[0\].m0_q (43)" \
  "$tmp/out" || fail "no not-toggle-counted line"

cat >"$rtl/waivers.txt" <<'EOT'
# my_lirp's waivers: the rounding modes no configuration of ours uses

my_lirp.sv /^\s+0:\s+q = lo;/ floor rounding (OutRound 0): no configuration uses it
my_lirp.sv:62 @^top\.my_lirp$ ties-up rounding (OutRound 1): none either
EOT
run "$tmp/waived" "$tmp/waived.json" --waivers "$rtl/waivers.txt" >"$tmp/out" 2>&1 ||
  fail "waived: $(cat "$tmp/out")"
cat "$tmp/out"
grep -q "^coverage (.*): lines .* ([0-9]* of [0-9]* points, 2 waived)" "$tmp/out" ||
  fail "the coverage line does not count the waived points"
grep -qF "waived by $rtl/waivers.txt:3 (1 line point: my_lirp.sv:61 in top.my_lirp): floor rounding (OutRound 0): no configuration uses it" \
  "$tmp/out" || fail "the report does not list the regex waiver"
grep -qF "waived by $rtl/waivers.txt:4 (1 line point: my_lirp.sv:62 in top.my_lirp): ties-up rounding" \
  "$tmp/out" || fail "the report does not list the line waiver"
python3 - "$tmp" "$rtl/waivers.txt" <<'EOT' || fail "JSON or HTML"
import json, re, sys
tmp, waivers = sys.argv[1], sys.argv[2]
base = json.load(open(f"{tmp}/base.json"))["coverage"]
waived = json.load(open(f"{tmp}/waived.json"))["coverage"]
b, w = base["lines"], waived["lines"]
assert b["waived"] == 0 and w["waived"] == 2, (b, w)
assert w["total"] == b["total"] - 2 and w["hit"] == b["hit"], ("the totals", b, w)
assert [(x["lines"], x["waiver"]) for x in w["waivers"]] == [("61", f"{waivers}:3"), ("62", f"{waivers}:4")], w
assert w["waivers"][0]["reason"].startswith("floor rounding") and w["waivers"][0]["instance"] == "top.my_lirp", w
# The points name this copy of the file, wherever the cached plugin was built from.
assert all(x["file"] == waivers.replace("waivers.txt", "my_lirp.sv") for x in w["waivers"]), w
assert waived["waiver_file"] == waivers and base["waiver_file"] is None
signals = {s["signal"]: s for s in base["not_toggle_counted"]}
assert signals["top.my_lirp.g_component[2].sum_q"] == {
    "signal": "top.my_lirp.g_component[2].sum_q", "bits": 43, "why": "in a generate or named block"}, signals
assert len(signals) == 12 and waived["not_toggle_counted"] == base["not_toggle_counted"]
# The HTML report's Branches row is the line figure, its Functions row the toggle figure.
def rows(d):
    text = re.sub(r"<[^>]+>", " ", open(f"{tmp}/{d}/html/index.html").read())
    return {k: (int(h), int(t)) for k, h, t in re.findall(r"(Lines|Functions|Branches):\s+(\d+)\s+(\d+)", text)}
for d, c in (("base", base), ("waived", waived)):
    r = rows(d)
    assert r["Branches"] == (c["lines"]["hit"], c["lines"]["total"]), (d, r, c["lines"])
    assert r["Functions"] == (c["toggles"]["hit"], c["toggles"]["total"]), (d, r, c["toggles"])
print("lines", b["hit"], "of", b["total"], "->", w["hit"], "of", w["total"], "(2 waived); HTML", rows("waived"))
EOT

# Stale waivers and a waiver without a reason: one line naming FILE:LINE, before any run.
data_files() { find "$tmp/stale" -name '*.dat' 2>/dev/null | wc -l; }
printf 'my_lirp.sv:62 ties-up rounding\nmy_lirp.sv /no such text in the file/ gone\n' >"$rtl/stale.txt"
expect_error "^phongsim: error: $rtl/stale.txt:2: the waiver 'my_lirp.sv /no such text in the file/' matches no coverage point \(/no such text in the file/ matches no line of .*my_lirp.sv" \
  run "$tmp/stale" "$tmp/stale.json" --waivers "$rtl/stale.txt"
printf '# moved\nmy_lirp.sv:5 a comment line now\n' >"$rtl/stale.txt"
expect_error "^phongsim: error: $rtl/stale.txt:2: the waiver 'my_lirp.sv:5' matches no coverage point \(no line or branch point lies on my_lirp.sv:5" \
  run "$tmp/stale" "$tmp/stale.json" --waivers "$rtl/stale.txt"
printf 'my_lirp.sv:62\n' >"$rtl/stale.txt"
expect_error "^phongsim: error: $rtl/stale.txt:1: a waiver needs a reason" \
  run "$tmp/stale" "$tmp/stale.json" --waivers "$rtl/stale.txt"
[ "$(data_files)" -eq 0 ] && [ ! -e "$tmp/stale.json" ] || fail "a refused waiver file left outputs"
# A waived point that is reached: the waiver's reason is wrong.
printf 'my_lirp.sv /default: q = lo/ half-even rounding is never used\n' >"$rtl/reached.txt"
expect_error "^phongsim: error: $rtl/reached.txt:1: .*my_lirp.sv line 63 in top.my_lirp is waived \(half-even rounding is never used\) but was reached" \
  run "$tmp/reached" "$tmp/reached.json" --waivers "$rtl/reached.txt"
[ ! -e "$tmp/reached.json" ] || fail "a reached waiver wrote its JSON"

# Verilator's own coverage_off: the case's three points are not in the data at all.
mkdir -p "$tmp/off"
sed 's|^      case (OutRound)|      /*verilator coverage_off*/\n      case (OutRound)|; s|^      endcase|      endcase\n      /*verilator coverage_on*/|' \
  "$rtl/my_lirp.sv" >"$tmp/off/my_lirp.sv"
grep -q "coverage_off" "$tmp/off/my_lirp.sv" || fail "sed did not insert coverage_off"
"$phongsim" cosim lirp --rtl "$tmp/off/my_lirp.sv" --top my_lirp --coverage "$tmp/offcov" --vectors 300 \
  --json "$tmp/off.json" >"$tmp/out" 2>&1 || fail "coverage_off: $(cat "$tmp/out")"
grep -q "^coverage" "$tmp/out" && grep "^coverage" "$tmp/out"
python3 - "$tmp" <<'EOT' || fail "coverage_off"
import json, sys
base = json.load(open(f"{sys.argv[1]}/base.json"))["coverage"]["lines"]
off = json.load(open(f"{sys.argv[1]}/off.json"))["coverage"]["lines"]
assert off["total"] == base["total"] - 3 and off["waived"] == 0, (base, off)
print("coverage_off: lines", base["total"], "->", off["total"])
EOT
! grep -aq "case" "$tmp"/offcov/data/*.dat || fail "coverage_off: case points in the data"
echo "coverage_waivers_test: ok"
