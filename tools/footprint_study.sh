#!/usr/bin/env bash
# The footprint study (docs/footprint_study.md) in one command: what the beam's footprint model
# (docs/scan_matching.md, "The beam's footprint") does to the SLAM's consistency and error at each
# beamwidth. Per beamwidth it simulates the calibration datasets (scenarios/open_area.yaml and
# scenarios/straight_channel.yaml at that beam, seeds 201-203: other seeds than the sweeps'),
# measures their table with `msislab footprint` into a SLAM config, then runs each scene's beam
# sweep (studies/beam/<scene>.yaml, at that beam only) three times on the same simulated data:
# with the default config, with the table, and with the table and, as the bearing sigma, the
# readings' bearing error measured on the same datasets. The page gives, per scene, back end and
# beamwidth, the share of scan steps inside the 95 % NEES bounds, the ANEES and the mean error
# of each arm.
# The marina loop is a scene the table was not measured on; the channel and the open area are
# measured on other seeds. With 20 runs a cell (the sweep files') the page is
# docs/footprint_study.md; with --runs N it is out/footprint_study/footprint_study.md.
# Usage: tools/footprint_study.sh [--jobs J] [--runs N] [--scenes "marina_loop ..."]
#                                 [--beams "1 2 3 6 9"] [--msislab EXE]
#   (20 runs a cell, three scenes, five beams: about 25 minutes on 2 cores; the replica's scene,
#   stpere_replica, can be named in --scenes and takes far longer)
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc)
runs=20
msislab=
scenes="marina_loop straight_channel open_area"
beams="1 2 3 6 9"
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) jobs="${2:?--jobs needs a number}"; shift 2 ;;
    --runs) runs="${2:?--runs needs a number}"; shift 2 ;;
    --scenes) scenes="${2:?--scenes needs a list}"; shift 2 ;;
    --beams) beams="${2:?--beams needs a list}"; shift 2 ;;
    --msislab) msislab="${2:?--msislab needs a path}"; shift 2 ;;
    -h|--help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/footprint_study.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
fail() { echo "tools/footprint_study.sh: $*" >&2; exit 2; }
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || fail "--jobs '$jobs' is not a whole number of 1 or more"
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || fail "--runs '$runs' is not a whole number of 1 or more"
for beam in $beams; do
  [[ "$beam" =~ ^[0-9]+(\.[0-9]+)?$ ]] || fail "--beams: '$beam' is not a beamwidth in deg"
done
for scene in $scenes; do
  [ -f "studies/beam/$scene.yaml" ] || fail "no sweep file studies/beam/$scene.yaml"
done
calibration_scenes="open_area straight_channel"
calibration_seeds="201 202 203"

source tools/run_fresh.sh
msislab_or_build tools/footprint_study.sh
out=out/footprint_study
claim_out_folder tools/footprint_study.sh "$out/inputs"
start=$(date +%s)
sigmas=
for beam in $beams; do
  # The table at this beam, from the calibration scenes' datasets.
  datasets=()
  for scene in $calibration_scenes; do
    for seed in $calibration_seeds; do
      name="${scene}_${beam}deg_seed$seed"
      scenario="$out/inputs/$name.yaml"
      python3 tools/scenario_variant.py "scenarios/$scene.yaml" "$scenario" footprint_study \
        "sonar.horizontal_beamwidth_deg=$beam"
      sed -i "s/^seed: .*/seed: $seed/" "$scenario"
      "$msislab" simulate "$scenario" --out "$out/calibration/$name" >/dev/null
      datasets+=("$out/calibration/$name")
    done
  done
  config="$out/inputs/footprint_${beam}deg.yaml"
  measured=$("$msislab" footprint "${datasets[@]}" --out "$config")
  echo "$measured"
  # The third arm: the table, and the readings' bearing error against truth on the same datasets
  # (their rms, which msislab footprint prints) as the scan points' bearing sigma.
  sigma_deg=$(sed -nE 's/.*; bearing error ([0-9.e+-]+) deg rms.*/\1/p' <<<"$measured")
  [ -n "$sigma_deg" ] || fail "msislab footprint printed no bearing error: $measured"
  bearing_config="$out/inputs/footprint_bearing_${beam}deg.yaml"
  { cat "$config"; printf 'segmentation:\n  sigma_bearing_deg: %s\n' "$sigma_deg"; } >"$bearing_config"
  sigmas="$sigmas $beam deg: $(printf '%.2f' "$sigma_deg");"
  for scene in $scenes; do
    for arm in default footprint bearing; do
      # The scene's sweep at this beam, its scenario path made absolute (a sweep's paths are
      # relative to its file); with the table's config in the footprint arm.
      sweep="$out/inputs/${scene}_${beam}deg_$arm.yaml"
      sed -e "s|^runs: .*|runs: $runs|" -e "s|^scenario: \.\./\.\./|scenario: $PWD/|" \
        -e "s|^  scenario.sonar.horizontal_beamwidth_deg: .*|  scenario.sonar.horizontal_beamwidth_deg: [$beam]|" \
        "studies/beam/$scene.yaml" >"$sweep"
      [ "$arm" = footprint ] && echo "config: $PWD/$config" >>"$sweep"
      [ "$arm" = bearing ] && echo "config: $PWD/$bearing_config" >>"$sweep"
      echo "== $scene at $beam deg, $arm config ($runs runs)"
      run_fresh "$out/$scene/${beam}deg_$arm" "$msislab" sweep "$sweep" \
        --out "$out/$scene/${beam}deg_$arm" --jobs "$jobs"
    done
  done
done
page="$out/footprint_study.md"
[ "$runs" = 20 ] && page=docs/footprint_study.md
marker=$(page_marker tools/footprint_study.sh "$page")
# A sweep's row for a method: "in bounds % (ANEES), mean error".
cell() {
  awk -F, -v m="$2" '
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    $col["method"] == m { printf "%.0f %% (%.1f), %.2f m", 100 * $col["nees_in_bounds_fraction"],
                            $col["anees"], $col["mean_error_m"] }' "$1/sweep.csv"
}
# A cell's consecutive match scale for a method: the mean over its runs of metrics.json's
# consecutive_match_scale (the accepted consecutive matches' length against the truth's; 1 is
# unbiased, docs/formats.md).
scale() {
  cat "$1"/cells/cell_000/runs/"$2"/run_*/metrics.json |
    sed -n 's/.*"consecutive_match_scale": \([0-9.e+-]*\).*/\1/p' |
    awk '{ s += $1; n++ } END { if (n) printf "%.3f", s / n; else printf "-" }'
}
# table SCENE FUNCTION: the scene's table, a row per back end and a column per beam, each cell
# FUNCTION's figure without the table -> with it -> with it and the measured bearing sigma
# (FUNCTION DIR METHOD: cell or scale).
table() {
  local line="| back end |" rule="| --- |" method beam
  for beam in $beams; do line="$line $beam deg |"; rule="$rule --- |"; done
  echo "$line"
  echo "$rule"
  for method in robocentric worldcentric posegraph; do
    line="| $method |"
    for beam in $beams; do
      line="$line $("$2" "$out/$1/${beam}deg_default" "$method") -> $("$2" "$out/$1/${beam}deg_footprint" "$method") -> $("$2" "$out/$1/${beam}deg_bearing" "$method") |"
    done
    echo "$line"
  done
}
{
  echo "$marker"
  echo "# The footprint study"
  echo
  echo "Written by \`tools/footprint_study.sh\` ($runs runs a cell): the beam study's sweeps"
  echo "(\`studies/beam/\`) at each beamwidth, on the same simulated data without and with the beam's"
  echo "footprint table (docs/scan_matching.md, \"The beam's footprint\"). The table at each beamwidth"
  echo "is measured by \`msislab footprint\` on the open area and the straight channel simulated at"
  echo "that beam with seeds ${calibration_seeds// /, } (the sweeps run seeds 1 on);"
  echo "the marina loop is a scene it was not measured on. The same command measures the readings'"
  echo "bearing error against truth on those datasets (docs/scan_matching.md, \"The bearing spread\"):"
  listed="${sigmas# }"
  echo "its rms in deg at each beam, ${listed%;},"
  echo "is the third arm's \`segmentation.sigma_bearing_deg\` (the default is 1.49 at every beam)."
  echo "Each cell: the share of scan steps inside the 95 % NEES bounds, the ANEES in brackets (3 when"
  echo "consistent) and the mean error, without the table -> with it -> with it and the measured"
  echo "bearing sigma."
  for scene in $scenes; do
    echo
    echo "## $scene"
    echo
    table "$scene" cell
    echo
    echo "The consecutive match scale (the mean over the runs; 1 is unbiased), in the same order:"
    echo
    table "$scene" scale
  done
  echo
  echo "## Made from"
  echo
  for file in $(for scene in $scenes; do echo "studies/beam/$scene.yaml"; done) \
    $(for scene in $calibration_scenes; do echo "scenarios/$scene.yaml"; done); do
    echo "- \`$file\` (sha256 $(sha256sum "$file" | cut -d' ' -f1))"
  done
} >"$page.tmp"
mv "$page.tmp" "$page"
echo "footprint study: $(wc -w <<<"$scenes") scenes at $(wc -w <<<"$beams") beams in" \
  "$(( $(date +%s) - start )) s; wrote $page"
