#include "results/montecarlo_files.hpp"

#include <charconv>
#include <cmath>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/json.hpp"
#include "io/text_lines.hpp"
#include "results/results.hpp"

namespace msislab::results {
namespace {

io::Json optional(const std::optional<double>& value) {
  return value ? io::Json(*value) : io::Json();
}

int int_of(const io::JsonObject& json, const std::string& key, int min) {
  return static_cast<int>(json.integer(key, min, std::numeric_limits<int>::max()));
}

}  // namespace

void to_json(io::Json& json, const MonteCarloManifest& m) {
  json = io::Json::object();
  json["scenario"] = "scenario.yaml";
  json["scenario_source"] = m.scenario_source;
  json["seed"] = m.first_seed;
  json["runs"] = m.runs;
  json["methods"] = m.methods;
  json["config"] = m.has_config ? io::Json("config.yaml") : io::Json();
  json["methods_file"] = m.has_methods_file ? io::Json("methods.yaml") : io::Json();
  json["shard"] = std::to_string(m.shard_index) + "/" + std::to_string(m.shard_count);
  json["executable_digest"] = m.executable_digest;
}

void write_manifest_json(const std::string& path, const MonteCarloManifest& m) {
  io::write_json_file(path, m);
}

void from_json(const io::JsonObject& json, MonteCarloManifest& m) {
  m.scenario_source = json.string("scenario_source");
  // A double would not hold every 64-bit seed: the seed must have been read as an unsigned.
  json.number("seed");
  const io::Json& seed = json.value().at("seed");
  if (!seed.is_number_unsigned()) {
    json.fail("seed", "expected a non-negative integer, got " + seed.dump());
  }
  m.first_seed = seed.get<std::uint64_t>();
  m.runs = int_of(json, "runs", 1);
  for (const io::Json& method : json.array("methods")) {
    if (!method.is_string()) json.fail("methods", "expected strings");
    m.methods.push_back(method.get<std::string>());
  }
  m.has_config = json.string_or_null("config").has_value();
  m.has_methods_file = json.has("methods_file") && json.string_or_null("methods_file").has_value();
  const std::string shard = json.string("shard");
  if (!parse_shard(shard, m.shard_index, m.shard_count)) {
    json.fail("shard", "expected i/N with 0 <= i < N, got '" + shard + "'");
  }
  if (json.has("executable_digest")) m.executable_digest = json.string("executable_digest");
}

MonteCarloManifest read_manifest_json(const std::string& path) {
  return io::read_json_file_as<MonteCarloManifest>(path);
}

bool parse_shard(const std::string& text, int& index, int& count) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return false;
  const char* begin = text.data();
  const auto [i_end, i_ec] = std::from_chars(begin, begin + slash, index);
  const auto [n_end, n_ec] = std::from_chars(begin + slash + 1, begin + text.size(), count);
  return i_ec == std::errc() && i_end == begin + slash && n_ec == std::errc() &&
         n_end == begin + text.size() && count >= 1 && index >= 0 && index < count;
}

void write_seeds_csv(const std::string& path, const std::vector<int>& runs,
                     std::uint64_t first_seed) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    out << "run,seed\n";
    for (const int r : runs) out << r << ',' << first_seed + static_cast<std::uint64_t>(r) << '\n';
  });
}

void to_json(io::Json& json, const RunFailure& f) {
  json = io::Json::object();
  json["run"] = f.run;
  json["seed"] = f.seed;
  json["stage"] = f.stage;
  json["reason"] = f.reason;
  if (!f.stderr_tail.empty()) json["stderr"] = f.stderr_tail;
}

void write_failure_json(const std::string& path, const RunFailure& f) {
  io::write_json_file(path, f);
}

void to_json(io::Json& json, const PairedDifference& d) {
  json = io::Json::object();
  json["reference"] = d.reference;
  json["runs"] = d.runs;
  json["mean_m"] = d.mean_m;
  json["sd_m"] = d.sd_m;
  json["ci95_m"] = {d.ci95_lower_m, d.ci95_upper_m};
  json["runs_lower"] = d.runs_lower;
}

void from_json(const io::JsonObject& p, PairedDifference& d) {
  d.reference = p.string("reference");
  d.runs = int_of(p, "runs", 2);
  d.mean_m = p.number("mean_m");
  d.sd_m = p.number("sd_m");
  const io::Json& ci = p.array("ci95_m");
  if (ci.size() != 2 || !ci[0].is_number() || !ci[1].is_number()) {
    p.fail("ci95_m", "expected [lower, upper]");
  }
  d.ci95_lower_m = ci[0].get<double>();
  d.ci95_upper_m = ci[1].get<double>();
  d.runs_lower = int_of(p, "runs_lower", 0);
}

void to_json(io::Json& json, const MethodSummary& s) {
  json = io::Json::object();
  json["runs"] = s.runs;
  json["failed"] = s.failed;
  json["failed_runs"] = s.failed_runs;
  json["missing"] = s.missing;
  json["mean_error_m"] = optional(s.mean_error_m);
  json["mean_error_quantiles_m"] = io::Json();
  if (const auto& q = s.mean_error_quantiles_m) {
    json["mean_error_quantiles_m"] = {{"p05", (*q)[0]}, {"p50", (*q)[1]}, {"p95", (*q)[2]}};
  }
  json["final_error_m"] = optional(s.final_error_m);
  json["anees"] = optional(s.anees);
  json["nees_in_bounds_fraction"] = optional(s.nees_in_bounds_fraction);
  json["nees_scans"] = s.nees.size();
  json["paired_difference"] = io::Json();
  if (s.paired) to_json(json["paired_difference"], *s.paired);
  io::Json& segments = json["segments"] = io::Json::object();
  for (const auto& [name, mean] : s.segments) segments[name] = optional(mean);
  io::Json& diagnostics = json["diagnostics"] = io::Json::object();
  for (const auto& [name, value] : s.diagnostics) diagnostics[name] = value;
  json["runtime_s"] = s.runtime_s;
}

void write_summary_json(const std::string& path, const std::vector<MethodSummary>& methods) {
  io::Json json = io::Json::object();
  for (const MethodSummary& s : methods) to_json(json[s.method], s);
  io::write_json_file(path, json, {2, {}});
}

void from_json(const io::JsonObject& m, StoredSummary& stored) {
  MethodSummary& s = stored.summary;
  s.runs = int_of(m, "runs", 0);
  s.failed = int_of(m, "failed", 0);
  for (const io::Json& run : m.array("failed_runs")) {
    if (!run.is_number_unsigned() || run.get<std::uint64_t>() > 1u << 30) {
      m.fail("failed_runs", "expected run indices");
    }
    s.failed_runs.push_back(run.get<int>());
  }
  s.missing = int_of(m, "missing", 0);
  s.mean_error_m = m.number_or_null("mean_error_m");
  if (m.has_value("mean_error_quantiles_m")) {
    const io::JsonObject q = m.object("mean_error_quantiles_m");
    s.mean_error_quantiles_m = {q.number("p05"), q.number("p50"), q.number("p95")};
  }
  s.final_error_m = m.number_or_null("final_error_m");
  s.anees = m.number_or_null("anees");
  s.nees_in_bounds_fraction = m.number_or_null("nees_in_bounds_fraction");
  stored.nees_scans = static_cast<std::size_t>(int_of(m, "nees_scans", 0));
  if (m.has_value("paired_difference")) {
    s.paired.emplace();
    from_json(m.object("paired_difference"), *s.paired);
  }
  const io::JsonObject segments = m.object("segments");
  for (const auto& [segment, mean] : segments.value().items()) {
    s.segments.emplace_back(segment, segments.number_or_null(segment));
  }
  if (m.has_value("diagnostics")) {  // absent from directories of earlier versions
    const io::JsonObject diagnostics = m.object("diagnostics");
    for (const auto& [name, value] : diagnostics.value().items()) {
      s.diagnostics.emplace_back(name, diagnostics.number(name));
    }
  }
  s.runtime_s = m.number("runtime_s");
}

std::vector<StoredSummary> read_summary_json(const std::string& path) {
  const io::Json root = io::read_json_file(path);
  const io::JsonObject json(root, path);
  std::vector<StoredSummary> methods;
  for (const auto& [name, value] : root.items()) {
    StoredSummary& stored = methods.emplace_back();
    stored.summary.method = name;
    from_json(json.object(name), stored);
  }
  if (methods.empty()) io::fail_file(path, "no method in it");
  return methods;
}

void write_error_spread_csv(const std::string& path, const std::vector<MethodSummary>& methods) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "method,t_s,runs,mean_m,p05_m,p50_m,p95_m\n";
    for (const MethodSummary& s : methods) {
      for (const ErrorSpread& e : s.error_spread) {
        text += s.method + ',';
        io::append_number(text, e.t_s);
        text += ',' + std::to_string(e.runs);
        for (const double v : {e.mean_m, e.p05_m, e.p50_m, e.p95_m}) {
          text += ',';
          io::append_number(text, v);
        }
        text += '\n';
      }
    }
    out << text;
  });
}

void write_error_histogram_csv(const std::string& path,
                               const std::vector<ErrorHistogram>& histograms) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "method,lower_m,upper_m,fraction\n";
    for (const ErrorHistogram& h : histograms) {
      for (std::size_t b = 0; b < h.fractions.size(); ++b) {
        text += h.method + ',';
        io::append_number(text, h.edges_m[b]);
        text += ',';
        io::append_number(text, h.edges_m[b + 1]);
        text += ',';
        io::append_number(text, h.fractions[b]);
        text += '\n';
      }
    }
    out << text;
  });
}

void write_montecarlo_nees_csv(const std::string& path, const std::vector<MethodSummary>& methods) {
  io::write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "method,scan,runs,mean_nees,lower,upper\n";
    for (const MethodSummary& s : methods) {
      for (std::size_t k = 0; k < s.nees.size(); ++k) {
        const AveragedNees& step = s.nees[k];
        text += s.method + ',' + std::to_string(k) + ',' + std::to_string(step.runs) + ',';
        io::append_number(text, step.mean);
        text += ',';
        io::append_number(text, step.lower);
        text += ',';
        io::append_number(text, step.upper);
        text += '\n';
      }
    }
    out << text;
  });
}

}  // namespace msislab::results
