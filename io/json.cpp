#include "io/json.hpp"

#include <cctype>
#include <charconv>
#include <cmath>

#include "io/input_error.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

const char* type_name(JsonValue::Type type) {
  switch (type) {
    case JsonValue::Type::null:
      return "null";
    case JsonValue::Type::boolean:
      return "a boolean";
    case JsonValue::Type::number:
      return "a number";
    case JsonValue::Type::string:
      return "a string";
    case JsonValue::Type::array:
      return "an array";
    case JsonValue::Type::object:
      return "an object";
  }
  return "";
}

class Parser {
 public:
  Parser(std::string_view text, const std::string& path) : text_(text), path_(path) {}

  JsonValue document() {
    JsonValue value = parse_value(0);
    skip_blanks();
    if (at_ < text_.size()) fail("unexpected text after the JSON value");
    return value;
  }

 private:
  static constexpr int kMaxDepth = 64;

  [[noreturn]] void fail(const std::string& what) const {
    std::size_t line = 1;
    for (std::size_t i = 0; i < at_ && i < text_.size(); ++i) line += text_[i] == '\n';
    fail_at(path_, line, what);
  }

  void skip_blanks() {
    while (at_ < text_.size() &&
           (text_[at_] == ' ' || text_[at_] == '\t' || text_[at_] == '\n' || text_[at_] == '\r')) {
      ++at_;
    }
  }

  bool consume(char c) {
    skip_blanks();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }

  void expect(char c) {
    if (!consume(c)) fail(std::string("expected '") + c + "'");
  }

  bool literal(std::string_view word) {
    if (text_.substr(at_, word.size()) != word) return false;
    at_ += word.size();
    return true;
  }

  JsonValue parse_value(int depth) {
    if (depth > kMaxDepth) fail("nesting too deep");
    skip_blanks();
    if (at_ >= text_.size()) fail("unexpected end of the file");
    JsonValue value;
    const char c = text_[at_];
    if (c == '{') {
      value.type = JsonValue::Type::object;
      ++at_;
      if (consume('}')) return value;
      do {
        skip_blanks();
        std::string key = parse_string();
        expect(':');
        value.members.emplace_back(std::move(key), parse_value(depth + 1));
      } while (consume(','));
      expect('}');
    } else if (c == '[') {
      value.type = JsonValue::Type::array;
      ++at_;
      if (consume(']')) return value;
      do {
        value.items.push_back(parse_value(depth + 1));
      } while (consume(','));
      expect(']');
    } else if (c == '"') {
      value.type = JsonValue::Type::string;
      value.text = parse_string();
    } else if (literal("null")) {
      value.type = JsonValue::Type::null;
    } else if (literal("true")) {
      value.type = JsonValue::Type::boolean;
      value.boolean = true;
    } else if (literal("false")) {
      value.type = JsonValue::Type::boolean;
    } else {
      value.type = JsonValue::Type::number;
      const std::size_t begin = at_;
      value.number = parse_number();
      value.text = std::string(text_.substr(begin, at_ - begin));
    }
    return value;
  }

  double parse_number() {
    const std::size_t begin = at_;
    while (at_ < text_.size() &&
           (std::isdigit(static_cast<unsigned char>(text_[at_])) || text_[at_] == '-' ||
            text_[at_] == '+' || text_[at_] == '.' || text_[at_] == 'e' || text_[at_] == 'E')) {
      ++at_;
    }
    const std::string_view token = text_.substr(begin, at_ - begin);
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() ||
        !std::isfinite(value)) {
      at_ = begin;
      fail("'" + std::string(token.empty() ? text_.substr(at_, 1) : token) +
           "' is not a JSON value");
    }
    return value;
  }

  std::string parse_string() {
    if (at_ >= text_.size() || text_[at_] != '"') fail("expected a string");
    ++at_;
    std::string out;
    while (true) {
      if (at_ >= text_.size()) fail("unterminated string");
      const char c = text_[at_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (at_ >= text_.size()) fail("unterminated string");
      const char e = text_[at_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u':
          append_utf8(out, parse_hex4());
          break;
        default:
          fail(std::string("bad escape '\\") + e + "'");
      }
    }
  }

  unsigned parse_hex4() {
    if (at_ + 4 > text_.size()) fail("truncated \\u escape");
    unsigned code = 0;
    const auto [ptr, ec] = std::from_chars(text_.data() + at_, text_.data() + at_ + 4, code, 16);
    if (ec != std::errc() || ptr != text_.data() + at_ + 4) fail("bad \\u escape");
    at_ += 4;
    return code;
  }

  // Surrogate pairs are not joined: msislab never writes them.
  static void append_utf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  std::string_view text_;
  const std::string& path_;
  std::size_t at_ = 0;
};

}  // namespace

const JsonValue* JsonValue::find(const std::string& key) const {
  for (const auto& [name, value] : members) {
    if (name == key) return &value;
  }
  return nullptr;
}

JsonValue parse_json(std::string_view text, const std::string& path) {
  return Parser(text, path).document();
}

JsonValue read_json_file(const std::string& path) {
  return parse_json(read_whole_file(path), path);
}

JsonObject::JsonObject(const JsonValue& value, std::string path, std::string prefix)
    : value_(value), path_(std::move(path)), prefix_(std::move(prefix)) {
  if (value_.type != JsonValue::Type::object) {
    fail_file(path_, prefix_.empty() ? "expected a JSON object"
                                     : "key '" + prefix_.substr(0, prefix_.size() - 1) +
                                           "': expected an object");
  }
}

void JsonObject::fail(const std::string& key, const std::string& what) const {
  fail_file(path_, "key '" + prefix_ + key + "': " + what);
}

bool JsonObject::has(const std::string& key) const { return value_.find(key) != nullptr; }

const JsonValue& JsonObject::get(const std::string& key, JsonValue::Type type) const {
  const JsonValue* member = value_.find(key);
  if (!member) fail(key, "missing");
  if (member->type != type) {
    fail(key, std::string("expected ") + type_name(type) + ", got " + type_name(member->type));
  }
  return *member;
}

double JsonObject::number(const std::string& key) const {
  return get(key, JsonValue::Type::number).number;
}

std::optional<double> JsonObject::number_or_null(const std::string& key) const {
  const JsonValue* member = value_.find(key);
  if (member && member->type == JsonValue::Type::null) return std::nullopt;
  return number(key);
}

std::string JsonObject::string(const std::string& key) const {
  return get(key, JsonValue::Type::string).text;
}

std::optional<std::string> JsonObject::string_or_null(const std::string& key) const {
  const JsonValue* member = value_.find(key);
  if (member && member->type == JsonValue::Type::null) return std::nullopt;
  return string(key);
}

JsonObject JsonObject::object(const std::string& key) const {
  return JsonObject(get(key, JsonValue::Type::object), path_, prefix_ + key + ".");
}

}  // namespace msislab::io
