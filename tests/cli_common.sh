# The shared part of the command-line tests (tests/cli_test.sh, tests/cli_hardening_test.sh):
# sourced with BUILD_DIR and CASE as $1 and $2.
set -uo pipefail

build=$(cd "$1" && pwd)
case_name=$2
src=$(cd "$(dirname "$0")/.." && pwd)
phongsim="$build/phongsim"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-cli.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
default="$src/configs/lirp/default.toml"
# No heartbeat lines (docs/cosim.md, "Progress") unless a case asks for them (cli.interface): on a
# slow machine they would add to the one stderr line expect_error counts.
export PHONGSIM_PROGRESS_AFTER=${PHONGSIM_PROGRESS_AFTER:-86400}

fail() { echo "FAIL: $*"; exit 1; }

# expect_error STDERR_PATTERN CMD...: exit 2, exactly one stderr line matching, no stdout files.
expect_error() {
  local pattern=$1
  shift
  "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  [ $rc -eq 2 ] || fail "expected exit 2, got $rc from: $* (stderr: $(cat "$tmp/err"))"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] || fail "expected one stderr line, got: $(cat "$tmp/err")"
  grep -qE -- "$pattern" "$tmp/err" || fail "stderr does not match '$pattern': $(cat "$tmp/err")"
  echo "ok: $(cat "$tmp/err")"
}

# no_files DIR: nothing but the inputs we put there.
no_outputs() {
  local left
  left=$(find "$tmp" -name 'result*' -o -name '*.phongsim-tmp-*' | head -1)
  [ -z "$left" ] || fail "partial output left behind: $left"
}

write_config() {  # write_config FILE P A OUT
  cat >"$1" <<EOT
pipeline = "lirp"
description = "test"
[format]
p = "$2"
a = "$3"
out = "$4"
[mode]
out_round = "half_even"
out_overflow = "saturate"
EOT
}
