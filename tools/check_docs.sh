#!/usr/bin/env bash
# Checks that the pages a user reads (README.md and every docs/*.md) stand on their own, with
# nothing but the repository: no page cites a page outside it (a path into ../shared/docs, or
# interfaces.md, field-notes.md or style.md, which live there and not in docs/), and no page cites
# a bare issue number ("issue 11", "Issues #12", "issue" at the end of a line and the number on
# the next), which a user cannot look up. Paths to the datasets (../shared/datasets/...) are an
# interface the tools use and are allowed.
# Usage: tools/check_docs.sh   (from any folder)
# Exit 0 and one line "tools/check_docs.sh: N pages stand on their own"; exit 1 and one line per
# offending place, "FILE:LINE: what it cites", when a page cites one of them; exit 2 when there is
# no page to check.
set -euo pipefail
cd "$(dirname "$0")/.."

mapfile -t pages < <({ [ -f README.md ] && echo README.md; find docs -name '*.md'; } | sort)
[ ${#pages[@]} -gt 0 ] || { echo "tools/check_docs.sh: no README.md and no docs/*.md" >&2; exit 2; }

# One awk over every page; an issue number wrapped onto the next line is caught at the line that
# holds the word "issue".
status=0
awk '
  function report(line, what) { print FILENAME ":" line ": " what; bad = 1 }
  FNR == 1 { pending = 0 }
  {
    if (pending && match($0, /^[ \t>]*#?[0-9]+/))
      report(FNR - 1, "cites an issue by number (\"" pending_word " " \
             substr($0, RSTART, RLENGTH) "\", wrapped), which a user cannot look up")
    pending = 0
    if (match($0, /\.\.\/shared\/docs[A-Za-z0-9_.\/-]*/))
      report(FNR, "cites " substr($0, RSTART, RLENGTH) ", which is not in the repository")
    else if (match($0, /(interfaces|field-notes|style)\.md/))
      report(FNR, "cites " substr($0, RSTART, RLENGTH) \
             ", a page outside the repository (../shared/docs)")
    line = $0
    while (match(line, /[Ii]ssues? #?[0-9]+/)) {
      report(FNR, "cites an issue by number (\"" substr(line, RSTART, RLENGTH) \
             "\"), which a user cannot look up")
      line = substr(line, RSTART + RLENGTH)
    }
    if (match($0, /[Ii]ssues?[ \t]*$/)) { pending = 1; pending_word = substr($0, RSTART, RLENGTH) }
  }
  END { exit bad }' "${pages[@]}" || status=$?
case $status in
  0) echo "tools/check_docs.sh: ${#pages[@]} pages stand on their own" ;;
  1) exit 1 ;;
  *) echo "tools/check_docs.sh: awk failed (status $status)" >&2; exit 2 ;;
esac
