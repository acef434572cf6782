#!/usr/bin/env bash
# How fragile is the one real-data figure? Runs robocentric, world-centric and the pose graph on
# the real St. Pere dataset with the innovation gate (trajectory_slam.innovation_gate_chi2) moved
# a little either side of its default 11.34, and prints each run's mean error (the pose graph's
# online and smoothed) and the matches the gate rejected. A report, never a way to pick a value:
# parameters are chosen on simulation (README, "Tune on simulation, report on reality").
# Usage: tools/real_sensitivity.sh [GATE...]   (after a release build; needs the real dataset;
#        default gates 11.0 11.2 11.34 11.5 11.7; about 8 s per gate)
set -euo pipefail
cd "$(dirname "$0")/.."

case "${1:-}" in
  -h|--help) sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
esac
gates=("$@")
[ ${#gates[@]} -gt 0 ] || gates=(11.0 11.2 11.34 11.5 11.7)
msislab=build/release/tools/msislab
[ -x "$msislab" ] || {
  echo "tools/real_sensitivity.sh: build first (cmake --preset release && cmake --build --preset release)" >&2
  exit 2
}
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
[ -f "$stpere/_040825_1735_DVL.log" ] || {
  echo "tools/real_sensitivity.sh: no real St. Pere dataset at $stpere (MSISLAB_STPERE_DIR)" >&2
  exit 2
}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# value KEY: a number from the method's metrics.json.
value() { sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p" "$out/$method/metrics.json" | head -1; }
printf '%-6s %-28s %-28s %s\n' gate robocentric worldcentric "posegraph online / smoothed"
for gate in "${gates[@]}"; do
  # The real run's config (its segments) with the gate set.
  { cat config/stpere.yaml; printf 'trajectory_slam:\n  innovation_gate_chi2: %s\n' "$gate"; } \
    >"$out/config.yaml"
  line=$(printf '%-6s' "$gate")
  for method in robocentric worldcentric posegraph; do
    "$msislab" run "$stpere" --method "$method" --out "$out/$method" --config "$out/config.yaml" \
      >/dev/null
    error=$(printf '%.2f' "$(value mean_error_m)")
    smoothed=$(value smoothed_mean_error_m)
    [ -z "$smoothed" ] || error+=$(printf ' / %.2f' "$smoothed")
    line+=$(printf ' %-16s%3d rejected ' "$error m," "$(value matches_rejected_innovation)")
  done
  echo "$line"
done
