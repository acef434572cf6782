# Sourced by tools/results.sh and tools/robocentric_study.sh (bash, set -euo pipefail).
# run_fresh DIR COMMAND...: runs a resumable msislab command writing DIR (montecarlo, sweep),
# its stderr shown and kept. When DIR was made by another msislab build or from another scenario
# (or, for a sweep, from another sweep file), the directory is stale for the caller's page: it is
# removed and the command run again from scratch. Any other failure exits 2.
run_fresh() {
  local dir="$1"
  shift
  mkdir -p "$(dirname "$dir")"
  # pipefail: the pipeline fails when the command does; tee has finished by then
  if ! { "$@" 2>&1 1>&3 | tee "$dir.stderr" >&2; } 3>&1; then
    if grep -q "made by another msislab build\|holds the cells of another sweep\|holds runs of another scenario" "$dir.stderr"; then
      echo "== $dir was made by another build or input file: running it again from scratch"
      rm -rf "$dir"
      "$@"
    else
      rm -f "$dir.stderr"
      exit 2
    fi
  fi
  rm -f "$dir.stderr"
}
