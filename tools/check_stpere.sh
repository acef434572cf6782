#!/usr/bin/env bash
# Checks the real St. Pere dataset against its own SHA256SUMS (sha256sum -c in its folder), so that
# the tests never pass on a damaged or different copy. tools/test.sh runs it before the build
# whenever the folder exists.
# Usage: tools/check_stpere.sh [DIR]   (DIR: default $MSISLAB_STPERE_DIR, else
#        ../shared/datasets/stpere from the repository root)
# Exit 0 and one line when every listed file matches; exit 2 and one line naming the files that do
# not match (or cannot be read), or the folder or SHA256SUMS that is missing or malformed.
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${1:-${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}}"
name="tools/check_stpere.sh"

if [ ! -d "$dir" ]; then
  echo "$name: $dir: no such folder (the real St. Pere dataset)" >&2
  exit 2
fi
if [ ! -f "$dir/SHA256SUMS" ]; then
  echo "$name: $dir/SHA256SUMS: missing, so the dataset cannot be checked" >&2
  exit 2
fi
# --strict: a malformed line fails too. Only the failures are printed ("FILE: FAILED ...").
if report=$(cd "$dir" && sha256sum --check --strict --quiet SHA256SUMS 2>/dev/null); then
  echo "$name: $dir matches its SHA256SUMS ($(grep -c . "$dir/SHA256SUMS") files)"
  exit 0
fi
mapfile -t failed < <(printf '%s\n' "$report" | sed -n 's/: FAILED.*$//p')
if [ ${#failed[@]} -eq 0 ]; then
  echo "$name: $dir/SHA256SUMS: malformed (sha256sum --check --strict refuses it)" >&2
  exit 2
fi
files=$(printf "$dir/%s, " "${failed[@]}")
echo "$name: ${files%, }: does not match $dir/SHA256SUMS (damaged, changed or unreadable)" >&2
exit 2
