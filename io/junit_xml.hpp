// JUnit XML, the test report CI systems display (GitLab, Jenkins, GitHub actions' reporters): one
// test suite of test cases, each passed, failed with a message, or skipped. msislab's own files
// carry a comment after the XML declaration by which a later write knows them for its own.
#pragma once

#include <string>
#include <vector>

namespace msislab::io {

struct JunitCase {
  std::string name;
  std::string classname;
  std::string failure;  ///< empty when it passed
  bool skipped = false;
};

/// Writes the suite atomically.
void write_junit_xml(const std::string& path, const std::string& suite,
                     const std::vector<JunitCase>& cases);

/// True when the file is a JUnit report msislab wrote.
bool junit_written_by_msislab(const std::string& path);

}  // namespace msislab::io
