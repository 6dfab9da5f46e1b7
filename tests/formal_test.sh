#!/usr/bin/env bash
# Bounded proofs of the stream primitives' assertions (tests/formal/stream_props.sv) with Yosys
# and yosys-smtbmc (z3): every input sequence up to DEPTH cycles after reset.
#   tests/formal_test.sh TOP [DEPTH]     TOP: stream_skid_props or pipe_props
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
top=$1
depth=${2:-24}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-formal.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
yosys -q -l "$tmp/yosys.log" -p "
  read_verilog -sv -formal $src/rtl/common/stream_check.sv $src/rtl/common/stream_skid.sv \
    $src/rtl/common/pipe_ctrl.sv \
    $src/rtl/common/pipe_delay.sv $src/tests/formal/stream_props.sv
  prep -top $top
  async2sync
  dffunmap
  write_smt2 -wires $tmp/$top.smt2" || { cat "$tmp/yosys.log"; exit 1; }
grep -q "assert" "$tmp/$top.smt2" || { echo "no assertions reached the proof"; exit 1; }
yosys-smtbmc -s z3 -t "$depth" --dump-vcd "$tmp/cex.vcd" "$tmp/$top.smt2" >"$tmp/bmc.log" 2>&1 || {
  cat "$tmp/bmc.log"
  echo "FAIL: $top: an assertion fails within $depth cycles (counterexample above)"
  exit 1
}
tr "\r" "\n" <"$tmp/bmc.log" | grep "Status" | tail -1
echo "PASS: $top: every assertion holds for every input sequence of $depth cycles"
