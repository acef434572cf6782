#!/usr/bin/env bash
# The table of docs/trajectory_slam.md, "Calibration states": robocentric and world-centric SLAM
# with the range-scale state off (the default config) and on
# (trajectory_slam.calibration.range_scale), on the replica (seed 42, read through its detections
# with config/stpere_replica.yaml) and on the real St. Pere run (config/stpere.yaml; skipped, said,
# when the dataset is not there). Prints a Markdown table: mean error; on simulation the ANEES and
# the share of scan steps whose NEES lies inside one run's 95 % bounds (3 DOF: 0.216-9.348), on
# the real run the loop's and the canal's mean error; the estimated range scale with its standard
# deviation; the consecutive matches' scale against the truth; the run time. Writes its results
# under out/calibration_states/.
# Usage: tools/calibration_states.sh [--msislab EXE]
set -euo pipefail
cd "$(dirname "$0")/.."
msislab=build/release/tools/msislab
if [ "${1:-}" = --msislab ]; then
  msislab="${2:?--msislab needs a path}"
elif [ $# -gt 0 ]; then
  echo "tools/calibration_states.sh: unknown argument '$1' (usage: [--msislab EXE])" >&2
  exit 2
fi
[ -x "$msislab" ] || { echo "tools/calibration_states.sh: no $msislab (build first)" >&2; exit 2; }

out=out/calibration_states
# Its configs are written beside the results: only into a folder this script made (its marker).
if [ -d "$out" ] && [ -n "$(ls -A "$out")" ] && [ ! -f "$out/.calibration_states" ]; then
  echo "tools/calibration_states.sh: $out exists and was not written by this script; refusing" >&2
  exit 2
fi
mkdir -p "$out"  # msislab replaces only the result folders it wrote itself (docs/cli.md)
touch "$out/.calibration_states"
replica="$out/sim/stpere_replica"
"$msislab" simulate scenarios/stpere_replica.yaml --out "$replica" >/dev/null

# The config with the state on: the given one plus the switch.
with_state() {
  cat "$1"
  if grep -q '^trajectory_slam:' "$1"; then
    echo "tools/calibration_states.sh: $1 has a trajectory_slam: section; merge by hand" >&2
    exit 2
  fi
  printf 'trajectory_slam:\n  calibration:\n    range_scale: true\n'
}

rows=()
run_dataset() {  # NAME DATASET CONFIG
  local name=$1 dataset=$2 config=$3
  with_state "$config" >"$out/$name.range_scale.yaml"
  for state in off on; do
    local cfg=$config
    [ $state = on ] && cfg="$out/$name.range_scale.yaml"
    for method in robocentric worldcentric; do
      "$msislab" run "$dataset" --method "$method" --out "$out/$name/$state/$method" \
        --config "$cfg" >/dev/null
      rows+=("$name $state $method $out/$name/$state/$method/metrics.json")
    done
  done
}
run_dataset replica "$replica" config/stpere_replica.yaml
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
if [ -f "$stpere/_040825_1735_DVL.log" ]; then
  run_dataset real "$stpere" config/stpere.yaml
else
  echo "tools/calibration_states.sh: no real St. Pere dataset at $stpere: its rows are left out" >&2
fi

python3 - "${rows[@]}" <<'EOF'
import csv, json, os, sys
LOWER, UPPER = 0.2158, 9.3484  # chi-square, 3 DOF, 2.5 % and 97.5 %
print("| dataset | range-scale state | method | mean error | "
      "ANEES (steps in bounds), or loop / canal | "
      "range scale (sd) | consecutive match scale | run time |")
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
    scale = (f"{d['range_scale']:.3f} ({d['range_scale_sigma']:.3f})" if "range_scale" in d
             else "")
    print(f"| {'replica, seed 42' if name == 'replica' else 'real St. Pere'} | {state} | "
          f"{method} | {m['mean_error_m']:.2f} m | {second} | {scale} | "
          f"{d.get('consecutive_match_scale', float('nan')):.3f} | {m['runtime_s']:.1f} s |")
EOF
