#!/usr/bin/env bash
# Regenerates docs/results.md and its figures (docs/results/) in one command:
#  1. tools/main.sh: builds, simulates the St. Pere replica, runs every method on it and on the
#     real St. Pere dataset (when present), scores and plots them;
#  2. the Monte Carlo consistency test: N seeded runs (default 50) of scenarios/stpere_replica.yaml
#     with robocentric and world-centric SLAM, the pose graph and dead reckoning (resumable: an
#     interrupted sweep keeps its finished runs when this is run again), and its NEES figure;
#  3. the failure scenarios (straight channel, open area) with the default config: 20 runs of
#     scenarios/straight_channel.yaml and 10 of scenarios/open_area.yaml, the same methods;
#  4. with the real dataset, tools/real_sensitivity.sh: the real run with each parameter moved
#     10 % (out/sensitivity/real.csv);
#  5. msislab report: writes the page from those folders and copies the figures beside it, with
#     the robocentric study's heading-noise and stress sweeps when tools/robocentric_study.sh
#     has filled out/study (docs/robocentric.md);
#  6. tools/claims.sh: the README's figures (docs/claims.yaml) checked against those folders.
# Usage: tools/results.sh [--runs N] [--jobs J]     (about 6 minutes on 2 cores with 50 runs)
set -euo pipefail
cd "$(dirname "$0")/.."

runs=50
jobs=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    -h|--help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/results.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

tools/main.sh
msislab=build/release/tools/msislab

source tools/run_fresh.sh
# montecarlo SCENARIO RUNS DIR [--config FILE]: a resumable sweep with every method and its
# nees.png; one made by an earlier build is stale for this page, so it starts again.
montecarlo() {
  local scenario="$1" n="$2" dir="$3"
  shift 3
  echo "== Monte Carlo: $n runs of $scenario into $dir"
  run_fresh "$dir" "$msislab" montecarlo "$scenario" --runs "$n" --jobs "$jobs" \
    --methods robocentric,worldcentric,posegraph,deadreckoning --out "$dir" "$@"
}
# The replica's config, as the main job's: its sonar read from detections like the real data.
mc="out/montecarlo/stpere_replica_${runs}runs"
montecarlo scenarios/stpere_replica.yaml "$runs" "$mc" --config config/stpere_replica.yaml
# The failure scenarios, with the default config they were made for.
channel=out/montecarlo/straight_channel_20runs
open_area=out/montecarlo/open_area_10runs
montecarlo scenarios/straight_channel.yaml 20 "$channel"
montecarlo scenarios/open_area.yaml 10 "$open_area"

report=(--sim out/sim --montecarlo "$mc" --montecarlo "$channel" --montecarlo "$open_area")
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
if [ -f "$stpere/_040825_1735_DVL.log" ]; then
  report+=(--real out/stpere)
  # How far the real figure can be trusted: every parameter moved 10 % (about 90 s).
  echo "== tools/real_sensitivity.sh into out/sensitivity/real.csv"
  tools/real_sensitivity.sh --csv out/sensitivity/real.csv 2>/dev/null
  report+=(--sensitivity out/sensitivity/real.csv)
fi
for sweep in heading_noise stress; do
  if [ -f "out/study/$sweep/sweep.csv" ]; then
    report+=(--sweep "out/study/$sweep")
  else
    echo "== out/study/$sweep not there: run tools/robocentric_study.sh for the study's section"
  fi
done
"$msislab" report docs/results.md "${report[@]}"
echo "docs/results.md and docs/results/ are up to date; review and commit them."
# The README's figures against these folders (out/fidelity/report: tools/fidelity.sh).
echo "== tools/claims.sh: the README's figures (docs/claims.yaml)"
tools/claims.sh --partial
