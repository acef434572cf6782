// `msislab plot`: the figures of a result directory, of a folder of results (small_basin simulated
// and run with dead reckoning and world-centric SLAM) and of a Monte Carlo directory are written,
// decodable, of the requested size, not blank, and show the methods' colours; bad input exits 2.
// Drawing needs an X display: CMake runs this test under `xvfb-run -a` when it is installed; with
// no display at all the drawing tests skip.
#include "app/plot_command.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "app/run_command.hpp"
#include "app/simulate_command.hpp"
#include "cli_runner.hpp"
#include "io/input_error.hpp"
#include "io/output_guard.hpp"
#include "plot/display.hpp"
#include "report/plot_figures.hpp"
#include "report/sweep_figures.hpp"
#include "results/results.hpp"
#include "results/sweep_files.hpp"
#include "test_support.hpp"

namespace msislab::app {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::run_msislab;
using testing::shell_quote;
using testing::TempDir;
using testing::write_text;

#define REQUIRE_X_DISPLAY()                                                                 \
  do {                                                                                      \
    if (!plot::x_display_available())                                                       \
      GTEST_SKIP() << "no X display: VTK cannot draw (run under `xvfb-run -a`, or install " \
                      "xvfb and xauth so that CMake does)";                                 \
  } while (0)

/// small_basin simulated once, with a dead-reckoning and a world-centric result beside it.
class PlotCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new TempDir;
    const std::string scenario = std::string(MSISLAB_SOURCE_DIR) + "/scenarios/small_basin.yaml";
    simulate({scenario, dir("small_basin"), std::nullopt, 2});
    run({dir("small_basin"), "deadreckoning", dir("deadreckoning"), ""});
    run({dir("small_basin"), "worldcentric", dir("worldcentric"), ""});
  }
  static void TearDownTestSuite() {
    delete tmp_;
    tmp_ = nullptr;
  }
  static std::string dir(const std::string& name) { return tmp_->file(name); }
  static TempDir* tmp_;
};
TempDir* PlotCommand::tmp_ = nullptr;

/// Pixels within a small distance of a colour given as 0xRRGGBB.
int pixels_of(const cv::Mat& image, std::uint32_t rgb) {
  const cv::Vec3i bgr(rgb & 0xff, rgb >> 8 & 0xff, rgb >> 16 & 0xff);
  int n = 0;
  for (auto it = image.begin<cv::Vec3b>(); it != image.end<cv::Vec3b>(); ++it) {
    const cv::Vec3i d = cv::Vec3i(*it) - bgr;
    n += std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]) < 40;
  }
  return n;
}

/// The PNG decodes at the given size, is mostly white (the background) but not blank, and shows
/// each colour (in more than min_pixels pixels: slanted lines are mostly anti-aliased).
void expect_figure(const std::string& path, int width, int height,
                   const std::vector<std::uint32_t>& colours, int min_pixels = 200) {
  SCOPED_TRACE(path);
  ASSERT_TRUE(fs::is_regular_file(path));
  EXPECT_GT(fs::file_size(path), 1000u);
  const cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty()) << "not decodable";
  EXPECT_EQ(image.cols, width);
  EXPECT_EQ(image.rows, height);
  const int total = image.cols * image.rows;
  const int white = pixels_of(image, 0xffffff);
  EXPECT_GT(white, total / 3) << "the background is not white";
  EXPECT_GT(total - white, total / 100) << "blank figure";
  for (const std::uint32_t rgb : colours) {
    EXPECT_GT(pixels_of(image, rgb), min_pixels) << "colour " << std::hex << rgb << " is missing";
  }
}

TEST_F(PlotCommand, ResultDirectoryGetsTrajectoryErrorAndAcousticImage) {
  REQUIRE_X_DISPLAY();
  report::PlotOptions options;
  options.dir = dir("worldcentric");
  const std::vector<std::string> written = plot(options);
  const fs::path figures = fs::path(dir("worldcentric")) / "figures";
  const std::vector<std::string> expected = {(figures / "trajectory.png").string(),
                                             (figures / "error.png").string(),
                                             (figures / "acoustic_image.png").string()};
  EXPECT_EQ(written, expected);
  const std::uint32_t blue = report::MethodStyles().colour("worldcentric");
  expect_figure(expected[0], 1200, 900, {blue, 0x202020});
  expect_figure(expected[1], 1200, 900, {blue});
  expect_figure(expected[2], 1200, 900, {});
  for (const fs::directory_entry& e : fs::directory_iterator(figures)) {
    if (e.path().filename() == io::kOutputMarkerName) continue;  // msislab's own marker
    EXPECT_EQ(e.path().extension(), ".png") << "a temporary file is left: " << e.path();
  }
}

TEST_F(PlotCommand, FolderOfResultsGetsComparisonFigures) {
  REQUIRE_X_DISPLAY();
  report::PlotOptions options;
  options.dir = tmp_->path().string();
  options.width_px = 1000;
  options.height_px = 800;
  const std::vector<std::string> written = plot(options);
  EXPECT_EQ(written.size(), 8u);  // 3 comparison, 2 x 2 per result, 1 acoustic image
  const fs::path figures = tmp_->path() / "figures";
  const std::uint32_t red = report::MethodStyles().colour("deadreckoning"),
                      blue = report::MethodStyles().colour("worldcentric");
  expect_figure((figures / "deadreckoning.png").string(), 1000, 800, {red, 0x202020});
  expect_figure((figures / "worldcentric.png").string(), 1000, 800, {blue, 0x202020});
  expect_figure((figures / "errors.png").string(), 1000, 800, {red, blue});
  EXPECT_TRUE(fs::is_regular_file(figures / "acoustic_image.png"));
  for (const char* method : {"deadreckoning", "worldcentric"}) {
    for (const char* figure : {"trajectory.png", "error.png"}) {
      EXPECT_TRUE(fs::is_regular_file(fs::path(dir(method)) / "figures" / figure))
          << method << "/" << figure;
    }
  }
}

std::string write_monte_carlo_dir(const TempDir& tmp) {
  const std::string mc = tmp.file("mc");
  fs::create_directories(mc);
  std::string csv = "method,scan,runs,mean_nees,lower,upper\n";
  for (int scan = 0; scan < 40; ++scan) {
    csv += "worldcentric," + std::to_string(scan) + ",25," + std::to_string(2.5 + 0.02 * scan) +
           ",2.12,4.03\n";
  }
  for (int scan = 0; scan < 40; ++scan) {
    csv += "deadreckoning," + std::to_string(scan) + ",25," + std::to_string(1.5 + 0.4 * scan) +
           ",2.12,4.03\n";
  }
  write_text(mc + "/nees.csv", csv);
  write_text(mc + "/summary.json", "{\"worldcentric\": {\"runs\": 25}}\n");
  return mc;
}

TEST(PlotMonteCarlo, NeesFigure) {
  REQUIRE_X_DISPLAY();
  const TempDir tmp;
  const std::string mc = write_monte_carlo_dir(tmp);
  const std::vector<std::string> written = plot({mc, "", 0, 1200, 900, -1});
  ASSERT_EQ(written.size(), 1u);
  EXPECT_EQ(written[0], mc + "/figures/nees.png");
  expect_figure(written[0], 1200, 900,
                {report::MethodStyles().colour("worldcentric"),
                 report::MethodStyles().colour("deadreckoning")});
}

// With the spread files the Monte Carlo directory gets its three figures: NEES, the error against
// time (mean and 5-95 % band per method) and the error distribution.
TEST(PlotMonteCarlo, SpreadFigures) {
  REQUIRE_X_DISPLAY();
  const TempDir tmp;
  const std::string mc = write_monte_carlo_dir(tmp);
  std::string spread = "method,t_s,runs,mean_m,p05_m,p50_m,p95_m\n";
  std::string histogram = "method,lower_m,upper_m,fraction\n";
  for (const auto& [method, scale] : {std::pair{"worldcentric", 1.0}, {"deadreckoning", 3.0}}) {
    for (int t = 0; t < 60; ++t) {
      const double e = scale * 0.05 * t;
      spread += std::string(method) + "," + std::to_string(t) + ",25," + std::to_string(e) + "," +
                std::to_string(0.5 * e) + "," + std::to_string(e) + "," + std::to_string(1.8 * e) +
                "\n";
    }
    for (int b = 0; b < 10; ++b) {
      histogram +=
          std::string(method) + "," + std::to_string(b) + "," + std::to_string(b + 1) + "," +
          std::to_string(method == std::string("worldcentric") ? (b < 5 ? 0.2 : 0.0) : 0.1) + "\n";
    }
  }
  write_text(mc + "/errors.csv", spread);
  write_text(mc + "/error_histogram.csv", histogram);
  const std::vector<std::string> written = plot({mc, "", 0, 1200, 900, -1});
  ASSERT_EQ(written,
            (std::vector<std::string>{mc + "/figures/nees.png", mc + "/figures/error_spread.png",
                                      mc + "/figures/error_distribution.png"}));
  for (const std::string& figure : written) {
    expect_figure(figure, 1200, 900,
                  {report::MethodStyles().colour("worldcentric"),
                   report::MethodStyles().colour("deadreckoning")});
  }
  // A malformed spread file is one clear error naming it.
  write_text(mc + "/errors.csv",
             "method,t_s,runs,mean_m,p05_m,p50_m,p95_m\nworldcentric,1,0,1,1,1,1\n");
  try {
    plot({mc, "", 0, 1200, 900, -1});
    ADD_FAILURE() << "no InputError";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(mc + "/errors.csv:2"), std::string::npos) << e.what();
  }
}

// A sweep directory: per swept key, the mean error (with its band) and the ANEES against it.
/// A 3 x 2 grid of heading noise and IEKF iterations, robocentric and dead reckoning, with the
/// paired differences and (robocentric) linearisation errors.
results::SweepTable grid_table() {
  results::SweepTable table;
  table.keys = {"scenario.mru.heading_noise_deg", "slam.trajectory_slam.iekf_iterations"};
  int cell = 0;
  for (const double noise : {0.5, 1.0, 2.0}) {
    for (const int iterations : {1, 5}) {
      for (const auto& [method, scale] : {std::pair{"robocentric", 1.0}, {"deadreckoning", 2.0}}) {
        const double e = scale * noise * (1.0 + 0.1 * iterations);  // no two lines coincide
        results::SweepRow r;
        r.cell = cell;
        r.values = {std::to_string(noise), std::to_string(iterations)};
        r.method = method;
        r.runs = 20;
        r.mean_error_m = e;
        r.p05_m = 0.5 * e;
        r.p50_m = e;
        r.p95_m = 1.5 * e;
        r.anees = 2.0 + noise;
        r.nees_in_bounds_fraction = 0.9;
        if (scale > 1.0) {
          r.paired_reference = "robocentric";
          r.paired_difference_m = e / 2.0;
          r.paired_ci95_lower_m = e / 4.0;
          r.paired_ci95_upper_m = 3.0 * e / 4.0;
          r.paired_runs_lower = 0;
        } else {
          r.linearisation_observation = 1e-4 * noise;
          r.linearisation_inversion = 2e-4 * noise;
          r.linearisation_pose = 3e-4 * noise * iterations;
        }
        table.rows.push_back(r);
      }
      ++cell;
    }
  }
  return table;
}

TEST(PlotSweep, AFigurePerKeyAndMetric) {
  REQUIRE_X_DISPLAY();
  const TempDir tmp;
  const std::string dir = tmp.file("sweep");
  fs::create_directories(dir);
  results::write_sweep_csv(dir + "/sweep.csv", grid_table());
  const std::vector<std::string> written = plot({dir, "", 0, 1200, 900, -1});
  ASSERT_EQ(written.size(), 8u);  // 2 keys x mean error, ANEES, paired difference, linearisation
  EXPECT_EQ(written[0], dir + "/figures/sweep_scenario_mru_heading_noise_deg_mean_error.png");
  EXPECT_EQ(written[2],
            dir + "/figures/sweep_scenario_mru_heading_noise_deg_paired_difference.png");
  EXPECT_EQ(written[7],
            dir + "/figures/sweep_slam_trajectory_slam_iekf_iterations_linearisation.png");
  for (const std::string& figure : written) {
    const bool paired = figure.find("paired") != std::string::npos;
    const bool linearisation = figure.find("linearisation") != std::string::npos;
    std::vector<std::uint32_t> colours;
    if (!paired) colours.push_back(report::MethodStyles().colour("robocentric"));
    if (!linearisation) colours.push_back(report::MethodStyles().colour("deadreckoning"));
    expect_figure(figure, 1200, 900, colours, 20);
  }
}

TEST(PlotSweep, LinesFollowTheOtherKeysUnlessTheirValueFollowsTheKey) {
  results::SweepTable table = grid_table();
  // Iterations split the lines against the noise: per method 2 lines (and their points).
  const auto labels = [](const plot::ChartSpec& chart) {
    std::vector<std::string> out;
    for (const plot::Series& s : chart.series) {
      if (!s.label.empty()) out.push_back(s.label);
    }
    return out;
  };
  EXPECT_EQ(labels(report::sweep_chart(report::MethodStyles(), table, 0, "mean_error", 800, 600)),
            (std::vector<std::string>{
                "Robocentric SLAM, iekf_iterations=1", "Dead reckoning, iekf_iterations=1",
                "Robocentric SLAM, iekf_iterations=5", "Dead reckoning, iekf_iterations=5"}));
  // A filter sigma set with each noise (its value follows the noise) does not.
  table.keys.push_back("slam.dead_reckoning.heading_sigma_deg");
  for (results::SweepRow& r : table.rows) r.values.push_back(r.values[0]);
  EXPECT_EQ(labels(report::sweep_chart(report::MethodStyles(), table, 0, "mean_error", 800, 600)),
            (std::vector<std::string>{
                "Robocentric SLAM, iekf_iterations=1", "Dead reckoning, iekf_iterations=1",
                "Robocentric SLAM, iekf_iterations=5", "Dead reckoning, iekf_iterations=5"}));
  // Against the iterations, the noise and the sigma both split them; linearisation errors: a
  // line per kind, robocentric only.
  const std::vector<std::string> lines =
      labels(report::sweep_chart(report::MethodStyles(), table, 1, "linearisation", 800, 600));
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[0],
            "Robocentric SLAM: match update, heading_noise_deg=0.500000, "
            "heading_sigma_deg=0.500000");
  EXPECT_EQ(lines[8],
            "Robocentric SLAM: pose read-out, heading_noise_deg=2.000000, "
            "heading_sigma_deg=2.000000");
  EXPECT_TRUE(report::sweep_has_metric(table, "paired_difference"));
  table.rows.erase(
      std::remove_if(table.rows.begin(), table.rows.end(),
                     [](const results::SweepRow& r) { return r.method != "robocentric"; }),
      table.rows.end());
  EXPECT_FALSE(report::sweep_has_metric(table, "paired_difference"));
  EXPECT_THROW(report::sweep_chart(report::MethodStyles(), table, 0, "speed", 800, 600),
               std::invalid_argument);
}

TEST(PlotMonteCarlo, CliPrintsTheFilesItWrote) {
  REQUIRE_X_DISPLAY();
  const TempDir tmp;
  const std::string mc = write_monte_carlo_dir(tmp);
  const CliResult result = run_msislab("plot " + shell_quote(mc), tmp);
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out, "wrote " + mc + "/figures/nees.png\n");
  EXPECT_EQ(result.err, "");
}

// Without a display the command runs itself again under xvfb-run.
TEST(PlotMonteCarlo, CliWithoutDisplayRerunsUnderXvfb) {
  const TempDir tmp;
  if (std::system("command -v xvfb-run >/dev/null && command -v xauth >/dev/null") != 0) {
    GTEST_SKIP() << "xvfb-run or xauth is not installed";
  }
  const std::string mc = write_monte_carlo_dir(tmp);
  const CliResult rerun = run_msislab("plot " + shell_quote(mc), tmp, "env -u DISPLAY");
  EXPECT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_EQ(rerun.out, "wrote " + mc + "/figures/nees.png\n");
  expect_figure(mc + "/figures/nees.png", 1200, 900,
                {report::MethodStyles().colour("worldcentric")});
}

TEST(PlotMonteCarlo, CliWithoutDisplayOrXvfbIsOneClearError) {
  const TempDir tmp;
  const std::string mc = write_monte_carlo_dir(tmp);
  const CliResult result =
      run_msislab("plot " + shell_quote(mc), tmp, "env -u DISPLAY PATH=/nonexistent");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("msislab: no X display", 0), 0u) << result.err;
  EXPECT_NE(result.err.find("xvfb-run -a"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(mc + "/figures/nees.png"));
}

// Bad input fails while reading, before any display is needed.
void expect_bad_input(const std::string& dir, const std::string& message_part) {
  const TempDir tmp;
  const CliResult result = run_msislab("plot " + shell_quote(dir), tmp);
  EXPECT_EQ(result.exit_code, 2) << result.out;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.err.rfind("msislab: ", 0), 0u) << result.err;
  EXPECT_NE(result.err.find(message_part), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(fs::path(dir) / "figures"));
}

TEST(PlotBadInput, MissingDirectory) {
  const TempDir tmp;
  expect_bad_input(tmp.file("nowhere"), "nowhere: no such directory");
}

TEST(PlotBadInput, NothingToPlot) {
  const TempDir tmp;
  fs::create_directories(tmp.file("empty/sub"));
  expect_bad_input(tmp.file("empty"), "nothing to plot");
}

TEST(PlotBadInput, MalformedNeesCsv) {
  const TempDir tmp;
  fs::create_directories(tmp.file("mc"));
  write_text(tmp.file("mc/nees.csv"),
             "method,scan,runs,mean_nees,lower,upper\nworldcentric,0,25,2.9,2.12,4.03\n"
             "worldcentric,1,25,abc,2.12,4.03\n");
  expect_bad_input(tmp.file("mc"), "nees.csv:3: field 4 (mean_nees) 'abc' is not a number");
}

TEST(PlotBadInput, MalformedScansCsvInAResult) {
  const TempDir tmp;
  fs::create_directories(tmp.file("r"));
  write_text(tmp.file("r/trajectory.tum"),
             "# t x y z qx qy qz qw\n0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n");
  write_text(tmp.file("r/scans.csv"),
             "t_s,x_m,y_m,yaw_rad,cov_xx,cov_xy,cov_xyaw,cov_yy,cov_yyaw,cov_yawyaw,points\n"
             "0.5,0,0,0,1,0,0,1,0,0.1\n");
  expect_bad_input(tmp.file("r"), "scans.csv:2: truncated line");
}

TEST(PlotBadInput, RecordedDatasetThatMoved) {
  const TempDir tmp;
  fs::create_directories(tmp.file("r"));
  write_text(tmp.file("r/trajectory.tum"),
             "# t x y z qx qy qz qw\n0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n");
  RunMetrics metrics;
  metrics.method = "deadreckoning";
  metrics.truth = "simulation";
  results::write_metrics_json(tmp.file("r/metrics.json"), metrics, tmp.file("gone"));
  expect_bad_input(tmp.file("r"), "pass --dataset");
}

}  // namespace
}  // namespace msislab::app
