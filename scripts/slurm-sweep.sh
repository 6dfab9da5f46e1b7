#!/usr/bin/env bash
# One point of a planned sweep as a Slurm array task:
#   phongsim sweep plan my.toml --out DIR
#   sbatch --array=0-$(( $(wc -l < DIR/jobs.txt) - 1 )) scripts/slurm-sweep.sh DIR
#   phongsim sweep merge my.toml --out DIR        # after the array has finished
# Locally the same jobs run with `parallel < DIR/jobs.txt` or `make -j -C DIR`.
#SBATCH --job-name=phongsim-sweep
#SBATCH --cpus-per-task=1
set -euo pipefail
dir=${1:?usage: slurm-sweep.sh PLAN_DIR}
line=$(( ${SLURM_ARRAY_TASK_ID:?run as a Slurm array task} + 1 ))
cmd=$(sed -n "${line}p" "$dir/jobs.txt")
[ -n "$cmd" ] || { echo "no job $line in $dir/jobs.txt" >&2; exit 2; }
eval "$cmd"
