// Helpers shared by the tests: a temporary folder, writing small text fixtures, and the location
// of the real St. Pere dataset (tests that need it call MSISLAB_REQUIRE_STPERE() and skip cleanly).
#pragma once

#include <gtest/gtest.h>

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

inline std::string stpere_dir() { return MSISLAB_STPERE_DIR; }
inline bool have_stpere() {
  return std::filesystem::exists(std::filesystem::path(stpere_dir()) / "_040825_1735_DVL.log");
}

}  // namespace msislab::testing

#define MSISLAB_REQUIRE_STPERE()                                                                \
  do {                                                                                          \
    if (!::msislab::testing::have_stpere())                                                     \
      GTEST_SKIP() << "real St. Pere dataset not found at " << ::msislab::testing::stpere_dir() \
                   << " (place it at ../shared/datasets/stpere to run this test)";              \
  } while (0)
