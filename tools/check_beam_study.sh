#!/usr/bin/env bash
# Whether docs/beam_study.md still shows what its sweep files ask for: tools/beam_study.sh writes,
# under the page's table, each sweep file it ran with its SHA-256; a sweep file changed since (its
# beams, runs, methods or scene) makes the page stale, and this names it. Run by the ctest
# Docs.BeamStudyMatchesItsSweepFiles. (A change to the SLAM or the simulator also makes the page
# stale; that this cannot see: the study takes far longer than the suite.)
# Usage: tools/check_beam_study.sh [PAGE]   (default docs/beam_study.md). Exit 0 when every sweep
# file matches, 1 when one does not or the page names none, 2 when the page is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
page="${1:-docs/beam_study.md}"
[ -f "$page" ] || { echo "check_beam_study: no page $page" >&2; exit 2; }
lines=$(grep -E '^- `studies/beam/[A-Za-z0-9_]+\.yaml` \(sha256 [0-9a-f]{64}\)' "$page" || true)
[ -n "$lines" ] || { echo "check_beam_study: $page names no sweep file with its digest" >&2; exit 1; }
stale=0
while read -r line; do
  file=$(sed -E 's/^- `([^`]+)`.*/\1/' <<<"$line")
  want=$(sed -E 's/.*sha256 ([0-9a-f]{64}).*/\1/' <<<"$line")
  if [ ! -f "$file" ]; then
    echo "check_beam_study: $page was made from $file, which is gone; run tools/beam_study.sh" >&2
    stale=1
  elif [ "$(sha256sum "$file" | cut -d' ' -f1)" != "$want" ]; then
    echo "check_beam_study: $file changed since $page was written; run tools/beam_study.sh" >&2
    stale=1
  fi
done <<<"$lines"
[ "$stale" = 0 ] && echo "check_beam_study: $page matches its $(wc -l <<<"$lines") sweep files"
exit "$stale"
