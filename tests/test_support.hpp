// Helpers shared by the tests: a temporary folder, writing small text fixtures, and the location
// of the real St. Pere dataset (tests that need it call MSISLAB_REQUIRE_STPERE(): they skip without
// it, and fail without it when MSISLAB_REQUIRE_REAL_DATA=1, which tools/test.sh sets when it has
// found and checked the dataset).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
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
