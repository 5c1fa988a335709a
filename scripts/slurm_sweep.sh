#!/usr/bin/env bash
# A visco2d sweep on a Slurm cluster as a job array, then one job that collects the table.
#
#   bash scripts/slurm_sweep.sh SHARDS OUT DECK... [--param NAME=VALUES ...] [--table CSV] [--zip] ...
#
# Run it on the login node of a cluster that shares OUT (and this repository) with its
# compute nodes, after `make build`. It
#   1. expands the sweep once: visco2d-batch expand ... -o OUT  (OUT/decks/<case>.inp),
#   2. submits a job array of SHARDS tasks (sbatch --array=0-(SHARDS-1)); task K runs
#        visco2d-batch run ... -o OUT --shard K/SHARDS -j $SLURM_CPUS_PER_TASK
#      (cases K, K+SHARDS, K+2*SHARDS, ... on the task's cores),
#   3. submits `visco2d-batch collect OUT` to run after every task has ended, failed or not
#      (--dependency=afterany): OUT/table.csv and OUT/table.md, failed and missing cases marked.
# More sbatch options (time, partition, cores, account) go in SBATCH_ARGS, e.g.
#   SBATCH_ARGS="--time=02:00:00 --cpus-per-task=16 --partition=compute" \
#     bash scripts/slurm_sweep.sh 32 out/apples inputs/examples/apple_drop_bruise.inp --param height=0.05:1.0:640
# The arguments after OUT are those of `visco2d-batch run` (doc/batch.md), except -o, -j, --shard and --mpi.
# Logs: OUT/slurm/. A task that dies leaves its cases `missing` in the table: rerun them with
#   build/install/bin/visco2d-batch run ... -o OUT --shard K/SHARDS    (or the whole sweep).
set -euo pipefail

if [ $# -lt 3 ] || ! [[ $1 =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: bash scripts/slurm_sweep.sh SHARDS OUT DECK... [visco2d-batch run options]" >&2
  exit 2
fi
shards=$1
out=$2
shift 2
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
batch="$root/build/install/bin/visco2d-batch"
if [ ! -x "$batch" ]; then
  echo "slurm_sweep.sh: no $batch: run 'make build' first" >&2
  exit 2
fi
command -v sbatch > /dev/null || { echo "slurm_sweep.sh: no sbatch: not a Slurm cluster" >&2; exit 2; }

mkdir -p "$out/slurm"
out=$(cd "$out" && pwd)
"$batch" expand "$@" -o "$out" > "$out/slurm/cases.txt"      # usage errors stop here, before any job
echo "slurm_sweep.sh: $(wc -l < "$out/slurm/cases.txt") cases in $shards shards into $out"

args=$(printf '%q ' "$@")
run="cd $(printf '%q' "$PWD") && $(printf '%q' "$batch") run $args -o $(printf '%q' "$out")"
run+=' --shard ${SLURM_ARRAY_TASK_ID}/'"$shards"' -j ${SLURM_CPUS_PER_TASK:-1} -q'
# shellcheck disable=SC2086  # SBATCH_ARGS is a list of options
array=$(sbatch --parsable ${SBATCH_ARGS:-} --job-name=visco2d-sweep --array=0-$((shards - 1)) \
  --output="$out/slurm/shard-%a.log" --wrap="$run")
array=${array%%;*}
collect="$(printf '%q' "$batch") collect $(printf '%q' "$out")"
# shellcheck disable=SC2086
final=$(sbatch --parsable --job-name=visco2d-collect --dependency=afterany:"$array" \
  --output="$out/slurm/collect.log" --wrap="$collect")
echo "slurm_sweep.sh: array job $array ($shards tasks), then job ${final%%;*} collects $out/table.csv"
