#!/usr/bin/env bash
# Regenerates docs/results.md and its figures (docs/results/) in one command:
#  1. tools/main.sh: builds, simulates the St. Pere replica, runs every method on it and on the
#     real St. Pere dataset (when present), scores and plots them;
#  2. the Monte Carlo consistency test: N seeded runs (default 50) of scenarios/stpere_replica.yaml
#     with robocentric and world-centric SLAM and dead reckoning (resumable: an interrupted sweep
#     keeps its finished runs when this is run again), and its NEES figure;
#  3. msislab report: writes the page from those folders and copies the figures beside it.
# Usage: tools/results.sh [--runs N] [--jobs J]     (about 10 minutes on 2 cores with 50 runs)
set -euo pipefail
cd "$(dirname "$0")/.."

runs=50
jobs=$(nproc)
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/results.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

tools/main.sh
msislab=build/release/tools/msislab

mc="out/montecarlo/stpere_replica_${runs}runs"
echo "== Monte Carlo: $runs runs of scenarios/stpere_replica.yaml into $mc"
montecarlo() {
  # The replica's config, as the main job's: its sonar read from detections like the real data.
  "$msislab" montecarlo scenarios/stpere_replica.yaml --runs "$runs" --jobs "$jobs" \
    --methods robocentric,worldcentric,deadreckoning --config config/stpere_replica.yaml \
    --out "$mc"   # it draws its nees.png
}
# An interrupted sweep resumes; one made by an earlier build is stale for this page: start again.
mkdir -p "$(dirname "$mc")"
if ! montecarlo 2> >(tee "$mc.stderr" >&2); then
  wait $! || true  # the tee: its file is complete before it is read
  if grep -q "made by another msislab build" "$mc.stderr"; then
    echo "== $mc was made by another build: running it again from scratch"
    rm -rf "$mc"
    montecarlo
  else
    exit 2
  fi
fi
rm -f "$mc.stderr"

report=(--sim out/sim --montecarlo "$mc")
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
if [ -f "$stpere/_040825_1735_DVL.log" ]; then report+=(--real out/stpere); fi
"$msislab" report docs/results.md "${report[@]}"
echo "docs/results.md and docs/results/ are up to date; review and commit them."
