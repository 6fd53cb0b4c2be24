#!/usr/bin/env bash
# locbench on a Slurm cluster: one array task per shard, then one merge.
#
#   sbatch --array=1-8 docs/slurm_array.sh                        # 8 shards of the default suite
#   EXPERIMENTS=odometry/sim_corridor RUNS=1000 sbatch --array=1-8 docs/slurm_array.sh
#   sbatch --dependency=afterok:<array job id> --wrap 'locbench merge shards -o merged'
#   locbench report merged -o report.html
#
# Array task K of N runs `locbench run … --shard K/N` (the Monte-Carlo runs i with
# i mod N = K − 1; an experiment without Monte-Carlo runs runs whole in shard 1) on the task's
# CPUs and writes $SHARD_DIR/K/<experiment>.shard-K-of-N.json. `locbench merge` checks that the
# shards belong together (same experiment, seed, runs, configuration, build; none missing or
# twice) and rebuilds reports equal to a single-machine `locbench run` with the same seed and
# runs. Every array task must use the same locbench build (merge refuses mixed git revisions).
#
# Settings (environment): LOCBENCH (the binary, default `locbench` on PATH), EXPERIMENTS (names
# or groups, default the default suite), SEED (default 1), RUNS (default: each experiment's),
# SHARD_DIR (default shards). Slurm sets SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT,
# SLURM_ARRAY_TASK_MIN and SLURM_CPUS_PER_TASK.
#SBATCH --job-name=locbench-shard
#SBATCH --cpus-per-task=4
#SBATCH --output=locbench-shard-%A_%a.log
set -euo pipefail

: "${SLURM_ARRAY_TASK_ID:?run this as a Slurm array job: sbatch --array=1-N docs/slurm_array.sh}"
: "${SLURM_ARRAY_TASK_COUNT:?SLURM_ARRAY_TASK_COUNT is not set}"
LOCBENCH=${LOCBENCH:-locbench}
SHARD_DIR=${SHARD_DIR:-shards}
N=$SLURM_ARRAY_TASK_COUNT
# Arrays may be numbered from 0 (--array=0-7) or 1 (--array=1-8): shard K counts from 1.
K=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-1} + 1))

args=(run)
# shellcheck disable=SC2206  # EXPERIMENTS is a space-separated list of names
[ -n "${EXPERIMENTS:-}" ] && args+=(${EXPERIMENTS})
args+=(--seed "${SEED:-1}" --threads "${SLURM_CPUS_PER_TASK:-1}" --shard "$K/$N"
       --out "$SHARD_DIR/$K")
[ -n "${RUNS:-}" ] && args+=(--runs "$RUNS")
exec "$LOCBENCH" "${args[@]}"
