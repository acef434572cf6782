#!/usr/bin/env bash
# Checks the real St. Pere dataset against the digests msislab pins for it
# (tools/datasets/stpere.sha256, through tools/check_dataset.sh), so that the tests never pass on a
# damaged or different copy, even one that brings its own SHA256SUMS. tools/test.sh runs it before
# the build whenever the folder exists.
# Usage: tools/check_stpere.sh [DIR]   (DIR: default $MSISLAB_STPERE_DIR, else
#        ../shared/datasets/stpere from the repository root)
# Exit 0 and one line when every pinned file matches; exit 2 and one line naming the files that do
# not match (or are missing or unreadable), or the folder that is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
exec tools/check_dataset.sh stpere "${1:-${MSISLAB_STPERE_DIR:-../shared/datasets/stpere}}"
