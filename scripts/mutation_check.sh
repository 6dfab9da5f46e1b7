#!/usr/bin/env bash
# Breaks the RTL on purpose, one mutant at a time, and checks that co-simulation catches each
# one with a first-failure report. A verification that cannot fail proves nothing.
#
# usage: scripts/mutation_check.sh BUILD_DIR [MUTANT...]     (default: every mutant)
# Each mutant: a copy of the sources with one sed edit, Verilated through sim/cosim/rtl_build into a
# scratch directory, then `phongsim cosim --rtl-plugin --trace` on the mutant's configuration
# under random source and sink stalls. Caught means: exit 1, a first-failure report with the
# reproduce command, and a waveform of the cycles before the failure. Exit 0 only if every
# mutant was caught.
set -euo pipefail

src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:?usage: $0 BUILD_DIR [MUTANT...]}" && pwd)
shift
work=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-mutants.XXXXXX")
trap 'rm -rf "$work"' EXIT

# name @ configuration @ file @ sed expression @ what it breaks
mutants=(
  "round@configs/lirp/default.toml@rtl/common/fx_resize.sv@s/assign bias = Half - IntW'(1) + /assign bias = Half + /@convergent rounding constant off by one LSB"
  "skid-valid@configs/lirp/default.toml@rtl/common/stream_skid.sv@/if (spare_valid_q) begin/,/end/ s/main_valid_d  = 1'b1;/main_valid_d  = 1'b0;/@skid buffer drops the transaction it caught during a stall"
  "ready@configs/lirp/default.toml@rtl/common/pipe_ctrl.sv@s/assign ready\\[i\\] = out_ready_i | ~valid_q\\[i\\];/assign ready[i] = out_ready_i | valid_q[i];/@last pipeline stage accepts while full: overwrites a stalled transaction"
  "sub-order@configs/lirp/default.toml@rtl/lirp/lirp_core.sv@s/.a_i    (p1_i\\[c\\*PW+:PW\\]),/.a_i    (p0_i[c*PW+:PW]),/@difference delta = p0 - p0 instead of p1 - p0"
  "lyon-g2@configs/lyon/default.toml@rtl/lyon/lyon_norm.sv@s/if (en_i\\[1\\]) g_q <= g_d;/if (en_i[1]) g_q <= g_d + 1'b1;/@g2 one LSB too large"
  "lyon-square@configs/lyon/default.toml@rtl/lyon/lyon_shape.sv@s/fx_rq #(.InFmt(SqSqFmt), .OutFmt(SqFmt), .Round(Round))/fx_rq #(.InFmt(SqSqFmt), .OutFmt(SqFmt), .Round(fx_pkg::FxTruncate))/@shape-function squarers truncate instead of rounding to even (one LSB)"
  "lyon-compare@configs/lyon/default.toml@rtl/lyon/lyon_x.sv@0,/assign zero_d = |xk\\[XkW-1:XkFrac\\];/ s/assign zero_d = |xk\\[XkW-1:XkFrac\\];/assign zero_d = |xk[XkW-1:XkFrac-1];/@comparator fires at x/2^k >= 1/2 instead of >= 1"
  "lyon-fig8-w@configs/lyon/fig8_k1.toml@rtl/lyon/lyon_x.sv@s/fx_rq #(.InFmt(UFmt), .OutFmt(WFmt), .Round(Round))/fx_rq #(.InFmt(UFmt), .OutFmt(WFmt), .Round(fx_pkg::FxTruncate))/@Fig. 8 squarer inputs truncated instead of rounded (one LSB)"
  "lyon-sqrt2@configs/lyon/fig8_k2.toml@rtl/lyon/lyon_x.sv@s/localparam int unsigned S         = (K + 2) \\/ 2;/localparam int unsigned S         = (K + 1) \\/ 2;/@Fig. 8 shift without the even-k sqrt(2) correction"
  "lyon-halfway@configs/lyon/halfway.toml@rtl/lyon/lyon_top.sv@s/.b_i(v_q1\\[c\\*VecW+:VecW\\])/.b_i(l_q1[c*VecW+:VecW])/@H = (L + L)/2 instead of (L + V)/2"
  "kb-event-late@configs/kb/default.toml@rtl/kb/kb_engine.sv@s/(head_n <= i_q)/(head_n < i_q)/@events applied one pixel late"
  "kb-reload@configs/kb/default.toml@rtl/kb/kb_engine.sv@s/assign d1_step = apply_event \\& head_reload ? head_d1 : d1;/assign d1_step = d1;/@reload of the first difference ignored"
  "kb-d2-hold@configs/kb/d2_only.toml@rtl/kb/kb_engine.sv@s/      d2_q <= d2_step;/      d2_q <= d2_q;/@an event's second difference lasts one step only"
  "kb-drain@configs/kb/default.toml@rtl/kb/kb_engine.sv@s/      remaining_q <= remaining_q - 1'b1;/      remaining_q <= remaining_q;/@left-over event words never dropped"
  "quad-fill@configs/quad/default.toml@rtl/quad/quad_walker.sv@s/assign carry = sum >= {1'b0, d_q};/assign carry = sum > {1'b0, d_q};/@edge DDA carries one remainder step late: spans off by a pixel"
  "quad-jump@configs/quad/default.toml@rtl/quad/quad_channel.sv@s/assign f_start = col_f + i0_ext \\* g0_q + a_q \\* i0_i0m1;/assign f_start = col_f + i0_ext * g0_q;/@row start forgets the quadratic term a·i0(i0-1)"
  "quad-column@configs/quad/default.toml@rtl/quad/quad_channel.sv@s/    .d2_step_i(c_q << 1),/    .d2_step_i(c_q),/@column second difference c instead of 2c"
  "quad-clip@configs/quad/default.toml@rtl/quad/quad_walker.sv@s/{1'b0}}, x0_q});/{1'b0}}, x0_q}) - 1;/@span not clipped to the box on the left"
  "lyon-diffuse-delay@configs/lyon/default.toml@rtl/lyon/lyon_top.sv@s/pipe_delay #(.Width(DiffW), .Depth(Depth - 7))/pipe_delay #(.Width(DiffW), .Depth(Depth - 8))/@diffuse term one stage short: paired with the wrong pixel"
)

selected=("$@")
failed=0
for m in "${mutants[@]}"; do
  IFS='@' read -r name config file expr what <<<"$m"
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
  echo "mutant $name ($config): $what"
  pipeline=$(basename "$(dirname "$config")")
  if ! { cmake -S "$tree/sim/cosim/rtl_build" -B "$work/$name/build" -DCMAKE_BUILD_TYPE=Release \
           -DPHONGSIM_SOURCE_DIR="$tree" -DPHONGSIM_PIPELINE="$pipeline" \
           -DPHONGSIM_CONFIG="$src/$config" \
           -DPHONGSIM_VERILATED_RUNTIME="$build/libphongsim_verilated.so" &&
         cmake --build "$work/$name/build" --parallel "$(nproc)"; } >"$work/$name/build.log" 2>&1; then
    echo "  could not build the mutant; log:"
    tail -20 "$work/$name/build.log"
    failed=1
    continue
  fi
  set +e
  out=$("$build/phongsim" cosim --config "$src/$config" \
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
