#!/usr/bin/env bash
# The size limits on the non-test sources (app, report, io, sim, slam, eval, geometry, stats, plot,
# tools, examples, bench): no file over 350 lines and, with --functions, no function over 60 lines
# (clang-tidy's readability-function-size, LineThreshold 60: a few minutes on 2 cores). Prints
# each breach as file:line and exits 1 if there is one.
# Usage: tools/check_sizes.sh [--functions [BUILD_DIR]]   (BUILD_DIR: default build/ci, needs its
#        compile_commands.json)
set -euo pipefail
cd "$(dirname "$0")/.."
dirs=(app report io sim slam eval geometry stats plot tools examples bench)
mapfile -t files < <(find "${dirs[@]}" \( -name '*.cpp' -o -name '*.hpp' \) | sort)
status=0
for f in "${files[@]}"; do
  lines=$(wc -l <"$f")
  if [ "$lines" -gt 350 ]; then
    echo "$f:1: $lines lines (the limit is 350)"
    status=1
  fi
done
echo "check_sizes: ${#files[@]} files, none over 350 lines$([ $status -eq 0 ] || echo ': NO')"
if [ "${1:-}" = --functions ]; then
  build="${2:-build/ci}"
  [ -f "$build/compile_commands.json" ] || { echo "check_sizes: no $build/compile_commands.json"; exit 2; }
  mapfile -t sources < <(printf '%s\n' "${files[@]}" | grep '\.cpp$')
  found=$(printf '%s\n' "${sources[@]}" | xargs -P 2 -n 8 clang-tidy -p "$build" --quiet \
    -checks='-*,readability-function-size' \
    -config='{CheckOptions: [{key: readability-function-size.LineThreshold, value: 60}]}' \
    2>/dev/null | grep "warning: function" || true)
  if [ -n "$found" ]; then
    echo "$found"
    status=1
  fi
  echo "check_sizes: ${#sources[@]} source files, $(grep -c . <<<"$found" || true) functions" \
    "over 60 lines"
fi
exit $status
