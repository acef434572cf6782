#!/usr/bin/env bash
# Times the issue-15 target: the pose graph on the whole real St. Pere run in under 5 s, the
# final smoothing included. Runs `msislab run` with posegraph and, for reference, robocentric on
# the real dataset N times (default 3) and prints each method's run time as metrics.json records
# it (the method alone, its inputs read) and the whole command's wall time, then the median's
# ratio to the target. Timings are figures, not pass/fail.
# Usage: tools/bench_posegraph.sh [--repeat N]   (after a release build; needs the real dataset)
set -euo pipefail
cd "$(dirname "$0")/.."

repeat=3
while [ $# -gt 0 ]; do
  case "$1" in
    --repeat) repeat="$2"; shift 2 ;;
    -h|--help) sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "tools/bench_posegraph.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

msislab=build/release/tools/msislab
build="cmake --preset release && cmake --build --preset release"
[ -x "$msislab" ] || { echo "tools/bench_posegraph.sh: build first ($build)" >&2; exit 2; }
stpere="${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}"
[ -f "$stpere/_040825_1735_DVL.log" ] || {
  echo "tools/bench_posegraph.sh: no real St. Pere dataset at $stpere (MSISLAB_STPERE_DIR)" >&2
  exit 2
}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for method in posegraph robocentric; do
  times=()
  for i in $(seq "$repeat"); do
    start=$(date +%s.%N)
    "$msislab" run "$stpere" --method "$method" --out "$out/$method" --config config/stpere.yaml \
      >/dev/null
    end=$(date +%s.%N)
    runtime=$(sed -n 's/.*"runtime_s": \([0-9.e+-]*\).*/\1/p' "$out/$method/metrics.json")
    times+=("$runtime")
    awk -v m="$method" -v r="$runtime" -v s="$start" -v e="$end" -v i="$i" 'BEGIN {
      printf "%s run %d: %.2f s (metrics.json runtime_s), whole command %.2f s wall\n",
        m, i, r, e - s }'
  done
  printf '%s\n' "${times[@]}" | sort -g | awk -v m="$method" '
    { v[NR] = $1 } END {
      t = v[int((NR + 1) / 2)]
      printf "%s: median %.2f s, %.2fx under the 5 s target\n", m, t, 5.0 / t }'
done
