#!/usr/bin/env bash
# Regenerates the robocentric study (docs/robocentric.md) in one command: builds, then
# runs every sweep of studies/robocentric/ (20 seeded runs per cell of the marina loop, both
# filters on the same simulated data) into out/study/<sweep>, draws each sweep's figures and
# copies those against its main key, with each sweep.csv, into docs/robocentric/. Resumable: an
# interrupted sweep keeps its finished runs when this is run again; one made by another build or
# sweep file is run again from scratch.
# Usage: tools/robocentric_study.sh [--jobs J]     (about 11 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) jobs="$2"; shift 2 ;;
    -h|--help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/robocentric_study.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

tools/install_deps.sh run
tools/configure.sh release
cmake --build --preset release --target msislab
msislab=build/release/tools/msislab
source tools/run_fresh.sh
# Each sweep and the key its figures are drawn against in docs/robocentric.md.
sweeps=(heading_noise dvl_noise revolution_period iekf compass loop_length stress)
declare -A figure_key=(
  [heading_noise]=scenario.mru.heading_noise_deg [dvl_noise]=scenario.dvl.noise_sigma_mps
  [revolution_period]=scenario.sonar.revolution_s [iekf]=scenario.mru.heading_noise_deg
  [compass]=scenario.mru.heading_noise_deg [loop_length]=slam.trajectory_slam.min_scan_gap
  [stress]=scenario.mru.heading_noise_deg)
docs=docs/robocentric
mkdir -p out/study "$docs"
start=$(date +%s)
for name in "${sweeps[@]}"; do
  dir="out/study/$name"
  echo "== sweep $name into $dir"
  # out/study is this script's own: a sweep made by another build or from an earlier version of
  # its sweep file is stale, and starts again.
  run_fresh "$dir" "$msislab" sweep "studies/robocentric/$name.yaml" --out "$dir" --jobs "$jobs" \
    --no-plot
  "$msislab" plot "$dir" >/dev/null
  key="${figure_key[$name]//./_}"
  for metric in mean_error anees paired_difference linearisation; do
    cp "$dir/figures/sweep_${key}_$metric.png" "$docs/${name}_$metric.png"
  done
  cp "$dir/sweep.csv" "$docs/$name.csv"
done
echo "robocentric study: ${#sweeps[@]} sweeps in $(( $(date +%s) - start )) s of sweeping;" \
  "figures and tables in $docs/ (docs/robocentric.md reads them)"
