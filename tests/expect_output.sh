#!/usr/bin/env bash
# expect_output.sh REGEX CMD...: runs CMD, shows its output, and passes only when CMD exits 0
# AND its output has a line matching REGEX (extended grep). ctest's PASS_REGULAR_EXPRESSION
# alone would ignore the exit status.
set -uo pipefail
pattern=$1
shift
out=$("$@" 2>&1)
rc=$?
printf '%s\n' "$out"
if [ $rc -ne 0 ]; then
  echo "expect_output: exit status $rc"
  exit 1
fi
if ! grep -qE -- "$pattern" <<<"$out"; then
  echo "expect_output: no line matches '$pattern'"
  exit 1
fi
