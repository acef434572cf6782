#include "io/ply.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <optional>
#include <string_view>

#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

enum class Format { ascii, little_endian, big_endian };

constexpr bool kHostIsLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

/// A scalar type of the header: its size in bytes, whether it is a float or signed integer.
struct ScalarType {
  std::size_t bytes = 0;
  bool is_float = false;
  bool is_signed = false;
};

std::optional<ScalarType> scalar_type(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, ScalarType>, 16> kTypes{{
      {"char", {1, false, true}},
      {"int8", {1, false, true}},
      {"uchar", {1, false, false}},
      {"uint8", {1, false, false}},
      {"short", {2, false, true}},
      {"int16", {2, false, true}},
      {"ushort", {2, false, false}},
      {"uint16", {2, false, false}},
      {"int", {4, false, true}},
      {"int32", {4, false, true}},
      {"uint", {4, false, false}},
      {"uint32", {4, false, false}},
      {"float", {4, true, true}},
      {"float32", {4, true, true}},
      {"double", {8, true, true}},
      {"float64", {8, true, true}},
  }};
  for (const auto& [type_name, type] : kTypes)
    if (type_name == name) return type;
  return std::nullopt;
}

struct Property {
  std::string name;
  ScalarType type;
  std::optional<ScalarType> list_count;  ///< set for a list property
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  std::size_t data_offset = 0;  ///< first byte after end_header's line
  std::size_t lines = 0;        ///< header lines
};

ScalarType required_type(std::string_view name, const std::string& path, std::size_t line) {
  const std::optional<ScalarType> type = scalar_type(name);
  if (!type) fail_at(path, line, "unknown property type '" + std::string(name) + "'");
  return *type;
}

void header_line(Header& h, std::string_view line, const std::string& path, std::size_t number) {
  std::vector<std::string_view> f;
  split_blanks(line, f);
  if (f.empty() || f[0] == "comment" || f[0] == "obj_info") return;
  if (f[0] == "format") {
    if (f.size() != 3) fail_at(path, number, "expected 'format TYPE 1.0'");
    if (f[1] == "ascii") {
      h.format = Format::ascii;
    } else if (f[1] == "binary_little_endian") {
      h.format = Format::little_endian;
    } else if (f[1] == "binary_big_endian") {
      h.format = Format::big_endian;
    } else {
      fail_at(path, number, "unknown format '" + std::string(f[1]) + "'");
    }
  } else if (f[0] == "element") {
    if (f.size() != 3) fail_at(path, number, "expected 'element NAME COUNT'");
    const std::int64_t count = parse_integer(f[2], {path, number, 3, "count"});
    if (count < 0) fail_field({path, number, 3, "count"}, f[2], "is negative");
    h.elements.push_back({std::string(f[1]), count, {}});
  } else if (f[0] == "property") {
    if (h.elements.empty()) fail_at(path, number, "property before any element");
    Property p;
    if (f.size() == 5 && f[1] == "list") {
      p = {std::string(f[4]), required_type(f[3], path, number), required_type(f[2], path, number)};
      if (p.list_count->is_float) fail_at(path, number, "a list count must be an integer type");
    } else if (f.size() == 3) {
      p = {std::string(f[2]), required_type(f[1], path, number), std::nullopt};
    } else {
      fail_at(path, number, "expected 'property TYPE NAME' or 'property list COUNT TYPE NAME'");
    }
    h.elements.back().properties.push_back(std::move(p));
  } else {
    fail_at(path, number, "unknown header line '" + std::string(line.substr(0, 60)) + "'");
  }
}

Header read_header(const std::string& text, const std::string& path) {
  Header h;
  std::size_t offset = 0;
  while (offset < text.size()) {
    const std::size_t newline = text.find('\n', offset);
    if (newline == std::string::npos) break;
    const std::string_view line = strip_cr(std::string_view(text).substr(offset, newline - offset));
    offset = newline + 1;
    ++h.lines;
    if (h.lines == 1) {
      if (line != "ply") fail_file(path, "not a PLY file (the first line is not 'ply')");
      continue;
    }
    if (line == "end_header") {
      h.data_offset = offset;
      return h;
    }
    header_line(h, line, path, h.lines);
  }
  if (h.lines == 0 && text.substr(0, 3) != "ply") {
    fail_file(path, "not a PLY file (the first line is not 'ply')");
  }
  fail_file(path, "no end_header line");
}

/// The values of one element instance, in property order (a list's count, then its items).
class DataReader {
 public:
  DataReader(const std::string& text, const Header& h, const std::string& path)
      : text_(text), format_(h.format), path_(path), offset_(h.data_offset), line_(h.lines) {}

  /// Starts an instance; false when the data is exhausted.
  bool begin_instance() {
    if (format_ != Format::ascii) return offset_ < text_.size();
    while (offset_ < text_.size()) {
      const std::size_t newline = std::min(text_.find('\n', offset_), text_.size());
      const std::string_view line =
          strip_cr(std::string_view(text_).substr(offset_, newline - offset_));
      offset_ = newline + 1;
      ++line_;
      split_blanks(line, tokens_);
      token_ = 0;
      if (!tokens_.empty()) return true;
    }
    return false;
  }

  double value(const ScalarType& type, const char* what) {
    if (format_ == Format::ascii) {
      if (token_ >= tokens_.size())
        fail_at(path_, line_, std::string("truncated line: no ") + what);
      const std::string_view token = tokens_[token_++];
      double v = 0.0;
      const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
      if (ec != std::errc() || end != token.data() + token.size())
        fail_field({path_, line_, token_, what}, token, "is not a number");
      return v;
    }
    if (offset_ + type.bytes > text_.size()) throw Truncated{};
    std::array<unsigned char, 8> bytes{};
    std::memcpy(bytes.data(), text_.data() + offset_, type.bytes);
    offset_ += type.bytes;
    if ((format_ == Format::big_endian) == kHostIsLittleEndian)
      std::reverse(bytes.begin(), bytes.begin() + static_cast<long>(type.bytes));
    return decode(bytes, type);
  }

  /// ASCII: the instance's line holds no more values than it read.
  void end_instance() const {
    if (format_ == Format::ascii && token_ != tokens_.size())
      fail_at(path_, line_, column_count_error(token_, tokens_.size()));
  }

  struct Truncated {};

 private:
  static double decode(const std::array<unsigned char, 8>& b, const ScalarType& type) {
    if (type.is_float) {
      if (type.bytes == 4) return load<float>(b);
      return load<double>(b);
    }
    const std::uint64_t bits = load<std::uint64_t>(b);
    if (!type.is_signed) return static_cast<double>(bits);
    const unsigned shift = static_cast<unsigned>(64 - 8 * type.bytes);
    return static_cast<double>(static_cast<std::int64_t>(bits << shift) >> shift);
  }
  template <typename T>
  static T load(const std::array<unsigned char, 8>& b) {
    T value{};
    std::memcpy(&value, b.data(), sizeof(T));
    return value;
  }

  const std::string& text_;
  Format format_;
  const std::string& path_;
  std::size_t offset_;
  std::size_t line_;
  std::vector<std::string_view> tokens_;
  std::size_t token_ = 0;
};

std::string plural(const std::string& element) {
  return element == "vertex" ? "vertices" : element + "s";
}

std::int64_t list_item(double value, const std::string& path, std::int64_t face) {
  if (value != std::floor(value) || std::abs(value) > 9e15)
    fail_file(path, "face " + std::to_string(face) + " has a vertex index that is not an integer");
  return static_cast<std::int64_t>(value);
}

void read_instance(DataReader& data, const Element& e, std::int64_t i, PlyData& out,
                   const std::string& path) {
  const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
  {
    Eigen::Vector3d vertex = Eigen::Vector3d::Zero();
    for (const Property& p : e.properties) {
      if (!p.list_count) {
        const double v = data.value(p.type, p.name.c_str());
        if (is_vertex && (p.name == "x" || p.name == "y" || p.name == "z"))
          vertex[p.name[0] - 'x'] = v;
        continue;
      }
      const double count = data.value(*p.list_count, p.name.c_str());
      if (count < 0 || count > 1e6)
        fail_file(path, e.name + " " + std::to_string(i) + ": bad list length");
      const bool keep = is_face && (p.name == "vertex_indices" || p.name == "vertex_index");
      std::vector<std::int64_t> items;
      for (int k = 0; k < static_cast<int>(count); ++k) {
        const double v = data.value(p.type, p.name.c_str());
        if (keep) items.push_back(list_item(v, path, i));
      }
      if (keep) out.faces.push_back(std::move(items));
    }
    data.end_instance();
    if (!is_vertex) return;
    if (!vertex.allFinite())
      fail_file(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    out.vertices_m.push_back(vertex);
  }
}

void read_element(DataReader& data, const Element& e, PlyData& out, const std::string& path) {
  if (e.properties.empty()) return;  // no data, however many instances are announced
  std::int64_t i = 0;
  try {
    for (; i < e.count; ++i) {
      if (!data.begin_instance()) throw DataReader::Truncated{};
      read_instance(data, e, i, out, path);
    }
  } catch (const DataReader::Truncated&) {
    fail_file(path, "truncated: the header announces " + std::to_string(e.count) + " " +
                        plural(e.name) + ", the file has " + std::to_string(i));
  }
}

/// The vertex element is there, with x and y.
void check_vertex_element(const Header& h, const std::string& path) {
  for (const Element& e : h.elements) {
    if (e.name != "vertex") continue;
    bool x = false, y = false;
    for (const Property& p : e.properties) {
      x = x || (p.name == "x" && !p.list_count);
      y = y || (p.name == "y" && !p.list_count);
    }
    if (x && y) return;
  }
  fail_file(path, "no 'element vertex' with x and y properties");
}

}  // namespace

PlyData read_ply(const std::string& path) {
  const std::string text = read_whole_file(path);
  const Header header = read_header(text, path);
  check_vertex_element(header, path);
  DataReader data(text, header, path);
  PlyData out;
  for (const Element& e : header.elements) read_element(data, e, out, path);
  return out;
}

}  // namespace msislab::io
