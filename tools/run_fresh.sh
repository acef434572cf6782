# shellcheck shell=bash
# Sourced by the tools/ scripts that write under out/ (bash, set -euo pipefail).
# run_fresh DIR COMMAND...: runs a resumable msislab command writing DIR (montecarlo, sweep),
# its stderr shown and kept. When DIR was made by another msislab build or from another scenario
# (or, for a sweep, from another sweep file), the directory is stale for the caller's page: it is
# removed and the command run again from scratch. When runs failed (exit 3: the summary is written,
# with holes) the caller stops with that status rather than publish it. Any other failure exits 2.
run_fresh() {
  local dir="$1" status=0
  shift
  mkdir -p "$(dirname "$dir")"
  # pipefail: the pipeline fails when the command does; tee has finished by then
  { "$@" 2>&1 1>&3 | tee "$dir.stderr" >&2; } 3>&1 || status=$?
  if [ "$status" -ne 0 ] &&
    grep -q "made by another msislab build\|holds the cells of another sweep\|holds runs of another scenario" "$dir.stderr"; then
    echo "== $dir was made by another build or input file: running it again from scratch"
    rm -rf "$dir"
    status=0
    "$@" || status=$?
  fi
  rm -f "$dir.stderr"
  if [ "$status" -eq 3 ]; then
    echo "== $dir: runs failed (their failed.json named above); stopping before anything is" \
      "published from it" >&2
    exit 3
  fi
  [ "$status" -eq 0 ] || exit 2
}

# claim_out_folder SCRIPT DIR: makes DIR this script's folder (the marker DIR/.NAME, NAME the
# folder's own name), refusing, exit 2, a non-empty DIR without that marker: a script writes its
# scenarios and configs beside the results only into a folder it made (msislab itself replaces
# only the result folders it wrote, docs/cli.md).
claim_out_folder() {
  local script="$1" dir="$2"
  local marker
  marker="$dir/.$(basename "$dir")"
  if [ -d "$dir" ] && [ -n "$(ls -A "$dir")" ] && [ ! -f "$marker" ]; then
    echo "$script: $dir exists and was not written by this script; refusing" >&2
    exit 2
  fi
  mkdir -p "$dir"
  touch "$marker"
}

# parse_table_options SCRIPT KIND ARGS...: the options of a table script into the caller's
# variables, set to their defaults before the call: --msislab EXE into `msislab`, and, for KIND
# montecarlo (a Monte Carlo table; KIND single: none), --runs N into `runs`. Anything else, a
# --runs that is not a count or an msislab that is not there: one line naming SCRIPT, exit 2.
parse_table_options() {
  local script="$1" kind="$2" usage="[--msislab EXE]"
  shift 2
  [ "$kind" = montecarlo ] && usage="[--runs N] $usage"
  while [ $# -gt 0 ]; do
    case "$1" in
      --runs) [ "$kind" = montecarlo ] || break; runs="${2:?--runs needs a count}"; shift 2 ;;
      --msislab) msislab="${2:?--msislab needs a path}"; shift 2 ;;
      *) break ;;
    esac
  done
  if [ $# -gt 0 ]; then
    echo "$script: unknown argument '$1' (usage: $usage)" >&2
    exit 2
  fi
  if [ "$kind" = montecarlo ] && ! [[ "$runs" =~ ^[1-9][0-9]*$ ]]; then
    echo "$script: --runs '$runs' is not a count" >&2
    exit 2
  fi
  [ -x "$msislab" ] || { echo "$script: no $msislab (build first)" >&2; exit 2; }
}

# msislab_or_build SCRIPT: the msislab the caller runs, into its variable `msislab`: the one its
# --msislab named (one line naming SCRIPT, exit 2, when that is not an executable), else the
# release build's, built first (the packages it needs installed when missing).
msislab_or_build() {
  local script="$1"
  if [ -n "$msislab" ]; then
    [ -x "$msislab" ] || { echo "$script: --msislab '$msislab' is not an executable" >&2; exit 2; }
  else
    tools/install_deps.sh run
    tools/configure.sh release
    cmake --build --preset release --target msislab
    msislab=build/release/tools/msislab
  fi
}

# page_marker SCRIPT PAGE: the first line SCRIPT writes on PAGE (docs/ pages a study writes),
# printed; refuses, exit 2, when PAGE exists and does not start with it (a page someone else wrote).
# Use as marker=$(page_marker SCRIPT PAGE), which set -e ends on refusal.
page_marker() {
  local script="$1" page="$2"
  local marker="<!-- written by $script; it replaces this file only when it starts with this line -->"
  if [ -f "$page" ] && [ "$(head -n 1 "$page")" != "$marker" ]; then
    echo "$script: $page was not written by this script; refusing to replace it" >&2
    exit 2
  fi
  echo "$marker"
}
