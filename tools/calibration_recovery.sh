#!/usr/bin/env bash
# Calibration recovery on simulation (docs/trajectory_slam.md, "Calibration states"): the St. Pere
# replica with a calibration error injected into its sensors, N Monte Carlo runs each (default 20,
# seeds 42..), robocentric SLAM (or --method's) read through the detections with config/stpere_replica.yaml plus
# the state that estimates the error. Cases: the sonar's range scale 0.96 and 1.03 (a water sound
# speed of 1500 / 0.96 and 1500 / 1.03 m/s against the sonar's 1500), the DVL's scale factor 1.01,
# the sonar clock's 0.66 s offset and the compass deviation (a, b) = (0.62, -3.39) deg, each left
# out of the dataset's calibration.yaml (stated_calibration). Prints a Markdown table, a row per
# estimated value: the runs whose
# estimate lies within two of its standard deviations of the injected value, the estimates' range
# and mean, their mean standard deviation, the mean error, ANEES and the steps in bounds of the
# Monte Carlo NEES test. Writes under out/calibration_recovery/.
# --method posegraph (or worldcentric) runs that back end instead, under
# out/calibration_recovery.METHOD/.
# Usage: tools/calibration_recovery.sh [--runs N] [--msislab EXE] [--method METHOD]
set -euo pipefail
cd "$(dirname "$0")/.."
msislab=build/release/tools/msislab
runs=20
method=robocentric
source tools/run_fresh.sh
rest=()
while [ $# -gt 0 ]; do
  case "$1" in
    --method) method="${2:?--method needs robocentric, worldcentric or posegraph}"; shift 2 ;;
    *) rest+=("$1"); shift ;;
  esac
done
case "$method" in
  robocentric | worldcentric | posegraph) ;;
  *) echo "tools/calibration_recovery.sh: --method '$method' is not robocentric, worldcentric" \
       "or posegraph" >&2
     exit 2 ;;
esac
parse_table_options tools/calibration_recovery.sh montecarlo "${rest[@]}"

out=out/calibration_recovery
[ "$method" = robocentric ] || out="$out.$method"
claim_out_folder tools/calibration_recovery.sh "$out"

# CASE  STATE  ESTIMATE=TRUE-VALUE[,...]  SCENARIO-KEY=VALUE[,...] (dotted paths into the scenario)
cases=(
  "range_scale_0.96 range_scale range_scale=0.96 sonar.water_sound_speed_mps=1562.5,stated_calibration.sonar.range_scale=1"
  "range_scale_1.03 range_scale range_scale=1.03 sonar.water_sound_speed_mps=1456.3106796116506,stated_calibration.sonar.range_scale=1"
  "dvl_scale_1.01 dvl_scale dvl_scale=1.01 dvl.scale_factor=1.01,stated_calibration.dvl.scale_factor=1"
  "clock_offset clock_offset clock_offset_s=0.66 stated_calibration.sonar.time_offset_s=0"
  "deviation compass_deviation compass_deviation_cos_deg=0.62,compass_deviation_sin_deg=-3.39 mru.deviation_cos_deg=0.62,mru.deviation_sin_deg=-3.39,stated_calibration.mru.deviation_cos_deg=0,stated_calibration.mru.deviation_sin_deg=0"
)
for c in "${cases[@]}"; do
  read -r name state _ keys <<<"$c"
  # The replica's scenario with the keys set, its relative paths made absolute.
  # shellcheck disable=SC2086  # the keys, one word each
  tools/scenario_variant.py scenarios/stpere_replica.yaml "$out/$name.scenario.yaml" \
    tools/calibration_recovery.sh ${keys//,/ }
  { cat config/stpere_replica.yaml; printf 'trajectory_slam:\n  calibration:\n    %s: true\n' "$state"; } \
    >"$out/$name.config.yaml"
  # A folder made by another build or from another scenario is stale: run_fresh starts it again.
  run_fresh "$out/$name" "$msislab" montecarlo "$out/$name.scenario.yaml" --runs "$runs" \
    --out "$out/$name" --methods "$method" --config "$out/$name.config.yaml" --no-plot >/dev/null
done

python3 - "$out" "$method" "${cases[@]}" <<'EOF'
import glob, json, os, sys
out, method = sys.argv[1], sys.argv[2]
print("| injected | state | estimate | runs within 2 sd | estimates (mean) | sd (mean) | mean error | ANEES | steps in bounds |")
print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
for case in sys.argv[3:]:
    name, state, truths, keys = case.split(" ")
    summary = json.load(open(os.path.join(out, name, "summary.json")))[method]
    runs = [json.load(open(p)).get("diagnostics", {}) for p in sorted(
        glob.glob(os.path.join(out, name, "runs", method, "run_*", "metrics.json")))]
    for item in truths.split(","):
        estimate, truth = item.split("=")
        truth = float(truth)
        values = [d[estimate] for d in runs]
        sigmas = [d[estimate + "_sigma"] for d in runs]
        within = sum(abs(v - truth) < 2 * s for v, s in zip(values, sigmas))
        print(f"| {keys.replace(',', ', ')} | {state} | {estimate} {truth:g} | "
              f"{within} of {len(values)} | "
              f"{min(values):.3f} to {max(values):.3f} ({sum(values) / len(values):.3f}) | "
              f"{sum(sigmas) / len(sigmas):.3f} | {summary['mean_error_m']:.2f} m | "
              f"{summary['anees']:.2f} | {100 * summary['nees_in_bounds_fraction']:.1f} % |")
EOF
