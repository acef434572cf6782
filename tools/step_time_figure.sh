#!/usr/bin/env bash
# Step time against state size for every SLAM back end, up to a long mission's 2,000 scans:
# runs msislab_slam_bench's rows (the synthetic basin loop; robocentric and world-centric filters
# with the default config, compass on, 25..2,000 scans; the pose graph over the whole graph,
# 100..2,000 scans, and with an online window of 100 scans, 100..2,000), writes their CPU time per
# step to DIR/step_time.csv (`backend,scans,ms_per_step`; the bench's own CSVs beside it) and draws
# DIR/step_time.png with msislab_step_time_plot. Timings are figures, not pass/fail; the machine's
# other load shows in them. docs/pose_graph.md, "Long missions", quotes the output.
#
# How long: about 40 minutes on 2 shared cores (the filters 26, setting up their 2,000-scan states
# most of it; the pose graph 14, its whole graph's 2,000-scan row 9 of them); the bench's peak
# memory about 450 MB (a 6,000 x 6,000 covariance is 288 MB).
#
# Usage: tools/step_time_figure.sh [--out DIR] [--build DIR] [--redraw]
#   --out DIR    default docs/long_mission. A new directory is created; an existing one is written
#                into only when this script made it (its marker file .step_time_figure), and then
#                only its own files are replaced; any other existing DIR is refused (exit 2).
#   --build DIR  the CMake build directory (default build/release; needs msislab_slam_bench and
#                msislab_step_time_plot)
#   --redraw     no bench: step_time.csv and the figure again from DIR's bench_*.csv
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
out="$root/docs/long_mission"
build="$root/build/release"
redraw=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) out="$2"; shift 2 ;;
    --build) build="$2"; shift 2 ;;
    --redraw) redraw=1; shift ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    *) echo "step_time_figure.sh: unknown argument '$1' (--help)" >&2; exit 2 ;;
  esac
done
bench="$build/bench/msislab_slam_bench"
plotter="$build/tools/msislab_step_time_plot"
for f in "$bench" "$plotter"; do
  [[ -x "$f" ]] || { echo "step_time_figure.sh: $f is missing (build it first)" >&2; exit 2; }
done

marker="$out/.step_time_figure"
if [[ -e "$out" && ! -e "$marker" ]]; then
  echo "step_time_figure.sh: $out exists and was not made by this script; refusing" >&2
  exit 2
fi
mkdir -p "$out"
echo "made by tools/step_time_figure.sh; it replaces only its own files here" >"$marker"

run_bench() {  # $1 file, $2 filter, further arguments to the bench
  local file="$1" filter="$2"
  shift 2
  if [[ $redraw -eq 1 ]]; then
    [[ -e "$file" ]] || { echo "step_time_figure.sh: --redraw: $file is missing" >&2; exit 2; }
    return 0
  fi
  echo "== $filter" >&2
  "$bench" --benchmark_filter="$filter" --benchmark_format=csv "$@" >"$file.part" 2>/dev/null
  mv -f -- "$file.part" "$file"
}
# The filters: the default config (compass on, the loop's window updated). Up to 400 scans the
# bench repeats its 10 timed steps for 0.5 s; the long rows once (each repetition rebuilds the
# state).
run_bench "$out/bench_filters.csv" 'BM_Step<.*>/scans:(25|50|100|200|400)/compass:1/whole:0$'
run_bench "$out/bench_filters_long.csv" 'BM_Step<.*>/scans:(1000|2000)/compass:1/whole:0$' \
  --benchmark_min_time=0.001
# The pose graph: every row runs once (Iterations(1) in the bench, which names it
# .../iterations:1).
run_bench "$out/bench_posegraph.csv" 'PoseGraphStep/scans:[0-9]+/solve_every:1/window:(0|100)/'

# name,iterations,real_time,cpu_time,time_unit,...: CPU ms per step (each row times 10 steps).
{
  echo "backend,scans,ms_per_step"
  cat "$out/bench_filters.csv" "$out/bench_filters_long.csv" "$out/bench_posegraph.csv" |
    awk -F, '
      /^"BM_Step<RoboCentricSlam>/ { b = "robocentric" }
      /^"BM_Step<WorldCentricSlam>/ { b = "worldcentric" }
      /^"BM_PoseGraphStep.*window:0[/"]/ { b = "posegraph whole" }
      /^"BM_PoseGraphStep.*window:100[/"]/ { b = "posegraph window 100" }
      /^"BM_/ {
        match($1, /scans:[0-9]+/); n = substr($1, RSTART + 6, RLENGTH - 6)
        ms = $4; if ($5 == "\"us\"" || $5 == "us") ms /= 1000; if ($5 == "ns") ms /= 1e6
        printf "%s,%d,%.3f\n", b, n, ms / 10
      }'
} >"$out/step_time.csv.part"
mv -f -- "$out/step_time.csv.part" "$out/step_time.csv"

rm -f -- "$out/step_time.png.part"
"$plotter" --csv "$out/step_time.csv" --out "$out/step_time.png.part"
mv -f -- "$out/step_time.png.part" "$out/step_time.png"
column -s, -t "$out/step_time.csv"
echo "wrote $out/step_time.csv and $out/step_time.png"
