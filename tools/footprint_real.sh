#!/usr/bin/env bash
# The beam's footprint table on the real St. Pere run (docs/footprint_real.md), reported, never
# tuned on: the table is measured by `msislab footprint` on the St. Pere replica as shipped
# (scenarios/stpere_replica.yaml, its 6 deg beam, seeds 301-303, read from its detections with
# config/stpere_replica.yaml, as the real sonar is), put into the real run's config
# (config/stpere.yaml), and the real run made without and with it: each back end's mean error and
# consecutive match scale against the GPS, the same with the innovation gate moved by up to 3 %
# either way (tools/real_sensitivity.sh --gates: how stable the one real figure is), and how many
# of the 22 parameters of tools/real_sensitivity.sh move robocentric's figure by more than 25 %.
# Usage: tools/footprint_real.sh [--msislab EXE]   (about 6 minutes on 2 cores; needs the real
#   dataset, MSISLAB_STPERE_DIR, default ../shared/datasets/stpere)
set -euo pipefail
cd "$(dirname "$0")/.."
source tools/run_fresh.sh

msislab=
while [ $# -gt 0 ]; do
  case "$1" in
    --msislab) msislab="${2:?--msislab needs a path}"; shift 2 ;;
    -h|--help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/footprint_real.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
fail() { echo "tools/footprint_real.sh: $*" >&2; exit 2; }
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
[ -f "$stpere/_040825_1735_DVL.log" ] || fail "no real St. Pere dataset at $stpere (MSISLAB_STPERE_DIR)"
msislab_or_build tools/footprint_real.sh
msislab=$(cd "$(dirname "$msislab")" && pwd)/$(basename "$msislab")
out=out/footprint_real
claim_out_folder tools/footprint_real.sh "$out"
mkdir -p "$out/inputs"
start=$(date +%s)

seeds="301 302 303"
datasets=()
for seed in $seeds; do
  scenario="$out/inputs/stpere_replica_seed$seed.yaml"
  python3 tools/scenario_variant.py scenarios/stpere_replica.yaml "$scenario" footprint_real
  sed -i "s/^seed: .*/seed: $seed/" "$scenario"
  rm -rf "$out/calibration/seed$seed"
  "$msislab" simulate "$scenario" --out "$out/calibration/seed$seed" >/dev/null
  datasets+=("$out/calibration/seed$seed")
done
rm -f "$out/inputs/replica_table.yaml"
"$msislab" footprint "${datasets[@]}" --config config/stpere_replica.yaml \
  --out "$out/inputs/replica_table.yaml"
# The real run's config with the replica's table: config/stpere.yaml and the section.
with_table="$out/inputs/stpere_with_table.yaml"
{
  cat config/stpere.yaml
  echo "# The beam's footprint table measured on the replica by tools/footprint_real.sh:"
  awk '/^footprint:/ { on = 1 } on' "$out/inputs/replica_table.yaml"
} >"$with_table"

# field DIR KEY: a number from a result's metrics.json.
field() { sed -n "s/.*\"$2\": \([0-9.e+-]*\).*/\1/p" "$1/metrics.json" | head -1; }
gates="11.00 11.11 11.23 11.34 11.45 11.57 11.68"
declare -A scale error gate_rows moved
for arm in without with; do
  config=config/stpere.yaml
  [ $arm = without ] || config="$with_table"
  for method in robocentric worldcentric posegraph; do
    dir="$out/runs/${method}_$arm"
    rm -rf "$dir"
    "$msislab" run "$stpere" --method "$method" --out "$dir" --config "$config" >/dev/null
    scale[$method,$arm]=$(field "$dir" consecutive_match_scale)
    error[$method,$arm]=$(field "$dir" mean_error_m)
  done
  echo "== the innovation gate moved, $arm the table"
  # shellcheck disable=SC2086
  gate_rows[$arm]=$(tools/real_sensitivity.sh --msislab "$msislab" --config "$config" --gates $gates |
    tail -n +2)
  echo "${gate_rows[$arm]}"
  echo "== 22 parameters moved 10 %, $arm the table (robocentric)"
  tools/real_sensitivity.sh --msislab "$msislab" --config "$config" \
    --csv "$out/sensitivity_$arm.csv" >/dev/null
  moved[$arm]=$(awk -F, 'NR > 1 { for (i = 6; i <= 8; i += 2) if ($i / $4 - 1 > 0.25 || 1 - $i / $4 > 0.25) { n++; break } }
                         END { print n + 0 }' "$out/sensitivity_$arm.csv")
done

page=docs/footprint_real.md
marker=$(page_marker tools/footprint_real.sh "$page")
{
  echo "$marker"
  echo "# The beam's footprint table on the real St. Pere run"
  echo
  echo "Written by \`tools/footprint_real.sh\`. Reported, never tuned on: the table"
  echo "(docs/scan_matching.md, \"The beam's footprint\") is measured by \`msislab footprint\` on the"
  echo "St. Pere replica as shipped (6 deg beam, seeds ${seeds// /, }, its detections read with"
  echo "config/stpere_replica.yaml), added to the real run's config (config/stpere.yaml), and the real"
  echo "run is made without and with it. The consecutive match scale is the accepted consecutive"
  echo "matches' length against the GPS's (docs/formats.md; 1 is unbiased)."
  echo
  echo "| back end | mean error without -> with | consecutive match scale without -> with |"
  echo "| --- | --- | --- |"
  for method in robocentric worldcentric posegraph; do
    printf '| %s | %.2f m -> %.2f m | %.3f -> %.3f |\n' "$method" "${error[$method,without]}" \
      "${error[$method,with]}" "${scale[$method,without]}" "${scale[$method,with]}"
  done
  echo
  echo "The same runs with the innovation gate (11.34 in both configs) moved by up to 3 % either way"
  echo "(\`tools/real_sensitivity.sh --gates\`; the pose graph's online / smoothed mean error):"
  echo
  echo "| gate | table | robocentric | worldcentric | posegraph |"
  echo "| --- | --- | --- | --- | --- |"
  for arm in without with; do
    while read -r gate robo _ world _ pg_online _ _ pg_smoothed _; do
      echo "| $gate | $arm | $robo m | $world m | $pg_online / $pg_smoothed m |"
    done <<<"${gate_rows[$arm]}"
  done
  echo
  echo "Of the 22 parameters \`tools/real_sensitivity.sh\` moves 10 % either way, those that move"
  echo "robocentric's real mean error (the pose graph's own two: its smoothed one) by more than 25 %:"
  echo "${moved[without]} without the table, ${moved[with]} with it."
  echo
  echo "## Made from"
  echo
  for file in scenarios/stpere_replica.yaml config/stpere_replica.yaml config/stpere.yaml; do
    echo "- \`$file\` (sha256 $(sha256sum "$file" | cut -d' ' -f1))"
  done
} >"$page.tmp"
mv "$page.tmp" "$page"
echo "footprint on the real run: $(( $(date +%s) - start )) s; wrote $page"
