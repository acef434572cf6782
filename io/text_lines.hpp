// The one way msislab reads text: LineReader gives the lines of a file, plain or gzip-compressed,
// and every text format reads through it (DataLines for the whitespace-separated .log and TUM
// files, for_each_csv_row for the CSV files). Also number parsing that names the file, line and
// column on any error, and shortest round-trip number formatting for the writers.
#pragma once

#include "io/input_error.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

struct gzFile_s;

namespace msislab::io {

/// Where a field came from, for error messages: "file:line: field 5 (bottomVelX) ...".
struct FieldAt {
  const std::string& path;
  std::size_t line = 0;     ///< 1-based line in the file
  std::size_t field = 0;    ///< 1-based field on the line
  std::string_view column;  ///< name of the column
};

/// Throws InputError "file:line: field 5 (bottomVelX) 'abc' <what>" (long tokens are cut).
[[noreturn]] void fail_field(const FieldAt& at, std::string_view token, const std::string& what);
/// Parses the whole token as a finite double; otherwise InputError ("is not a number", "is not
/// finite", "is out of range").
double parse_finite(std::string_view token, const FieldAt& at);
/// Parses the whole token as a decimal integer; otherwise InputError ("is not an integer").
std::int64_t parse_integer(std::string_view token, const FieldAt& at);

/// The fields of a line split on runs of spaces and tabs (a '\r' counts as a blank), into
/// `fields` (cleared first).
void split_blanks(std::string_view line, std::vector<std::string_view>& fields);

/// Reads the whole file into memory; a missing or unreadable file is an InputError.
std::string read_whole_file(const std::string& path);

/// The lines of a text file, numbered from 1, without their '\n' and a trailing '\r'. The file is
/// read through zlib in large chunks, so a gzip-compressed file (any name) reads as its text; a
/// cut gzip file, a missing file or a read error is an InputError naming the path.
class LineReader {
 public:
  explicit LineReader(std::string path);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  /// The next line; false at the end of the file. The view is valid until the next call.
  bool next(std::string_view& line);
  /// The number of the line `next` gave last.
  std::size_t line_number() const { return line_number_; }
  const std::string& path() const { return path_; }

 private:
  bool read_chunk();

  struct Closer {
    void operator()(gzFile_s* file) const;
  };
  std::string path_;
  std::unique_ptr<gzFile_s, Closer> file_;
  static constexpr unsigned kMaxChunk = 1u << 22;
  std::string buffer_;
  std::size_t consumed_ = 0;
  unsigned chunk_ = 1u << 14;  ///< the next read's size, doubling up to kMaxChunk
  bool more_ = true;
  std::size_t line_number_ = 0;
};

/// The last `count` non-empty lines of a text file, in order; none when the file is missing (for
/// the scratch notes and stderr files of child processes, which may not exist).
std::vector<std::string> last_lines(const std::string& path, std::size_t count);
/// The last non-empty line of a text file; empty when the file is missing or has none.
std::string last_line(const std::string& path);

/// The data lines of a text file: skips blank lines and lines whose first non-blank character is
/// the comment character, and splits on runs of spaces and tabs.
class DataLines {
 public:
  explicit DataLines(std::string path, char comment = '%');

  /// Advances to the next data line; false at the end of the file.
  bool next();

  const std::string& path() const { return lines_.path(); }
  std::size_t line_number() const { return lines_.line_number(); }
  std::size_t size() const { return fields_.size(); }
  std::string_view field(std::size_t index) const { return fields_[index]; }

  /// Field index (0-based) as a finite double; column names it in the error message.
  double number(std::size_t index, std::string_view column) const;
  /// Fails unless the line has exactly `expected` fields ("truncated line" when fewer).
  void expect_columns(std::size_t expected) const;
  /// Throws InputError("path:line: what").
  [[noreturn]] void fail(const std::string& what) const;

 private:
  LineReader lines_;
  char comment_;
  std::vector<std::string_view> fields_;  ///< into the current line
};

/// Rows of a log are in logging order: InputError "time goes backwards (t after previous)" when
/// t_s < previous_s.
void check_time_order(const DataLines& lines, double previous_s, double t_s);

/// InputError "path: no data rows (empty file?)" when rows is zero.
void require_data_rows(const std::string& path, std::size_t rows);

/// The column-count error text, "truncated line: expected 32 columns, got 17" or
/// "too many columns: expected 32 columns, got 40".
std::string column_count_error(std::size_t expected, std::size_t got);

/// The line without a trailing '\r' (CRLF files).
std::string_view strip_cr(std::string_view line);

/// Splits a CSV line (no quoting) into exactly `count` fields written to `fields`; otherwise
/// InputError "path:line: truncated line: expected N comma-separated fields, got M" (or "too many
/// fields: ...").
void split_csv_fields(std::string_view line, const std::string& path, std::size_t line_number,
                      std::string_view* fields, std::size_t count);

/// split_csv_fields into an array of N fields.
template <std::size_t N>
std::array<std::string_view, N> split_csv(std::string_view line, const std::string& path,
                                          std::size_t line_number) {
  std::array<std::string_view, N> fields;
  split_csv_fields(line, path, line_number, fields.data(), N);
  return fields;
}

/// The shortest text that reads back as exactly the same double.
std::string format_number(double value);
/// The value with a fixed number of decimals, for tables and figure labels ("2.57").
std::string format_fixed(double value, int decimals);
/// A count with thousands separators ("1,092,064"), for tables and figure labels.
std::string format_count(std::size_t n);
/// Appends the shortest text that reads back as exactly the same double.
void append_number(std::string& out, double value);
/// For a writer: a non-finite value is an InputError naming the file, the 1-based data row and the
/// column.
void check_finite(double value, const std::string& path, std::size_t row, std::string_view column);
/// check_finite, then append_number.
void append_finite(std::string& out, double value, const std::string& path, std::size_t row,
                   std::string_view column);

/// Calls row(line, line_number) for every non-empty line of a CSV file after its first line, which
/// must be exactly `header` (InputError "path:1: wrong header: expected '...', got '...'" else);
/// returns the number of rows.
template <typename Row>
std::size_t for_each_csv_row(const std::string& path, std::string_view header, Row&& row) {
  LineReader lines(path);
  std::string_view line;
  if (!lines.next(line)) fail_file(path, "empty file: no header line");
  if (line != header) {
    fail_at(path, 1,
            "wrong header: expected '" + std::string(header) + "', got '" +
                std::string(line.substr(0, 120)) + "'");
  }
  std::size_t rows = 0;
  while (lines.next(line)) {
    if (line.empty()) continue;
    row(line, lines.line_number());
    ++rows;
  }
  return rows;
}

}  // namespace msislab::io
