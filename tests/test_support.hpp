// Helpers shared by the tests: a temporary folder, writing small text fixtures, and the location
// of the real St. Pere dataset (tests that need it call MSISLAB_REQUIRE_STPERE(): they skip without
// it, and fail without it when MSISLAB_REQUIRE_REAL_DATA=1, which tools/test.sh sets when it has
// found and checked the dataset), and the seeds of the statistical tests (seed(N): N plus the
// environment's MSISLAB_TEST_SEED_OFFSET, for tools/seed_offsets.sh).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

namespace msislab::testing {

/// A fresh folder under the system temporary directory, removed with its contents at scope end.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("msislab_test_" + std::to_string(rd()) + "_" + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

/// Writes text to a file byte for byte (no newline translation) and returns its path.
inline std::string write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  return path;
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The environment's MSISLAB_STPERE_DIR when set (tools/test.sh sets it, absolute, to the folder it
/// checked), else the CMake cache's MSISLAB_STPERE_DIR.
inline std::string stpere_dir() {
  const char* from_environment = std::getenv("MSISLAB_STPERE_DIR");
  return (from_environment != nullptr && *from_environment != '\0') ? from_environment
                                                                    : MSISLAB_STPERE_DIR;
}
inline bool have_stpere() {
  return std::filesystem::exists(std::filesystem::path(stpere_dir()) / "_040825_1735_DVL.log");
}
/// True when the run promises the real dataset (MSISLAB_REQUIRE_REAL_DATA=1): a test that needs it
/// and does not find it then fails instead of skipping, so a suite cannot pass with it unread.
inline bool real_data_required() {
  const char* required = std::getenv("MSISLAB_REQUIRE_REAL_DATA");
  return required != nullptr && std::string(required) == "1";
}

/// The seed a statistical test draws from: base plus the environment's MSISLAB_TEST_SEED_OFFSET (a
/// whole number, 0 when unset or empty). A test that checks a statistic against a bound (NEES,
/// chi-square, a mean within k sigma, a coverage) passes on its sample, not on its statistic: at a
/// 95 % bound it fails about once in 20 random streams. Statistical tests therefore draw from
/// seed(N), so that tools/seed_offsets.sh can run them on other random streams and count how
/// often each fails; with no offset every test draws exactly the samples it draws today. A value
/// that is not a whole number (from 0 to 2^32 - 1) throws std::invalid_argument, naming the
/// variable and the value, so a mistyped offset fails the test loudly instead of running the
/// default stream.
inline unsigned seed(unsigned base) {
  const char* text = std::getenv("MSISLAB_TEST_SEED_OFFSET");
  if (text == nullptr || *text == '\0') return base;
  const std::string value(text);
  std::size_t end = 0;
  unsigned long offset = 0;
  bool ok = value.find_first_not_of("0123456789") == std::string::npos;
  if (ok) {
    try {
      offset = std::stoul(value, &end);
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok || end != value.size() || offset > 0xFFFFFFFFul)
    throw std::invalid_argument("MSISLAB_TEST_SEED_OFFSET='" + value +
                                "' is not a whole number from 0 to 4294967295 (the seed "
                                "offset of the statistical tests; unset it for the default "
                                "streams)");
  return base + static_cast<unsigned>(offset);
}

}  // namespace msislab::testing

#define MSISLAB_REQUIRE_STPERE()                                                                  \
  do {                                                                                            \
    if (!::msislab::testing::have_stpere()) {                                                     \
      if (::msislab::testing::real_data_required())                                               \
        GTEST_FAIL() << "real St. Pere dataset not found at " << ::msislab::testing::stpere_dir() \
                     << ", but MSISLAB_REQUIRE_REAL_DATA=1 says this run has it";                 \
      GTEST_SKIP() << "real St. Pere dataset not found at " << ::msislab::testing::stpere_dir()   \
                   << " (place it at ../shared/datasets/stpere to run this test)";                \
    }                                                                                             \
  } while (0)
