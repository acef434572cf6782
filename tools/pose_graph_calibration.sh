#!/usr/bin/env bash
# The table of docs/pose_graph.md, "The scale factors, the clock offset and the compass deviation":
# the pose graph without its constants' blocks, then with each alone
# (trajectory_slam.calibration.range_scale, dvl_scale, clock_offset, compass_deviation), N Monte
# Carlo runs each (default 10): the replica read through its detections (config/stpere_replica.yaml), whole graph and with
# a 20-scan online window, the straight channel and the open area (the default config); then the
# real St. Pere run once each (reported: the estimate is the run's, not chosen on it; skipped, said,
# without the dataset). Prints a Markdown table: mean error, ANEES and the share of scan steps
# whose run-averaged NEES lies inside the two-sided 95 % bounds; the real run's mean error, loop
# and canal, the estimate with its standard deviation (the smoothed graph's). Writes under out/pose_graph_calibration/.
# Usage: tools/pose_graph_calibration.sh [--runs N] [--msislab EXE]
set -euo pipefail
cd "$(dirname "$0")/.."
msislab=build/release/tools/msislab
runs=10
source tools/run_fresh.sh
parse_table_options tools/pose_graph_calibration.sh montecarlo "$@"

out=out/pose_graph_calibration
claim_out_folder tools/pose_graph_calibration.sh "$out"

# CONFIG (- : none) WINDOW STATE(off|range_scale) -> the config's path
config_of() {
  local cfg
  cfg="$out/config.$(basename "${1%.yaml}").w$2.$3.yaml"
  { [ "$1" = - ] || cat "$1"
    [ "$2" = 0 ] || printf 'pose_graph:\n  online_window_scans: %s\n' "$2"
    [ "$3" = off ] || printf 'trajectory_slam:\n  calibration:\n    %s: true\n' "$3"; } >"$cfg"
  echo "$cfg"
}

states=(off range_scale dvl_scale clock_offset compass_deviation)
# NAME SCENARIO CONFIG WINDOW
cases=(
  "stpere_replica scenarios/stpere_replica.yaml config/stpere_replica.yaml 0"
  "stpere_replica_window20 scenarios/stpere_replica.yaml config/stpere_replica.yaml 20"
  "straight_channel scenarios/straight_channel.yaml - 0"
  "open_area scenarios/open_area.yaml - 0"
)
for c in "${cases[@]}"; do
  read -r name scenario config window <<<"$c"
  for state in "${states[@]}"; do
    run_fresh "$out/$name.$state" "$msislab" montecarlo "$scenario" --runs "$runs" \
      --out "$out/$name.$state" --methods posegraph --config "$(config_of "$config" "$window" "$state")" \
      --no-plot >/dev/null 2>&1
  done
done
real=../shared/datasets/stpere
if [ -d "$real" ]; then
  for state in "${states[@]}"; do
    run_fresh "$out/real.$state" "$msislab" run "$real" --method posegraph \
      --config "$(config_of config/stpere.yaml 0 "$state")" --out "$out/real.$state" >/dev/null 2>&1
  done
else
  echo "tools/pose_graph_calibration.sh: no $real: the real run's rows are left out" >&2
fi

python3 - "$out" "$runs" "${cases[@]}" <<'PY'
import json, os, sys
out, runs = sys.argv[1], sys.argv[2]
states = ("off", "range_scale", "dvl_scale", "clock_offset", "compass_deviation")
keys = {"range_scale": ["range_scale"], "dvl_scale": ["dvl_scale"],
        "clock_offset": ["clock_offset_s"],
        "compass_deviation": ["compass_deviation_cos_deg", "compass_deviation_sin_deg"]}


def estimate(d, state):
    """The state's estimates with their standard deviations (the deviation's a, b in deg)."""
    return ", ".join(f"{d[k]:.4f} +- {d[k + '_sigma']:.4f}" for k in keys[state])
print("| scene (runs) | block | mean error, ANEES, steps in bounds | estimate (run 0) |")
print("| --- | --- | ---: | ---: |")
for case in sys.argv[3:]:
    name = case.split(" ")[0]
    for state in states:
        s = json.load(open(os.path.join(out, f"{name}.{state}", "summary.json")))["posegraph"]
        est = ""
        if state != "off":
            m = json.load(open(os.path.join(out, f"{name}.{state}", "runs", "posegraph",
                                            "run_0000", "metrics.json")))["diagnostics"]
            est = estimate(m, state)
        print(f"| {name} ({runs}) | {state} | {s['mean_error_m']:.2f} m, {s['anees']:.2f}, "
              f"{100 * s['nees_in_bounds_fraction']:.0f} % | {est} |")
if os.path.isdir(os.path.join(out, "real.off")):
    print("\n| real St. Pere | block | mean error (loop, canal) | estimate |")
    print("| --- | --- | ---: | ---: |")
    for state in states:
        m = json.load(open(os.path.join(out, f"real.{state}", "metrics.json")))
        seg = m.get("segments", {})
        est = ""
        if state != "off":
            d = m["diagnostics"]
            est = estimate(d, state)
        print(f"| posegraph | {state} | {m['mean_error_m']:.2f} m ({seg.get('loop', float('nan')):.2f}, "
              f"{seg.get('canal', float('nan')):.2f}) | {est} |")
PY
