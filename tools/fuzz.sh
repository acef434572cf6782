#!/usr/bin/env bash
# Fuzzes every reader of outside input (tests/fuzz/reader_targets.cpp) with libFuzzer: builds its
# executable in the asan preset (clang, AddressSanitizer + UndefinedBehaviorSanitizer, the readers'
# libraries with libFuzzer's coverage; tools/sanitize.sh's build) and runs each target for
# SECONDS (default 60), two at a time (FUZZ_JOBS). Seeds: tests/fuzz/corpus/<target> and
# tests/fuzz/findings/<target> (read only); what the fuzzer adds goes to build/fuzz/corpus/<target>,
# kept between runs. A finding (a crash, a sanitizer report, an exception other than
# io::InputError, a timeout of 10 s, more than 2 GB) is saved to build/fuzz/findings/<target>/
# and makes the script exit 1; fix it and keep the input as tests/fuzz/findings/<target>/bad_<what>.
# Prints per target the executions, executions per second and coverage (libFuzzer's cov: edges,
# ft: features).
# Usage: tools/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
[[ "$seconds" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: SECONDS must be a whole number" >&2; exit 2; }
jobs="${FUZZ_JOBS:-2}"
targets=("$@")
for target in "${targets[@]}"; do
  if [ ! -d "tests/fuzz/corpus/$target" ]; then
    echo "fuzz.sh: no target '$target' (targets: $(ls tests/fuzz/corpus | paste -sd ' '))" >&2
    exit 2
  fi
done

tools/install_deps.sh
tools/configure.sh asan >/dev/null
cmake --build --preset asan --target msislab_fuzz_readers
fuzzer="$PWD/build/asan/tests/fuzz/msislab_fuzz_readers"

if [ ${#targets[@]} -eq 0 ]; then
  # tests/fuzz/corpus_test.cpp checks that these folders are exactly the targets.
  mapfile -t targets < <(find tests/fuzz/corpus -mindepth 1 -maxdepth 1 -type d -printf '%f\n' |
                           sort)
fi

export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
logs="build/fuzz/logs"
mkdir -p "$logs"

fuzz_one() {
  local target="$1"
  mkdir -p "build/fuzz/corpus/$target" "build/fuzz/findings/$target"
  local seeds=("tests/fuzz/corpus/$target")
  [ -d "tests/fuzz/findings/$target" ] && seeds+=("tests/fuzz/findings/$target")
  local status=0
  MSISLAB_FUZZ_TARGET="$target" "$fuzzer" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="build/fuzz/findings/$target/" \
    "build/fuzz/corpus/$target" "${seeds[@]}" >"$logs/$target.log" 2>&1 || status=$?
  echo "$status" >"$logs/$target.status"
}

echo "fuzz.sh: ${#targets[@]} targets, ${seconds} s each, ${jobs} at a time"
start=$(date +%s)
running=0
for target in "${targets[@]}"; do
  rm -f "$logs/$target.status"
  fuzz_one "$target" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n
    running=$((running - 1))
  fi
done
wait
failed=()
for target in "${targets[@]}"; do
  [ "$(cat "$logs/$target.status")" = 0 ] || failed+=("$target")
done

printf '%-22s %10s %8s %7s %7s %7s  %s\n' target executions exec/s cov ft corpus result
for target in "${targets[@]}"; do
  log="$logs/$target.log"
  runs=$(grep -oP 'stat::number_of_executed_units: +\K[0-9]+' "$log" || echo "?")
  rate=$(grep -oP 'stat::average_exec_per_sec: +\K[0-9]+' "$log" || echo "?")
  # The last status line: "#N DONE cov: C ft: F corp: K/..." (or the last pulse before a finding).
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(grep -oP 'cov: \K[0-9]+' <<<"$last" || echo "?")
  ft=$(grep -oP 'ft: \K[0-9]+' <<<"$last" || echo "?")
  corp=$(grep -oP 'corp: \K[0-9]+' <<<"$last" || echo "?")
  result="ok"
  if printf '%s\n' "${failed[@]}" | grep -qx "$target"; then
    result="FINDING: $(ls -t "build/fuzz/findings/$target" | head -1), see $log"
  fi
  printf '%-22s %10s %8s %7s %7s %7s  %s\n' "$target" "$runs" "$rate" "$cov" "$ft" "$corp" \
    "$result"
done
echo "fuzz.sh: $(( $(date +%s) - start )) s"
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz.sh: ${#failed[@]} target(s) with a finding: ${failed[*]}" >&2
  exit 1
fi
