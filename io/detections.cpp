#include "io/detections.hpp"

#include <zlib.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <limits>
#include <memory>
#include <ostream>
#include <string_view>

#include "io/atomic_file.hpp"
#include "io/gzip_stream.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

constexpr std::string_view kHeader =
    "keyframe,beam_row,t_log_s,sensor_time_ms,angle_idx,angle_rad,range_m";
constexpr std::array<std::string_view, 7> kNames = {
    "keyframe", "beam_row", "t_log_s", "sensor_time_ms", "angle_idx", "angle_rad", "range_m"};

bool is_gzip_name(const std::string& path) {
  constexpr std::string_view kSuffix = ".gz";
  return path.size() >= kSuffix.size() &&
         path.compare(path.size() - kSuffix.size(), kSuffix.size(), kSuffix) == 0;
}

std::int32_t parse_int32(std::string_view token, const FieldAt& at) {
  const std::int64_t value = parse_integer(token, at);
  if (value < std::numeric_limits<std::int32_t>::min() ||
      value > std::numeric_limits<std::int32_t>::max())
    fail_field(at, token, "is out of range");
  return static_cast<std::int32_t>(value);
}

DetectionRecord parse_row(std::string_view line, std::size_t line_number, const std::string& path) {
  const std::array<std::string_view, 7> f = split_csv<7>(line, path, line_number);
  const auto at = [&](std::size_t i) { return FieldAt{path, line_number, i + 1, kNames[i]}; };
  DetectionRecord r;
  r.keyframe = parse_int32(f[0], at(0));
  r.beam_row = parse_integer(f[1], at(1));
  r.t_log_s = parse_finite(f[2], at(2));
  r.sensor_time_ms = parse_integer(f[3], at(3));
  r.angle_idx = parse_int32(f[4], at(4));
  r.angle_rad = parse_finite(f[5], at(5));
  r.range_m = parse_finite(f[6], at(6));
  return r;
}

// The header, then one record per non-blank line in beam_row order.
class DetectionParser {
 public:
  explicit DetectionParser(const std::string& path) : path_(path) {}

  void line(std::string_view text) {
    text = strip_cr(text);
    ++line_number_;
    if (line_number_ == 1) return check_header(text);
    if (text.empty()) return;
    const DetectionRecord record = parse_row(text, line_number_, path_);
    if (!rows_.empty() && record.beam_row < rows_.back().beam_row)
      fail_at(path_, line_number_,
              "beam_row goes backwards (" + std::to_string(record.beam_row) + " after " +
                  std::to_string(rows_.back().beam_row) + ")");
    rows_.push_back(record);
  }

  std::vector<DetectionRecord> finish() {
    if (line_number_ == 0) fail_file(path_, "empty file: no header line");
    require_data_rows(path_, rows_.size());
    return std::move(rows_);
  }

 private:
  void check_header(std::string_view text) const {
    if (text != kHeader)
      fail_at(path_, 1,
              "wrong header: expected '" + std::string(kHeader) + "', got '" +
                  std::string(text.substr(0, 100)) + "'");
  }

  const std::string& path_;
  std::size_t line_number_ = 0;
  std::vector<DetectionRecord> rows_;
};

struct GzFileCloser {
  void operator()(gzFile_s* file) const { gzclose(file); }
};

// Appends up to one big chunk of decompressed text; false once the data is exhausted. gzread
// returns a cut gzip file's data without an error, so the error state is checked every time.
bool read_chunk(gzFile_s* file, const std::string& path, std::string& buffer) {
  constexpr unsigned kChunk = 1u << 22;
  const std::size_t kept = buffer.size();
  buffer.resize(kept + kChunk);
  const int got = gzread(file, buffer.data() + kept, kChunk);
  int code = Z_OK;
  const char* message = gzerror(file, &code);
  if (code == Z_BUF_ERROR) fail_file(path, "truncated gzip data (unexpected end of file)");
  if (got < 0 || code != Z_OK) fail_file(path, std::string("cannot read: ") + message);
  buffer.resize(kept + static_cast<std::size_t>(got));
  return got > 0;
}

// gzread also reads an uncompressed file as is, so one path serves .csv and .csv.gz. A partial
// last line of each chunk is carried into the next one.
template <typename OnLine>
void for_each_line(const std::string& path, OnLine&& on_line) {
  const std::unique_ptr<gzFile_s, GzFileCloser> file(gzopen(path.c_str(), "rb"));
  if (!file) fail_file(path, std::string("cannot open: ") + std::strerror(errno));
  gzbuffer(file.get(), 1u << 20);
  std::string buffer;
  std::size_t consumed = 0;
  bool more = true;
  while (more) {
    buffer.erase(0, consumed);
    consumed = 0;
    more = read_chunk(file.get(), path, buffer);
    for (std::size_t newline = 0; (newline = buffer.find('\n', consumed)) != std::string::npos;
         consumed = newline + 1)
      on_line(std::string_view(buffer).substr(consumed, newline - consumed));
  }
  if (consumed < buffer.size()) on_line(std::string_view(buffer).substr(consumed));
}

void append_row(std::string& out, const DetectionRecord& r, const std::string& path,
                std::size_t row) {
  out += std::to_string(r.keyframe);
  out += ',';
  out += std::to_string(r.beam_row);
  out += ',';
  append_finite(out, r.t_log_s, path, row, "t_log_s");
  out += ',';
  out += std::to_string(r.sensor_time_ms);
  out += ',';
  out += std::to_string(r.angle_idx);
  out += ',';
  append_finite(out, r.angle_rad, path, row, "angle_rad");
  out += ',';
  append_finite(out, r.range_m, path, row, "range_m");
  out += '\n';
}

void check_beam_order(const std::string& path, const std::vector<DetectionRecord>& rows) {
  for (std::size_t row = 1; row < rows.size(); ++row)
    if (rows[row].beam_row < rows[row - 1].beam_row)
      fail_file(path, "row " + std::to_string(row + 1) + ": beam_row goes backwards (" +
                          std::to_string(rows[row].beam_row) + " after " +
                          std::to_string(rows[row - 1].beam_row) + "), cannot write it");
}

}  // namespace

bool DetectionRecord::operator==(const DetectionRecord& other) const {
  return keyframe == other.keyframe && beam_row == other.beam_row && t_log_s == other.t_log_s &&
         sensor_time_ms == other.sensor_time_ms && angle_idx == other.angle_idx &&
         angle_rad == other.angle_rad && range_m == other.range_m;
}

std::vector<DetectionRecord> read_detections(const std::string& path) {
  DetectionParser parser(path);
  for_each_line(path, [&](std::string_view line) { parser.line(line); });
  return parser.finish();
}

void write_detections(const std::string& path, const std::vector<DetectionRecord>& rows) {
  check_beam_order(path, rows);
  write_file_atomically(path, [&](std::ostream& out) {
    GzipStream gzip(out, path, is_gzip_name(path));
    std::string text(kHeader);
    text += '\n';
    constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
    for (std::size_t row = 0; row < rows.size(); ++row) {
      append_row(text, rows[row], path, row + 1);
      if (text.size() < kFlushBytes) continue;
      gzip.write(text);
      text.clear();
    }
    gzip.write(text);
    gzip.finish();
  });
}

}  // namespace msislab::io
