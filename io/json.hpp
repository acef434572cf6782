// A strict reader for the JSON files msislab writes itself (metrics.json, summary.json,
// montecarlo.json): RFC 8259 values, objects keeping their key order. Errors name the file and
// line; the accessors name the key.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace msislab::io {

struct JsonValue {
  enum class Type { null, boolean, number, string, array, object };
  Type type = Type::null;
  bool boolean = false;
  double number = 0.0;
  std::string text;                                        ///< string
  std::vector<JsonValue> items;                            ///< array
  std::vector<std::pair<std::string, JsonValue>> members;  ///< object, in file order

  /// The member named key of an object; nullptr when absent.
  const JsonValue* find(const std::string& key) const;
};

/// Parses one JSON document; `path` names it in errors ("path:line: what").
JsonValue parse_json(std::string_view text, const std::string& path);
/// Reads and parses a JSON file.
JsonValue read_json_file(const std::string& path);

/// Typed access to the members of an object, with errors "path: key 'a.b': what".
class JsonObject {
 public:
  JsonObject(const JsonValue& value, std::string path, std::string prefix = "");

  bool has(const std::string& key) const;
  /// A required member of the given type.
  const JsonValue& get(const std::string& key, JsonValue::Type type) const;
  double number(const std::string& key) const;
  /// A number or null (nullopt).
  std::optional<double> number_or_null(const std::string& key) const;
  std::string string(const std::string& key) const;
  /// A string or null (nullopt).
  std::optional<std::string> string_or_null(const std::string& key) const;
  JsonObject object(const std::string& key) const;
  /// Fails naming the key.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  const JsonValue& value() const { return value_; }
  const std::string& path() const { return path_; }

 private:
  const JsonValue& value_;
  std::string path_;
  std::string prefix_;  ///< "a." for a nested object
};

}  // namespace msislab::io
