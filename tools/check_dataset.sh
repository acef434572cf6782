#!/usr/bin/env bash
# Checks a real dataset's files against the digests msislab pins for it (tools/datasets/NAME.sha256,
# committed with the code), never against a list that travels with the copy: a different or altered
# copy that brings its own SHA256SUMS still fails. tools/test.sh runs it before the build for every
# dataset folder that exists (St. Pere through tools/check_stpere.sh, the Ping360 tank).
# Usage: tools/check_dataset.sh NAME [DIR]   (NAME: stpere or ping360_tank; DIR: default
#        ../shared/datasets/NAME from the repository root)
# Exit 0 and one line when every pinned file matches; exit 2 and one line naming the files that do
# not match (or are missing or unreadable), or the folder that is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
name="tools/check_dataset.sh"
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $name NAME [DIR]" >&2
  exit 2
fi
pinned="tools/datasets/$1.sha256"
if [ ! -f "$pinned" ]; then
  known=$(cd tools/datasets && ls -- *.sha256 | sed 's/\.sha256$//' | paste -sd, - | sed 's/,/, /g')
  echo "$name: no pinned digests for a dataset '$1' (known: $known)" >&2
  exit 2
fi
dir="${2:-../shared/datasets/$1}"
if [ ! -d "$dir" ]; then
  echo "$name: $dir: no such folder (the real $1 dataset)" >&2
  exit 2
fi
# --strict: a malformed line fails too. Only the failures are printed ("FILE: FAILED ...").
pinned_abs="$PWD/$pinned"
if report=$(cd "$dir" && sha256sum --check --strict --quiet "$pinned_abs" 2>/dev/null); then
  echo "$name: $dir matches msislab's pinned digests ($pinned, $(grep -c . "$pinned") files)"
  exit 0
fi
mapfile -t failed < <(printf '%s\n' "$report" | sed -n 's/: FAILED.*$//p')
if [ ${#failed[@]} -eq 0 ]; then
  echo "$name: $pinned: malformed (sha256sum --check --strict refuses it)" >&2
  exit 2
fi
files=$(printf "$dir/%s, " "${failed[@]}")
echo "$name: ${files%, }: does not match msislab's pinned digest ($pinned): damaged, changed," \
  "missing or not the real dataset" >&2
exit 2
