// Strict reading of YAML mappings into plain structs: every key read is checked for type and
// finiteness, and finish() rejects keys nobody read, so typos fail with "FILE:LINE: key 'a.b':
// ...". Internal to io/: nothing outside this module includes yaml-cpp.
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

namespace msislab::io {

/// Loads a YAML file; a missing file or a syntax error becomes an InputError naming the file/line.
YAML::Node load_yaml_file(const std::string& path);
/// The same for YAML text; `name` stands for the file in errors.
YAML::Node load_yaml_text(const std::string& text, const std::string& name);

class YamlMap {
 public:
  /// node must be a mapping (or null/absent, read as empty). `prefix` is the dotted key path.
  /// `line` is the 0-based line of this mapping's own key (used when the mapping is empty or
  /// absent, since yaml-cpp places an empty value on the line after its key); -1 for the root.
  YamlMap(const YAML::Node& node, std::string file, std::string prefix, int line = -1);

  bool has(const std::string& key) const;
  /// Reads a finite number into out if the key is present; returns whether it was.
  bool number(const std::string& key, double& out);
  /// Like number() but the key must be present.
  double required_number(const std::string& key);
  /// Fails for a required key that is absent: names a present key that looks like a typo of it
  /// ("unknown key 'sped_mps' (did you mean 'speed_mps'?)"), else "key: what" at the mapping.
  [[noreturn]] void fail_required(const std::string& key, const std::string& what) const;
  bool integer(const std::string& key, long long& out);
  bool text(const std::string& key, std::string& out);
  /// true/false (YAML 1.2 core spelling only).
  bool boolean(const std::string& key, bool& out);
  /// A sequence of finite numbers.
  bool numbers(const std::string& key, std::vector<double>& out);
  /// A sequence of words (scalars).
  bool texts(const std::string& key, std::vector<std::string>& out);
  /// A child mapping (empty when absent).
  YamlMap map(const std::string& key);
  /// The keys of this mapping in file order (for user-named entries such as segments).
  std::vector<std::string> keys() const;
  /// The raw node of a key, for structures a caller parses itself.
  YAML::Node node(const std::string& key);

  /// Throws for the first key that was never read.
  void finish() const;

  /// Throws InputError "FILE:LINE: key 'prefix.key': what".
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  [[noreturn]] void fail_node(const YAML::Node& at, const std::string& key,
                              const std::string& what) const;
  std::string path_of(const std::string& key) const;
  /// "FILE:LINE" of a node (of the key's line when `at` is empty or null), or "FILE" when unknown:
  /// what fail_node() puts in front, for messages that are not errors (warnings).
  std::string location(const YAML::Node& at, const std::string& key) const;
  /// 0-based line of a key in the file (of the mapping when the key is absent; -1 when unknown).
  int key_line(const std::string& key) const;
  const std::string& file() const { return file_; }

 private:
  YAML::Node node_;
  std::string file_;
  std::string prefix_;
  std::set<std::string> read_;
  int line_ = -1;
};

/// How a value reads in an error message: 'text', an empty value, a list or a mapping.
std::string describe(const YAML::Node& value);

/// The candidate nearest to `key` by edit distance (optimal string alignment: an insertion, a
/// deletion, a substitution or a swap of neighbours counts 1), if it is near enough to be a typo:
/// at most 1 edit for candidates of up to 4 characters, 2 up to 8, 3 beyond. "" when none is.
std::string closest_key(const std::string& key, const std::vector<std::string>& candidates);

/// Parses a YAML scalar as a finite double; false when it is not one.
bool parse_finite_scalar(const std::string& text, double& out);

}  // namespace msislab::io
