#!/usr/bin/env bash
# A CI job that gates a SLAM method on simulation, without real data: seeded runs of a scenario
# with your method (here the Python dead reckoning of examples/external_method) beside msislab's
# own dead reckoning, then `msislab check` against the stated expectations (expectations.yaml).
# It fails (exit 1) when an expectation is missed, 3 when a run failed, 2 on bad input, and leaves
# a JUnit report for the CI to display (docs/cli.md, "msislab check").
# Usage: examples/ci_gate/ci_job.sh OUT_DIR [SCENARIO.yaml]   (MSISLAB: the executable; default
#        msislab on the PATH)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ $# -ge 1 ] || { echo "usage: $0 OUT_DIR [SCENARIO.yaml]" >&2; exit 2; }
out=$1
scenario=${2:-$here/../../scenarios/small_basin.yaml}
msislab=${MSISLAB:-msislab}

"$msislab" montecarlo "$scenario" --runs 4 --jobs 2 --no-plot \
  --methods deadreckoning,mydr --methods-file "$here/../external_method/methods.yaml" \
  --out "$out/montecarlo"
"$msislab" check "$here/expectations.yaml" "basin=$out/montecarlo" --junit "$out/check.xml"
