#!/usr/bin/env bash
# The second simulator (`--simulator icarus`) on its own vectors, and that it can fail:
#   tests/icarus_test.sh BUILD_DIR PIPELINE   the pipeline's default configuration under random
#                                             source and sink stalls through Icarus: PASS
#   tests/icarus_test.sh BUILD_DIR wrong      examples/your-rtl's deliberately wrong LIRP: FAIL
#   tests/icarus_test.sh BUILD_DIR ports      a LIRP whose output port is a bit narrower than the
#                                             contract: refused before simulating (Icarus would
#                                             only warn and connect what fits)
#   tests/icarus_test.sh BUILD_DIR x          a LIRP whose y component is X: a failure, exit 1
#                                             and in the JUnit report (a two-state simulator
#                                             would see some value)
set -uo pipefail
phongsim="$1/phongsim"
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-icarus-test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
stalls=(--vectors 300 --seed 5 --source-idle random:0.3 --backpressure random:0.4)
case "$2" in
  wrong)
    out=$("$phongsim" cosim lirp --simulator icarus --rtl "$src/examples/your-rtl/my_lirp.sv" \
      "$src/examples/your-rtl/my_lirp_wrong.sv" --top my_lirp_wrong "${stalls[@]}" 2>&1)
    rc=$?
    printf '%s\n' "$out"
    [ $rc -eq 1 ] && grep -q "^FAIL lirp/default" <<<"$out" && grep -q -- "--simulator icarus" <<<"$out"
    ;;
  ports)
    sed 's/output logic \[3\*OW-1:0\] out_p_o/output logic [3*OW-2:0] out_p_o/' \
      "$src/examples/your-rtl/my_lirp.sv" >"$tmp/my_lirp.sv"
    grep -q "3\*OW-2:0" "$tmp/my_lirp.sv" || { echo "the narrow variant was not made"; exit 1; }
    out=$("$phongsim" cosim lirp --simulator icarus --rtl "$tmp/my_lirp.sv" --top my_lirp \
      "${stalls[@]}" 2>&1)
    rc=$?
    printf '%s\n' "$out"
    [ $rc -eq 2 ] && grep -q "port out_p_o of my_lirp is 35 bits wide, the contract says 36" <<<"$out" && ! grep -q "^PASS" <<<"$out"
    ;;
  x)
    sed 's/assign out_p_o\[c\*OW+:OW\] = p_q;/assign out_p_o[c*OW+:OW] = c == 1 ? {OW{1'"'"'bx}} : p_q;/' \
      "$src/examples/your-rtl/my_lirp.sv" >"$tmp/my_lirp.sv"
    grep -q "1'bx" "$tmp/my_lirp.sv" || { echo "the X variant was not made"; exit 1; }
    # A wrong design, not bad input: exit 1, a failure in the JUnit report.
    out=$("$phongsim" cosim lirp --simulator icarus --rtl "$tmp/my_lirp.sv" --top my_lirp \
      "${stalls[@]}" --junit "$tmp/x.xml" 2>&1)
    rc=$?
    printf '%s\n' "$out"
    [ $rc -eq 1 ] && grep -q "UNKNOWN VALUE (X or Z): cycle .*: out_p_o is .*x.* while out_valid_o" <<<"$out" &&
      grep -q '<failure type="unknown value"' "$tmp/x.xml"
    ;;
  *)
    # quad: every vector is a triangle of up to thousands of pixels, at ~10^4 cycles/s in Icarus
    [ "$2" = quad ] && stalls[1]=20
    # shade_quad: the same walker core and channels, framed as triangle in, pixels out; quad's
    # directed triangles (~5*10^5 pixels) went through Icarus above, so random triangles only
    [ "$2" = shade_quad ] && stalls+=(--no-directed)
    out=$("$phongsim" cosim "$2" --simulator icarus "${stalls[@]}" 2>&1)
    rc=$?
    printf '%s\n' "$out"
    [ $rc -eq 0 ] && grep -qE "^PASS $2/default: .* 0 mismatches.*Icarus" <<<"$out"
    ;;
esac
