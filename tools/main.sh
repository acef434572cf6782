#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the pipeline end to end on the real
# St. Pere dataset (dead reckoning and the plain velocity-integration reference), scored against GPS.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install_deps.sh
cmake --preset release
cmake --build --preset release

stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
if [ ! -f "$stpere/_040825_1735_DVL.log" ]; then
  echo "main: the real St. Pere dataset is not at $stpere."
  echo "main: it needs *_DVL.log, *_MTi.log and *_DGPS.log there (or set MSISLAB_STPERE_DIR)."
  echo "main: the build is done; 'tools/test.sh' runs the tests without it."
  exit 0
fi

msislab=build/release/tools/msislab
for method in deadreckoning integration; do
  "$msislab" run "$stpere" --method "$method" --out "out/stpere_$method" --config config/stpere.yaml
done
echo
echo "Results (mean position error against GPS; the paper's Table I uses the same measure):"
for method in deadreckoning integration; do
  printf '  %-14s ' "$method"
  grep -E '"(mean_error_m|final_error_m|max_error_m)"' "out/stpere_$method/metrics.json" | tr -d '\n ,'
  echo
done
echo "Trajectories and metrics are in out/stpere_deadreckoning/ and out/stpere_integration/."
