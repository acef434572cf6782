#!/usr/bin/env bash
# What the DVL-scale state reads on the replica, and why (docs/trajectory_slam.md, "Recovery on
# the replica"): the shipped replica (seed 42) with its DVL reading 1.01 times the true velocity
# and calibration.yaml stating 1, read through its detections with config/stpere_replica.yaml and
# `dvl_scale` on, by the robocentric filter and the pose graph: first with the state free (prior
# 1 +- 0.02, the default; then 1 +- 0.1 and 1 +- 0.005), then held at 0.95, 1.01 and 1.07 (prior
# sd 0.0005); last the pose graph with the default prior solved with 1000 iterations, without
# the robust loss and in one stage. Prints a Markdown table: the
# estimate with its standard deviation, the consecutive matches' scale against the truth
# (metrics.json's consecutive_match_scale) and the mean error. Writes under out/dvl_scale_feedback/.
# Usage: tools/dvl_scale_feedback.sh [--msislab EXE]
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/dvl_scale_feedback
source tools/run_fresh.sh
msislab=build/release/tools/msislab
parse_table_options tools/dvl_scale_feedback.sh single "$@"
claim_out_folder tools/dvl_scale_feedback.sh "$out"
tools/scenario_variant.py scenarios/stpere_replica.yaml "$out/replica_dvl_1.01.yaml" \
  tools/dvl_scale_feedback.sh dvl.scale_factor=1.01 stated_calibration.dvl.scale_factor=1
dataset="$out/sim/replica_dvl_1.01"
"$msislab" simulate "$out/replica_dvl_1.01.yaml" --out "$dataset" >/dev/null

rows=()
# free: the default prior 1 +- 0.02; sigma_S: prior 1 +- S; held_K: prior K +- 0.0005.
for prior in free sigma_0.1 sigma_0.005 held_0.95 held_1.01 held_1.07; do
  config="$out/dvl_scale.$prior.yaml"
  {
    cat config/stpere_replica.yaml
    printf 'trajectory_slam:\n  calibration:\n    dvl_scale: true\n'
    case $prior in
      sigma_*) printf '    dvl_scale_sigma: %s\n' "${prior#sigma_}" ;;
      held_*) printf '    dvl_scale_prior: %s\n    dvl_scale_sigma: 0.0005\n' "${prior#held_}" ;;
    esac
  } >"$config"
  for method in robocentric posegraph; do
    "$msislab" run "$dataset" --method $method --out "$out/$method.$prior" --config "$config" \
      >/dev/null
    rows+=("$method $prior $out/$method.$prior/metrics.json")
  done
done
# The pose graph's solve, the default prior: more iterations, no robust loss, one stage.
for solver in max_iterations:1000 robust_scale_chi2:0 robust_start_factor:1; do
  config="$out/dvl_scale.${solver%%:*}.yaml"
  { cat "$out/dvl_scale.free.yaml"; printf 'pose_graph:\n  %s %s\n' "${solver%%:*}:" "${solver#*:}"; } \
    >"$config"
  "$msislab" run "$dataset" --method posegraph --out "$out/posegraph.${solver%%:*}" \
    --config "$config" >/dev/null
  rows+=("posegraph $solver $out/posegraph.${solver%%:*}/metrics.json")
done
python3 - "${rows[@]}" <<'EOF'
import json, sys
print("| method | DVL scale state | estimate (sd) | consecutive match scale | mean error |")
print("| --- | --- | ---: | ---: | ---: |")
for row in sys.argv[1:]:
    method, prior, path = row.split(" ", 2)
    m = json.load(open(path))
    d = m["diagnostics"]
    if prior == "free":
        state = "free (prior 1 +- 0.02)"
    elif prior.startswith("sigma_"):
        state = f"free (prior 1 +- {prior[6:]})"
    elif prior.startswith("held_"):
        state = f"held at {prior[5:]}"
    else:
        state = "free (prior 1 +- 0.02), " + prior.replace(":", " ")
    print(f"| {method} | {state} | {d['dvl_scale']:.3f} ({d['dvl_scale_sigma']:.4f}) | "
          f"{d['consecutive_match_scale']:.3f} | {m['mean_error_m']:.2f} m |")
EOF
