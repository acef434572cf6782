#include "settings/expectations_yaml.hpp"

#include <set>

#include "io/input_error.hpp"
#include "io/yaml_fields.hpp"

namespace msislab::settings {

namespace {

const std::vector<std::string> kChecks = {"at_most", "at_least", "equals", "anees_in_bounds",
                                          "below"};

/// The decimals of a number as written ("2.84" -> "2.84"), for the quote.
std::string scalar_text(io::YamlMap& map, const std::string& key) {
  const YAML::Node node = map.node(key);
  return node.IsScalar() ? node.Scalar() : std::string();
}

void read_quote(io::YamlMap& entry, Expectation& e) {
  if (!entry.has("quote")) return;
  io::YamlMap quote = entry.map("quote");
  if (!quote.text("file", e.quote_file)) quote.fail_required("file", "the page that quotes it");
  if (!quote.text("text", e.quote_text)) quote.fail_required("text", "the quoted text with {}");
  quote.finish();
  if (e.quote_text.find("{}") == std::string::npos) {
    quote.fail("text", "must hold {} where the figure stands");
  }
  if (!e.equals) entry.fail("quote", "a quote needs equals (the figure it quotes)");
}

Expectation read_entry(io::YamlMap& entry) {
  Expectation e;
  e.location = entry.location(YAML::Node(), "");
  entry.text("name", e.name);
  entry.text("result", e.result);
  entry.text("method", e.method);
  long long cell = 0;
  if (entry.integer("cell", cell)) {
    if (cell < 0) entry.fail("cell", "must be 0 or more");
    e.cell = static_cast<int>(cell);
    if (e.method.empty()) entry.fail_required("method", "a sweep's cell needs its method");
  }
  if (entry.text("metric", e.metric) && !is_figure_name(e.metric)) {
    const std::string near = io::closest_key(e.metric, figure_names());
    entry.fail("metric", "no result of any kind has a figure '" + e.metric + "'" +
                             (near.empty() ? " (see docs/cli.md, \"msislab check\")"
                                           : " (did you mean '" + near + "'?)"));
  }
  double number = 0.0;
  if (entry.number("at_most", number)) e.at_most = number;
  if (entry.number("at_least", number)) e.at_least = number;
  if (entry.number("equals", number)) {
    e.equals = number;
    e.equals_text = scalar_text(entry, "equals");
    if (!entry.number("tolerance", e.tolerance)) {
      entry.fail_required("tolerance", "equals needs a tolerance (0 for an exact figure)");
    }
    if (e.tolerance < 0.0) entry.fail("tolerance", "must be 0 or more");
  } else if (entry.has("tolerance")) {
    entry.fail("tolerance", "goes with equals");
  }
  entry.boolean("anees_in_bounds", e.anees_in_bounds);
  if (e.anees_in_bounds && entry.has("metric")) {
    entry.fail("metric", "anees_in_bounds reads the anees; leave metric out");
  }
  entry.text("below", e.below);
  if (!e.below.empty() && e.below == e.method) entry.fail("below", "names the same method");
  read_quote(entry, e);
  entry.finish();  // an unknown key first: a misspelt check is not a missing one
  bool any = false;
  for (const std::string& check : kChecks) any = any || entry.has(check);
  if (!any) {
    throw io::InputError(e.location +
                         ": an expectation states nothing to check (give at_most, "
                         "at_least, equals with tolerance, anees_in_bounds or below)");
  }
  if (e.at_most && e.at_least && *e.at_least > *e.at_most) {
    entry.fail("at_least", "is above at_most");
  }
  if (e.name.empty()) {
    e.name = (e.result.empty() ? "" : e.result + " ") + (e.method.empty() ? "" : e.method + " ") +
             (e.cell ? "cell " + std::to_string(*e.cell) + " " : "") +
             (e.anees_in_bounds ? "anees" : e.metric);
  }
  return e;
}

}  // namespace

std::vector<Expectation> read_expectations_yaml(const std::string& path) {
  io::YamlMap root(io::load_yaml_file(path), path, "");
  const YAML::Node list = root.node("expectations");
  if (!list.IsSequence() || list.size() == 0) {
    root.fail("expectations", "expected a non-empty list of expectations");
  }
  std::vector<Expectation> expectations;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i].IsMap()) root.fail_node(list[i], "expectations", "each entry is a mapping");
    io::YamlMap entry(list[i], path, "expectations[" + std::to_string(i) + "]",
                      static_cast<int>(list[i].Mark().line));
    Expectation e = read_entry(entry);
    if (!names.insert(e.name).second) {
      entry.fail("name", "'" + e.name + "' is used by an earlier expectation");
    }
    expectations.push_back(std::move(e));
  }
  root.finish();
  return expectations;
}

}  // namespace msislab::settings
