#!/usr/bin/env bash
# The layering of docs/architecture.md, checked on the sources: each library includes project
# headers only from the libraries below it (stats, geometry < sim, slam < eval; sim < io, the file
# formats, which know no SLAM and no evaluation; eval, io < settings < dataset; eval, io < results
# < plot < report < app), so the dependency graph has no cycle, sim/ and slam/ do not know each
# other, and io/ reads and writes formats only.
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
  [io]="stats geometry sim io"
  [settings]="stats geometry sim slam eval io settings"
  [dataset]="stats geometry sim slam eval io settings dataset"
  [results]="stats geometry sim slam eval io results"
  [plot]="stats geometry sim slam eval io results plot"
  [report]="stats geometry sim slam eval io settings dataset results plot report"
  [app]="stats geometry sim slam eval io settings dataset results plot report app"
)
status=0
dirs=$(printf '%s\n' "${!allowed[@]}" | sort | tr '\n' ' ')
for dir in $dirs; do
  [ -d "$dir" ] || continue
  # One awk over the folder's includes (file:line:text): the folder each names, against the list.
  grep -rn '#include "' "$dir" --include='*.hpp' --include='*.cpp' |
    awk -v dir="$dir" -v allowed="${allowed[$dir]}" '
      { text = $0; sub(/^[^:]*:[^:]*:/, "", text) }
      match(text, /#include "[a-z_]*\//) {
        used = substr(text, RSTART + 10, RLENGTH - 11)
        if (used != "" && index(" " allowed " ", " " used " ") == 0) {
          split($0, at, ":")
          print at[1] ":" at[2] ": " dir "/ includes " used "/ (allowed: " allowed ")"
          bad = 1
        }
      }
      END { exit bad }' || status=1
done
# One namespace convention: the core a user's method composes with (stats, geometry, slam, eval)
# in msislab::, every other library in msislab::<its folder> (helpers nested inside either).
core=" stats geometry slam eval "
for dir in $dirs; do
  [ -d "$dir" ] || continue
  grep -rnE '^namespace msislab(::[a-z_:]+)? [{]' "$dir" --include='*.hpp' --include='*.cpp' |
    awk -v dir="$dir" -v core="$core" -v folders=" $dirs " '
      { split($0, at, ":"); text = $0; sub(/^[^:]*:[^:]*:namespace /, "", text); sub(/ [{].*/, "", text)
        outer = text; sub(/^msislab::/, "", outer); sub(/::.*/, "", outer)
        if (index(core, " " dir " ")) {
          bad_here = text != "msislab" && index(folders, " " outer " ")
          want = "msislab"
        } else {
          bad_here = outer != dir
          want = "msislab::" dir
        }
        if (bad_here) {
          print at[1] ":" at[2] ": " dir "/ code in namespace " text "; its namespace is " want
          bad = 1
        }
      }
      END { exit bad }' || status=1
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
# Running a method knows nothing of presentation: in app/, only the commands that draw or write
# pages (plot, report, fidelity) include report/; the method catalogue, run_method and the
# commands that run methods hand names to those, never styles or figures.
if [ -d app ]; then
  while IFS=: read -r file line text; do
    case "$(basename "$file")" in
      plot_command.* | report_command.* | fidelity_command.*) continue ;;
    esac
    echo "$file:$line: only the plot, report and fidelity commands include report/: $text"
    status=1
  done < <(grep -rnE '#include "report/' app --include='*.cpp' --include='*.hpp')
fi
[ "$status" -eq 0 ] && echo "layering holds: $dirs; one namespace per folder; app/ computes no" \
  "statistics; no command file includes another's; only the presentation commands include report/"
exit "$status"
