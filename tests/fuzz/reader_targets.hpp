// Every reader of outside input, as a table the fuzzer (fuzz_readers.cpp, tools/fuzz.sh) and the
// corpus regression test (corpus_test.cpp) share. A target writes the bytes it is given to a file
// of the name the reader expects and calls the reader. A reader may accept the bytes or reject
// them with io::InputError (one line, exit 2 at the command line); anything else it does (another
// exception, a crash, a sanitizer report, a hang) is a finding.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace msislab::fuzz {

struct ReaderTarget {
  std::string name;       ///< the corpus folder's name, tests/fuzz/corpus/<name>
  std::string file_name;  ///< what the bytes are called: the reader dispatches on the extension
  void (*read)(const std::string& path);
};

/// Every target, in a fixed order.
const std::vector<ReaderTarget>& reader_targets();

/// The target of that name; throws std::invalid_argument listing the names when there is none.
const ReaderTarget& reader_target(std::string_view name);

enum class Outcome { kAccepted, kRejected };

/// Writes `bytes` to dir/target.file_name (replacing it) and reads it. kRejected: the reader threw
/// io::InputError. Every other exception propagates: it is a finding.
Outcome read_bytes(const ReaderTarget& target, std::string_view bytes,
                   const std::filesystem::path& dir);

}  // namespace msislab::fuzz
