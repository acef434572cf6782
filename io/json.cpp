#include "io/json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

/// nlohmann's message without its "[json.exception...] parse error at line L, column C: " head.
std::string parse_error_text(const Json::parse_error& e) {
  std::string what = e.what();
  const std::size_t column = what.find("column ");
  const std::size_t colon = what.find(": ", column == std::string::npos ? 0 : column);
  return colon == std::string::npos ? what : what.substr(colon + 2);
}

const char* type_name(const Json& value) {
  if (value.is_null()) return "null";
  if (value.is_boolean()) return "a boolean";
  if (value.is_number()) return "a number";
  if (value.is_string()) return "a string";
  if (value.is_array()) return "an array";
  return "an object";
}

std::string json_string_literal(const std::string& text) {
  return Json(text).dump(-1, ' ', false, Json::error_handler_t::replace);
}

class Printer {
 public:
  explicit Printer(const JsonLayout& layout) : layout_(layout) {}

  void value(const Json& v, int level, bool expanded) {
    if (v.is_object()) {
      container(v, level, expanded, '{', '}');
    } else if (v.is_array()) {
      container(v, level, expanded, '[', ']');
    } else if (v.is_number_float()) {
      const double number = v.get<double>();
      text_ += std::isfinite(number) ? format_number(number) : "null";
    } else if (v.is_string()) {
      text_ += json_string_literal(v.get<std::string>());
    } else {
      text_ += v.dump();  // null, booleans and integers
    }
  }

  std::string text() && { return std::move(text_); }

 private:
  void container(const Json& v, int level, bool expanded, char open, char close) {
    text_ += open;
    const std::string pad(2 * static_cast<std::size_t>(level + 1), ' ');
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      text_ += first ? "" : ",";
      text_ += expanded ? "\n" + pad : std::string(first ? "" : " ");
      first = false;
      bool expand_child = level + 1 < layout_.expanded_levels;
      if (v.is_object()) {
        text_ += json_string_literal(it.key()) + ": ";
        expand_child = expand_child || std::count(layout_.expanded_members.begin(),
                                                  layout_.expanded_members.end(), it.key()) > 0;
      }
      value(*it, level + 1, expand_child);
    }
    if (expanded) text_ += "\n" + pad.substr(2);
    text_ += close;
  }

  const JsonLayout& layout_;
  std::string text_;
};

std::size_t line_at(std::string_view text, std::size_t offset) {
  const std::size_t at = std::min(offset, text.size());
  return static_cast<std::size_t>(
             std::count(text.begin(), text.begin() + static_cast<long>(at), '\n')) +
         1;
}

}  // namespace

Json parse_json(std::string_view text, const std::string& path) {
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const Json::parse_error& e) {
    fail_at(path, line_at(text, e.byte == 0 ? 0 : e.byte - 1), parse_error_text(e));
  } catch (const Json::out_of_range& e) {
    // A number beyond a double's range (1e999) is nlohmann's out_of_range, not a parse_error.
    // nlohmann names the number but not where it is: its first occurrence.
    const std::string what = e.what();
    const std::size_t open = what.find('\'');
    const std::size_t close = what.rfind('\'');
    const std::string number =
        open < close ? what.substr(open + 1, close - open - 1) : std::string();
    const std::size_t at = number.empty() ? std::string_view::npos : text.find(number);
    const std::string message = "number " + number + " is out of range";
    if (at == std::string_view::npos) fail_file(path, message);
    fail_at(path, line_at(text, at), message);
  }
}

Json read_json_file(const std::string& path) { return parse_json(read_whole_file(path), path); }

std::string format_json(const Json& value, const JsonLayout& layout) {
  Printer printer(layout);
  printer.value(value, 0, layout.expanded_levels > 0);
  return std::move(printer).text() + "\n";
}

void write_json_file(const std::string& path, const Json& value, const JsonLayout& layout) {
  const std::string text = format_json(value, layout);
  write_text_atomically(path, text);
}

JsonObject::JsonObject(const Json& value, std::string path, std::string prefix)
    : value_(value), path_(std::move(path)), prefix_(std::move(prefix)) {
  if (!value_.is_object()) {
    fail_file(path_, prefix_.empty() ? "expected a JSON object"
                                     : "key '" + prefix_.substr(0, prefix_.size() - 1) +
                                           "': expected an object");
  }
}

void JsonObject::fail(const std::string& key, const std::string& what) const {
  fail_file(path_, "key '" + prefix_ + key + "': " + what);
}

bool JsonObject::has(const std::string& key) const { return value_.contains(key); }

bool JsonObject::has_value(const std::string& key) const {
  const auto it = value_.find(key);
  return it != value_.end() && !it->is_null();
}

const Json& JsonObject::member(const std::string& key) const {
  const auto it = value_.find(key);
  if (it == value_.end()) fail(key, "missing");
  return *it;
}

const Json& JsonObject::array(const std::string& key) const {
  const Json& v = member(key);
  if (!v.is_array()) fail(key, std::string("expected an array, got ") + type_name(v));
  return v;
}

double JsonObject::number(const std::string& key) const {
  const Json& v = member(key);
  if (!v.is_number()) fail(key, std::string("expected a number, got ") + type_name(v));
  return v.get<double>();
}

std::optional<double> JsonObject::number_or_null(const std::string& key) const {
  if (has(key) && value_.at(key).is_null()) return std::nullopt;
  return number(key);
}

long long JsonObject::integer(const std::string& key, long long min, long long max) const {
  const double value = number(key);
  if (value != std::floor(value) || value < static_cast<double>(min) ||
      value > static_cast<double>(max)) {
    fail(key, "expected a whole number in [" + std::to_string(min) + ", " + std::to_string(max) +
                  "], got " + format_number(value));
  }
  return static_cast<long long>(value);
}

std::string JsonObject::string(const std::string& key) const {
  const Json& v = member(key);
  if (!v.is_string()) fail(key, std::string("expected a string, got ") + type_name(v));
  return v.get<std::string>();
}

std::optional<std::string> JsonObject::string_or_null(const std::string& key) const {
  if (has(key) && value_.at(key).is_null()) return std::nullopt;
  return string(key);
}

JsonObject JsonObject::object(const std::string& key) const {
  const Json& v = member(key);
  if (!v.is_object()) fail(key, std::string("expected an object, got ") + type_name(v));
  return JsonObject(v, path_, prefix_ + key + ".");
}

}  // namespace msislab::io
