#!/usr/bin/env bash
# The scan-errors study (docs/scan_errors_study.md) in one command: the robocentric filter on the
# marina loop with none, the motion or the motion and the points of the scans' shared errors in its
# state (trajectory_slam.scan_shared_errors), at 1.5, 3 (the scene's own), 6 and 9 deg beams and
# with 1 or 3 matches per scan. Builds, runs the sweep studies/scan_errors/marina_loop.yaml into
# out/scan_errors_study/marina_loop (resumable, as tools/beam_study.sh's) and writes the page's
# table: per beam and matches per scan, the share of scan steps inside the 95 % NEES bounds, the
# ANEES (3 when consistent) and the mean error, for each choice of states.
# Usage: tools/scan_errors_study.sh [--jobs J] [--msislab EXE]   (about 3 minutes on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."

jobs=$(nproc)
msislab=
while [ $# -gt 0 ]; do
  case "$1" in
    --jobs) jobs="${2:?--jobs needs a number}"; shift 2 ;;
    --msislab) msislab="${2:?--msislab needs a path}"; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/scan_errors_study.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || { echo "tools/scan_errors_study.sh: --jobs '$jobs' is not a whole number of 1 or more" >&2; exit 2; }

source tools/run_fresh.sh
msislab_or_build tools/scan_errors_study.sh
sweep=studies/scan_errors/marina_loop.yaml
out=out/scan_errors_study/marina_loop
run_fresh "$out" "$msislab" sweep "$sweep" --out "$out" --jobs "$jobs"
page=docs/scan_errors_study.md
marker=$(page_marker tools/scan_errors_study.sh "$page")
{
  echo "$marker"
  echo "# The scan-errors study"
  echo
  echo "Written by \`tools/scan_errors_study.sh\` (the sweep \`$sweep\`, 20 runs a cell, the"
  echo "robocentric filter, the default SLAM config otherwise): on the marina loop, per beamwidth and"
  echo "matches per scan, the share of scan steps inside the 95 % NEES bounds, the ANEES in brackets"
  echo "(a consistent filter gives 3) and the mean error, for each choice of the scans' shared errors"
  echo "the state holds (\`trajectory_slam.scan_shared_errors\`; docs/trajectory_slam.md, \"Scan"
  echo "registration errors\", says what the table shows). The sweep's own figures and \`sweep.csv\`"
  echo "are in \`$out/\`."
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
    }' "$out/sweep.csv"
  echo
  echo "## Made from"
  echo
  echo "- \`$sweep\` (sha256 $(sha256sum "$sweep" | cut -d' ' -f1))"
  echo "- \`scenarios/marina_loop.yaml\` (sha256 $(sha256sum scenarios/marina_loop.yaml | cut -d' ' -f1))"
} >"$page.tmp"
mv "$page.tmp" "$page"
echo "scan-errors study: wrote $page"
