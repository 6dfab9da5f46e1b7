#!/bin/sh
# Compare your RTL against phongsim's golden model in CI: every configuration x source-idle x
# sink-backpressure pattern, one JUnit testcase each. Copy it into your repository and set:
#   PIPELINE   lirp | lyon | kb | quad (phongsim list)
#   RTL        your SystemVerilog files and folders (space-separated)
#   TOP        your top module (default: phongsim's top name for the pipeline)
#   CONFIGS    configuration files (default: every configs/<pipeline>/*.toml phongsim has)
#   JUNIT      where the JUnit XML goes (default: phongsim-cosim.xml)
#   PHONGSIM   the phongsim binary (default: phongsim on PATH)
#   VECTORS    random vectors per run (default: the pipeline's, about a million outputs)
# Exit status: 0 every run passed, 1 a run failed (its first-mismatch report is printed and in
# the JUnit file), 2 bad input (one line on stderr).
set -eu
: "${PIPELINE:?set PIPELINE}" "${RTL:?set RTL}"
PHONGSIM=${PHONGSIM:-phongsim}
JUNIT=${JUNIT:-phongsim-cosim.xml}
SOURCES=${SOURCES:-none,periodic:1110,random:0.3,long:64:200}
SINKS=${SINKS:-none,random:0.5,periodic:0001,long:100:300}

set --
for config in ${CONFIGS:-}; do set -- "$@" --config "$config"; done
[ $# -gt 0 ] || set -- "$PIPELINE"
[ -z "${TOP:-}" ] || set -- "$@" --top "$TOP"
[ -z "${VECTORS:-}" ] || set -- "$@" --vectors "$VECTORS"
# shellcheck disable=SC2086  # RTL is a list of paths
exec "$PHONGSIM" cosim "$@" --rtl $RTL --source-idle "$SOURCES" --backpressure "$SINKS" \
  --junit "$JUNIT"
