#!/usr/bin/env bash
# Times the issue-6 target: 50 Monte Carlo runs of scenarios/stpere_replica.yaml with both SLAM
# methods in under 15 minutes on a 2-core machine. Runs into a fresh temporary directory (nothing
# resumed), prints the wall time and its ratio to the target. Timings are figures, not pass/fail.
# Usage: tools/bench_montecarlo.sh [--runs N] [--methods a,b] [--jobs J]   (after a release build)
set -euo pipefail
cd "$(dirname "$0")/.."

runs=50
methods=robocentric,worldcentric
jobs=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --methods) methods="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    -h|--help) sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/bench_montecarlo.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

msislab=build/release/tools/msislab
[ -x "$msislab" ] || { echo "tools/bench_montecarlo.sh: build first (cmake --preset release && cmake --build --preset release)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
start=$(date +%s.%N)
"$msislab" montecarlo scenarios/stpere_replica.yaml --runs "$runs" --methods "$methods" \
  --jobs "$jobs" --out "$out/mc" </dev/null
end=$(date +%s.%N)
awk -v s="$start" -v e="$end" -v n="$runs" -v m="$methods" -v j="$jobs" -v c="$(nproc)" 'BEGIN {
  t = e - s
  printf "montecarlo stpere_replica: %d runs x (%s), %d jobs on %d cores: %.0f s wall (%.1f min)\n", n, m, j, c, t, t / 60
  printf "target for 50 runs: 900 s; scaled to 50 runs: %.0f s, %.2f of the target\n", t * 50 / n, t * 50 / n / 900
}'
