#include "io/junit_xml.hpp"

#include <algorithm>
#include <fstream>

#include "io/atomic_file.hpp"

namespace msislab::io {

namespace {

const std::string kDeclaration = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
const std::string kSignature = "<!-- written by msislab check -->\n";

std::string escaped(const std::string& text) {
  std::string out;
  for (const char ch : text) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // XML 1.0 allows no control characters but tab, newline and carriage return.
        if (static_cast<unsigned char>(ch) >= 0x20 || ch == '\t' || ch == '\n' || ch == '\r') {
          out += ch;
        }
    }
  }
  return out;
}

}  // namespace

void write_junit_xml(const std::string& path, const std::string& suite,
                     const std::vector<JunitCase>& cases) {
  const auto failures = std::count_if(cases.begin(), cases.end(),
                                      [](const JunitCase& c) { return !c.failure.empty(); });
  const auto skipped =
      std::count_if(cases.begin(), cases.end(), [](const JunitCase& c) { return c.skipped; });
  std::string xml = kDeclaration + kSignature;
  const std::string counts = " tests=\"" + std::to_string(cases.size()) + "\" failures=\"" +
                             std::to_string(failures) + "\" errors=\"0\" skipped=\"" +
                             std::to_string(skipped) + "\"";
  xml += "<testsuites name=\"" + escaped(suite) + "\"" + counts + ">\n";
  xml += "  <testsuite name=\"" + escaped(suite) + "\"" + counts + ">\n";
  for (const JunitCase& c : cases) {
    xml +=
        "    <testcase classname=\"" + escaped(c.classname) + "\" name=\"" + escaped(c.name) + "\"";
    if (c.failure.empty() && !c.skipped) {
      xml += "/>\n";
      continue;
    }
    xml += ">\n";
    if (!c.failure.empty()) {
      xml += "      <failure message=\"" + escaped(c.failure) + "\">" + escaped(c.failure) +
             "</failure>\n";
    } else {
      xml += "      <skipped/>\n";
    }
    xml += "    </testcase>\n";
  }
  xml += "  </testsuite>\n</testsuites>\n";
  write_text_atomically(path, xml);
}

bool junit_written_by_msislab(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(kDeclaration.size() + kSignature.size(), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  return in && head == kDeclaration + kSignature;
}

}  // namespace msislab::io
