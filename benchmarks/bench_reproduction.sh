#!/bin/bash
# Reproduction timing the way a user meets it: a fresh clone of the committed HEAD, an empty numba
# cache, `snakemake -j2`, then a no-op re-run; RUNS times (default 2). Prints one line per run and the
# medians. Do not run anything else on the machine meanwhile. Usage: [REV=commit] benchmarks/bench_reproduction.sh [RUNS]
set -u
repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
runs=${1:-2}
full=(); noop=()
for i in $(seq 1 "$runs"); do
  d=$(mktemp -d)/vcor
  git clone -q "$repo" "$d"
  git -C "$d" checkout -q "${REV:-HEAD}"
  export NUMBA_CACHE_DIR=$(mktemp -d)
  export PYTHONPATH="$d/src"  # the clone's own package, not the editable install's
  s=$(date +%s.%N); (cd "$d" && python -m snakemake -j2 > "$d.log" 2>&1); rc=$?; e=$(date +%s.%N)
  s2=$(date +%s.%N); (cd "$d" && python -m snakemake -j2 > "$d.noop.log" 2>&1); e2=$(date +%s.%N)
  f=$(echo "$e - $s" | bc); n=$(echo "$e2 - $s2" | bc)
  full+=("$f"); noop+=("$n")
  printf "run %d: exit %d, full reproduction %.1f s wall, no-op re-run %.1f s, %d jobs (log %s)\n" \
    "$i" "$rc" "$f" "$n" "$(grep -c 'Finished jobid' "$d.log")" "$d.log"
done
median() { printf "%s\n" "$@" | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
printf "median of %d runs: full %.1f s, no-op %.1f s\n" "$runs" "$(median "${full[@]}")" "$(median "${noop[@]}")"
