#!/usr/bin/env bash
# The main job: installs what is missing, builds, then
#  1. simulates the default scenario (scenarios/stpere_replica.yaml) and runs robocentric and
#     world-centric trajectory SLAM, dead reckoning and the plain-integration reference on it,
#     scored against the exact simulation truth;
#  2. runs them on the real St. Pere dataset (when ../shared/datasets/stpere is there), scored
#     against GPS;
#  3. draws an acoustic image of one simulated revolution, and the figures of every result
#     (msislab plot; VTK needs an X display, and without one it reruns itself under xvfb-run).
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install_deps.sh
cmake --preset release
cmake --build --preset release

msislab=build/release/tools/msislab
methods=(robocentric worldcentric deadreckoning integration)

summary() {  # summary DIR...: one line per result directory
  for dir in "$@"; do
    awk -v dir="$dir" -F': ' '
      /"truth"/ { gsub(/[",]/, "", $2); truth = $2 }
      /"mean_error_m"/ { mean = $2 + 0 }
      /"final_error_m"/ { final = $2 + 0 }
      /"max_error_m"/ { max = $2 + 0 }
      END { printf "  %-26s against %-10s mean %6.2f m   final %6.2f m   max %6.2f m\n",
                   dir, truth, mean, final, max }' "$dir/metrics.json"
  done
}

echo "== Simulating scenarios/stpere_replica.yaml"
"$msislab" simulate scenarios/stpere_replica.yaml --out out/sim/stpere_replica
for m in "${methods[@]}"; do
  "$msislab" run out/sim/stpere_replica --method "$m" --out "out/sim/$m" \
    --config config/stpere_replica.yaml
done
"$msislab" image out/sim/stpere_replica --revolution 60 --out out/sim/acoustic_image.png

stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
real=()
if [ -f "$stpere/_040825_1735_DVL.log" ]; then
  echo "== The real St. Pere dataset ($stpere)"
  for m in "${methods[@]}"; do
    "$msislab" run "$stpere" --method "$m" --out "out/stpere/$m" --config config/stpere.yaml
    real+=("out/stpere/$m")
  done
else
  echo "== The real St. Pere dataset is not at $stpere: skipped."
  echo "   It needs *_DVL.log, *_MTi.log and *_DGPS.log there (or set MSISLAB_STPERE_DIR)."
fi

echo "== Figures"
"$msislab" plot out/sim
if [ ${#real[@]} -gt 0 ]; then "$msislab" plot out/stpere; fi

echo
echo "Results (mean, final and max position error; the paper's Table I uses the mean):"
summary "${methods[@]/#/out/sim/}" ${real[@]+"${real[@]}"}
echo "Trajectories and metrics: out/sim/<method>/ and out/stpere/<method>/;"
echo "the simulated dataset: out/sim/stpere_replica/; acoustic image: out/sim/acoustic_image.png;"
echo "figures: out/sim/figures/ and out/stpere/figures/ (and figures/ in every result folder)."
