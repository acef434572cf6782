#!/usr/bin/env bash
# The layering of docs/architecture.md, checked on the sources: each library includes project
# headers only from the libraries below it (stats, geometry < sim, slam < eval < io < plot <
# report < app), so the dependency graph has no cycle and sim/ and slam/ do not know each other.
# Prints every include that breaks it as file:line and fails; CMake's target links say the same,
# this says it before anything is linked. And app/ defines no statistics or numerical estimation
# (below).
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
  [report]="stats geometry sim slam eval io plot report"
  [app]="stats geometry sim slam eval io plot report app"
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
# app/ reads inputs, calls the libraries and writes results: no statistics or numerical estimation
# of its own (those live in stats/ and eval/, where users and tests can call them). Caught: the
# numerical parts of Eigen and Boost.Math, decompositions and solves, selection for order
# statistics, special functions, and a definition of a statistic by name.
numerics='#include <(Eigen/(Dense|Cholesky|LU|QR|SVD|Eigenvalues)|boost/math/)'
numerics+='|std::nth_element|[.](ldlt|llt|solve|inverse|jacobiSvd|bdcSvd)[(]'
numerics+='|std::(lgamma|erfc?|tgamma)[(]'
numerics+='|^[A-Za-z_][A-Za-z0-9_:<>,]*( [A-Za-z0-9_:<>,]+)*[ *&]+([a-z0-9]+_)*'
numerics+='(quantile|median|mean|variance|stddev|covariance|ks_distance|chi2|fit)(_[a-z0-9_]+)?[(]'
if [ -d app ]; then
  while IFS=: read -r file line text; do
    echo "$file:$line: app/ computes statistics or estimates; move it to stats/ or eval/: $text"
    status=1
  done < <(grep -rnE "$numerics" app --include='*.hpp' --include='*.cpp')
fi
# A command file (app/X_command.cpp and .hpp: its options, its messages, the call) uses the units
# of app/ and the libraries, never another command's file: what two commands share is a unit.
if [ -d app ]; then
  while IFS=: read -r file line text; do
    own=$(basename "$file")
    used=$(sed -n 's/.*#include "app\/\([a-z_]*_command\)\.hpp".*/\1/p' <<<"$text")
    [ "$used" = "${own%.*}" ] && continue
    echo "$file:$line: a command file includes another command's app/$used.hpp; move what" \
      "both use into a unit of app/"
    status=1
  done < <(grep -rnE '#include "app/[a-z_]+_command[.]hpp"' app --include='*_command.cpp' \
             --include='*_command.hpp')
fi
[ "$status" -eq 0 ] && echo "layering holds: $dirs; app/ computes no statistics; no command" \
  "file includes another's"
exit "$status"
