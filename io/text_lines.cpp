#include "io/text_lines.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <memory>
#include <system_error>

#include <zlib.h>

#include "io/input_error.hpp"

namespace msislab::io {
namespace {

// Long tokens are cut so that one bad field cannot flood the one-line error message.
std::string quoted(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  if (token.size() <= kMaxShown) return "'" + std::string(token) + "'";
  return "'" + std::string(token.substr(0, kMaxShown)) + "...'";
}

// Digits and letters fail the first comparison, which keeps the split loop cheap.
bool is_blank(char c) {
  return static_cast<unsigned char>(c) <= ' ' && (c == ' ' || c == '\t' || c == '\r');
}

}  // namespace

void split_blanks(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  const char* p = line.data();
  const char* const end = p + line.size();
  while (p < end) {
    while (p < end && is_blank(*p)) ++p;
    const char* const start = p;
    while (p < end && !is_blank(*p)) ++p;
    if (p > start) fields.emplace_back(start, static_cast<std::size_t>(p - start));
  }
}

void fail_field(const FieldAt& at, std::string_view token, const std::string& what) {
  fail_at(at.path, at.line,
          "field " + std::to_string(at.field) + " (" + std::string(at.column) + ") " +
              quoted(token) + " " + what);
}

double parse_finite(std::string_view token, const FieldAt& at) {
  double value = 0.0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec == std::errc::result_out_of_range && ptr == end) fail_field(at, token, "is out of range");
  if (ec != std::errc() || ptr != end) fail_field(at, token, "is not a number");
  if (!std::isfinite(value)) fail_field(at, token, "is not finite");
  return value;
}

std::int64_t parse_integer(std::string_view token, const FieldAt& at) {
  std::int64_t value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec == std::errc::result_out_of_range && ptr == end) fail_field(at, token, "is out of range");
  if (ec != std::errc() || ptr != end) fail_field(at, token, "is not an integer");
  return value;
}

std::string read_whole_file(const std::string& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) fail_file(path, std::string("cannot open: ") + std::strerror(errno));
  std::error_code ec;
  const auto size_hint = std::filesystem::file_size(path, ec);
  std::string text;
  // The first read asks for one byte more than the file's size (so a file that did not grow ends
  // the loop at once, without zero-filling a large chunk a small file does not need).
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  std::size_t chunk = ec ? kChunk : static_cast<std::size_t>(size_hint) + 1;
  while (true) {
    const std::size_t old_size = text.size();
    text.resize(old_size + chunk);
    const std::size_t got = std::fread(text.data() + old_size, 1, chunk, file.get());
    text.resize(old_size + got);
    if (got < chunk) break;
    chunk = kChunk;
  }
  if (std::ferror(file.get())) fail_file(path, std::string("cannot read: ") + std::strerror(errno));
  return text;
}

void LineReader::Closer::operator()(gzFile_s* file) const { gzclose(file); }

LineReader::LineReader(std::string path) : path_(std::move(path)) {
  std::error_code error;
  if (std::filesystem::is_directory(path_, error)) fail_file(path_, "cannot open: is a folder");
  file_.reset(gzopen(path_.c_str(), "rb"));
  if (!file_) fail_file(path_, std::string("cannot open: ") + std::strerror(errno));
  // zlib's buffers (this size in, twice it out): 1 MB for a large file, no more than the file
  // for a small one (at least 16 kB), so that reading many small files allocates little.
  constexpr std::uintmax_t kLargest = 1u << 20;
  const std::uintmax_t size = std::filesystem::file_size(path_, error);
  const std::uintmax_t buffer =
      error ? kLargest : std::clamp<std::uintmax_t>(size, 1u << 14, kLargest);
  gzbuffer(file_.get(), static_cast<unsigned>(buffer));
}

LineReader::~LineReader() = default;

// Appends up to one chunk of (decompressed) text; false once the data is exhausted. gzread
// returns a cut gzip file's data without an error, so the error state is checked every time.
bool LineReader::read_chunk() {
  buffer_.erase(0, consumed_);
  consumed_ = 0;
  const std::size_t kept = buffer_.size();
  buffer_.resize(kept + chunk_);
  const int got = gzread(file_.get(), buffer_.data() + kept, chunk_);
  int code = Z_OK;
  const char* message = gzerror(file_.get(), &code);
  if (code == Z_BUF_ERROR) fail_file(path_, "truncated gzip data (unexpected end of file)");
  if (got < 0 || code != Z_OK) fail_file(path_, std::string("cannot read: ") + message);
  buffer_.resize(kept + static_cast<std::size_t>(got));
  // Chunks grow from 16 kB to 4 MB: a small file costs no large zero-filled buffer, a large one
  // is read in a few big steps.
  chunk_ = std::min(chunk_ * 2, kMaxChunk);
  return got > 0;
}

bool LineReader::next(std::string_view& line) {
  while (true) {
    const std::size_t newline = buffer_.find('\n', consumed_);
    if (newline != std::string::npos) {
      line = strip_cr(std::string_view(buffer_).substr(consumed_, newline - consumed_));
      consumed_ = newline + 1;
      ++line_number_;
      return true;
    }
    if (more_) {
      more_ = read_chunk();
      continue;
    }
    if (consumed_ >= buffer_.size()) return false;
    line = strip_cr(std::string_view(buffer_).substr(consumed_));  // a last line without '\n'
    consumed_ = buffer_.size();
    ++line_number_;
    return true;
  }
}

std::vector<std::string> last_lines(const std::string& path, std::size_t count) {
  std::error_code error;
  if (count == 0 || !std::filesystem::is_regular_file(path, error)) return {};
  LineReader lines(path);
  std::deque<std::string> last;
  for (std::string_view line; lines.next(line);) {
    if (line.empty()) continue;
    last.emplace_back(line);
    if (last.size() > count) last.pop_front();
  }
  return {last.begin(), last.end()};
}

std::string last_line(const std::string& path) {
  const std::vector<std::string> last = last_lines(path, 1);
  return last.empty() ? "" : last.front();
}

DataLines::DataLines(std::string path, char comment) : lines_(std::move(path)), comment_(comment) {}

bool DataLines::next() {
  std::string_view line;
  while (lines_.next(line)) {
    std::size_t first = 0;
    while (first < line.size() && is_blank(line[first])) ++first;
    if (first == line.size() || line[first] == comment_) continue;
    split_blanks(line.substr(first), fields_);
    return true;
  }
  fields_.clear();
  return false;
}

double DataLines::number(std::size_t index, std::string_view column) const {
  return parse_finite(fields_[index], FieldAt{path(), line_number(), index + 1, column});
}

void DataLines::expect_columns(std::size_t expected) const {
  if (fields_.size() != expected) fail(column_count_error(expected, fields_.size()));
}

void DataLines::fail(const std::string& what) const { fail_at(path(), line_number(), what); }

// A step back means a corrupt or concatenated file; equal times (two sensor rows logged in one
// clock tick) are allowed.
void check_time_order(const DataLines& lines, double previous_s, double t_s) {
  if (t_s < previous_s)
    lines.fail("time goes backwards (" + format_number(t_s) + " after " +
               format_number(previous_s) + ")");
}

void require_data_rows(const std::string& path, std::size_t rows) {
  if (rows == 0) fail_file(path, "no data rows (empty file?)");
}

std::string column_count_error(std::size_t expected, std::size_t got) {
  const std::string counts =
      "expected " + std::to_string(expected) + " columns, got " + std::to_string(got);
  return (got < expected ? "truncated line: " : "too many columns: ") + counts;
}

void append_number(std::string& out, double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

std::string format_number(double value) {
  std::string text;
  append_number(text, value);
  return text;
}

std::string format_fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string format_count(std::size_t n) {
  std::string digits = std::to_string(n);
  for (std::size_t at = digits.size(); at > 3; at -= 3) digits.insert(at - 3, ",");
  return digits;
}

void check_finite(double value, const std::string& path, std::size_t row, std::string_view column) {
  if (std::isfinite(value)) return;
  fail_file(path, "row " + std::to_string(row) + ": " + std::string(column) + " is not finite (" +
                      format_number(value) + "), cannot write it");
}

void append_finite(std::string& out, double value, const std::string& path, std::size_t row,
                   std::string_view column) {
  check_finite(value, path, row, column);
  append_number(out, value);
}

std::string_view strip_cr(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

void split_csv_fields(std::string_view line, const std::string& path, std::size_t line_number,
                      std::string_view* fields, std::size_t count) {
  std::size_t found = 0;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? line.size() : comma;
    if (found < count) fields[found] = line.substr(start, end - start);
    ++found;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (found != count) {
    fail_at(path, line_number,
            std::string(found < count ? "truncated line" : "too many fields") + ": expected " +
                std::to_string(count) + " comma-separated fields, got " + std::to_string(found));
  }
}

}  // namespace msislab::io
