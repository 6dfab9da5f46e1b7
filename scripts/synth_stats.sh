#!/usr/bin/env bash
# Yosys generic synthesis of a configuration's RTL top: prints the cell count and the cells by
# type (and checks there are no latches). The figures in docs/lyon.md come from this script.
#   scripts/synth_stats.sh configs/lyon/default.toml [more configs...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
python=/usr/bin/python3
[ -x "$python" ] || python=python3

for config in "$@"; do
  pipeline=$(basename "$(dirname "$config")")
  # The pipeline's top and sources, as cmake/PhongsimRtl.cmake lists them.
  top=$(sed -n "s/^set(PHONGSIM_RTL_${pipeline}_TOP \(.*\))/\1/p" "$root/cmake/PhongsimRtl.cmake")
  script=$(mktemp --suffix=.cmake)
  cat >"$script" <<'EOT'
include("${PHONGSIM_SOURCE_DIR}/cmake/PhongsimRtl.cmake")
phongsim_rtl_sources(${PIPELINE} files)
string(REPLACE ";" " " files "${files}")
message("${files}")
EOT
  sources=$(cmake -DPHONGSIM_SOURCE_DIR="$root" -DPIPELINE="$pipeline" -P "$script" 2>&1)
  rm -f "$script"
  chparams=$("$python" "$root/scripts/config_gflags.py" "$config" | sed -E 's/^-G([A-Za-z0-9_]+)=([0-9]+)$/-set \1 \2/' | tr '\n' ' ')
  log=$(mktemp)
  yosys -q -p "read_verilog -sv $sources; chparam $chparams $top; synth -top $top; check -assert; select -assert-none t:\$dlatch t:\$_DLATCH_*; tee -o $log stat" >/dev/null
  cells=$(awk '/Number of cells:/ {n=$4} END {print n}' "$log")
  echo "$config ($top): $cells cells, no latches"
  # Cells by type of the whole design: the last "Number of cells" block (the flattened total).
  awk '/Number of cells:/ {buf=""; on=1; next} on && /^ *\$_/ {buf=buf sprintf("  %-16s %s\n", $1, $2)} /^$/ {on=0} END {printf "%s", buf}' "$log" | sort -k2 -n -r
  rm -f "$log"
done
