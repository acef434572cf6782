#!/usr/bin/env bash
# The table of docs/dead_reckoning.md, "Noise matched to the sensors": every shipped scenario with
# the navigation noise of the config (the defaults: St. Pere's figures) against the noise its
# sensors have (`navigation_noise: dataset`, the scenario's navigation_noise.yaml), N Monte Carlo
# runs each (default 10; the concrete basin 6), robocentric SLAM, the pose graph and dead
# reckoning; and the replica again with a 2 deg beam (stpere_replica_beam2); each also with the
# sensors' noise and one match per scan (trajectory_slam.max_matches_per_scan: 1). The replica is read
# through its detections (config/stpere_replica.yaml), the others with the default config. Prints a Markdown table: mean error, ANEES and the share of scan steps
# whose run-averaged NEES lies inside the two-sided 95 % bounds. Writes under out/navigation_noise/.
# Usage: tools/navigation_noise.sh [--runs N] [--msislab EXE]
set -euo pipefail
cd "$(dirname "$0")/.."
msislab=build/release/tools/msislab
runs=10
source tools/run_fresh.sh
parse_table_options tools/navigation_noise.sh montecarlo "$@"

out=out/navigation_noise
claim_out_folder tools/navigation_noise.sh "$out"

# The replica with a 2 deg beam instead of its 6 deg one (whose matches shorten the motion,
# docs/simulator.md, "Scan-match scale"): its relative paths made absolute.
sed -e "s|\.\./scenes/|$PWD/scenes/|; s|heading_csv: |heading_csv: $PWD/scenarios/|" \
  -e 's|horizontal_beamwidth_deg: 6$|horizontal_beamwidth_deg: 2|' scenarios/stpere_replica.yaml \
  >"$out/stpere_replica_beam2.yaml"
grep -q 'horizontal_beamwidth_deg: 2$' "$out/stpere_replica_beam2.yaml" ||
  { echo "tools/navigation_noise.sh: the replica's beam width not found" >&2; exit 2; }

# NAME  SCENARIO  CONFIG (- : none)  RUNS
cases=(
  "stpere_replica scenarios/stpere_replica.yaml config/stpere_replica.yaml $runs"
  "stpere_replica_beam2 $out/stpere_replica_beam2.yaml config/stpere_replica.yaml $runs"
  "straight_channel scenarios/straight_channel.yaml - $runs"
  "open_area scenarios/open_area.yaml - $runs"
  "marina_loop scenarios/marina_loop.yaml - $runs"
  "concrete_basin scenarios/concrete_basin.yaml - $(( runs < 6 ? runs : 6 ))"
)
for c in "${cases[@]}"; do
  read -r name scenario config n <<<"$c"
  for noise in config dataset one_match; do
    cfg="$out/$name.$noise.yaml"
    { [ "$config" = - ] || cat "$config"
      if [ $noise = one_match ]; then
        printf 'navigation_noise: dataset\ntrajectory_slam:\n  max_matches_per_scan: 1\n'
      else
        echo "navigation_noise: $noise"
      fi; } >"$cfg"
    run_fresh "$out/$name.$noise" "$msislab" montecarlo "$scenario" --runs "$n" \
      --out "$out/$name.$noise" --methods robocentric,posegraph,deadreckoning --config "$cfg" \
      --no-plot >/dev/null
  done
done

python3 - "$out" "${cases[@]}" <<'PY'
import json, os, sys
out = sys.argv[1]
methods = ["robocentric", "posegraph", "deadreckoning"]
print("| scenario (runs) | noise | " + " | ".join(
    f"{m}: mean error, ANEES, steps in bounds" for m in methods) + " |")
print("| --- | --- |" + " ---: |" * len(methods))
for case in sys.argv[2:]:
    name, _, _, n = case.split(" ")
    for noise in ("config", "dataset", "one_match"):
        s = json.load(open(os.path.join(out, f"{name}.{noise}", "summary.json")))
        cells = [f"{s[m]['mean_error_m']:.2f} m, {s[m]['anees']:.2f}, "
                 f"{100 * s[m]['nees_in_bounds_fraction']:.0f} %" for m in methods]
        label = {"config": "the defaults", "dataset": "the sensors' (dataset)",
                 "one_match": "the sensors', one match per scan"}[noise]
        print(f"| {name} ({n}) | {label} | " + " | ".join(cells) + " |")
PY
