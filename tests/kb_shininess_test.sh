#!/usr/bin/env bash
# Issue 18: the Kuijk-Blake methods must not change quality in a step at shininess 32, where the
# halfway exponent 4n passes the paper's table (n <= 125). The teapot, specular only, against
# Blinn (Vlasic's protocol), at shininess 31 and 32: PSNR of kb-exact and kb-onevec (through
# the RTL) within 1 dB of each other. With the old closed-form fallback they were 10 dB apart.
#   tests/kb_shininess_test.sh BUILD_DIR
set -euo pipefail
phongsim="$1/phongsim"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/phongsim-kb-step.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
psnr() {  # scene shininess method -> PSNR (dB)
  cat >"$tmp/s$1.toml" <<SCENE
name = "teapot-s$1"
builtin = "teapot"
[material]
ambient = [0.0, 0.0, 0.0]
diffuse = [0.0, 0.0, 0.0]
specular = [1.0, 1.0, 1.0]
shininess = $1
[[light]]
position = [2.0, 3.0, 4.0]
SCENE
  "$phongsim" render --scene "$tmp/s$1.toml" --method kb-exact,kb-onevec \
    --terms specular --reference blinn --out "$tmp/out$1" >/dev/null
  awk -F, -v m="$2" '$1 == m { print $4 }' "$tmp/out$1/teapot-s$1_metrics.csv"
}
status=0
for method in kb-exact kb-onevec; do
  a=$(psnr 31 "$method")
  b=$(psnr 32 "$method")
  echo "$method: PSNR $a dB at shininess 31, $b dB at 32"
  if ! awk -v a="$a" -v b="$b" 'BEGIN { d = a - b; exit !(a > 40 && (d < 0 ? -d : d) < 1) }'; then
    echo "FAIL: $method changes by more than 1 dB between shininess 31 and 32"
    status=1
  fi
done
exit $status
