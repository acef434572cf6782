#include "io/yaml_fields.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

#include "io/input_error.hpp"

namespace msislab::io {

YAML::Node load_yaml_file(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) fail_file(path, "cannot open: no such file");
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::ParserException& e) {
    fail_at(path, static_cast<std::size_t>(e.mark.line + 1), "malformed YAML: " + e.msg);
  } catch (const YAML::BadFile&) {
    fail_file(path, "cannot open");
  }
}

YAML::Node load_yaml_text(const std::string& text, const std::string& name) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    fail_at(name, static_cast<std::size_t>(e.mark.line + 1), "malformed YAML: " + e.msg);
  }
}

namespace {
std::size_t edit_distance(const std::string& a, const std::string& b) {
  // d[i][j]: edits from a's first i characters to b's first j (Damerau's swap of neighbours
  // included, each character edited once at most).
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
      }
    }
  }
  return d[a.size()][b.size()];
}
}  // namespace

std::string closest_key(const std::string& key, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = 0;
  for (const std::string& candidate : candidates) {
    const std::size_t limit = candidate.size() <= 4 ? 1 : candidate.size() <= 8 ? 2 : 3;
    const std::size_t distance = edit_distance(key, candidate);
    if (distance == 0 || distance > limit) continue;
    if (best.empty() || distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

bool parse_finite_scalar(const std::string& text, double& out) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (begin != end && *begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, out);
  return ec == std::errc() && ptr == end && std::isfinite(out);
}

YamlMap::YamlMap(const YAML::Node& node, std::string file, std::string prefix, int line)
    : node_(node), file_(std::move(file)), prefix_(std::move(prefix)), line_(line) {
  if (node_ && !node_.IsNull() && !node_.IsMap()) {
    const std::string where = prefix_.empty() ? "the document" : "key '" + prefix_ + "'";
    fail_at(file_, static_cast<std::size_t>(node_.Mark().line + 1),
            where + ": expected a mapping of keys");
  }
  // yaml-cpp keeps repeated keys and lookups return the first: reject them here, or the second
  // occurrence (and any typo inside it) would be ignored silently.
  std::set<std::string> seen;
  if (node_ && node_.IsMap()) {
    for (const auto& item : node_) {
      if (!seen.insert(item.first.Scalar()).second) {
        fail_node(item.first, item.first.Scalar(), "duplicate key");
      }
    }
  }
}

std::string YamlMap::path_of(const std::string& key) const {
  return prefix_.empty() ? key : prefix_ + "." + key;
}

int YamlMap::key_line(const std::string& key) const {
  if (node_ && node_.IsMap()) {
    for (const auto& item : node_) {
      if (item.first.Scalar() == key) return item.first.Mark().line;
    }
  }
  // An absent key is reported at its mapping's own key ("vehicle:"), or at the mapping's start.
  if (line_ >= 0) return line_;
  return node_ && node_.IsMap() ? node_.Mark().line : -1;
}

std::string YamlMap::location(const YAML::Node& at, const std::string& key) const {
  const int line = at && !at.IsNull() ? at.Mark().line : key_line(key);
  return line >= 0 ? file_ + ":" + std::to_string(line + 1) : file_;
}

void YamlMap::fail_node(const YAML::Node& at, const std::string& key,
                        const std::string& what) const {
  // An empty value's mark points past its key, so empty and absent values use the key's line.
  const int line = at && !at.IsNull() ? at.Mark().line : key_line(key);
  const std::string msg = "key '" + path_of(key) + "': " + what;
  if (line >= 0) fail_at(file_, static_cast<std::size_t>(line + 1), msg);
  fail_file(file_, msg);
}

void YamlMap::fail(const std::string& key, const std::string& what) const {
  fail_node(has(key) ? node_[key] : YAML::Node(), key, what);
}

std::string describe(const YAML::Node& value) {
  if (value.IsNull()) return "an empty value";
  if (value.IsScalar()) return "'" + value.Scalar() + "'";
  return value.IsSequence() ? "a list" : "a mapping";
}

bool YamlMap::has(const std::string& key) const {
  return node_ && node_.IsMap() && node_[key].IsDefined();
}

YAML::Node YamlMap::node(const std::string& key) {
  read_.insert(key);
  return has(key) ? node_[key] : YAML::Node();
}

bool YamlMap::number(const std::string& key, double& out) {
  read_.insert(key);
  if (!has(key)) return false;
  const YAML::Node value = node_[key];
  if (!value.IsScalar() || !parse_finite_scalar(value.Scalar(), out)) {
    fail_node(value, key, "expected a finite number, got " + describe(value));
  }
  return true;
}

double YamlMap::required_number(const std::string& key) {
  double out = 0.0;
  if (!number(key, out)) fail_required(key, "is required");
  return out;
}

void YamlMap::fail_required(const std::string& key, const std::string& what) const {
  // The key the user meant may be there, misspelt: it is the one to name, at its own line.
  if (node_ && node_.IsMap()) {
    for (const auto& item : node_) {
      const std::string present = item.first.Scalar();
      if (read_.count(present) == 0 && closest_key(present, {key}) == key) {
        fail_node(item.first, present, "unknown key (did you mean '" + key + "'?)");
      }
    }
  }
  fail(key, what);
}

bool YamlMap::integer(const std::string& key, long long& out) {
  read_.insert(key);
  if (!has(key)) return false;
  const YAML::Node value = node_[key];
  const std::string text = value.IsScalar() ? value.Scalar() : "";
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size()) {
    fail_node(value, key, "expected an integer, got '" + text + "'");
  }
  return true;
}

bool YamlMap::text(const std::string& key, std::string& out) {
  read_.insert(key);
  if (!has(key)) return false;
  const YAML::Node value = node_[key];
  if (!value.IsScalar()) fail_node(value, key, "expected a text value, got " + describe(value));
  out = value.Scalar();
  return true;
}

bool YamlMap::boolean(const std::string& key, bool& out) {
  read_.insert(key);
  if (!has(key)) return false;
  const YAML::Node value = node_[key];
  const std::string text = value.IsScalar() ? value.Scalar() : "";
  if (text != "true" && text != "false") {
    fail_node(value, key, "expected true or false, got " + describe(value));
  }
  out = text == "true";
  return true;
}

bool YamlMap::numbers(const std::string& key, std::vector<double>& out) {
  read_.insert(key);
  if (!has(key)) return false;
  const YAML::Node value = node_[key];
  if (!value.IsSequence())
    fail_node(value, key, "expected a list of numbers, got " + describe(value));
  out.clear();
  for (const YAML::Node& item : value) {
    double x = 0.0;
    if (!item.IsScalar() || !parse_finite_scalar(item.Scalar(), x)) {
      fail_node(item, key, "expected finite numbers in the list");
    }
    out.push_back(x);
  }
  return true;
}

bool YamlMap::texts(const std::string& key, std::vector<std::string>& out) {
  read_.insert(key);
  if (!has(key)) return false;
  const YAML::Node value = node_[key];
  if (!value.IsSequence())
    fail_node(value, key, "expected a list of words, got " + describe(value));
  out.clear();
  for (const YAML::Node& item : value) {
    if (!item.IsScalar()) fail_node(item, key, "expected words in the list, got " + describe(item));
    out.push_back(item.Scalar());
  }
  return true;
}

YamlMap YamlMap::map(const std::string& key) {
  read_.insert(key);
  return YamlMap(has(key) ? node_[key] : YAML::Node(), file_, path_of(key), key_line(key));
}

std::vector<std::string> YamlMap::keys() const {
  std::vector<std::string> out;
  if (!node_ || !node_.IsMap()) return out;
  for (const auto& item : node_) out.push_back(item.first.Scalar());
  return out;
}

void YamlMap::finish() const {
  if (!node_ || !node_.IsMap()) return;
  for (const auto& item : node_) {
    const std::string key = item.first.Scalar();
    if (read_.count(key)) continue;
    const std::string near = closest_key(key, {read_.begin(), read_.end()});
    if (!near.empty()) fail_node(item.first, key, "unknown key (did you mean '" + near + "'?)");
    std::string known;
    for (const std::string& k : read_) known += (known.empty() ? "" : ", ") + k;
    fail_node(item.first, key, "unknown key (known here: " + known + ")");
  }
}

}  // namespace msislab::io
