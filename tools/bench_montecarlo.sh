# Times the Monte Carlo target: 50 runs of scenarios/stpere_replica.yaml with robocentric,
# worldcentric and deadreckoning, 2 jobs, in at most 100 s wall on a 2-core machine (243 s when
# the target was set). Runs into a fresh temporary directory (nothing resumed) and prints the wall
# time, its ratio to the target, and with --reference the same sweep by another msislab build
# (an older one, the file path: measured in the same run, so both see the same machine), the
# speed-up, and whether the two summaries agree (the runtime_s lines apart). Timings are figures,
# not pass/fail.
# Usage: tools/bench_montecarlo.sh [--runs N] [--methods a,b] [--jobs J] [--reference MSISLAB]
set -euo pipefail
cd "$(dirname "$0")/.."

runs=50
methods=robocentric,worldcentric,deadreckoning
jobs=$(nproc)
reference=""
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --methods) methods="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --reference) reference="$2"; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/bench_montecarlo.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

msislab=build/release/tools/msislab
[ -x "$msislab" ] || { echo "tools/bench_montecarlo.sh: build first (cmake --preset release && cmake --build --preset release)" >&2; exit 2; }
[ -z "$reference" ] || [ -x "$reference" ] || { echo "tools/bench_montecarlo.sh: --reference $reference is not an executable" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Wall seconds of one sweep by the given executable into the given directory.
sweep() {
  local start end
  start=$(date +%s.%N)
  "$1" montecarlo scenarios/stpere_replica.yaml --runs "$runs" --methods "$methods" \
    --jobs "$jobs" --no-plot --out "$2" </dev/null >/dev/null 2>"$2.err" \
    || { echo "tools/bench_montecarlo.sh: $1 failed:" >&2; tail -3 "$2.err" >&2; exit 1; }
  end=$(date +%s.%N)
  awk -v s="$start" -v e="$end" 'BEGIN { printf "%.1f", e - s }'
}

t=$(sweep "$msislab" "$out/mc")
awk -v t="$t" -v n="$runs" -v m="$methods" -v j="$jobs" -v c="$(nproc)" 'BEGIN {
  printf "montecarlo stpere_replica: %d runs x (%s), %d jobs on %d cores: %.1f s wall\n", n, m, j, c, t
  printf "target for 50 runs: 100 s; scaled to 50 runs: %.0f s, %.2f of the target\n", t * 50 / n, t * 50 / n / 100
}'
if [ -n "$reference" ]; then
  r=$(sweep "$reference" "$out/reference")
  awk -v t="$t" -v r="$r" -v ref="$reference" 'BEGIN {
    printf "reference (%s): %.1f s wall; speed-up %.2fx (target 2.4x)\n", ref, r, r / t
  }'
  if diff <(grep -v '"runtime_s"\|mean_error_quantiles_m' "$out/mc/summary.json") \
          <(grep -v '"runtime_s"\|mean_error_quantiles_m' "$out/reference/summary.json") >/dev/null &&
     cmp -s "$out/mc/nees.csv" "$out/reference/nees.csv"; then
    echo "summary.json and nees.csv: the same numbers as the reference (runtime_s and the new quantiles aside)"
  else
    echo "summary.json or nees.csv DIFFER from the reference:"
    diff <(grep -v '"runtime_s"' "$out/reference/summary.json") <(grep -v '"runtime_s"' "$out/mc/summary.json") | head -20 || true
  fi
fi
