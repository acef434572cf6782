#!/usr/bin/env bash
# The second test command (docs/reliability.md): the unit and library tests again under
# AddressSanitizer + UndefinedBehaviorSanitizer (tools/sanitize.sh; the end-to-end command tests
# run once, in tools/test.sh, not under the sanitizers), then every reader fuzzed for FUZZ_SECONDS
# (default 20) each (tools/fuzz.sh). CI (.ci/run) runs it after tools/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

start=$(date +%s)
stage=$start
stamp() {
  local now
  now=$(date +%s)
  echo "reliability.sh: $1 took $((now - stage)) s ($((now - start)) s in all)"
  stage=$now
}
tools/sanitize.sh
stamp "sanitizer suite"
tools/fuzz.sh "${FUZZ_SECONDS:-20}"
stamp "fuzzing"
