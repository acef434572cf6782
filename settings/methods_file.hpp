// The methods file (docs/formats.md): SLAM programs of the user's, each declared by the command
// that runs it, which msislab then runs, scores and lists like its built-in methods.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace msislab::settings {

/// One method of a methods file, as declared (the command's placeholders not yet filled in).
struct ExternalMethod {
  std::string name;                  ///< [a-z0-9_]+, not a built-in method's
  std::string title;                 ///< in figures and tables
  std::vector<std::string> command;  ///< program and arguments, with {placeholders}
  double time_limit_s = 0.0;         ///< wall time before the program is stopped, s (> 0)
  /// Added to (or replacing in) the inherited environment, in file order.
  std::vector<std::pair<std::string, std::string>> environment;
  std::optional<std::uint32_t> colour;  ///< 0xRRGGBB from "#rrggbb"; none: from the name
  std::string line_style;               ///< "", solid, dashed, dotted or points
  std::string methods_dir;              ///< the methods file's folder, absolute
};

/// The file and its methods in file order; `text` is its bytes (a Monte Carlo directory keeps
/// a copy and compares it on resume and merge).
struct MethodsFile {
  std::string path;
  std::string text;
  std::vector<ExternalMethod> methods;
};

/// The placeholders a command may use (docs/formats.md).
const std::vector<std::string>& method_placeholders();

/// Reads and checks a methods file: unknown keys or placeholders, a missing or empty command, a
/// name that is malformed, repeated or one of `reserved_names` (the built-in methods), a time
/// limit not > 0, a malformed colour or line style are InputErrors naming the file, line and key.
MethodsFile read_methods_file(const std::string& path,
                              const std::vector<std::string>& reserved_names);

/// The values of the placeholders for one run of a method.
struct PlaceholderValues {
  std::string dataset;  ///< the dataset directory, absolute
  std::string out;      ///< the fresh folder the program writes into, absolute
  std::string config;   ///< a SLAM config YAML file, absolute
  std::uint64_t seed = 0;
};

/// The command with every {placeholder} replaced (read_methods_file checked their names).
std::vector<std::string> expand_command(const ExternalMethod& method,
                                        const PlaceholderValues& values);

}  // namespace msislab::settings
