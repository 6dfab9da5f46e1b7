#!/usr/bin/env bash
# Issue 19: the frame's clocks that `render --backend rtl` measures on every unit method equal
# what the cycle model gives on the model backend (the render itself refuses a disagreement, and
# its RTL outputs must equal the model's; this checks the reported numbers end to end), and the
# breakdown adds up. The teapot, every unit kind: the composed pipelines (shade_quad: gouraud,
# quadratic; shade_kb: kb-onevec; shade_lyon: lyon-k2-tri, the walker with Lyon's unit behind
# it), Lyon's unit alone, and through --unit-config the walker alone (quad) and one Kuijk-Blake
# engine serving the channels in turn (kb): the same images, their own clocks.
#   tests/frame_cycles_test.sh BUILD_DIR
set -euo pipefail
phongsim="$1/phongsim"
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-frame.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
methods=gouraud,quadratic,lyon-k2,lyon-fig8-k1,kb-onevec,lyon-k2-tri
for backend in rtl model; do
  "$phongsim" render --scene teapot --method "$methods" --backend "$backend" --no-build \
    --out "$tmp/$backend" --json "$tmp/$backend.json" >/dev/null
  "$phongsim" render --scene teapot --method gouraud --backend "$backend" --no-build \
    --unit-config "$src/configs/quad/linear.toml" --out "$tmp/quad-$backend" \
    --json "$tmp/quad-$backend.json" >/dev/null
  "$phongsim" render --scene teapot --method kb-onevec --backend "$backend" --no-build \
    --unit-config "$src/configs/kb/default.toml" --out "$tmp/kb-$backend" \
    --json "$tmp/kb-$backend.json" >/dev/null
done
# A float method has no unit and no frame.
"$phongsim" render --scene teapot --method phong,gouraud --backend float --out "$tmp/float" \
  --json - | python3 -c 'import json, sys; assert all(m["frame"] is None for m in json.load(sys.stdin)["methods"])'

python3 - "$tmp/rtl.json" "$tmp/model.json" <<'PY'
import json, sys
rtl, model = (json.load(open(f))["methods"] for f in sys.argv[1:3])
for r, m in zip(rtl, model):
    name = r["method"]
    assert r["backend"] == "rtl" and m["backend"] == "model", name
    f, g = r["frame"], m["frame"]
    assert f == g, f"{name}: RTL {f} != cycle model {g}"
    parts = ["outputs", "fill_cycles", "setup_cycles", "empty_row_cycles", "stall_cycles"]
    assert f["cycles"] == sum(f[k] for k in parts), f"{name}: {f}"
    assert f["cycles"] > f["pixels"] > 1000, f"{name}: {f}"
    assert f["pixels_per_clock"] == f["pixels"] / f["cycles"], f"{name}: {f}"
    if name in ("gouraud", "quadratic", "lyon-k2-tri"):  # a set-up clock per row, some rows empty
        assert f["setup_cycles"] > 0 and f["empty_row_cycles"] > 0, f"{name}: {f}"
    if name == "kb-onevec":  # shade_kb: an engine per channel, a pixel in colour per output
        assert f["outputs"] == f["pixels"], f"{name}: {f}"
    print(f"ok: {name}: {f['cycles']} cycles, {f['pixels']} pixels")
PY
# The units alone: RTL clocks = cycle model; the walker's as shade_quad's (the number costs no
# clock); one engine emits each pixel once per channel, so about three times shade_kb's clocks.
python3 - "$tmp" <<'PY'
import json, sys
t = sys.argv[1]
frame = lambda name, method: next(m["frame"] for m in json.load(open(f"{t}/{name}.json"))["methods"]
                                  if m["method"] == method)
for unit, method in (("quad", "gouraud"), ("kb", "kb-onevec")):
    f, g = frame(f"{unit}-rtl", method), frame(f"{unit}-model", method)
    assert f == g, f"{unit}: RTL {f} != cycle model {g}"
    assert f["pixels"] == frame("rtl", method)["pixels"], (unit, f)
assert frame("quad-rtl", "gouraud") == frame("rtl", "gouraud")
one, three = frame("kb-rtl", "kb-onevec"), frame("rtl", "kb-onevec")
assert one["outputs"] == 3 * one["pixels"] and one["cycles"] > 2.9 * three["cycles"], (one, three)
print(f"ok: walker alone {frame('quad-rtl', 'gouraud')['cycles']} cycles, one engine {one['cycles']}")
PY
# Frames per second (--clock-mhz): a given clock for every unit, or one engine's iCE40 fmax from
# the synthesis flow (phongsim synth --ice40), each frame's cycles at that clock.
"$phongsim" render --scene teapot --method gouraud,kb-onevec --backend model --clock-mhz 50 \
  --out "$tmp/clock" --json "$tmp/clock.json" >"$tmp/clock.txt"
grep -q "| clock (MHz) | frames/s |$" "$tmp/clock.txt" || { echo "FAIL: no fps columns"; exit 1; }
"$phongsim" render --scene teapot --method kb-onevec --backend model --clock-mhz ice40 \
  --unit-config "$src/configs/kb/default.toml" --out "$tmp/ice40" --json "$tmp/ice40.json" \
  >/dev/null 2>&1
"$phongsim" synth --config "$src/configs/kb/default.toml" --ice40 --json "$tmp/synth.json" >/dev/null 2>&1
python3 - "$tmp" <<'PY'
import json, sys
t = sys.argv[1]
frames = lambda name: [m["frame"] for m in json.load(open(f"{t}/{name}.json"))["methods"]]
for f in frames("clock"):
    assert f["clock_mhz"] == 50 and f["clock"] == "--clock-mhz", f
    assert abs(f["frames_per_second"] - 50e6 / f["cycles"]) < 1e-9 * f["frames_per_second"], f
(f,) = frames("ice40")
fmax = json.load(open(f"{t}/synth.json"))["ice40"]["fmax_mhz"]
assert fmax > 0 and f["clock_mhz"] == fmax and f["clock"].startswith("nextpnr-ice40"), (f, fmax)
assert abs(f["frames_per_second"] - fmax * 1e6 / f["cycles"]) < 1e-6, f
assert all(g["clock_mhz"] is None and g["frames_per_second"] is None for g in frames("model")), t
print(f"ok: one engine at {fmax} MHz: {f['frames_per_second']:.1f} teapot frames per second")
PY
cmp "$tmp/rtl/teapot_gouraud.png" "$tmp/quad-rtl/teapot_gouraud.png" ||
  { echo "FAIL: gouraud on the walker alone differs from shade_quad's"; exit 1; }
cmp "$tmp/rtl/teapot_kb-onevec.png" "$tmp/kb-rtl/teapot_kb-onevec.png" ||
  { echo "FAIL: kb-onevec on one engine differs from shade_kb's"; exit 1; }
# Per triangle (the walker methods): every pixel once, each triangle at least its pixels plus a
# clock per row, and with the fill at least the frame.
python3 - "$tmp/model.json" "$tmp/model/teapot_triangle_cycles.csv" <<'PY'
import csv, json, sys
frames = {m["method"]: m["frame"] for m in json.load(open(sys.argv[1]))["methods"]}
rows = list(csv.DictReader(open(sys.argv[2])))
for method in ("gouraud", "quadratic", "lyon-k2-tri"):
    mine = [r for r in rows if r["method"] == method]
    f = frames[method]
    assert sum(int(r["pixels"]) for r in mine) == f["pixels"], method
    for r in mine:
        c, p = int(r["cycles"]), int(r["pixels"])
        assert c == p + int(r["setup_cycles"]) + int(r["empty_row_cycles"]) and c > p, r
    assert sum(int(r["cycles"]) for r in mine) + f["fill_cycles"] >= f["cycles"], method
    print(f"ok: {method}: {len(mine)} triangles")
assert {r["method"] for r in rows} == {"gouraud", "quadratic", "lyon-k2-tri"}, "only walker methods"
# The composed pipeline is the walker's clocks plus Lyon's 15 stages (light and viewer at
# infinity: one program per triangle), and shades the teapot exactly as Lyon's unit alone.
assert frames["lyon-k2-tri"]["cycles"] == frames["gouraud"]["cycles"] + 15, frames
PY
cmp "$tmp/rtl/teapot_lyon-k2.png" "$tmp/rtl/teapot_lyon-k2-tri.png" ||
  { echo "FAIL: lyon-k2-tri differs from lyon-k2 on the teapot"; exit 1; }
[ -s "$tmp/model/teapot_triangle_cycles.png" ] || { echo "FAIL: no triangle cycles plot"; exit 1; }
