#!/usr/bin/env bash
# Times the issue-11 target: `msislab simulate scenarios/stpere_replica.yaml` at least 300x real
# time on a 2-core machine. Simulates the replica N times (default 3) into a temporary directory
# with T threads (default: the cores) and prints each run's rendering speed as msislab reports it
# (simulated seconds over rendering seconds), the whole command's wall time, and the median's
# ratio to the target. Timings are figures, not pass/fail.
# Usage: tools/bench_simulate.sh [--repeat N] [--threads T]   (after a release build)
set -euo pipefail
cd "$(dirname "$0")/.."

repeat=3
threads=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    -h|--help) sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/bench_simulate.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

msislab=build/release/tools/msislab
[ -x "$msislab" ] || { echo "tools/bench_simulate.sh: build first (cmake --preset release && cmake --build --preset release)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
speeds=()
for i in $(seq "$repeat"); do
  start=$(date +%s.%N)
  line=$("$msislab" simulate scenarios/stpere_replica.yaml --out "$out/sim" --threads "$threads" | tail -n 1)
  end=$(date +%s.%N)
  speed=$(sed -n 's/.*(\([0-9.]*\)x real time).*/\1/p' <<<"$line")
  duration=$(sed -n 's/.* over \([0-9.]*\) s;.*/\1/p' <<<"$line")
  speeds+=("$speed")
  awk -v s="$start" -v e="$end" -v x="$speed" -v d="$duration" -v i="$i" 'BEGIN {
    printf "run %d: rendering %.0fx real time; whole command %.1f s wall = %.0fx real time\n",
      i, x, e - s, d / (e - s) }'
done
printf '%s\n' "${speeds[@]}" | sort -g | awk -v t="$threads" -v c="$(nproc)" '
  { v[NR] = $1 } END {
    m = v[int((NR + 1) / 2)]
    printf "median rendering speed %.0fx real time with %d threads on %d cores: %.1f x the 300x target\n", m, t, c, m / 300 }'
