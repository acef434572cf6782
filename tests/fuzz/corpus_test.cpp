// The fuzzing corpus as a regression suite in every build (tools/fuzz.sh runs the fuzzer itself).
// tests/fuzz/corpus/<target>/ holds the seeds, tests/fuzz/findings/<target>/ every input the
// fuzzer ever found a fault with. A file named ok_* must be read, bad_* must be rejected with
// io::InputError; for either, anything else the reader does (another exception, a sanitizer report
// under the asan preset) fails the test.
#include "tests/fuzz/reader_targets.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace msislab::fuzz {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = MSISLAB_FUZZ_DIR;

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> files;
  if (!fs::is_directory(dir)) return files;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(FuzzCorpus, EveryTargetHasAcceptedAndRejectedSeeds) {
  for (const ReaderTarget& target : reader_targets()) {
    int ok = 0;
    int bad = 0;
    for (const fs::path& file : files_in(kFuzzDir / "corpus" / target.name)) {
      const std::string name = file.filename().string();
      ok += name.rfind("ok_", 0) == 0;
      bad += name.rfind("bad_", 0) == 0;
    }
    EXPECT_GE(ok, 1) << target.name << ": no ok_* seed";
    EXPECT_GE(bad, 1) << target.name << ": no bad_* seed";
  }
}

TEST(FuzzCorpus, EveryFolderIsATarget) {
  std::set<std::string> names;
  for (const ReaderTarget& target : reader_targets()) names.insert(target.name);
  for (const char* kind : {"corpus", "findings"}) {
    for (const fs::directory_entry& entry : fs::directory_iterator(kFuzzDir / kind)) {
      if (!entry.is_directory()) continue;  // findings/README.md
      EXPECT_TRUE(names.count(entry.path().filename().string())) << entry.path();
    }
  }
}

TEST(FuzzCorpus, ReadersAcceptOkAndRejectBad) {
  testing::TempDir tmp;
  int files = 0;
  for (const ReaderTarget& target : reader_targets()) {
    for (const char* kind : {"corpus", "findings"}) {
      for (const fs::path& file : files_in(kFuzzDir / kind / target.name)) {
        const std::string name = file.filename().string();
        const bool want_ok = name.rfind("ok_", 0) == 0;
        ASSERT_TRUE(want_ok || name.rfind("bad_", 0) == 0) << file << ": name it ok_* or bad_*";
        SCOPED_TRACE(file.string());
        Outcome outcome = Outcome::kRejected;
        try {
          outcome = read_bytes(target, read_all(file), tmp.path());
        } catch (const std::exception& e) {
          ADD_FAILURE() << "not an io::InputError: " << e.what();
          continue;
        }
        EXPECT_EQ(outcome, want_ok ? Outcome::kAccepted : Outcome::kRejected);
        ++files;
      }
    }
  }
  EXPECT_GT(files, 0);
}

TEST(FuzzCorpus, UnknownTargetIsNamed) {
  EXPECT_THROW(reader_target("no_such_reader"), std::invalid_argument);
  EXPECT_EQ(reader_target("tum").file_name, "trajectory.tum");
}

}  // namespace
}  // namespace msislab::fuzz
