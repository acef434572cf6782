#!/usr/bin/env bash
# The long mission, timed: simulates scenarios/long_survey.yaml (about 5.8 h, 1,504 scans; 35 s,
# 416 MB) into a new temporary directory, runs each method on it with config/long_survey.yaml
# (the pose graph's online window; the filters and dead reckoning read only the defaults in it)
# and prints, per method, the command's wall time, metrics.json's runtime_s, the mean error, the
# ANEES (and the pose graph's smoothed ones), then the pose graph's step time at 200 and 2,000
# scans from the bench (msislab_slam_bench, window 100: the run writes no per-step time).
# Timings are figures, not pass/fail. docs/pose_graph.md, "Long missions", quotes its output.
#
# How long, on 2 shared cores: about 12 minutes. Simulate 30-35 s, posegraph 14 s, deadreckoning
# 2 s; the filters hold a dense covariance of 3 x 1,504 rows and take about 5 minutes each
# (robocentric 291 s, worldcentric 282 s; 410 s beside other jobs); the bench rows about 1 min.
#
# Usage: tools/long_mission.sh [--out DIR] [--methods LIST] [--build DIR] [--no-bench]
#   --out DIR       keep the results in DIR (must not exist; created); default: a new directory
#                   under ${TMPDIR:-/tmp}, printed at the end
#   --methods LIST  comma-separated, default posegraph,deadreckoning,robocentric,worldcentric
#   --build DIR     the CMake build directory (default build/release)
#   --no-bench      skip the bench's step times
# The simulated dataset is removed at the end (this script made it); results are kept.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
out=""
methods="posegraph,deadreckoning,robocentric,worldcentric"
build="$root/build/release"
bench=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --methods) methods="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    --no-bench) bench=0; shift ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "long_mission.sh: unknown argument '$1' (--help)" >&2; exit 2 ;;
  esac
done

msislab="$build/tools/msislab"
slam_bench="$build/bench/msislab_slam_bench"
scenario="$root/scenarios/long_survey.yaml"
config="$root/config/long_survey.yaml"
for f in "$msislab" "$scenario" "$config"; do
  [[ -e "$f" ]] || { echo "long_mission.sh: $f is missing (build first?)" >&2; exit 2; }
done

if [[ -n "$out" ]]; then
  if [[ -e "$out" ]]; then
    echo "long_mission.sh: $out exists; refusing to write into it (give a new path)" >&2
    exit 2
  fi
  mkdir -p "$out"
else
  out=$(mktemp -d "${TMPDIR:-/tmp}/long_mission.XXXXXX")
fi
dataset="$out/dataset"
cleanup() { [[ -d "$dataset" ]] && rm -rf -- "$dataset"; }
trap cleanup EXIT

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

echo "== simulate $scenario"
t0=$(now)
"$msislab" simulate "$scenario" --out "$dataset" | tail -n 1
echo "simulate wall time: $(elapsed "$t0" "$(now)") s"

# One line of metrics.json's figures (plain text parsing: the keys are unique in the file).
metric() {
  sed -n "s/.*\"$2\": *\([-0-9.eE+]*\).*/\1/p" "$1" | head -n 1
}

printf '\n%-14s %9s %10s %12s %8s %14s %8s\n' method wall_s runtime_s mean_err_m anees \
  smoothed_err_m sm_anees | tee "$out/summary.txt"
IFS=',' read -r -a list <<<"$methods"
for m in "${list[@]}"; do
  t0=$(now)
  "$msislab" run "$dataset" --method "$m" --config "$config" --out "$out/$m" >"$out/$m.log" 2>&1 \
    || { echo "$m: failed (see $out/$m.log)" | tee -a "$out/summary.txt"; continue; }
  wall=$(elapsed "$t0" "$(now)")
  j="$out/$m/metrics.json"
  sm_err=$(metric "$j" smoothed_mean_error_m); sm_anees=$(metric "$j" smoothed_anees)
  printf '%-14s %9s %10.1f %12.3f %8.2f %14s %8s\n' "$m" "$wall" "$(metric "$j" runtime_s)" \
    "$(metric "$j" mean_error_m)" "$(metric "$j" anees)" "${sm_err:0:6}" "${sm_anees:0:6}" \
    | tee -a "$out/summary.txt"
done

if [[ $bench -eq 1 && -x "$slam_bench" ]]; then
  echo
  echo "== pose graph step time (bench, window 100, the synthetic loop; CPU ms per step: each row"
  echo "   times 10 steps)"
  "$slam_bench" --benchmark_filter='PoseGraphStep/scans:(200|2000)/solve_every:1/window:100/' \
    --benchmark_format=csv 2>/dev/null | tee "$out/pose_graph_step.csv" \
    | awk -F, '/PoseGraphStep/ { gsub(/"/, "", $1); printf "%-62s %8.1f ms\n", $1, $4 / 10 }'
fi
echo
echo "results: $out (summary.txt; the dataset, made here, is removed)"
