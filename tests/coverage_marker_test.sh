#!/usr/bin/env bash
# phongsim's own coverage waivers follow the markers in its RTL (docs/cosim.md, "Waivers"), with
# Verilator's real points:
#   tests/coverage_marker_test.sh BUILD_DIR SOURCE_DIR
# kb's configuration waives the low saturation arm of its output requantization, marked
# `// phongsim: waive saturate.low` in rtl/common/fx_resize.sv. On a copy of the tree's RTL
# (`cosim kb --rtl`, a line-coverage build), then with three lines inserted above the arm, the
# same point is waived, three lines further down, and the figures are the same; with the marker
# removed the command fails (exit 2) naming the file and the marker.
set -uo pipefail
phongsim="$1/phongsim"
src=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-coverage-marker.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() { echo "coverage_marker_test: $*"; exit 1; }
cp -r "$src/rtl" "$tmp/rtl"
resize="$tmp/rtl/common/fx_resize.sv"
run() {  # NAME: kb's default configuration on the copy, into $tmp/NAME and $tmp/NAME.json
  "$phongsim" cosim kb --rtl "$tmp/rtl/common" "$tmp/rtl/kb" --coverage "$tmp/$1" \
    --no-toggle-coverage --vectors 200 --json "$tmp/$1.json" >"$tmp/$1.out" 2>&1
}
run before || fail "the tree's RTL: $(cat "$tmp/before.out")"
python3 - "$resize" <<'EOT' || fail "no always_comb in fx_resize.sv"
import sys
p = sys.argv[1]
s = open(p).read()
assert "    always_comb begin\n" in s
open(p, "w").write(s.replace("    always_comb begin\n", "    // one\n    // two\n    // three\n    always_comb begin\n", 1))
EOT
run moved || fail "lines moved: $(cat "$tmp/moved.out")"
python3 - "$tmp" <<'EOT' || fail "waived points: $(grep -h '^coverage' "$tmp"/*.out)"
import json, sys
a, b = (json.load(open(f"{sys.argv[1]}/{n}.json"))["coverage"]["lines"] for n in ("before", "moved"))
assert a["waived"] == 1 and a["waivers"][0]["reason"].startswith("value.low"), a
assert (b["waived"], b["hit"], b["total"]) == (a["waived"], a["hit"], a["total"]), (a, b)
shift = lambda lines: "-".join(str(int(l) + 3) for l in lines.split("-"))
for x, y in zip(a["waivers"], b["waivers"]):
    assert x["file"].endswith("rtl/common/fx_resize.sv") and y["file"] == x["file"], (x, y)
    assert (y["lines"], y["instance"], y["reason"]) == (shift(x["lines"]), x["instance"], x["reason"]), (x, y)
print("waived", a["waivers"][0]["lines"], "->", b["waivers"][0]["lines"], b["waivers"][0]["instance"])
EOT
sed -i 's|// phongsim: waive saturate.low|//|' "$resize"
run removed && fail "a removed marker was taken: $(cat "$tmp/removed.out")"
grep -q "^phongsim: error: $resize: phongsim's waiver marker 'saturate.low' is on no line" \
  "$tmp/removed.out" || fail "the marker removed: $(cat "$tmp/removed.out")"
echo "coverage_marker_test: passed"
