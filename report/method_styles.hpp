// How figures and tables show the methods: each method's name, title, colour and line style, for
// the built-in methods and those of a methods file (docs/formats.md). What a method is and how it
// runs is the application's (app/method_catalogue.hpp); a command hands the styles of the methods
// it knows to the figures and pages it draws. A method the styles do not know (an old result)
// still shows: under its name, in a colour of its own.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "plot/chart.hpp"
#include "settings/methods_file.hpp"

namespace msislab::report {

struct MethodStyle {
  std::string name;   ///< on the command line and in result files
  std::string title;  ///< in figures and tables
  std::uint32_t colour = 0x000000;
  plot::SeriesStyle line = plot::SeriesStyle::kLine;  ///< where methods are compared
};

/// The styles of a set of methods, in the order tables list them: the built-in methods (the
/// paper's two filters, the pose graph, dead reckoning, integration), then a methods file's.
class MethodStyles {
 public:
  /// The built-in methods'.
  MethodStyles();
  /// The built-in methods' and those of the methods file's methods (a name declared again
  /// replaces the earlier external method's style).
  explicit MethodStyles(const settings::MethodsFile& file);

  const std::vector<MethodStyle>& all() const { return styles_; }
  /// The title, or the name itself for a method these styles do not know.
  std::string title(const std::string& name) const;
  /// The colour; an unknown method gets name_colour(name).
  std::uint32_t colour(const std::string& name) const;
  /// The line style; solid for an unknown method.
  plot::SeriesStyle line(const std::string& name) const;
  /// Where its row goes in a table: its index; unknown methods after all of them.
  std::size_t rank(const std::string& name) const;

 private:
  const MethodStyle* find(const std::string& name) const;
  std::vector<MethodStyle> styles_;
};

/// The fixed colour an unknown method gets from its name.
std::uint32_t name_colour(const std::string& name);

}  // namespace msislab::report
