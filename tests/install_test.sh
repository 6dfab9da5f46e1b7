#!/usr/bin/env bash
# phongsim installed into a temporary prefix, then moved elsewhere (so nothing can point back
# into the source or build tree), used only from there:
#  (a) the installed `phongsim cosim lirp` Verilates from the installed files (fresh cache) and
#      passes; no source path is compiled into the binary;
#  (b) examples/testbench, a user's own Verilator testbench, configures against
#      find_package(phongsim), builds and passes;
#  (c) examples/python/explore_lirp.py runs with the installed module, and its model outputs
#      equal `phongsim eval --backend model` on the same vectors.
#   tests/install_test.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

cmake --install "$build" --prefix "$tmp/first" >"$tmp/install.log" || fail "$(cat "$tmp/install.log")"
mv "$tmp/first" "$tmp/prefix"  # relocated: the install must not know where it was put
prefix="$tmp/prefix"
export PHONGSIM_CACHE="$tmp/cache" PATH="$prefix/bin:/usr/bin:/bin"
unset PHONGSIM_ROOT PYTHONPATH

# (a)
! grep -q -- "$src" "$prefix/bin/phongsim" || fail "the installed binary contains $src"
# Into a file, not a pipe: `grep -q` quits at the first match and, under pipefail, a later write
# by phongsim would fail the line with SIGPIPE.
(cd "$tmp" && phongsim list) >"$tmp/list" 2>&1 || fail "installed list: $(cat "$tmp/list")"
grep -q "configs/lirp/default.toml" "$tmp/list" || fail "installed list: $(cat "$tmp/list")"
(cd "$tmp" && phongsim cosim lirp --vectors 20000 --source-idle random:0.3 --backpressure random:0.5) \
  >"$tmp/cosim" 2>&1 || fail "installed cosim: $(cat "$tmp/cosim")"
grep -q "^PASS lirp/default: .* 0 mismatches" "$tmp/cosim" || fail "installed cosim: $(cat "$tmp/cosim")"
grep -q "Verilating lirp" "$tmp/cosim" || fail "the installed cosim did not build from the install"

# (b)
cmake -S "$src/examples/testbench" -B "$tmp/tb" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >"$tmp/tb.log" 2>&1 || fail "testbench configure: $(tail -20 "$tmp/tb.log")"
cmake --build "$tmp/tb" >>"$tmp/tb.log" 2>&1 || fail "testbench build: $(tail -20 "$tmp/tb.log")"
"$tmp/tb/lirp_tb" >"$tmp/tb.out" 2>&1 || fail "testbench run: $(cat "$tmp/tb.out")"
grep -q "^own loop: 20000 outputs checked, 0 mismatches" "$tmp/tb.out" || fail "$(cat "$tmp/tb.out")"
grep -q "^phongsim harness: PASS lirp/default" "$tmp/tb.out" || fail "$(cat "$tmp/tb.out")"

# (c)
export PYTHONPATH="$prefix/lib/python3/dist-packages"
(cd "$tmp" && /usr/bin/python3 "$src/examples/python/explore_lirp.py" "$tmp/py" 4) >"$tmp/py.out" 2>&1 ||
  fail "python example: $(cat "$tmp/py.out")"
grep -q "^narrowest within 4.0 LSB: p S1.8, a 1.9" "$tmp/py.out" || fail "$(cat "$tmp/py.out")"
[ -s "$tmp/py/lirp-widths.png" ] || fail "no plot"
phongsim eval --config "$prefix/share/phongsim/configs/lirp/default.toml" --in "$tmp/py/vectors.csv" \
  --out "$tmp/py/eval.csv" >/dev/null || fail "installed eval"
cmp "$tmp/py/eval.csv" "$tmp/py/model.csv" || fail "Python model outputs differ from phongsim eval"
echo "install test: cosim, testbench and Python example pass from a relocated prefix"
