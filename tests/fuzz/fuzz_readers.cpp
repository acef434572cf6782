// The libFuzzer entry (preset asan, tools/fuzz.sh): one executable for every reader target, the
// target chosen by the environment variable MSISLAB_FUZZ_TARGET (a name of reader_targets()).
// Each input is written to a file in a private temporary folder and read. io::InputError is the
// reader doing its job; any other exception aborts, so libFuzzer keeps the input as a finding, as
// it does for a crash, a sanitizer report, a timeout or running out of memory.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include <unistd.h>

#include "tests/fuzz/reader_targets.hpp"

namespace {

const msislab::fuzz::ReaderTarget* g_target = nullptr;
std::filesystem::path g_dir;

void remove_dir() {
  std::error_code ignored;
  std::filesystem::remove_all(g_dir, ignored);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  const char* name = std::getenv("MSISLAB_FUZZ_TARGET");
  try {
    g_target = &msislab::fuzz::reader_target(name ? name : "");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "MSISLAB_FUZZ_TARGET: %s\n", e.what());
    std::exit(2);
  }
  g_dir = std::filesystem::temp_directory_path() /
          ("msislab_fuzz_" + g_target->name + "_" + std::to_string(getpid()));
  std::filesystem::create_directories(g_dir);
  std::atexit(remove_dir);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    msislab::fuzz::read_bytes(*g_target, {reinterpret_cast<const char*>(data), size}, g_dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "finding: %s: not an io::InputError: %s\n", g_target->name.c_str(),
                 e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "finding: %s: an exception of unknown type\n", g_target->name.c_str());
    std::abort();
  }
  return 0;
}
