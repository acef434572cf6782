#!/usr/bin/env bash
# How far can the one real-data figure be trusted? Runs a method on the real St. Pere dataset
# (config/stpere.yaml) with every numeric parameter of the front end and back end that the default
# config sets moved 10 % down and up, one at a time, and prints the method's mean error against
# the unchanged run's, as a table (Markdown, and CSV with --csv FILE for `msislab report
# --sensitivity`). A report, never a way to pick a value: parameters are chosen on simulation
# (README, "Tune on simulation, report on reality").
# Integer parameters move by one step (10 % of them rounds to the same value); a probability p
# moves its complement 1 - p by 10 %. The pose graph's own parameters are scored on the pose
# graph (its smoothed trajectory), every other one on --method (default robocentric).
#   tools/real_sensitivity.sh [--method M] [--csv FILE]   (about 2 s per run)
#       [--dataset DIR --config FILE]   another dataset (a simulated one: scored against its
#                                       truth) and its config instead of the real run's
#   tools/real_sensitivity.sh --gates G...   the innovation gate alone at the given values, all
#                                            three back ends (the earlier form of this script)
#       [--msislab EXE]                 the msislab to run (default build/release/tools/msislab)
# After a release build; needs the real dataset (MSISLAB_STPERE_DIR, default ../shared/...).
set -euo pipefail
cd "$(dirname "$0")/.."

method=robocentric
dataset=""
config=config/stpere.yaml
csv=""
step=0.1  # 10 %: the table and `msislab report` say so
gates=()
msislab=build/release/tools/msislab
while [ $# -gt 0 ]; do
  case "$1" in
    --method) method="$2"; shift 2 ;;
    --csv) csv="$2"; shift 2 ;;
    --dataset) dataset="$2"; shift 2 ;;
    --config) config="$2"; shift 2 ;;
    --msislab) msislab="$2"; shift 2 ;;
    --gates) shift; while [ $# -gt 0 ] && [[ "$1" != --* ]]; do gates+=("$1"); shift; done ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/real_sensitivity.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$msislab" ] || {
  echo "tools/real_sensitivity.sh: build first (cmake --preset release && cmake --build --preset release)" >&2
  exit 2
}
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
if [ -n "$dataset" ]; then
  stpere="$dataset"
elif [ ! -f "$stpere/_040825_1735_DVL.log" ]; then
  echo "tools/real_sensitivity.sh: no real St. Pere dataset at $stpere (MSISLAB_STPERE_DIR)" >&2
  exit 2
fi
[ -f "$config" ] || { echo "tools/real_sensitivity.sh: no config file $config" >&2; exit 2; }
if [ -n "$csv" ] && [ -e "$csv" ] && ! head -1 "$csv" | grep -q '^parameter,default,'; then
  echo "tools/real_sensitivity.sh: $csv exists and is not a table of this script; choose another --csv" >&2
  exit 2
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# value DIR KEY: a number from a result's metrics.json.
value() { sed -n "s/.*\"$2\": \([0-9.e+-]*\).*/\1/p" "$1/metrics.json" | head -1; }

# nested_yaml a.b.c VALUE [INDENT]: the YAML that sets a.b.c.
nested_yaml() {
  local path="$1" value="$2" indent="${3:-}" part
  IFS=. read -r -a parts <<<"$path"
  for part in "${parts[@]:0:${#parts[@]}-1}"; do
    printf '%s%s:\n' "$indent" "$part"
    indent+="  "
  done
  printf '%s%s: %s\n' "$indent" "${parts[-1]}" "$value"
}

# with_key CONFIG a.b.c VALUE: CONFIG with a.b.c set; when CONFIG has the top-level section a
# (block style), the rest goes under it, else the whole path is appended.
with_key() {
  local config="$1" path="$2" value="$3" top="${2%%.*}"
  if [ "$top" != "$path" ] && grep -q "^$top:[[:space:]]*$" "$config"; then
    awk -v top="$top:" -v block="$(nested_yaml "${path#*.}" "$value" "  ")" \
      '{ print } $0 ~ "^" top "[[:space:]]*$" { print block }' "$config"
  else
    cat "$config"
    nested_yaml "$path" "$value"
  fi
}

# run_with METHOD KEY VALUE: the mean error (the pose graph's smoothed one) with KEY set.
run_with() {
  local m="$1" key="$2" val="$3" dir="$out/run"
  if [ -z "$key" ]; then cp "$config" "$out/config.yaml"; else with_key "$config" "$key" "$val" >"$out/config.yaml"; fi
  rm -rf "$dir"
  "$msislab" run "$stpere" --method "$m" --out "$dir" --config "$out/config.yaml" >/dev/null
  if [ "$m" = posegraph ]; then value "$dir" smoothed_mean_error_m; else value "$dir" mean_error_m; fi
}

if [ ${#gates[@]} -gt 0 ]; then
  printf '%-6s %-18s %-18s %s\n' gate robocentric worldcentric "posegraph online / smoothed"
  for gate in "${gates[@]}"; do
    line=$(printf '%-6s' "$gate")
    for m in robocentric worldcentric posegraph; do
      run_with "$m" trajectory_slam.innovation_gate_chi2 "$gate" >/dev/null
      line+=$(printf ' %.2f m' "$(value "$out/run" mean_error_m)")
      [ "$m" != posegraph ] || line+=$(printf ' / %.2f m' "$(value "$out/run" smoothed_mean_error_m)")
    done
    echo "$line"
  done
  exit 0
fi

# KEY DEFAULT KIND (real, int or prob): the numbers the default config sets (slam/*.hpp).
params=(
  "dead_reckoning.dvl_sigma_mps 0.2 real"
  "dead_reckoning.heading_sigma_deg 1 real"
  "dead_reckoning.accel_sigma_mps2 0.05 real"
  "dead_reckoning.yaw_accel_sigma_radps2 0.02 real"
  "dead_reckoning.initial_velocity_sigma_mps 0.3 real"
  "dead_reckoning.initial_yaw_rate_sigma_radps 0.1 real"
  "segmentation.min_range_m 1 real"
  "segmentation.sigma_range_m 0.1 real"
  "segmentation.sigma_bearing_deg 1.4897 real"
  "trajectory_slam.association_distance_m 10 real"
  "trajectory_slam.max_matches_per_scan 3 int"
  "trajectory_slam.iekf_iterations 5 int"
  "trajectory_slam.innovation_gate_chi2 11.34 real"
  "trajectory_slam.compass_gate_chi2 6.63 real"
  "trajectory_slam.matching.association_gate_chi2 9.21 real"
  "trajectory_slam.matching.min_inliers 8 int"
  "trajectory_slam.matching.max_iterations 50 int"
  "trajectory_slam.validation.restart_offset_m 1.5 real"
  "trajectory_slam.validation.max_kept_fraction 0.5 real"
  "trajectory_slam.validation.ambiguity_probability 0.99 prob"
  "pose_graph.robust_scale_chi2 11.34 real"
  "pose_graph.robust_start_factor 100 real"
)
# moved VALUE KIND SIGN: the value moved by step in direction SIGN (-1 or 1).
moved() {
  awk -v v="$1" -v kind="$2" -v s="$3" -v f="$step" 'BEGIN {
    if (kind == "int") { m = int(v * (1 + s * f) + 0.5); if (m == v) m = v + s; if (m < 1) m = 1; print m }
    else if (kind == "prob") printf "%.6g\n", 1 - (1 - v) * (1 - s * f)
    else printf "%.6g\n", v * (1 + s * f) }'
}
declare -A base
rows=()
for entry in "${params[@]}"; do
  read -r key default kind <<<"$entry"
  m="$method"
  [[ "$key" != pose_graph.* ]] || m=posegraph
  [ -n "${base[$m]:-}" ] || base[$m]=$(run_with "$m" "" "")
  low=$(moved "$default" "$kind" -1)
  high=$(moved "$default" "$kind" 1)
  error_low=$(run_with "$m" "$key" "$low")
  error_high=$(run_with "$m" "$key" "$high")
  rows+=("$key,$default,$m,${base[$m]},$low,$error_low,$high,$error_high")
  echo "$key: $low -> $error_low m, $high -> $error_high m (${base[$m]} m at $default, $m)" >&2
done

table() {
  echo "parameter,default,method,mean_error_m,low,low_mean_error_m,high,high_mean_error_m"
  printf '%s\n' "${rows[@]}"
}
if [ -n "$csv" ]; then
  mkdir -p "$(dirname "$csv")"
  partial=$(mktemp "$csv.XXXXXX")  # a new file of this script's, renamed into place whole
  table >"$partial"
  mv "$partial" "$csv"
fi
table | awk -F, 'NR == 1 {
    print "| parameter | default | method | mean error [m] | -10 %: value | mean error [m] (change) | +10 %: value | mean error [m] (change) |"
    print "| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: |"; next }
  { printf "| `%s` | %s | %s | %.2f | %s | %.2f (%+.0f %%) | %s | %.2f (%+.0f %%) |\n",
      $1, $2, $3, $4, $5, $6, 100 * ($6 / $4 - 1), $7, $8, 100 * ($8 / $4 - 1) }'
