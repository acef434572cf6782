#!/usr/bin/env bash
# The tables of docs/trajectory_slam.md, "Where the real canal is lost". On the real St. Pere run
# (config/stpere.yaml), with the published calibration and with the calibration every sensor agrees
# on (config/stpere_sensor_agreed_calibration.yaml): dead reckoning and robocentric SLAM, then,
# under the sensor-agreed calibration, robocentric SLAM with one thing changed at a time; then
# tools/match_direction_check.py on every robocentric run (on the published one also for matches
# that skip one and two scans). Then the simulated analogue: the replica
# (seed 42, config/stpere_replica.yaml) with that deviation and the 3.9 deg in its MRU
# (mru.deviation_*, mru.mount.yaw_offset_deg 89.9), read with a calibration.yaml stating neither,
# the deviation only, or both (stated_calibration); last, the shipped replica's and the straight
# channel's matches with the reciprocal association and one-way, the replica's that skip scans,
# and the channel's read with its ranges 5 % long. Prints
# Markdown tables (mean error; loop and canal) and the direction check's lines. Writes its results
# under out/canal_check/. The real rows need the dataset (MSISLAB_STPERE_DIR, default
# ../shared/datasets/stpere): without it they are left out, said.
# Usage: tools/canal_check.sh [--msislab EXE]
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/canal_check
source tools/run_fresh.sh
msislab=build/release/tools/msislab
parse_table_options tools/canal_check.sh single "$@"
claim_out_folder tools/canal_check.sh "$out"
agreed=config/stpere_sensor_agreed_calibration.yaml

# A Markdown row per run: NAME METRICS_JSON.
table() {
  python3 - "$@" <<'EOF'
import json, sys
print("| run | mean error | loop | canal |")
print("| --- | ---: | ---: | ---: |")
args = sys.argv[1:]
for name, path in zip(args[::2], args[1::2]):
    m = json.load(open(path))
    seg = m["segments"]
    print(f"| {name} | {m['mean_error_m']:.2f} m | {seg['loop']:.2f} m | {seg['canal']:.2f} m |")
EOF
}

# The SLAM config with one variant's keys: CONFIG NAME.
variant() {
  cat "$1"
  case $2 in
    default) ;;
    range_scale | dvl_scale) printf 'trajectory_slam:\n  calibration:\n    %s: true\n' "$2" ;;
    one_way) printf 'trajectory_slam:\n  matching:\n    reciprocal_association: false\n' ;;
    point_to_line)
      printf 'trajectory_slam:\n  matching:\n    point_to_line_covariance: true\n'
      printf '    point_to_line_estimate: true\n'
      ;;
    one_match) printf 'trajectory_slam:\n  max_matches_per_scan: 1\n' ;;
  esac
}

stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
if [ -f "$stpere/_040825_1735_DVL.log" ]; then
  rows=()
  for calibration in published agreed; do
    cal_args=()
    [ $calibration = agreed ] && cal_args=(--calibration "$agreed")
    variants=(default)
    [ $calibration = agreed ] && variants=(default range_scale dvl_scale one_way point_to_line one_match)
    "$msislab" run "$stpere" --method deadreckoning --out "$out/real/$calibration/deadreckoning" \
      --config config/stpere.yaml "${cal_args[@]}" >/dev/null
    rows+=("$calibration calibration, dead reckoning" "$out/real/$calibration/deadreckoning/metrics.json")
    for v in "${variants[@]}"; do
      variant config/stpere.yaml "$v" >"$out/real.$v.yaml"
      "$msislab" run "$stpere" --method robocentric --out "$out/real/$calibration/robocentric.$v" \
        --config "$out/real.$v.yaml" "${cal_args[@]}" >/dev/null
      label="$calibration calibration, robocentric"
      [ "$v" = default ] || label="$label, $v"
      rows+=("${label//_/ }" "$out/real/$calibration/robocentric.$v/metrics.json")
    done
  done
  echo "Real St. Pere (config/stpere.yaml):"
  table "${rows[@]}"
  echo
  for run in "$out"/real/published/robocentric.default "$out"/real/agreed/robocentric.*; do
    python3 tools/match_direction_check.py "$run"
  done
  for gap in 2 3; do
    python3 tools/match_direction_check.py "$out/real/published/robocentric.default" --gap $gap
  done
else
  echo "tools/canal_check.sh: no real St. Pere dataset at $stpere: its rows are left out" >&2
fi

# The simulated analogue: the replica's MRU with the deviation and the constant, stated or not.
rows=()
for stated in none deviation both; do
  case $stated in
    none) stated_keys=(stated_calibration.mru.yaw_offset_deg=86
                       stated_calibration.mru.deviation_cos_deg=0
                       stated_calibration.mru.deviation_sin_deg=0) ;;
    deviation) stated_keys=(stated_calibration.mru.yaw_offset_deg=86) ;;
    both) stated_keys=() ;;
  esac
  tools/scenario_variant.py scenarios/stpere_replica.yaml "$out/replica.$stated.scenario.yaml" \
    tools/canal_check.sh mru.mount.yaw_offset_deg=89.9 mru.deviation_cos_deg=0.62 \
    mru.deviation_sin_deg=-3.39 "${stated_keys[@]}"
  dataset="$out/sim/replica.$stated"
  "$msislab" simulate "$out/replica.$stated.scenario.yaml" --out "$dataset" >/dev/null
  for method in deadreckoning robocentric; do
    "$msislab" run "$dataset" --method $method --out "$out/replica/$stated/$method" \
      --config config/stpere_replica.yaml >/dev/null
    rows+=("replica, calibration.yaml stating $stated, $method" "$out/replica/$stated/$method/metrics.json")
  done
done
echo
echo "The replica, seed 42, its MRU with the deviation (0.62, -3.39) deg and 3.9 deg in its mount:"
table "${rows[@]}"
echo
python3 tools/match_direction_check.py "$out/replica/both/robocentric"

# How much the association sets the along-axis solution: the shipped replica and the straight
# channel, each with the reciprocal association (the default) and one-way.
"$msislab" simulate scenarios/stpere_replica.yaml --out "$out/sim/replica" >/dev/null
tools/scenario_variant.py scenarios/straight_channel.yaml "$out/straight_channel.scenario.yaml" \
  tools/canal_check.sh
"$msislab" simulate "$out/straight_channel.scenario.yaml" --out "$out/sim/straight_channel" >/dev/null
for dataset in replica straight_channel; do
  config=/dev/null  # the defaults
  [ $dataset = replica ] && config=config/stpere_replica.yaml
  for v in default one_way; do
    variant $config $v >"$out/$dataset.$v.yaml"
    "$msislab" run "$out/sim/$dataset" --method robocentric --out "$out/$dataset/$v" \
      --config "$out/$dataset.$v.yaml" >/dev/null
    python3 tools/match_direction_check.py "$out/$dataset/$v"
  done
done
for gap in 2 3; do
  python3 tools/match_direction_check.py "$out/replica/default" --gap $gap
done
# The straight channel read with its ranges 5 % long (calibration.yaml's range_scale 1 / 1.05).
sed 's/^\(  range_scale:\).*/\1 0.95238095238095233/' "$out/sim/straight_channel/calibration.yaml" \
  >"$out/straight_channel.ranges_long.calibration.yaml"
"$msislab" run "$out/sim/straight_channel" --method robocentric \
  --out "$out/straight_channel/ranges_long" \
  --calibration "$out/straight_channel.ranges_long.calibration.yaml" >/dev/null
python3 tools/match_direction_check.py "$out/straight_channel/ranges_long"
