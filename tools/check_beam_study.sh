#!/usr/bin/env bash
# Whether a study's page (docs/beam_study.md, docs/footprint_study.md, docs/footprint_real.md,
# docs/scan_errors_study.md) still shows what its input files ask for: the script that writes it
# (named on the page's first line) lists, under its tables, each sweep, scenario or config file it
# ran with its SHA-256; a file changed since (its beams, runs, methods or scene) makes the page
# stale, and this names it. Run by the ctests Docs.BeamStudyMatchesItsSweepFiles,
# Docs.FootprintStudyMatchesItsInputFiles, Docs.FootprintRealMatchesItsInputFiles and
# Docs.ScanErrorsStudyMatchesItsInputFiles. (A change to the SLAM or the simulator also makes the
# page stale; that this cannot see: a study takes far longer than the suite.)
# Usage: tools/check_beam_study.sh [PAGE]   (default docs/beam_study.md). Exit 0 when every file
# matches, 1 when one does not or the page names none, 2 when the page is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
page="${1:-docs/beam_study.md}"
[ -f "$page" ] || { echo "check_beam_study: no page $page" >&2; exit 2; }
writer=$(head -n 1 "$page" | sed -nE 's/^<!-- written by (tools\/[a-z_]+\.sh);.*/\1/p')
writer="${writer:-the script that wrote it}"
lines=$(grep -E '^- `[A-Za-z0-9_/]+\.yaml` \(sha256 [0-9a-f]{64}\)' "$page" || true)
[ -n "$lines" ] || { echo "check_beam_study: $page names no input file with its digest" >&2; exit 1; }
stale=0
while read -r line; do
  file=$(sed -E 's/^- `([^`]+)`.*/\1/' <<<"$line")
  want=$(sed -E 's/.*sha256 ([0-9a-f]{64}).*/\1/' <<<"$line")
  if [ ! -f "$file" ]; then
    echo "check_beam_study: $page was made from $file, which is gone; run $writer" >&2
    stale=1
  elif [ "$(sha256sum "$file" | cut -d' ' -f1)" != "$want" ]; then
    echo "check_beam_study: $file changed since $page was written; run $writer" >&2
    stale=1
  fi
done <<<"$lines"
[ "$stale" = 0 ] && echo "check_beam_study: $page matches its $(wc -l <<<"$lines") input files"
exit "$stale"
