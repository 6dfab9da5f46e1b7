#!/usr/bin/env bash
# Breaks the LIRP RTL on purpose, one mutant at a time, and checks that co-simulation catches
# each one with a first-failure report. A verification that cannot fail proves nothing.
#
# usage: scripts/mutation_check.sh BUILD_DIR [MUTANT...]     (default: every mutant)
# Each mutant: a copy of the sources with one sed edit, Verilated through sim/rtl_build into a
# scratch directory, then `phongsim cosim --rtl-plugin --trace` on the default LIRP configuration
# under random source and sink stalls. Caught means: exit 1, a first-failure report with the
# reproduce command, and a waveform of the cycles before the failure. Exit 0 only if every
# mutant was caught.
set -euo pipefail

src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:?usage: $0 BUILD_DIR [MUTANT...]}" && pwd)
shift
work=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-mutants.XXXXXX")
trap 'rm -rf "$work"' EXIT

# name @ file @ sed expression @ what it breaks
mutants=(
  "round@rtl/common/fx_resize.sv@s/assign bias = Half - IntW'(1) + /assign bias = Half + /@convergent rounding constant off by one LSB"
  "skid-valid@rtl/common/stream_skid.sv@/if (spare_valid_q) begin/,/end/ s/main_valid_d  = 1'b1;/main_valid_d  = 1'b0;/@skid buffer drops the transaction it caught during a stall"
  "ready@rtl/common/stream_register.sv@s/assign in_ready_o  = out_ready_i | ~valid_q;/assign in_ready_o  = out_ready_i | valid_q;/@stage accepts while full: overwrites a stalled transaction"
  "sub-order@rtl/lirp/lirp_unit.sv@s/.a_i   (in_p1_i\[c\*PW+:PW\]),/.a_i   (in_p0_i[c*PW+:PW]),/@difference p0 - p0 instead of p1 - p0"
)

selected=("$@")
failed=0
for m in "${mutants[@]}"; do
  IFS='@' read -r name file expr what <<<"$m"
  if [ ${#selected[@]} -gt 0 ] && [[ ! " ${selected[*]} " == *" $name "* ]]; then continue; fi
  tree="$work/$name/src"
  mkdir -p "$tree"
  cp -r "$src/rtl" "$src/sim" "$src/model" "$src/cmake" "$src/scripts" "$tree/"
  sed -i "$expr" "$tree/$file"
  if cmp -s "$src/$file" "$tree/$file"; then
    echo "mutant $name: the edit did not apply to $file (update this script)"
    failed=1
    continue
  fi
  echo "mutant $name: $what"
  if ! { cmake -S "$tree/sim/rtl_build" -B "$work/$name/build" -DCMAKE_BUILD_TYPE=Release \
           -DPHONGSIM_SOURCE_DIR="$tree" -DPHONGSIM_PIPELINE=lirp \
           -DPHONGSIM_CONFIG="$src/configs/lirp/default.toml" &&
         cmake --build "$work/$name/build" --parallel "$(nproc)"; } >"$work/$name/build.log" 2>&1; then
    echo "  could not build the mutant; log:"
    tail -20 "$work/$name/build.log"
    failed=1
    continue
  fi
  set +e
  out=$("$build/phongsim" cosim --config "$src/configs/lirp/default.toml" \
          --rtl-plugin "$work/$name/build/plugin.so" --vectors 20000 --seed 7 \
          --source-idle random:0.3 --backpressure random:0.5 --timeout 2000 \
          --trace "$work/$name/fail.fst" --trace-window 200 2>&1)
  rc=$?
  set -e
  if [ $rc -eq 1 ] && grep -qE '^(MISMATCH|UNEXPECTED OUTPUT|DEADLOCK|HANDSHAKE VIOLATION)' <<<"$out" &&
     grep -q 'reproduce: ' <<<"$out" && grep -q 'waveform of cycles' <<<"$out" &&
     [ -s "$work/$name/fail.fst" ]; then
    echo "  caught:"
    sed "s/^/    /" <<<"$out"
  else
    echo "  NOT CAUGHT (exit $rc):"
    sed 's/^/    /' <<<"$out"
    failed=1
  fi
done
exit $failed
