#!/usr/bin/env bash
# The scan-errors study (docs/scan_errors_study.md) in one command: the robocentric filter with
# none, the motion or the motion and the points of the scans' shared errors in its state
# (trajectory_slam.scan_shared_errors), on the marina loop (1.5, 3 (its own), 6 and 9 deg beams,
# 1 or 3 matches per scan) and on the St. Pere replica (its own 6 deg and 3 matches). Builds, runs
# the sweeps studies/scan_errors/<scene>.yaml into out/scan_errors_study/<scene> (resumable, as
# tools/beam_study.sh's) and writes the page's tables: per beam and matches per scan, the share of
# scan steps inside the 95 % NEES bounds, the ANEES (3 when consistent) and the mean error, for
# each choice of states.
# Usage: tools/scan_errors_study.sh [--jobs J] [--msislab EXE]   (about 6 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc)
msislab=
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) jobs="${2:?--jobs needs a number}"; shift 2 ;;
    --msislab) msislab="${2:?--msislab needs a path}"; shift 2 ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/scan_errors_study.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "tools/scan_errors_study.sh: --jobs '$jobs' is not a whole number of 1 or more" >&2; exit 2; }

source tools/run_fresh.sh
msislab_or_build tools/scan_errors_study.sh
scenes="marina_loop stpere_replica"
for scene in $scenes; do
  run_fresh "out/scan_errors_study/$scene" "$msislab" sweep "studies/scan_errors/$scene.yaml" \
    --out "out/scan_errors_study/$scene" --jobs "$jobs"
done
page=docs/scan_errors_study.md
marker=$(page_marker tools/scan_errors_study.sh "$page")
{
  echo "$marker"
  echo "# The scan-errors study"
  echo
  echo "Written by \`tools/scan_errors_study.sh\` (the sweeps \`studies/scan_errors/<scene>.yaml\`, the"
  echo "robocentric filter, each scene's SLAM config otherwise): per beamwidth and matches per scan,"
  echo "the share of scan steps inside the 95 % NEES bounds, the ANEES in brackets (a consistent"
  echo "filter gives 3) and the mean error, for each choice of the scans' shared errors the state holds"
  echo "(\`trajectory_slam.scan_shared_errors\`; docs/trajectory_slam.md, \"Scan registration"
  echo "errors\", says what the tables show). Each sweep's own figures and \`sweep.csv\` are in"
  echo "\`out/scan_errors_study/<scene>/\`."
  for scene in $scenes; do
    echo
    echo "## $scene ($(sed -nE 's/^runs: ([0-9]+).*/\1/p' "studies/scan_errors/$scene.yaml") runs a cell)"
    echo
    awk -F, '
      NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
      {
        key = $col["scenario.sonar.horizontal_beamwidth_deg"] " deg, " \
              $col["slam.trajectory_slam.max_matches_per_scan"]
        if (!(key in seen)) { seen[key] = 1; keys[++n] = key }
        cell[key, $col["slam.trajectory_slam.scan_shared_errors"]] = \
          sprintf("%.0f %% (%.1f), %.2f m", 100 * $col["nees_in_bounds_fraction"], $col["anees"],
                  $col["mean_error_m"])
      }
      END {
        print "| beam, matches per scan | none | motion | motion_and_points |"
        print "| --- | --- | --- | --- |"
        for (k = 1; k <= n; k++) {
          print "| " keys[k] " | " cell[keys[k], "none"] " | " cell[keys[k], "motion"] " | " \
                cell[keys[k], "motion_and_points"] " |"
        }
      }' "out/scan_errors_study/$scene/sweep.csv"
  done
  echo
  echo "## Made from"
  echo
  for file in studies/scan_errors/marina_loop.yaml studies/scan_errors/stpere_replica.yaml \
    scenarios/marina_loop.yaml scenarios/stpere_replica.yaml config/stpere_replica.yaml; do
    echo "- \`$file\` (sha256 $(sha256sum "$file" | cut -d' ' -f1))"
  done
} >"$page.tmp"
mv "$page.tmp" "$page"
echo "scan-errors study: wrote $page"
