#!/usr/bin/env bash
# The beam study (docs/beam_study.md) in one command: how the SLAM's consistency and error move
# with the sonar's horizontal beamwidth. Builds, then runs the sweeps of studies/beam/ (the marina
# loop, the straight channel, the open area and the St. Pere replica; 1, 2, 3, 6 and 9 deg; the
# robocentric and world-centric filters and the pose graph on the same simulated data, the
# default SLAM config) into out/beam_study/<scene>, and writes their table: per scene, back end
# and beamwidth the share of scan steps inside the 95 % NEES bounds, the ANEES and the mean
# error. With the sweep files' 20 runs a cell the page is docs/beam_study.md; with --runs N (a
# quicker look, fewer runs a cell) it is out/beam_study/beam_study.md and docs/ is left alone.
# Resumable: an interrupted sweep keeps its finished runs when this is run again; one made by
# another build or sweep file is run again from scratch.
# Usage: tools/beam_study.sh [--jobs J] [--runs N] [--scenes "marina_loop ..."] [--msislab EXE]
#   (20 runs a cell: about an hour on 2 cores, most of it the replica; --msislab: an msislab
#   already built, instead of building the release one)
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc)
runs=20
msislab=
scenes="marina_loop straight_channel open_area stpere_replica"
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) jobs="${2:?--jobs needs a number}"; shift 2 ;;
    --runs) runs="${2:?--runs needs a number}"; shift 2 ;;
    --scenes) scenes="${2:?--scenes needs a list}"; shift 2 ;;
    --msislab) msislab="${2:?--msislab needs a path}"; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/beam_study.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "tools/beam_study.sh: --jobs '$jobs' is not a whole number of 1 or more" >&2; exit 2; }
[[ "$runs" =~ ^[1-9][0-9]*$ ]] || { echo "tools/beam_study.sh: --runs '$runs' is not a whole number of 1 or more" >&2; exit 2; }
for scene in $scenes; do
  [ -f "studies/beam/$scene.yaml" ] || { echo "tools/beam_study.sh: no sweep file studies/beam/$scene.yaml" >&2; exit 2; }
done

source tools/run_fresh.sh
msislab_or_build tools/beam_study.sh
out=out/beam_study
[ "$runs" = 20 ] || claim_out_folder tools/beam_study.sh "$out/sweeps"
start=$(date +%s)
for scene in $scenes; do
  sweep="studies/beam/$scene.yaml"
  if [ "$runs" != 20 ]; then
    # A copy with fewer runs, its scenario path made absolute (a sweep's paths are relative to
    # its file).
    copy="$out/sweeps/$scene.yaml"
    sed -e "s|^runs: .*|runs: $runs|" -e "s|^scenario: \.\./\.\./|scenario: $PWD/|" "$sweep" >"$copy"
    sweep="$copy"
  fi
  echo "== sweep $scene ($runs runs a cell) into $out/$scene"
  run_fresh "$out/$scene" "$msislab" sweep "$sweep" --out "$out/$scene" --jobs "$jobs"
done
page="$out/beam_study.md"
[ "$runs" = 20 ] && page=docs/beam_study.md
marker=$(page_marker tools/beam_study.sh "$page")
# The table: a row per scene and method, a column per beamwidth, each cell the share of scan
# steps inside the 95 % NEES bounds with the ANEES (3 when consistent) and the mean error.
{
  echo "$marker"
  echo "# The beam study"
  echo
  echo "Written by \`tools/beam_study.sh\` (sweep files in \`studies/beam/\`, $runs runs a cell,"
  echo "the default SLAM config): per scene and back end, as the sonar's horizontal beamwidth (the"
  echo "two-way -3 dB width) grows, the share of scan steps inside the 95 % NEES bounds, the ANEES"
  echo "in brackets (a consistent filter gives 3) and the mean error. Each sweep's own figures and"
  echo "\`sweep.csv\` are in \`out/beam_study/<scene>/\`."
  for scene in $scenes; do
    echo
    echo "## $scene"
    echo
    awk -F, -v scene="$scene" '
      NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
      {
        beam = $col["scenario.sonar.horizontal_beamwidth_deg"]; m = $col["method"]
        if (!(beam in seen_beam)) { seen_beam[beam] = 1; beams[++nb] = beam }
        if (!(m in seen_m)) { seen_m[m] = 1; methods[++nm] = m }
        cell[m, beam] = sprintf("%.0f %% (%.1f), %.2f m", 100 * $col["nees_in_bounds_fraction"],
                                $col["anees"], $col["mean_error_m"])
      }
      END {
        line = "| back end |"; rule = "| --- |"
        for (b = 1; b <= nb; b++) { line = line " " beams[b] " deg |"; rule = rule " --- |" }
        print line; print rule
        for (k = 1; k <= nm; k++) {
          line = "| " methods[k] " |"
          for (b = 1; b <= nb; b++) line = line " " cell[methods[k], beams[b]] " |"
          print line
        }
      }' "$out/$scene/sweep.csv"
  done
  # What the page was made from (tools/check_beam_study.sh compares these with the files).
  echo
  echo "## Made from"
  echo
  for scene in $scenes; do
    echo "- \`studies/beam/$scene.yaml\` (sha256 $(sha256sum "studies/beam/$scene.yaml" | cut -d' ' -f1))"
  done
} >"$page.tmp"
mv "$page.tmp" "$page"
echo "beam study: $(wc -w <<<"$scenes") sweeps in $(( $(date +%s) - start )) s of sweeping; wrote $page"
