#include "settings/methods_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "io/input_error.hpp"
#include "io/text_lines.hpp"
#include "io/yaml_fields.hpp"

namespace msislab::settings {

namespace fs = std::filesystem;

namespace {

bool all_of_chars(const std::string& text, bool (*ok)(char)) {
  return !text.empty() && std::all_of(text.begin(), text.end(), ok);
}

bool name_char(char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; }

bool environment_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
}

/// Calls visit(name) for each {name} of an argument; text without a closing brace is literal.
template <typename Visit>
void for_each_placeholder(const std::string& arg, Visit&& visit) {
  for (std::size_t open = arg.find('{'); open != std::string::npos;
       open = arg.find('{', open + 1)) {
    const std::size_t close = arg.find('}', open);
    if (close == std::string::npos) return;
    visit(open, close);
  }
}

std::vector<std::string> read_command(io::YamlMap& m) {
  if (!m.has("command")) m.fail_required("command", "required: the program and its arguments");
  const YAML::Node node = m.node("command");
  if (!node.IsSequence() || node.size() == 0) {
    m.fail("command", "expected a non-empty list of words (the program, then its arguments)");
  }
  std::vector<std::string> command;
  const std::vector<std::string>& known = method_placeholders();
  for (const YAML::Node& word : node) {
    if (!word.IsScalar() || word.Scalar().empty()) {
      m.fail_node(word, "command", "expected a word, got " + io::describe(word));
    }
    const std::string arg = word.Scalar();
    for_each_placeholder(arg, [&](std::size_t open, std::size_t close) {
      const std::string name = arg.substr(open + 1, close - open - 1);
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        std::string list;
        for (const std::string& k : known) list += (list.empty() ? "{" : ", {") + k + "}";
        m.fail_node(word, "command", "unknown placeholder {" + name + "} (known: " + list + ")");
      }
    });
    command.push_back(arg);
  }
  return command;
}

std::vector<std::pair<std::string, std::string>> read_environment(io::YamlMap& m) {
  std::vector<std::pair<std::string, std::string>> environment;
  io::YamlMap env = m.map("environment");
  for (const std::string& key : env.keys()) {
    if (!all_of_chars(key, environment_char) || (key[0] >= '0' && key[0] <= '9')) {
      env.fail(key, "not a variable name (letters, digits and _, not starting with a digit)");
    }
    std::string value;
    env.text(key, value);
    environment.emplace_back(key, value);
  }
  env.finish();
  return environment;
}

std::optional<std::uint32_t> read_colour(io::YamlMap& m) {
  std::string text;
  if (!m.text("colour", text)) return std::nullopt;
  const bool hex = text.size() == 7 && text[0] == '#' &&
                   std::all_of(text.begin() + 1, text.end(),
                               [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
  if (!hex) m.fail("colour", "expected #rrggbb (six hex digits), got '" + text + "'");
  return static_cast<std::uint32_t>(std::stoul(text.substr(1), nullptr, 16));
}

ExternalMethod read_method(io::YamlMap m, const std::vector<std::string>& taken,
                           const std::vector<std::string>& reserved) {
  ExternalMethod method;
  if (!m.text("name", method.name)) m.fail_required("name", "required: the method's name");
  if (!all_of_chars(method.name, name_char)) {
    m.fail("name", "'" + method.name + "': expected lower-case letters, digits and _");
  }
  if (std::find(reserved.begin(), reserved.end(), method.name) != reserved.end()) {
    m.fail("name", "'" + method.name + "' is a built-in method; choose another name");
  }
  if (std::find(taken.begin(), taken.end(), method.name) != taken.end()) {
    m.fail("name", "'" + method.name + "' is declared twice");
  }
  method.title = method.name;
  m.text("title", method.title);
  method.command = read_command(m);
  if (!m.has("time_limit_s")) m.fail_required("time_limit_s", "required: seconds, > 0");
  method.time_limit_s = m.required_number("time_limit_s");
  if (!(method.time_limit_s > 0.0)) m.fail("time_limit_s", "must be > 0");
  method.environment = read_environment(m);
  method.colour = read_colour(m);
  if (m.text("line_style", method.line_style)) {
    const std::vector<std::string> styles = {"solid", "dashed", "dotted", "points"};
    if (std::find(styles.begin(), styles.end(), method.line_style) == styles.end()) {
      m.fail("line_style", "'" + method.line_style + "': expected solid, dashed, dotted or points");
    }
  }
  m.finish();
  return method;
}

}  // namespace

const std::vector<std::string>& method_placeholders() {
  static const std::vector<std::string> names = {"dataset", "out", "config", "seed", "methods_dir"};
  return names;
}

MethodsFile read_methods_file(const std::string& path,
                              const std::vector<std::string>& reserved_names) {
  MethodsFile file;
  file.path = path;
  file.text = io::read_whole_file(path);
  io::YamlMap root(io::load_yaml_text(file.text, path), path, "");
  if (!root.has("methods")) root.fail_required("methods", "required: a list of methods");
  const YAML::Node list = root.node("methods");
  if (!list.IsSequence() || list.size() == 0) {
    root.fail("methods", "expected a non-empty list of methods");
  }
  root.finish();
  const std::string dir = fs::absolute(fs::path(path)).lexically_normal().parent_path().string();
  std::vector<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string prefix = "methods[" + std::to_string(i) + "]";
    ExternalMethod method =
        read_method(io::YamlMap(list[i], path, prefix, list[i].Mark().line), names, reserved_names);
    method.methods_dir = dir;
    names.push_back(method.name);
    file.methods.push_back(std::move(method));
  }
  return file;
}

std::vector<std::string> expand_command(const ExternalMethod& method,
                                        const PlaceholderValues& values) {
  const auto value_of = [&](const std::string& name) {
    if (name == "dataset") return values.dataset;
    if (name == "out") return values.out;
    if (name == "config") return values.config;
    if (name == "seed") return std::to_string(values.seed);
    return method.methods_dir;
  };
  std::vector<std::string> command;
  for (const std::string& arg : method.command) {
    std::string expanded;
    std::size_t done = 0;
    for_each_placeholder(arg, [&](std::size_t open, std::size_t close) {
      if (open < done) return;
      expanded += arg.substr(done, open - done) + value_of(arg.substr(open + 1, close - open - 1));
      done = close + 1;
    });
    command.push_back(expanded + arg.substr(done));
  }
  return command;
}

}  // namespace msislab::settings
