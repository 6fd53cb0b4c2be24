#!/usr/bin/env bash
# locbench with GNU parallel: N shards as N jobs, then one merge — on this machine, or on several
# with parallel's --sshlogin (every machine needs the same locbench build and a shared folder).
#
#   docs/gnu_parallel.sh                                    # 4 shards of the default suite
#   N=16 EXPERIMENTS=noise RUNS=200 OUT=merged docs/gnu_parallel.sh
#
# What it runs (the documented recipe):
#   parallel --halt now,fail=1 locbench run EXPERIMENTS --shard {}/N --threads T \
#            --out shards/{} ::: $(seq 1 N)
#   locbench merge shards -o merged
# and, across machines: parallel -S host1,host2 --workdir "$PWD" … (same command).
#
# Settings (environment): LOCBENCH (default `locbench` on PATH), EXPERIMENTS (default: the
# default suite), N (shards, default 4), THREADS (per shard, default 1), SEED (default 1), RUNS,
# SHARD_DIR (default shards), OUT (merged reports, default merged), SSHLOGIN (parallel -S list).
# Without GNU parallel (or with LOCBENCH_NO_PARALLEL=1) it falls back to xargs -P on this machine.
set -euo pipefail

LOCBENCH=${LOCBENCH:-locbench}
N=${N:-4}
SHARD_DIR=${SHARD_DIR:-shards}
OUT=${OUT:-merged}
common=(--seed "${SEED:-1}" --threads "${THREADS:-1}")
[ -n "${RUNS:-}" ] && common+=(--runs "$RUNS")
# shellcheck disable=SC2206  # EXPERIMENTS is a space-separated list of names
experiments=(${EXPERIMENTS:-})

if command -v parallel >/dev/null 2>&1 && [ -z "${LOCBENCH_NO_PARALLEL:-}" ]; then
  remote=()
  [ -n "${SSHLOGIN:-}" ] && remote=(-S "$SSHLOGIN" --workdir "$PWD")
  parallel "${remote[@]}" --halt now,fail=1 \
    "$LOCBENCH" run "${experiments[@]}" "${common[@]}" --shard "{}/$N" --out "$SHARD_DIR/{}" \
    ::: $(seq 1 "$N")
else
  echo "gnu_parallel.sh: GNU parallel not used; running the shards with xargs -P $N" >&2
  seq 1 "$N" | xargs -P "$N" -I{} \
    "$LOCBENCH" run "${experiments[@]}" "${common[@]}" --shard "{}/$N" --out "$SHARD_DIR/{}"
fi
"$LOCBENCH" merge "$SHARD_DIR" -o "$OUT"
