// Navigation front end speed: reading the St. Pere logs and running dead reckoning over the whole
// 3343 s run. Real-data cases report an error (not a failure) when the dataset is absent.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "dataset/dataset.hpp"
#include "io/detections.hpp"
#include "io/stpere_logs.hpp"
#include "slam/dead_reckoning.hpp"

namespace {

const std::string kStPere = MSISLAB_STPERE_DIR;

bool have_stpere(benchmark::State& state) {
  if (std::filesystem::exists(kStPere + "/_040825_1735_DVL.log")) return true;
  state.SkipWithError(("St. Pere dataset not found at " + kStPere).c_str());
  return false;
}

void BM_ReadMtiLog(benchmark::State& state) {
  if (!have_stpere(state)) return;
  for (auto _ : state) {
    benchmark::DoNotOptimize(msislab::io::read_mti_log(kStPere + "/_040825_1735_MTi.log"));
  }
  state.SetItemsProcessed(state.iterations() * 33457);
}
BENCHMARK(BM_ReadMtiLog)->Unit(benchmark::kMillisecond);

void BM_ReadDetections(benchmark::State& state) {
  if (!have_stpere(state)) return;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        msislab::io::read_detections(kStPere + "/_040825_1735_detections.csv.gz"));
  }
  state.SetItemsProcessed(state.iterations() * 1092064);
}
BENCHMARK(BM_ReadDetections)->Unit(benchmark::kMillisecond);

void BM_DeadReckoningWholeRun(benchmark::State& state) {
  if (!have_stpere(state)) return;
  const auto files = msislab::dataset::find_dataset_files(kStPere);
  const auto navigation = msislab::dataset::load_navigation(files, msislab::Calibration{});
  msislab::StampedPose start;
  start.t_s = navigation.heading.front().t_s;
  start.pose.mean = msislab::Pose2(0.0, 0.0, navigation.heading.front().yaw_rad);
  const msislab::DeadReckoningConfig config;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        msislab::run_dead_reckoning(navigation, config, Eigen::Vector2d::Zero(), start));
  }
  state.SetItemsProcessed(
      state.iterations() *
      static_cast<std::int64_t>(navigation.dvl.size() + navigation.heading.size()));
}
BENCHMARK(BM_DeadReckoningWholeRun)->Unit(benchmark::kMillisecond);

}  // namespace
