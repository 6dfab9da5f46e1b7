#!/usr/bin/env bash
# Randomized power-up catches a missing reset (--x-init random, docs/cosim.md):
#   tests/xinit_reset_test.sh BUILD_DIR
# A copy of rtl/ whose pipe_ctrl keeps every stage's valid bit through reset instead of clearing
# it. Verilator's default build starts every register at 0, the value the reset would have
# given, so LIRP passes there; from a random power-up state (three seeds) a stage is valid
# before any input came, and the co-simulation fails.
set -uo pipefail
phongsim="$1/phongsim"
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-xinit-test.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cp -r "$src/rtl" "$tmp/rtl"
sed -i 's/        valid_q\[i\] <= 1.b0;/        valid_q[i] <= valid_q[i];/' "$tmp/rtl/common/pipe_ctrl.sv"
! cmp -s "$src/rtl/common/pipe_ctrl.sv" "$tmp/rtl/common/pipe_ctrl.sv" || { echo "no mutant"; exit 1; }
run=("$phongsim" cosim lirp --rtl "$tmp/rtl/common" "$tmp/rtl/lirp" --vectors 200)
out=$("${run[@]}" 2>&1)
rc=$?
printf '%s\n' "$out"
[ $rc -eq 0 ] && grep -q "^PASS lirp/default" <<<"$out" || { echo "zero power-up: expected PASS"; exit 1; }
for seed in 1 2 3; do
  out=$("${run[@]}" --x-init random --x-seed $seed 2>&1)
  rc=$?
  printf '%s\n' "$out"
  [ $rc -eq 1 ] && grep -q "^FAIL lirp/default: .*x-init random, seed $seed)" <<<"$out" &&
    grep -q -- "reproduce: .*--x-init random --x-seed $seed" <<<"$out" ||
    { echo "random power-up, seed $seed: expected FAIL with a reproduce command"; exit 1; }
done
