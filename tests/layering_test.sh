#!/usr/bin/env bash
# The layering of docs/architecture.md, checked on the sources: each library includes project
# headers only from the libraries below it (stats, geometry < sim, slam < eval < io < plot <
# app), so the dependency graph has no cycle and sim/ and slam/ do not know each other. Prints every
# include that breaks it as file:line and fails; CMake's target links say the same, this says it
# before anything is linked.
# Usage: tests/layering_test.sh SOURCE_DIR
set -euo pipefail
cd "${1:?usage: tests/layering_test.sh SOURCE_DIR}"

declare -A allowed=(
  [stats]="stats"
  [geometry]="geometry"
  [sim]="stats geometry sim"
  [slam]="stats geometry slam"
  [eval]="stats geometry sim slam eval"
  [io]="stats geometry sim slam eval io"
  [plot]="stats geometry sim slam eval io plot"
  [app]="stats geometry sim slam eval io plot app"
)
status=0
dirs=$(printf '%s\n' "${!allowed[@]}" | sort | tr '\n' ' ')
for dir in $dirs; do
  [ -d "$dir" ] || continue
  while IFS=: read -r file line text; do
    used=$(sed -n 's/.*#include "\([a-z_]*\)\/.*/\1/p' <<<"$text")
    [ -n "$used" ] || continue
    case " ${allowed[$dir]} " in
      *" $used "*) ;;
      *) echo "$file:$line: $dir/ includes $used/ (allowed: ${allowed[$dir]})"; status=1 ;;
    esac
  done < <(grep -rn '#include "' "$dir" --include='*.hpp' --include='*.cpp')
done
[ "$status" -eq 0 ] && echo "layering holds: $dirs"
exit "$status"
