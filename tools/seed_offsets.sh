#!/usr/bin/env bash
# The statistical tests on other random streams.
# A fixed-seed test of a statistic passes on its sample, not on its statistic: a bound at 95 %
# fails about once in 20 streams. Every statistical unit and library test draws from
# testing::seed(N) (tests/test_support.hpp), N plus the environment's MSISLAB_TEST_SEED_OFFSET;
# this runs ctest in BUILD_DIR N times (default 20) over those tests, run k with the offset
# k x STRIDE (k = 1..N), and prints per test how many of the N runs failed and under which
# offsets: a test's failure count against its stated false-alarm rate says whether its bound
# holds on its statistic or only on today's sample.
# STRIDE (environment MSISLAB_SEED_STRIDE, default 1000) keeps the runs apart: the tests that
# loop over seeds (make_loop(seed) for seed 1..10, the dead-reckoning NEES's runs 100..149) would
# share all but one of their seeds between offsets 1 and 2; 1000 is past the longest such range
# (50), so every run of N draws streams none of the others draw. MSISLAB_SEED_STRIDE=1 gives the
# offsets 1..N themselves.
# CTEST_REGEX (a ctest -R regex) picks the tests; the default lists the statistical tests that
# draw from testing::seed (tools/check_stat_bounds.sh lists the bounds among them that name no
# statistic). Each run's JUnit report and ctest output are kept in BUILD_DIR/seed_offsets/.
# Tests run one at a time (SEED_OFFSETS_JOBS, default 1, is ctest's -j).
# Takes N times one run of the tests: the default set (56 tests) runs in about 100 s on 2 cores
# in a Release build (mostly the slam recovery tests, 3-7 s each), so 20 runs take about 35
# minutes; a smaller N or a narrower CTEST_REGEX for a quick look.
# Usage: tools/seed_offsets.sh BUILD_DIR [N] [CTEST_REGEX]
# Exit status: 0 after the table (a report: failures are its content, not an error); 2 on bad
# arguments (no ctest tests in BUILD_DIR, N not a whole number of 1 or more, a regex that picks
# no test).
set -euo pipefail

usage() {
  echo "usage: tools/seed_offsets.sh BUILD_DIR [N] [CTEST_REGEX]" >&2
  exit 2
}

# The statistical tests wired to testing::seed, by ctest name (gtest's Suite.Test; the
# parameterised ones carry a prefix and an index).
default_tests=(
  'GaussianPose2MonteCarlo\.ComposeMatchesSampleCovariance'
  'GaussianPose2MonteCarlo\.InvertMatchesSampleCovariance'
  'ScanMatching\.RecoversAKnownPoseFromPerturbedGuesses'
  'ScanMatching\.ReciprocalAssociationRemovesTheShortMotionBiasInACanal'
  'ScanMatching\.CrossCovarianceOfTwoMatchesSharingTheCurrentScanMatchesMonteCarlo'
  'MatchValidation\.ACorridorMatchKeepsOnlyTheDirectionsTheWallsFix'
  'MatchValidation\.ARichSceneKeepsEveryDirection'
  'MatchValidation\.TheInitialGuessTermIsTheSpreadOfSpicFromTheGuess'
  'MatchValidation\.AWrongCorridorMatchDoesNotMoveTheFilterAlongTheAxis'
  'MatchValidation\.AClosedBasinIsNotAmbiguousAtAnyScale'
  'LinearisationError\.QuadraticMatchesItsClosedForm'
  'LinearisationError\.InversionGrowsWithTheHeadingUncertainty'
  'TrajectorySlam/BothMethods\.ClosesTheLoopBetterThanOdometry/.*'
  'TrajectorySlam/BothMethods\.CompassBoundsTheHeadingOfABlindRun/.*'
  'PoseGraph\.CovariancesAreConsistentWithTheTruth'
  'DeadReckoning\.ConsistentWhenTheModelHolds'
  'DeadReckoning\.ConsistentWithAWalkingHeadingBias'
  'DeadReckoning\.ConsistentWithAnUncertainDvlScale'
  'DeadReckoning\.MotionSinceKeyIsConsistent'
  'CalibrationStates\.RecoverThe[A-Za-z0-9]*'
  'PoseGraphHeadingBias\.(Whole|Windowed)GraphRecoversAWalkingCompassesBias'
  'PoseGraphScale\.(Whole|Windowed)GraphRecovers[A-Za-z0-9]*'
  'PoseGraphDeviation\.(Whole|Windowed)GraphRecoversTheCompassDeviation'
  'DifferenceNoise\.RecoversWhiteNoiseOnASmoothSignal'
  'DvlNoise\.RecoversSigmaRateAndSkipsGaps'
  'Dropouts\.IndependentLossesAreNotClustered'
  'HeadingNoise\.RecoversSigmaAcrossTheWrap'
  'Compasses\.RecoversOffsetAndDeviationCurve'
  'GpsStatistics\.RecoversAKnownLagTetherAndWhiteNoise'
  'GpsStatistics\.StructureFunctionOfAGaussMarkovError'
  'ContaminatedNormal\.[A-Za-z]*'
  'GilbertElliott\.[A-Za-z]*'
  'MonteCarlo\.ConsistentSamplesAreInsideAboutNinetyFivePercentOfTheTime'
  'DvlModel\.HeavyTailedNoiseHasTheMixturesMoments'
  'DvlModel\.DropoutsFollowTheTwoStateChain'
  'MruModel\.WhiteNoiseAndBiasRandomWalk'
  'GpsModel\.GaussMarkovErrorAndWhiteNoise'
  'NavigationNoise\.StatesWhatTheSimulatedSensorsDo'
  'SonarPhysics\.RoughnessFieldHasUnitVarianceEverywhereAndAFiniteMemory'
  'NavigationStatisticsStPere\.ReplicaMatchesTheRealStatistics'
)

[ $# -ge 1 ] && [ $# -le 3 ] || usage
build="$1"
runs="${2:-20}"
[ -f "$build/CTestTestfile.cmake" ] || {
  echo "seed_offsets.sh: no ctest tests in '$build' (configure and build it first)" >&2
  exit 2
}
[[ "$runs" =~ ^[0-9]+$ ]] && [ "$runs" -ge 1 ] || {
  echo "seed_offsets.sh: N must be a whole number of 1 or more, not '$runs'" >&2
  exit 2
}
stride="${MSISLAB_SEED_STRIDE:-1000}"
[[ "$stride" =~ ^[0-9]+$ ]] && [ "$stride" -ge 1 ] || {
  echo "seed_offsets.sh: MSISLAB_SEED_STRIDE must be a whole number of 1 or more" >&2
  exit 2
}
jobs="${SEED_OFFSETS_JOBS:-1}"
if [ $# -ge 3 ]; then
  regex="$3"
else
  regex="^($(IFS='|'; echo "${default_tests[*]}"))\$"
fi
build="$(cd "$build" && pwd)"
selected=$(ctest --test-dir "$build" -N -R "$regex" | sed -n 's/^Total Tests: //p')
[ "${selected:-0}" -gt 0 ] || {
  echo "seed_offsets.sh: the regex picks no test in $build: $regex" >&2
  exit 2
}

out="$build/seed_offsets"
mkdir -p "$out"
echo "seed_offsets.sh: $selected tests, $runs runs (MSISLAB_TEST_SEED_OFFSET = k x $stride," \
  "k = 1..$runs), reports in $out"
start=$(date +%s)
offsets=()
for k in $(seq 1 "$runs"); do
  offset=$((k * stride))
  offsets+=("$offset")
  t0=$(date +%s)
  # ctest exits 8 when a test fails: that is what is being counted.
  MSISLAB_TEST_SEED_OFFSET="$offset" ctest --test-dir "$build" -R "$regex" -j "$jobs" \
    --output-junit "$out/offset_$offset.xml" >"$out/offset_$offset.log" 2>&1 || true
  failed=$(grep -c 'status="fail"' "$out/offset_$offset.xml" 2>/dev/null || true)
  echo "seed_offsets.sh: offset $offset: ${failed:-?} of $selected failed ($(($(date +%s) - t0)) s)"
done

# One row per test: its failures over the runs and the offsets they failed under. A run whose
# report is missing (ctest did not finish) counts as a failure of every test, offset marked "!".
for offset in "${offsets[@]}"; do
  xml="$out/offset_$offset.xml"
  if [ -f "$xml" ]; then
    # CTest's JUnit: <testcase name="..." classname="..." time="..." status="run|fail|notrun|...">
    grep -o '<testcase name="[^"]*"[^>]*status="[a-z]*"' "$xml" |
      sed -E 's/<testcase name="([^"]*)".*status="([a-z]*)"/\1\t\2/' |
      sed -e 's/&quot;/"/g' -e "s/&apos;/'/g" -e 's/&lt;/</g' -e 's/&gt;/>/g' -e 's/&amp;/\&/g' |
      awk -F'\t' -v o="$offset" '{ print $1 "\t" o "\t" $2 }'
  else
    ctest --test-dir "$build" -N -R "$regex" | sed -n 's/^ *Test *#[0-9]*: //p' |
      awk -v o="$offset" '{ print $1 "\t" o "!\tfail" }'
  fi
done | awk -F'\t' -v n="$runs" '
  { seen[$1] = 1
    if ($3 == "fail") { fails[$1]++; where[$1] = where[$1] (where[$1] == "" ? "" : " ") $2 }
    else if ($3 != "run") { other[$1]++ } }
  END {
    for (t in seen) printf "%d\t%s\t%s\t%s\n", fails[t] + 0, t, where[t], other[t] + 0
  }' | sort -t$'\t' -k1,1nr -k2,2 | awk -F'\t' -v n="$runs" '
  BEGIN { printf "%-88s %9s  %s\n", "test", "failures", "offsets" }
  { printf "%-88s %5d/%-3d  %s%s\n", $2, $1, n, ($3 == "" ? "-" : $3),
           ($4 > 0 ? "  (not run or skipped in " $4 ")" : "")
    tests++; if ($1 > 0) failing++; total += $1 }
  END { printf "seed_offsets.sh: %d tests, %d failed at least once, %d failures in %d runs\n",
               tests, failing, total, n }'
echo "seed_offsets.sh: $(($(date +%s) - start)) s in all"
