// msislab's JSON files (metrics.json, summary.json, montecarlo.json, failed.json, fidelity.json)
// through nlohmann-json: its strict RFC 8259 parser, objects keeping their key order. Each schema
// has one `to_json(Json&, const T&)` beside one `from_json(const JsonObject&, T&)`; errors name
// the file and line (syntax) or the file and key (content). The writer lays a document out the
// way the files have always looked: the outer levels one member per line, the rest on one line.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace msislab::io {

/// A JSON value whose objects keep their members in insertion (file) order.
using Json = nlohmann::ordered_json;

/// Parses one JSON document; `path` names it in errors ("path:line: what").
Json parse_json(std::string_view text, const std::string& path);
/// Reads and parses a JSON file.
Json read_json_file(const std::string& path);

/// How a document is laid out: objects and arrays at the first `expanded_levels` levels (0 is
/// the document), and the values of the members named in `expanded_members`, have one member
/// per line indented by two spaces a level; everything deeper is written on one line as
/// `{"a": 1, "b": [2, 3]}`. Numbers are written in their shortest round-trip form, and a
/// non-finite double as null.
struct JsonLayout {
  int expanded_levels = 1;
  std::vector<std::string> expanded_members;
};

/// The text of a document, ending in a newline.
std::string format_json(const Json& value, const JsonLayout& layout = {});
/// Writes format_json(value, layout) to path atomically.
void write_json_file(const std::string& path, const Json& value, const JsonLayout& layout = {});

/// Typed access to the members of an object, with errors "path: key 'a.b': what".
class JsonObject {
 public:
  JsonObject(const Json& value, std::string path, std::string prefix = "");

  bool has(const std::string& key) const;
  /// The key is there and not null.
  bool has_value(const std::string& key) const;
  /// A required member that is an array.
  const Json& array(const std::string& key) const;
  double number(const std::string& key) const;
  /// A number or null (nullopt).
  std::optional<double> number_or_null(const std::string& key) const;
  /// A whole number in [min, max].
  long long integer(const std::string& key, long long min, long long max) const;
  std::string string(const std::string& key) const;
  /// A string or null (nullopt).
  std::optional<std::string> string_or_null(const std::string& key) const;
  JsonObject object(const std::string& key) const;
  /// Fails naming the key.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  const Json& value() const { return value_; }
  const std::string& path() const { return path_; }

 private:
  const Json& member(const std::string& key) const;

  const Json& value_;
  std::string path_;
  std::string prefix_;  ///< "a." for a nested object
};

/// Reads a file of schema T: parses it and calls `from_json(const JsonObject&, T&)`.
template <class T>
T read_json_file_as(const std::string& path) {
  const Json root = read_json_file(path);
  T value{};
  from_json(JsonObject(root, path), value);
  return value;
}

}  // namespace msislab::io
