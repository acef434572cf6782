// Folders put in place whole: replace_directory renames a complete folder over an earlier one,
// leaves nothing aside, and on failure keeps the earlier folder and names the target.
#include "io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/input_error.hpp"
#include "test_support.hpp"

namespace msislab::io {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

TEST(ReplaceDirectory, CreatesTheTarget) {
  const TempDir tmp;
  fs::create_directory(tmp.path() / ".new");
  write_text(tmp.file(".new/a.txt"), "new");
  replace_directory(tmp.file(".new"), tmp.file("out"));
  EXPECT_EQ(read_text(tmp.file("out/a.txt")), "new");
  EXPECT_FALSE(fs::exists(tmp.path() / ".new"));
}

TEST(ReplaceDirectory, ReplacesAnEarlierFolderWhole) {
  const TempDir tmp;
  fs::create_directory(tmp.path() / "out");
  write_text(tmp.file("out/stale.txt"), "old");
  fs::create_directory(tmp.path() / ".new");
  write_text(tmp.file(".new/a.txt"), "new");
  replace_directory(tmp.file(".new"), tmp.file("out"));
  EXPECT_EQ(read_text(tmp.file("out/a.txt")), "new");
  EXPECT_FALSE(fs::exists(tmp.path() / "out" / "stale.txt"));
  std::size_t entries = 0;
  for (const auto& entry : fs::directory_iterator(tmp.path())) entries += entry.exists();
  EXPECT_EQ(entries, 1u) << "nothing left aside";
}

TEST(ReplaceDirectory, FailureKeepsTheEarlierFolder) {
  const TempDir tmp;
  fs::create_directory(tmp.path() / "out");
  write_text(tmp.file("out/kept.txt"), "old");
  try {
    replace_directory(tmp.file(".missing"), tmp.file("out"));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(tmp.file("out") + ": cannot put the folder in place", 0),
              0u)
        << e.what();
  }
  EXPECT_EQ(read_text(tmp.file("out/kept.txt")), "old");
}

}  // namespace
}  // namespace msislab::io
