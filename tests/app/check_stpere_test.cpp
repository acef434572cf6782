// tools/check_stpere.sh on copies of the real St. Pere dataset, checked against the digests msislab
// pins (tools/datasets/stpere.sha256), not the copy's own SHA256SUMS: an intact copy passes; one
// flipped byte or a missing log fails with exit status 2 and one line naming the file, and so does
// an altered log whose copy brings a SHA256SUMS made for it. Copying the whole folder (8.5 MB)
// takes tens of milliseconds.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"

namespace msislab {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char ch : text) quoted += (ch == '\'') ? std::string("'\\''") : std::string(1, ch);
  return quoted + "'";
}

struct Checked {
  int exit_code = -1;
  std::string out, err;
};

Checked check(const fs::path& dataset, const TempDir& tmp) {
  const std::string out = tmp.file("stdout.txt"), err = tmp.file("stderr.txt");
  const std::string command =
      "bash " + shell_quote(std::string(MSISLAB_SOURCE_DIR) + "/tools/check_stpere.sh") + " " +
      shell_quote(dataset.string()) + " >" + shell_quote(out) + " 2>" + shell_quote(err) +
      " </dev/null";
  const int status = std::system(command.c_str());
  Checked result;
  if (status != -1 && WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  result.out = read_text(out);
  result.err = read_text(err);
  return result;
}

/// The dataset copied into tmp, writable (the shared copy is read-only).
fs::path copy_of_dataset(const TempDir& tmp) {
  const fs::path copy = tmp.path() / "stpere";
  fs::copy(testing::stpere_dir(), copy, fs::copy_options::recursive);
  fs::permissions(copy, fs::perms::owner_all, fs::perm_options::add);
  for (const auto& entry : fs::directory_iterator(copy)) {
    fs::permissions(entry.path(), fs::perms::owner_write, fs::perm_options::add);
  }
  return copy;
}

void flip_one_byte(const fs::path& file, std::streamoff at) {
  std::fstream io(file, std::ios::binary | std::ios::in | std::ios::out);
  io.seekg(at);
  const char byte = static_cast<char>(io.get() ^ 0x01);
  io.seekp(at);
  io.put(byte);
}

TEST(CheckStPere, AnIntactCopyPassesAndADamagedFileIsNamed) {
  MSISLAB_REQUIRE_STPERE();
  const TempDir tmp;
  const fs::path copy = copy_of_dataset(tmp);
  Checked r = check(copy, tmp);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("matches msislab's pinned digests (tools/datasets/stpere.sha256, 6 files)"),
            std::string::npos)
      << r.out;

  // One bit of one byte of the DVL log, in the middle of a row.
  const fs::path dvl = copy / "_040825_1735_DVL.log";
  const std::string pinned =
      " does not match msislab's pinned digest (tools/datasets/stpere.sha256)";
  flip_one_byte(dvl, 1000);
  r = check(copy, tmp);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tools/check_dataset.sh: " + dvl.string() + ":" + pinned +
                       ": damaged, changed, missing or not the real dataset\n");

  // The same altered log with a SHA256SUMS made for the altered copy: still refused.
  ASSERT_EQ(
      std::system(("cd " + shell_quote(copy.string()) + " && sha256sum _040825_1735_* > SHA256SUMS")
                      .c_str()),
      0);
  r = check(copy, tmp);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(dvl.string() + ":" + pinned), std::string::npos) << r.err;
  flip_one_byte(dvl, 1000);
  EXPECT_EQ(check(copy, tmp).exit_code, 0);

  // A log gone is named too; the copy's SHA256SUMS is not needed.
  fs::remove(copy / "SHA256SUMS");
  EXPECT_EQ(check(copy, tmp).exit_code, 0);
  fs::remove(copy / "_040825_1735_MTi.log");
  r = check(copy, tmp);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find((copy / "_040825_1735_MTi.log").string() + ":" + pinned), std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace msislab
