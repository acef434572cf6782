# Sourced by tools/fidelity.sh and tools/replica_verdict.sh (bash, set -euo pipefail).
# copy_without_truth SIM_DATASET DIR: the simulated dataset's logs, detections and calibration
# into DIR, without truth/, so that `msislab run DIR` scores against the simulated GPS buoy (with
# the buoy's own error) as the real run is scored against the real GPS.
copy_without_truth() {
  local sim="$1" dir="$2"
  mkdir -p "$dir"
  cp "$sim"/*_DVL.log "$sim"/*_MTi.log "$sim"/*_DGPS.log "$sim"/*_SETUP.log \
    "$sim"/*_IS_timestamps.log "$sim"/*_detections.csv.gz "$sim"/calibration.yaml "$dir"/
}
