// Every reader against every class of malformed input: each must throw InputError whose message
// names the file and line ("bad.log:7:") and says what is wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <sstream>

#include "io/detections.hpp"
#include "io/gzip_stream.hpp"
#include "io/input_error.hpp"
#include "io/stpere_logs.hpp"
#include "io/tum.hpp"
#include "test_support.hpp"

namespace msislab::io {
namespace {

using testing::TempDir;
using testing::write_text;
using Tokens = std::vector<std::string>;

void expect_input_error(const std::function<void()>& action, const std::string& where,
                        const std::vector<std::string>& words) {
  try {
    action();
    ADD_FAILURE() << "no InputError, expected one at " << where;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(where, 0), 0u) << "message: " << message << "\nexpected at " << where;
    for (const std::string& word : words)
      EXPECT_NE(message.find(word), std::string::npos)
          << "message: " << message << "\nno '" << word << "'";
  }
}

// A valid file of one format, as header text and token rows, that each test corrupts one way.
struct LogCase {
  std::string name;
  std::function<void(const std::string&)> read;
  std::string header;  ///< complete lines, '%' or '#' comments and blank lines
  std::vector<Tokens> rows;
  std::string separator = " ";
  std::string line_end = "\n";
  bool timed = true;  ///< first column is a time that must not go backwards
  std::string backwards_word = "backwards";
};

std::ostream& operator<<(std::ostream& os, const LogCase& c) { return os << c.name; }

std::string render(const LogCase& c, const std::vector<Tokens>& rows) {
  std::string text = c.header;
  for (const Tokens& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) text += (i == 0 ? "" : c.separator) + row[i];
    text += c.line_end;
  }
  return text;
}

Tokens split(const std::string& line) {
  Tokens tokens;
  std::istringstream in(line);
  for (std::string token; in >> token;) tokens.push_back(token);
  return tokens;
}

std::vector<LogCase> log_cases() {
  const std::string dvl_tail =
      " 2007 3 16 13 0 56 38.20 -47.00 1.80 1 6.10 -4.90 2.80 1 1.84 1.88 1.86 143.00 142.00 "
      "149.00 100 207.70 -0.50 1.60 14.27 1488.00 12.80 0.50 1.50 0.08 -0.25";
  const std::string mti_tail = " 0.506328 -2.5422 -126.276 0.01 -0.006 0.005 -0.42 -0.07 -9.77";
  const std::string gps_tail = " 4212.225 306.2832 1 -2.1 51.8 23.6 24 0.1 0.1";
  const std::string bins = " 0 12 255 7 99";
  const std::string pose_tail = " 1 2 -3 0 0 0.3826834323650898 0.9238795325112867";
  std::vector<LogCase> cases(7);
  cases[0] = {"Dvl",
              read_dvl_log,
              "% ---\r\n% Data columns: \r\n% logTime ...\r\n% ---\r\n\r\n",
              {split("100.1" + dvl_tail), split("100.7" + dvl_tail), split("101.3" + dvl_tail)},
              "\t",
              "\r\n"};
  cases[1] = {"Mti",
              read_mti_log,
              "% ---\r\n% Time: 17:35:35\r\n% Data columns: \r\n% x\r\n% ---\r\n\r\n",
              {split("100.05" + mti_tail), split("100.1" + mti_tail), split("100.2" + mti_tail)},
              "\t",
              "\r\n"};
  cases[2] = {"Gps",
              read_gps_log,
              "% ---\r\n% Data columns: \r\n% logTime ...\r\n% ---\r\n\r\n",
              {split("100" + gps_tail), split("101" + gps_tail), split("102" + gps_tail)},
              "\t",
              "\r\n"};
  cases[3] = {"BeamTimes",
              read_beam_times_log,
              "",
              {split("100.578 63224578"), split("100.646 63224646"), split("100.718 63224718")}};
  cases[4] = {
      "IsLog",
      read_is_log,
      "% 1\n% 2\n% 3\n% 4\n% 5\n% 6\n% 7\n% 8\n",
      {split("100.5 1 0.5" + bins), split("100.6 2 0.6" + bins), split("100.7 3 0.7" + bins)}};
  cases[5] = {"Setup", read_setup_log, "", {split("50 0.1 0.03141592653590")}};
  cases[5].timed = false;
  cases[6] = {"Tum",
              read_tum,
              "# t x y z qx qy qz qw\n\n",
              {split("10" + pose_tail), split("11" + pose_tail), split("12" + pose_tail)}};
  cases[6].backwards_word = "does not increase";
  return cases;
}

class MalformedLog : public ::testing::TestWithParam<LogCase> {
 protected:
  // Line number of data row `row` (0-based) in the rendered file.
  std::size_t line_of(std::size_t row) const {
    const std::string& h = GetParam().header;
    return static_cast<std::size_t>(std::count(h.begin(), h.end(), '\n')) + row + 1;
  }
  std::string at(const std::string& path, std::size_t row) const {
    return path + ":" + std::to_string(line_of(row)) + ":";
  }
  std::string write(const std::string& name, const std::vector<Tokens>& rows) const {
    return write_text(dir_.file(name), render(GetParam(), rows));
  }
  // The valid rows with row `row`, field `field` replaced by `token`.
  std::vector<Tokens> with_field(std::size_t row, std::size_t field,
                                 const std::string& token) const {
    std::vector<Tokens> rows = GetParam().rows;
    rows.at(row).at(field) = token;
    return rows;
  }
  std::size_t middle_row() const { return GetParam().rows.size() / 2; }

  TempDir dir_;
};

TEST_P(MalformedLog, ValidFileReads) {
  const std::string path = write("good.log", GetParam().rows);
  EXPECT_NO_THROW(GetParam().read(path));
}

// The last line ends half-way through its middle field, with no line end.
TEST_P(MalformedLog, TruncatedLastLine) {
  const LogCase& c = GetParam();
  std::vector<Tokens> rows = c.rows;
  Tokens last = rows.back();
  rows.pop_back();
  std::string text = render(c, rows);
  const std::size_t cut = (last.size() - 1) / 2;
  for (std::size_t i = 0; i < cut; ++i) text += last[i] + c.separator;
  text += last[cut].substr(0, (last[cut].size() + 1) / 2);
  const std::string path = write_text(dir_.file("bad.log"), text);
  expect_input_error([&] { c.read(path); }, at(path, c.rows.size() - 1), {"truncated"});
}

TEST_P(MalformedLog, NonNumericField) {
  const std::string path = write("bad.log", with_field(middle_row(), 1, "abc"));
  expect_input_error([&] { GetParam().read(path); }, at(path, middle_row()),
                     {"field 2", "'abc'", "not a number"});
}

TEST_P(MalformedLog, NumberWithTrailingGarbage) {
  const std::string path = write("bad.log", with_field(middle_row(), 1, "1.5x"));
  expect_input_error([&] { GetParam().read(path); }, at(path, middle_row()), {"not a number"});
}

TEST_P(MalformedLog, NanField) {
  for (const std::string nan : {"nan", "NaN", "-nan"}) {
    const std::string path = write("bad.log", with_field(middle_row(), 1, nan));
    expect_input_error([&] { GetParam().read(path); }, at(path, middle_row()), {"not finite"});
  }
}

TEST_P(MalformedLog, InfField) {
  for (const std::string inf : {"inf", "-inf", "Infinity"}) {
    const std::string path = write("bad.log", with_field(middle_row(), 1, inf));
    expect_input_error([&] { GetParam().read(path); }, at(path, middle_row()), {"not finite"});
  }
}

TEST_P(MalformedLog, MissingFile) {
  const std::string path = dir_.file("missing.log");
  expect_input_error([&] { GetParam().read(path); }, path + ": ", {"cannot open"});
}

TEST_P(MalformedLog, EmptyFile) {
  const std::string path = write_text(dir_.file("empty.log"), "");
  expect_input_error([&] { GetParam().read(path); }, path + ": ", {"no data rows"});
}

TEST_P(MalformedLog, HeaderOnlyFile) {
  const LogCase& c = GetParam();
  const std::string header = c.header.empty() ? "% only a comment\n" : c.header;
  const std::string path = write_text(dir_.file("header.log"), header);
  expect_input_error([&] { c.read(path); }, path + ": ", {"no data rows"});
}

TEST_P(MalformedLog, TooManyColumns) {
  std::vector<Tokens> rows = GetParam().rows;
  const std::size_t row = middle_row();
  const std::size_t expected = rows[row].size();
  rows[row].insert(rows[row].end(), 8, "1");
  const std::string path = write("bad.log", rows);
  expect_input_error([&] { GetParam().read(path); }, at(path, row),
                     {"too many columns", "expected " + std::to_string(expected) + " columns",
                      "got " + std::to_string(expected + 8)});
}

TEST_P(MalformedLog, TimeGoesBackwards) {
  const LogCase& c = GetParam();
  if (!c.timed) GTEST_SKIP() << c.name << " has no time column";
  const std::string earlier = c.rows[0][0];
  const std::string path = write("bad.log", with_field(2, 0, earlier));
  expect_input_error([&] { c.read(path); }, at(path, 2), {c.backwards_word, earlier});
}

INSTANTIATE_TEST_SUITE_P(AllLogReaders, MalformedLog, ::testing::ValuesIn(log_cases()),
                         [](const ::testing::TestParamInfo<LogCase>& test) {
                           return test.param.name;
                         });

// The raw IS log specifics: bins are integers 0..255 and every row has the same count.
class MalformedIsLog : public ::testing::Test {
 protected:
  std::string write(const std::string& rows) {
    return write_text(dir_.file("bad_IS.log"), "% 1\n% 2\n% 3\n% 4\n% 5\n% 6\n% 7\n% 8\n" + rows);
  }
  void expect_error(const std::string& rows, std::size_t line,
                    const std::vector<std::string>& words) {
    const std::string path = write(rows);
    expect_input_error([&] { read_is_log(path); }, path + ":" + std::to_string(line) + ":", words);
  }
  TempDir dir_;
};

TEST_F(MalformedIsLog, BinOutOfRange) {
  expect_error("1 1 0 5 6 7\n2 2 0 5 256 7\n", 10,
               {"field 5 (bin 2)", "'256'", "out of range 0..255"});
  expect_error("1 1 0 5 -1 7\n", 9, {"bin 2", "'-1'", "0..255"});
  expect_error("1 1 0 5 6 99999999999999999999\n", 9, {"bin 3", "0..255"});
}

TEST_F(MalformedIsLog, BinNotAnInteger) {
  expect_error("1 1 0 5 6 7\n2 2 0 5 6 12.5\n", 10, {"bin 3", "'12.5'", "not an integer"});
  expect_error("1 1 0 abc 6 7\n", 9, {"bin 1", "not an integer"});
  expect_error("1 1 0 nan 6 7\n", 9, {"bin 1", "not an integer"});
}

TEST_F(MalformedIsLog, DifferingBinCounts) {
  expect_error("1 1 0 5 6 7\n2 2 0 5 6\n", 10, {"truncated", "3 bins", "line 9"});
  expect_error("1 1 0 5 6 7\n2 2 0 5 6 7\n3 3 0 5 6 7 8\n", 11, {"too many columns", "3 bins"});
}

TEST_F(MalformedIsLog, NoBins) { expect_error("1 1 0\n", 9, {"truncated", "at least 4 columns"}); }

TEST(MalformedSetupLog, ExtraRowAndNonPositiveSizes) {
  const TempDir dir;
  const std::string two_rows = write_text(dir.file("SETUP.log"), "50 0.1 0.0314\n50 0.1 0.0314\n");
  expect_input_error([&] { read_setup_log(two_rows); }, two_rows + ":2:", {"extra data row"});
  const std::string negative = write_text(dir.file("neg.log"), "% h\n50 -0.1 0.0314\n");
  expect_input_error([&] { read_setup_log(negative); }, negative + ":2:", {"positive"});
}

TEST(MalformedTum, ZeroQuaternion) {
  const TempDir dir;
  const std::string path =
      write_text(dir.file("bad.tum"), "# t x y z qx qy qz qw\n1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 0\n");
  expect_input_error([&] { read_tum(path); }, path + ":3:", {"zero quaternion"});
}

TEST(MalformedTum, EqualTimes) {
  const TempDir dir;
  const std::string path =
      write_text(dir.file("bad.tum"), "1 0 0 0 0 0 0 1\n# c\n1 0 0 0 0 0 0 1\n");
  expect_input_error([&] { read_tum(path); }, path + ":3:", {"does not increase"});
}

// Detections: the exact header, 7 comma-separated fields, integers where the record has them.
class MalformedDetections : public ::testing::Test {
 protected:
  static constexpr const char* kHeader =
      "keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m\n";
  static constexpr const char* kRow1 = "1,147,1093455234.723,63234722,199,6.251769,19.4\n";
  static constexpr const char* kRow2 = "1,148,1093455234.791,63234790,198,6.220353,19.5\n";

  std::string write_csv(const std::string& text) { return write_text(dir_.file("bad.csv"), text); }
  std::string write_gz(const std::string& text) {
    const std::string path = dir_.file("bad.csv.gz");
    std::ofstream out(path, std::ios::binary);
    GzipStream gzip(out, path, true);
    gzip.write(text);
    gzip.finish();
    return path;
  }
  // Checks the same malformed text as .csv and as .csv.gz.
  void expect_error(const std::string& text, const std::string& line,
                    const std::vector<std::string>& words) {
    for (const std::string& path : {write_csv(text), write_gz(text)})
      expect_input_error([&] { read_detections(path); }, path + ":" + line, words);
  }
  TempDir dir_;
};

TEST_F(MalformedDetections, ValidFileReads) {
  EXPECT_EQ(read_detections(write_gz(std::string(kHeader) + kRow1 + kRow2)).size(), 2u);
  EXPECT_EQ(read_detections(write_csv(std::string(kHeader) + kRow1 + kRow2)).size(), 2u);
}

TEST_F(MalformedDetections, WrongHeader) {
  expect_error(
      "keyframe,beam,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m\n" + std::string(kRow1),
      "1:", {"wrong header", "'keyframe,beam,"});
  expect_error(std::string(kRow1) + kRow2, "1:", {"wrong header"});
}

TEST_F(MalformedDetections, WrongFieldCount) {
  expect_error(std::string(kHeader) + kRow1 + "1,148,1093455234.791,63234790,198,6.2\n",
               "3:", {"truncated", "7 comma-separated fields, got 6"});
  expect_error(std::string(kHeader) + "1,147,1093455234.723,63234722,199,6.251769,19.4,7\n" + kRow2,
               "2:", {"too many fields", "got 8"});
}

TEST_F(MalformedDetections, TruncatedLastLine) {
  expect_error(std::string(kHeader) + kRow1 + "1,148,1093455", "3:", {"truncated"});
}

TEST_F(MalformedDetections, NonIntegerKeyframe) {
  expect_error(std::string(kHeader) + kRow1 + "1.5,148,1093455234.791,63234790,198,6.220353,19.5\n",
               "3:", {"field 1 (keyframe)", "'1.5'", "not an integer"});
  expect_error(std::string(kHeader) + "1,147,1093455234.723,63234722.5,199,6.251769,19.4\n",
               "2:", {"sensor_time_ms", "not an integer"});
  expect_error(std::string(kHeader) + "99999999999,147,1093455234.723,1,199,6.251769,19.4\n",
               "2:", {"keyframe", "out of range"});
}

TEST_F(MalformedDetections, NonNumericNanAndInf) {
  expect_error(std::string(kHeader) + "1,147,1093455234.723,63234722,199,6.251769,abc\n",
               "2:", {"field 7 (range_m)", "not a number"});
  expect_error(std::string(kHeader) + "1,147,1093455234.723,63234722,199,6.251769,\n",
               "2:", {"range_m", "not a number"});
  expect_error(std::string(kHeader) + "1,147,nan,63234722,199,6.251769,19.4\n",
               "2:", {"t_log_s", "not finite"});
  expect_error(std::string(kHeader) + "1,147,1093455234.723,63234722,199,-inf,19.4\n",
               "2:", {"angle_rad", "not finite"});
}

TEST_F(MalformedDetections, BeamRowBackwards) {
  expect_error(std::string(kHeader) + kRow2 + kRow1,
               "3:", {"beam_row goes backwards (147 after 148)"});
}

TEST_F(MalformedDetections, MissingEmptyAndHeaderOnly) {
  const std::string missing = dir_.file("missing.csv.gz");
  expect_input_error([&] { read_detections(missing); }, missing + ": ", {"cannot open"});
  expect_error("", " ", {"empty file"});
  expect_error(kHeader, " ", {"no data rows"});
}

TEST_F(MalformedDetections, CorruptGzip) {
  const std::string path = write_gz(std::string(kHeader) + kRow1 + kRow2);
  std::string bytes = testing::read_text(path);
  bytes[bytes.size() - 8] = static_cast<char>(bytes[bytes.size() - 8] ^ 0x5a);  // the CRC-32
  write_text(path, bytes);
  expect_input_error([&] { read_detections(path); }, path + ": ", {"cannot read"});
}

TEST_F(MalformedDetections, CutGzip) {
  std::string text = kHeader;
  for (int i = 0; i < 2000; ++i) text += kRow1;
  const std::string path = write_gz(text);
  const std::string bytes = testing::read_text(path);
  write_text(path, bytes.substr(0, bytes.size() / 2));
  expect_input_error([&] { read_detections(path); }, path + ": ", {"truncated gzip"});
}

}  // namespace
}  // namespace msislab::io
