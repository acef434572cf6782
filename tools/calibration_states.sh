#!/usr/bin/env bash
# The table of docs/trajectory_slam.md, "Calibration states": robocentric and world-centric SLAM
# with every calibration state off (the default config) and with each on alone
# (trajectory_slam.calibration.range_scale, dvl_scale, compass_deviation, heading_bias), on the
# replica (seed 42,
# read through its detections with config/stpere_replica.yaml) and on the real St. Pere run
# (config/stpere.yaml; skipped, said, when the dataset is not there). Prints a Markdown table: mean
# error; on simulation the ANEES and the share of scan steps whose NEES lies inside one run's 95 %
# bounds (3 DOF: 0.216-9.348), on the real run the loop's and the canal's mean error; the
# estimates with their standard deviations; the consecutive matches' scale against the truth; the
# run time. Then the clock-offset state on each dataset read with calibration.yaml stating no sonar
# clock offset (the true one is 0.66 s on both); then the sensor-only fits of the deviation and
# the clock offset (tools/compass_deviation_fit.py, tools/clock_offset_fit.py). Writes its results under
# out/calibration_states/.
# Usage: tools/calibration_states.sh [--msislab EXE]
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/calibration_states
source tools/run_fresh.sh
msislab=build/release/tools/msislab
parse_table_options tools/calibration_states.sh single "$@"
claim_out_folder tools/calibration_states.sh "$out"
replica="$out/sim/stpere_replica"
"$msislab" simulate scenarios/stpere_replica.yaml --out "$replica" >/dev/null

# The config with a state on: the given one plus the switch.
with_state() {  # CONFIG STATE
  cat "$1"
  if grep -q '^trajectory_slam:' "$1"; then
    echo "tools/calibration_states.sh: $1 has a trajectory_slam: section; merge by hand" >&2
    exit 2
  fi
  printf 'trajectory_slam:\n  calibration:\n    %s: true\n' "$2"
  # The heading bias's model is the dead reckoning's: the simulated MRU's walk (its default).
  if [ "$2" = heading_bias ]; then
    if grep -q '^dead_reckoning:' "$1"; then
      echo "tools/calibration_states.sh: $1 has a dead_reckoning: section; merge by hand" >&2
      exit 2
    fi
    printf 'dead_reckoning:\n  heading_bias_walk_deg_per_sqrt_s: 0.01\n'
  fi
}

rows=()
run_dataset() {  # NAME DATASET CONFIG
  local name=$1 dataset=$2 config=$3
  for state in off range_scale dvl_scale compass_deviation heading_bias; do
    local cfg=$config
    if [ $state != off ]; then
      cfg="$out/$name.$state.yaml"
      with_state "$config" $state >"$cfg"
    fi
    for method in robocentric worldcentric; do
      "$msislab" run "$dataset" --method "$method" --out "$out/$name/$state/$method" \
        --config "$cfg" >/dev/null
      rows+=("$name $state $method $out/$name/$state/$method/metrics.json")
    done
  done
}
# The same dataset with calibration.yaml stating no sonar clock offset (its files linked, not
# copied): the clock-offset state then has the whole offset to find.
without_clock_offset() {  # SOURCE DESTINATION
  rm -rf "$2" && mkdir -p "$2"
  for f in "$1"/*; do
    [ "$(basename "$f")" = calibration.yaml ] || ln -s "$(realpath "$f")" "$2/"
  done
  if [ -f "$1/calibration.yaml" ]; then
    sed 's/^\(  time_offset_s:\).*/\1 0/' "$1/calibration.yaml" >"$2/calibration.yaml"
  else
    printf 'sonar:\n  time_offset_s: 0\n' >"$2/calibration.yaml"
  fi
}
run_clock() {  # NAME DATASET CONFIG
  local name=$1 config=$3
  without_clock_offset "$2" "$out/$name.no_clock_offset"
  with_state "$config" clock_offset >"$out/$name.clock_offset.yaml"
  for method in robocentric worldcentric; do
    "$msislab" run "$out/$name.no_clock_offset" --method "$method" \
      --out "$out/$name/clock_offset/$method" --config "$out/$name.clock_offset.yaml" >/dev/null
    rows+=("$name clock_offset $method $out/$name/clock_offset/$method/metrics.json")
  done
}

run_dataset replica "$replica" config/stpere_replica.yaml
run_clock replica "$replica" config/stpere_replica.yaml
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
if [ -f "$stpere/_040825_1735_DVL.log" ]; then
  run_dataset real "$stpere" config/stpere.yaml
  run_clock real "$stpere" config/stpere.yaml
else
  echo "tools/calibration_states.sh: no real St. Pere dataset at $stpere: its rows are left out" >&2
fi

python3 - "${rows[@]}" <<'EOF'
import csv, json, os, sys
LOWER, UPPER = 0.2158, 9.3484  # chi-square, 3 DOF, 2.5 % and 97.5 %
print("| dataset | state on | method | mean error | "
      "ANEES (steps in bounds), or loop / canal | "
      "estimate (sd) | consecutive match scale | run time |")
print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |")
for row in sys.argv[1:]:
    name, state, method, path = row.split(" ", 3)
    m = json.load(open(path))
    d = m.get("diagnostics", {})
    if name == "real":
        seg = m.get("segments", {})
        second = f"{seg['loop']:.2f} m / {seg['canal']:.2f} m"
    else:
        with open(os.path.join(os.path.dirname(path), "nees.csv")) as f:
            nees = [float(r["nees"]) for r in csv.DictReader(f)]
        inside = sum(LOWER <= x <= UPPER for x in nees) / len(nees)
        second = f"{m['anees']:.2f} ({100 * inside:.0f} %)"
    names = {"range_scale": "s", "dvl_scale": "k", "clock_offset_s": "tau",
             "compass_deviation_cos_deg": "a", "compass_deviation_sin_deg": "b",
             "heading_bias_deg": "beta"}
    scale = ", ".join(f"{short} {d[key]:.3f} ({d[key + '_sigma']:.3f})"
                      for key, short in names.items() if key in d)
    if state in ("compass_deviation", "heading_bias"):
        scale += " deg"
    if state == "clock_offset":
        scale += " s (calibration.yaml: 0 s)"
    state = state.replace("_", " ")
    print(f"| {'replica, seed 42' if name == 'replica' else 'real St. Pere'} | {state} | "
          f"{method} | {m['mean_error_m']:.2f} m | {second} | {scale} | "
          f"{d.get('consecutive_match_scale', float('nan')):.3f} | {m['runtime_s']:.1f} s |")
EOF

# The sensor-only fits beside the estimates: the run without a state, its matches against the
# MTi log (the deviation and the clock offset beyond calibration.yaml's, from the sensors alone).
echo
echo "Sensor-only fits (the robocentric run without a state against the heading log;" \
  "tools/compass_deviation_fit.py, tools/clock_offset_fit.py, its offset beyond calibration.yaml's):"
for name in replica real; do
  run="$out/$name/off/robocentric"
  [ -d "$run" ] || continue
  dataset=$replica
  [ $name = real ] && dataset=$stpere
  echo "- $name: $(python3 tools/compass_deviation_fit.py "$run" --dataset "$dataset");" \
    "$(python3 tools/clock_offset_fit.py "$run" --dataset "$dataset")"
done
