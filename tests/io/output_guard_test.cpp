// The output rule: msislab creates an output or replaces what it wrote itself, and refuses
// everything else (a plain file, a foreign folder, an input, a folder holding an input or the
// current directory) before writing, leaving the user's files byte for byte as they were. Staged
// folders are put in place whole and leave nothing behind when they fail.
#include "io/output_guard.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "io/input_error.hpp"
#include "test_support.hpp"

namespace msislab::io {
namespace {

namespace fs = std::filesystem;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

/// The error check_output_folder or a StagedFolder gives, or "" when it accepts.
template <typename F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) n += entry.exists() ? 1 : 0;
  return n;
}

OutputRequest dataset_at(const std::string& path) {
  return {path, "dataset", "simulate", {}, false};
}

TEST(OutputGuard, StagedFolderCreatesTheTargetWithItsMarker) {
  const TempDir tmp;
  StagedFolder staged(dataset_at(tmp.file("out")));
  write_text(staged.path() + "/a.txt", "new");
  EXPECT_FALSE(fs::exists(tmp.path() / "out")) << "nothing at the target before commit";
  staged.commit();
  EXPECT_EQ(read_text(tmp.file("out/a.txt")), "new");
  EXPECT_EQ(output_kind(tmp.file("out")), "dataset");
  EXPECT_EQ(entries(tmp.path()), 1u) << "nothing left aside";
}

TEST(OutputGuard, ReplacesAnEarlierOutputOfTheSameKindWhole) {
  const TempDir tmp;
  {
    StagedFolder first(dataset_at(tmp.file("out")));
    write_text(first.path() + "/stale.txt", "old");
    first.commit();
  }
  StagedFolder second(dataset_at(tmp.file("out/")));  // a trailing separator names it too
  write_text(second.path() + "/a.txt", "new");
  second.commit();
  EXPECT_EQ(read_text(tmp.file("out/a.txt")), "new");
  EXPECT_FALSE(fs::exists(tmp.path() / "out" / "stale.txt"));
  EXPECT_EQ(entries(tmp.path()), 1u);
}

TEST(OutputGuard, AFileTheUserPutIntoAnOutputIsKept) {
  const TempDir tmp;
  StagedFolder first(dataset_at(tmp.file("out")));
  write_text(first.path() + "/a.txt", "msislab's");
  first.commit();
  write_text(tmp.file("out/notes.txt"), "the user's");
  const std::string why = refusal([&] { StagedFolder staged(dataset_at(tmp.file("out"))); });
  EXPECT_NE(why.find("holds 'notes.txt', which msislab did not write"), std::string::npos) << why;
  EXPECT_EQ(read_text(tmp.file("out/notes.txt")), "the user's");
  EXPECT_EQ(entries(tmp.path()), 1u) << "no staging folder left";
}

TEST(OutputGuard, WhatMsislabAddsToAnOutputLaterIsItsOwnToo) {
  const TempDir tmp;
  const OutputRequest result{tmp.file("res"), "result", "run", {}, false};
  StagedFolder first(result);
  write_text(first.path() + "/trajectory.tum", "t");
  first.commit();
  claim_output_folder({tmp.file("res/figures"), "figures", "plot", {}, false});  // plot, later
  write_text(tmp.file("res/metrics.json"), "{}");                                // eval, later
  record_output_entries(tmp.file("res"), {"metrics.json"});
  StagedFolder second(result);  // accepted: nothing in res/ is the user's
  second.commit();
  EXPECT_FALSE(fs::exists(tmp.path() / "res" / "figures"));
  fs::create_directory(tmp.path() / "res" / "mine");  // a folder without a marker is the user's
  EXPECT_NE(refusal([&] { StagedFolder third(result); }).find("holds 'mine'"), std::string::npos);
}

TEST(OutputGuard, AnEmptyFolderIsFilled) {
  const TempDir tmp;
  fs::create_directory(tmp.path() / "out");
  StagedFolder staged(dataset_at(tmp.file("out")));
  staged.commit();
  EXPECT_EQ(output_kind(tmp.file("out")), "dataset");
}

TEST(OutputGuard, RefusesAPlainFileAndKeepsIt) {
  const TempDir tmp;
  write_text(tmp.file("f"), "user's");
  const std::string why = refusal([&] { StagedFolder staged(dataset_at(tmp.file("f"))); });
  EXPECT_EQ(why.rfind(tmp.file("f") + ": is a file", 0), 0u) << why;
  EXPECT_EQ(read_text(tmp.file("f")), "user's");
  EXPECT_EQ(entries(tmp.path()), 1u);
}

TEST(OutputGuard, RefusesAForeignFolderAndNamesWhatItHolds) {
  const TempDir tmp;
  fs::create_directory(tmp.path() / "mine");
  write_text(tmp.file("mine/keep.txt"), "keep");
  const std::string why = refusal([&] { StagedFolder staged(dataset_at(tmp.file("mine"))); });
  EXPECT_NE(why.find("msislab did not write (it holds 'keep.txt')"), std::string::npos) << why;
  EXPECT_EQ(read_text(tmp.file("mine/keep.txt")), "keep");
  EXPECT_EQ(entries(tmp.path()), 1u) << "no staging folder left";
  EXPECT_EQ(entries(tmp.path() / "mine"), 1u);
}

TEST(OutputGuard, ForceReplacesAForeignFolderButNeverAnInput) {
  const TempDir tmp;
  fs::create_directory(tmp.path() / "mine");
  write_text(tmp.file("mine/old.txt"), "old");
  StagedFolder staged({tmp.file("mine"), "dataset", "simulate", {}, true});
  staged.commit();
  EXPECT_FALSE(fs::exists(tmp.path() / "mine" / "old.txt"));
  const std::string why = refusal([&] {
    check_output_folder({tmp.file("mine"), "dataset", "simulate", {tmp.file("mine")}, true});
  });
  EXPECT_NE(why.find("is an input of this simulate"), std::string::npos) << why;
}

TEST(OutputGuard, RefusesAnotherKindOfMsislabOutput) {
  const TempDir tmp;
  StagedFolder dataset(dataset_at(tmp.file("out")));
  dataset.commit();
  const std::string why = refusal([&] {
    check_output_folder({tmp.file("out"), "result", "run", {}, false});
  });
  EXPECT_NE(why.find("holds msislab's dataset, not a result"), std::string::npos) << why;
}

TEST(OutputGuard, RefusesAnInputAndAFolderHoldingOne) {
  const TempDir tmp;
  fs::create_directories(tmp.path() / "data" / "in");
  write_text(tmp.file("data/in/scenario.yaml"), "x");
  const std::string scenario = tmp.file("data/in/scenario.yaml");
  const std::string input = refusal([&] {
    check_output_folder({scenario, "dataset", "simulate", {scenario}, false});
  });
  EXPECT_NE(input.find("is an input of this simulate"), std::string::npos) << input;
  const std::string holds = refusal([&] {
    check_output_folder({tmp.file("data"), "dataset", "simulate", {scenario}, true});
  });
  EXPECT_NE(holds.find("holds the input " + scenario), std::string::npos) << holds;
  // A new folder inside an input folder is no input.
  EXPECT_EQ(refusal([&] {
              check_output_folder(
                  {tmp.file("data/in/out"), "result", "run", {tmp.file("data/in")}, false});
            }),
            "");
}

TEST(OutputGuard, RefusesTheCurrentDirectoryAndLeavesNothing) {
  const TempDir tmp;
  fs::create_directory(tmp.path() / "here");
  const fs::path before = fs::current_path();
  fs::current_path(tmp.path() / "here");
  const std::string dot = refusal([&] { StagedFolder staged(dataset_at(".")); });
  const std::string parent = refusal([&] { StagedFolder staged(dataset_at("..")); });
  fs::current_path(before);
  EXPECT_EQ(dot.rfind(".: is the current directory", 0), 0u) << dot;
  EXPECT_EQ(parent.rfind("..: is the current directory or holds it", 0), 0u) << parent;
  EXPECT_EQ(entries(tmp.path()), 1u);
  EXPECT_EQ(entries(tmp.path() / "here"), 0u);
}

TEST(OutputGuard, AnUncommittedOrFailedStagingLeavesNothingBehind) {
  const TempDir tmp;
  {
    StagedFolder abandoned(dataset_at(tmp.file("out")));
    write_text(abandoned.path() + "/half.txt", "half");
  }
  EXPECT_EQ(entries(tmp.path()), 0u);
  // The user puts a file at the target while the output is being made: commit refuses it.
  StagedFolder staged(dataset_at(tmp.file("out")));
  write_text(staged.path() + "/a.txt", "new");
  write_text(tmp.file("out"), "user's, meanwhile");
  const std::string why = refusal([&] { staged.commit(); });
  EXPECT_NE(why.find("is a file"), std::string::npos) << why;
  EXPECT_EQ(read_text(tmp.file("out")), "user's, meanwhile");
}

TEST(OutputGuard, StagingIsRemovedWhenTheStagedFolderFails) {
  const TempDir tmp;
  const std::string why = refusal([&] {
    StagedFolder staged(dataset_at(tmp.file("out")));
    write_text(staged.path() + "/a.txt", "new");
    throw InputError("a writer failed");
  });
  EXPECT_EQ(why, "a writer failed");
  EXPECT_EQ(entries(tmp.path()), 0u);
}

TEST(OutputGuard, ClaimCreatesOrKeepsAFolderOfItsKind) {
  const TempDir tmp;
  const OutputRequest mc{tmp.file("mc"), "montecarlo", "montecarlo", {}, false};
  claim_output_folder(mc);
  write_text(tmp.file("mc/run.txt"), "kept");
  claim_output_folder(mc);  // resumes: nothing removed
  EXPECT_EQ(read_text(tmp.file("mc/run.txt")), "kept");
  fs::create_directory(tmp.path() / "foreign");
  write_text(tmp.file("foreign/x"), "x");
  EXPECT_NE(refusal([&] {
              claim_output_folder({tmp.file("foreign"), "montecarlo", "m", {}, false});
            }),
            "");
  EXPECT_FALSE(fs::exists(tmp.path() / "foreign" / kOutputMarkerName));
}

TEST(OutputGuard, PagesAndImagesAreKnownByTheirSignature) {
  const TempDir tmp;
  write_text(tmp.file("page.md"), page_signature("report") + "# Results\n");
  write_text(tmp.file("mine.md"), "# My notes\n");
  EXPECT_TRUE(page_written_by_msislab(tmp.file("page.md")));
  EXPECT_FALSE(page_written_by_msislab(tmp.file("mine.md")));
  const OutputRequest page{tmp.file("mine.md"), "page", "report", {}, false};
  EXPECT_NE(
      refusal([&] { check_output_file(page, page_written_by_msislab); }).find("did not write"),
      std::string::npos);
  EXPECT_EQ(refusal([&] {
              check_output_file({tmp.file("page.md"), "page", "report", {}, false},
                                page_written_by_msislab);
            }),
            "");
  EXPECT_NE(refusal([&] {
              check_output_file({tmp.path().string(), "page", "report", {}, false},
                                page_written_by_msislab);
            }).find("is a folder"),
            std::string::npos);
  // A minimal PNG: the signature and an IHDR chunk (lengths, not pixels, matter here).
  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0,
                                    13,   'I', 'H', 'D', 'R',  0,    0,    0,    1, 0, 0,
                                    0,    1,   8,   2,   0,    0,    0,    0,    0, 0, 0};
  write_text(tmp.file("plain.png"), std::string(png.begin(), png.end()));
  const std::vector<unsigned char> signed_bytes = signed_png(png);
  write_text(tmp.file("signed.png"), std::string(signed_bytes.begin(), signed_bytes.end()));
  EXPECT_FALSE(png_written_by_msislab(tmp.file("plain.png")));
  EXPECT_TRUE(png_written_by_msislab(tmp.file("signed.png")));
  EXPECT_EQ(signed_bytes.size(), png.size() + 12 + 16);  // length, type, 16 data bytes, CRC
}

}  // namespace
}  // namespace msislab::io
