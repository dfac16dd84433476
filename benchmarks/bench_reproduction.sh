#!/bin/bash
# The full reproduction the way a user meets it: per run a fresh clone of the commit (REV, default the
# committed HEAD), its own src on PYTHONPATH, an empty numba cache, `snakemake -j2`, then a no-op
# re-run; RUNS times (default 2). Prints (or writes with --out, atomically) a table of the runs and
# the medians; the number of jobs comes from the log. Nothing else should run on the machine meanwhile.
# --rules-out PATH: also the time by rule (jobs, start-up, work; benchmarks/bench_rules.py over the runs).
# --quick: the same steps on a one-scene config of three SLS impacts (--configfile), to check that it runs.
# Usage: [REV=commit] bash benchmarks/bench_reproduction.sh [--runs N] [--quick] [--out PATH] [--rules-out PATH]
set -u
here=$(cd "$(dirname "$0")" && pwd)
repo=$(git -C "$here" rev-parse --show-toplevel)
runs=2; out=(); quick=0; rules_out=(); projects=(); tmps=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs=$2; shift 2 ;;
    --out) out=(--out "$2"); shift 2 ;;
    --quick) quick=1; shift ;;
    --rules-out) rules_out=(--out "$2"); shift 2 ;;
    -h|--help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "unknown argument $1 (usage: [REV=commit] $0 [--runs N] [--quick] [--out PATH])" >&2; exit 2 ;;
  esac
done
if ! [ "$runs" -ge 2 ] 2>/dev/null; then echo "--runs: at least two runs" >&2; exit 2; fi
rev=$(git -C "$repo" rev-parse --short "${REV:-HEAD}") || exit 2
config=()
if [ "$quick" = 1 ]; then
  config=(--configfile quick.yaml)
fi
rows=$(printf 'run\texit\tfull reproduction [s]\tno-op re-run [s]\tjobs')
full=(); noop=()
for i in $(seq 1 "$runs"); do
  tmp=$(mktemp -d); d=$tmp/vcor
  git clone -q "$repo" "$d" && git -C "$d" checkout -q "$rev" || exit 1
  if [ "$quick" = 1 ]; then
    printf 'shard_size: 100\nmaterial_dir: results/materials\nscenes:\n  quick:\n    materials: [sls]\n    grid: {v0: [1, 5, 10]}\n' > "$d/quick.yaml"
  fi
  cache=$(mktemp -d)
  s=$(date +%s.%N)
  (cd "$d" && NUMBA_CACHE_DIR=$cache PYTHONPATH="$d/src" python -m snakemake -j2 "${config[@]}" > "$tmp/run.log" 2>&1)
  rc=$?; e=$(date +%s.%N)
  (cd "$d" && NUMBA_CACHE_DIR=$cache PYTHONPATH="$d/src" python -m snakemake -j2 "${config[@]}" > "$tmp/noop.log" 2>&1)
  e2=$(date +%s.%N)
  f=$(echo "$e - $s" | bc); n=$(echo "$e2 - $e" | bc); jobs=$(grep -c 'Finished jobid' "$tmp/run.log")
  full+=("$f"); noop+=("$n")
  rows+=$(printf '\n%d\t%d\t%.1f\t%.1f\t%d' "$i" "$rc" "$f" "$n" "$jobs")
  rm -rf "$cache"
  if [ "$rc" = 0 ]; then projects+=("$d"); tmps+=("$tmp"); kept=""; else kept=" (logs kept in $tmp)"; fi
  echo "run $i: exit $rc, full reproduction $f s, no-op re-run $n s, $jobs jobs$kept" >&2
done
median() { printf "%s\n" "$@" | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
rows+=$(printf '\nmedian\t\t%.1f\t%.1f\t' "$(median "${full[@]}")" "$(median "${noop[@]}")")
what="Per run: a fresh clone of $rev, its own src on PYTHONPATH, an empty numba cache, \`snakemake -j2\`"
[ "$quick" = 1 ] && what+=" on a one-scene config of three SLS impacts (--quick)"
what+=", then a no-op re-run; wall times measured around each; jobs: those of the full run, from its log."
cmd="bash benchmarks/bench_reproduction.sh --runs $runs$([ "$quick" = 1 ] && echo ' --quick')"
printf '%s\n' "$rows" | python "$here/timing.py" markdown --command "$cmd" --runs "$runs" --commit "$rev" \
  --note "$what" "${out[@]}"
if [ "${#projects[@]}" -gt 0 ]; then
  python "$here/bench_rules.py" "${projects[@]}" --command "$cmd" --commit "$rev" "${rules_out[@]}"
fi
rm -rf "${tmps[@]}"
