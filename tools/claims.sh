#!/usr/bin/env bash
# Checks every figure the README's overview quotes (docs/claims.yaml) against the result folders
# it comes from, with `msislab check`, and writes out/claims.xml (JUnit). The folders are made by
# tools/results.sh (out/stpere, out/sim, out/montecarlo/stpere_replica_50runs) and
# tools/fidelity.sh (out/fidelity/report); tools/results.sh runs this script at its end. A figure
# that moved is a MISS naming the claim, its measured value and the claimed one: change the README
# and docs/claims.yaml together. Exit status: 0 all met, 1 a claim missed, 2 a folder missing.
# Usage: tools/claims.sh [--msislab EXE] [--partial]
#   --msislab: the executable (default build/release/tools/msislab)
#   --partial: a missing folder is said in one line and its claims are listed as not checked
set -euo pipefail
cd "$(dirname "$0")/.."

msislab=build/release/tools/msislab
partial=()
while [ $# -gt 0 ]; do
  case "$1" in
    --msislab) msislab="$2"; shift 2 ;;
    --partial) partial=(--partial); shift ;;
    -h|--help) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/claims.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$msislab" ] || { echo "tools/claims.sh: $msislab not built (see --help)" >&2; exit 2; }

results=()
for r in real=out/stpere sim=out/sim replica_mc=out/montecarlo/stpere_replica_50runs \
         fidelity=out/fidelity/report; do
  dir=${r#*=}
  if [ -d "$dir" ]; then
    results+=("$r")
  elif [ ${#partial[@]} -gt 0 ]; then
    echo "tools/claims.sh: $dir is missing: its claims are not checked"
  else
    echo "tools/claims.sh: $dir is missing: run tools/results.sh (and tools/fidelity.sh for" \
      "out/fidelity/report) first, or give --partial" >&2
    exit 2
  fi
done
mkdir -p out
"$msislab" check docs/claims.yaml ${results[@]+"${results[@]}"} ${partial[@]+"${partial[@]}"} \
  --junit out/claims.xml
