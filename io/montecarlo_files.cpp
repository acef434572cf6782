#include "io/montecarlo_files.hpp"

#include <algorithm>

#include <charconv>
#include <cmath>
#include <limits>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/json.hpp"
#include "io/results.hpp"
#include "io/text_lines.hpp"

namespace msislab::io {
namespace {

std::string json_optional(const std::optional<double>& value) {
  return value ? json_number(*value) : "null";
}

int int_of(const JsonObject& json, const std::string& key, int min) {
  const double value = json.number(key);
  if (value != std::floor(value) || value < min || value > std::numeric_limits<int>::max()) {
    json.fail(key,
              "expected an integer >= " + std::to_string(min) + ", got " + format_number(value));
  }
  return static_cast<int>(value);
}

/// The key is there and not null (optional sections of summary.json).
bool has_non_null(const JsonObject& json, const std::string& key) {
  const auto& members = json.value().members;
  const auto it = std::find_if(members.begin(), members.end(),
                               [&](const auto& member) { return member.first == key; });
  return it != members.end() && it->second.type != JsonValue::Type::null;
}

}  // namespace

void write_manifest_json(const std::string& path, const MonteCarloManifest& m) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "{\n"
        << "  \"scenario\": \"scenario.yaml\",\n"
        << "  \"scenario_source\": " << json_string(m.scenario_source) << ",\n"
        << "  \"seed\": " << m.first_seed << ",\n"
        << "  \"runs\": " << m.runs << ",\n"
        << "  \"methods\": [";
    for (std::size_t i = 0; i < m.methods.size(); ++i) {
      out << (i ? ", " : "") << json_string(m.methods[i]);
    }
    out << "],\n"
        << "  \"config\": " << (m.has_config ? "\"config.yaml\"" : "null") << ",\n"
        << "  \"shard\": \"" << m.shard_index << "/" << m.shard_count << "\",\n"
        << "  \"executable_digest\": " << json_string(m.executable_digest) << "\n"
        << "}\n";
  });
}

MonteCarloManifest read_manifest_json(const std::string& path) {
  const JsonValue root = read_json_file(path);
  const JsonObject json(root, path);
  MonteCarloManifest m;
  m.scenario_source = json.string("scenario_source");
  // The seed is read from its token: a double would not hold every 64-bit seed.
  const std::string& seed = json.get("seed", JsonValue::Type::number).text;
  const auto [end, ec] = std::from_chars(seed.data(), seed.data() + seed.size(), m.first_seed);
  if (ec != std::errc() || end != seed.data() + seed.size()) {
    json.fail("seed", "expected a non-negative integer, got " + seed);
  }
  m.runs = int_of(json, "runs", 1);
  for (const JsonValue& method : json.get("methods", JsonValue::Type::array).items) {
    if (method.type != JsonValue::Type::string) json.fail("methods", "expected strings");
    m.methods.push_back(method.text);
  }
  m.has_config = json.string_or_null("config").has_value();
  const std::string shard = json.string("shard");
  if (!parse_shard(shard, m.shard_index, m.shard_count)) {
    json.fail("shard", "expected i/N with 0 <= i < N, got '" + shard + "'");
  }
  if (json.has("executable_digest")) m.executable_digest = json.string("executable_digest");
  return m;
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
  write_file_atomically(path, [&](std::ostream& out) {
    out << "run,seed\n";
    for (const int r : runs) out << r << ',' << first_seed + static_cast<std::uint64_t>(r) << '\n';
  });
}

void write_failure_json(const std::string& path, const RunFailure& f) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "{\n"
        << "  \"run\": " << f.run << ",\n"
        << "  \"seed\": " << f.seed << ",\n"
        << "  \"stage\": " << json_string(f.stage) << ",\n"
        << "  \"reason\": " << json_string(f.reason) << "\n"
        << "}\n";
  });
}

void write_summary_json(const std::string& path, const std::vector<MethodSummary>& methods) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "{";
    for (std::size_t i = 0; i < methods.size(); ++i) {
      const MethodSummary& s = methods[i];
      out << (i ? ",\n" : "\n") << "  " << json_string(s.method) << ": {\n"
          << "    \"runs\": " << s.runs << ",\n"
          << "    \"failed\": " << s.failed << ",\n"
          << "    \"failed_runs\": [";
      for (std::size_t k = 0; k < s.failed_runs.size(); ++k) {
        out << (k ? ", " : "") << s.failed_runs[k];
      }
      out << "],\n"
          << "    \"missing\": " << s.missing << ",\n"
          << "    \"mean_error_m\": " << json_optional(s.mean_error_m) << ",\n"
          << "    \"mean_error_quantiles_m\": ";
      if (s.mean_error_quantiles_m) {
        const auto& q = *s.mean_error_quantiles_m;
        out << "{\"p05\": " << json_number(q[0]) << ", \"p50\": " << json_number(q[1])
            << ", \"p95\": " << json_number(q[2]) << "}";
      } else {
        out << "null";
      }
      out << ",\n"
          << "    \"final_error_m\": " << json_optional(s.final_error_m) << ",\n"
          << "    \"anees\": " << json_optional(s.anees) << ",\n"
          << "    \"nees_in_bounds_fraction\": " << json_optional(s.nees_in_bounds_fraction)
          << ",\n"
          << "    \"nees_scans\": " << s.nees.size() << ",\n"
          << "    \"paired_difference\": ";
      if (s.paired) {
        const PairedDifference& d = *s.paired;
        out << "{\"reference\": " << json_string(d.reference) << ", \"runs\": " << d.runs
            << ", \"mean_m\": " << json_number(d.mean_m) << ", \"sd_m\": " << json_number(d.sd_m)
            << ", \"ci95_m\": [" << json_number(d.ci95_lower_m) << ", "
            << json_number(d.ci95_upper_m) << "], \"runs_lower\": " << d.runs_lower << "}";
      } else {
        out << "null";
      }
      out << ",\n"
          << "    \"segments\": {";
      for (std::size_t k = 0; k < s.segments.size(); ++k) {
        out << (k ? ", " : "") << json_string(s.segments[k].first) << ": "
            << json_optional(s.segments[k].second);
      }
      out << "},\n"
          << "    \"diagnostics\": {";
      for (std::size_t k = 0; k < s.diagnostics.size(); ++k) {
        out << (k ? ", " : "") << json_string(s.diagnostics[k].first) << ": "
            << json_number(s.diagnostics[k].second);
      }
      out << "},\n"
          << "    \"runtime_s\": " << json_number(s.runtime_s) << "\n"
          << "  }";
    }
    out << "\n}\n";
  });
}

std::vector<StoredSummary> read_summary_json(const std::string& path) {
  const JsonValue root = read_json_file(path);
  const JsonObject json(root, path);
  std::vector<StoredSummary> methods;
  for (const auto& [name, value] : root.members) {
    const JsonObject m = json.object(name);
    StoredSummary stored;
    MethodSummary& s = stored.summary;
    s.method = name;
    s.runs = int_of(m, "runs", 0);
    s.failed = int_of(m, "failed", 0);
    for (const JsonValue& run : m.get("failed_runs", JsonValue::Type::array).items) {
      if (run.type != JsonValue::Type::number || run.number != std::floor(run.number) ||
          run.number < 0) {
        m.fail("failed_runs", "expected run indices");
      }
      s.failed_runs.push_back(static_cast<int>(run.number));
    }
    s.missing = int_of(m, "missing", 0);
    s.mean_error_m = m.number_or_null("mean_error_m");
    if (has_non_null(m, "mean_error_quantiles_m")) {
      const JsonObject q = m.object("mean_error_quantiles_m");
      s.mean_error_quantiles_m = {q.number("p05"), q.number("p50"), q.number("p95")};
    }
    s.final_error_m = m.number_or_null("final_error_m");
    s.anees = m.number_or_null("anees");
    s.nees_in_bounds_fraction = m.number_or_null("nees_in_bounds_fraction");
    stored.nees_scans = static_cast<std::size_t>(int_of(m, "nees_scans", 0));
    if (has_non_null(m, "paired_difference")) {
      const JsonObject p = m.object("paired_difference");
      PairedDifference d;
      d.reference = p.string("reference");
      d.runs = int_of(p, "runs", 2);
      d.mean_m = p.number("mean_m");
      d.sd_m = p.number("sd_m");
      const std::vector<JsonValue>& ci = p.get("ci95_m", JsonValue::Type::array).items;
      if (ci.size() != 2 || ci[0].type != JsonValue::Type::number ||
          ci[1].type != JsonValue::Type::number) {
        p.fail("ci95_m", "expected [lower, upper]");
      }
      d.ci95_lower_m = ci[0].number;
      d.ci95_upper_m = ci[1].number;
      d.runs_lower = int_of(p, "runs_lower", 0);
      s.paired = d;
    }
    const JsonObject segments = m.object("segments");
    for (const auto& [segment, window] : segments.value().members) {
      s.segments.emplace_back(segment, segments.number_or_null(segment));
    }
    if (has_non_null(m, "diagnostics")) {  // absent from directories of earlier versions
      const JsonObject diagnostics = m.object("diagnostics");
      for (const auto& member : diagnostics.value().members) {
        s.diagnostics.emplace_back(member.first, diagnostics.number(member.first));
      }
    }
    s.runtime_s = m.number("runtime_s");
    methods.push_back(std::move(stored));
  }
  if (methods.empty()) fail_file(path, "no method in it");
  return methods;
}

void write_error_spread_csv(const std::string& path, const std::vector<MethodSummary>& methods) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "method,t_s,runs,mean_m,p05_m,p50_m,p95_m\n";
    for (const MethodSummary& s : methods) {
      for (const ErrorSpread& e : s.error_spread) {
        text += s.method + ',';
        append_number(text, e.t_s);
        text += ',' + std::to_string(e.runs);
        for (const double v : {e.mean_m, e.p05_m, e.p50_m, e.p95_m}) {
          text += ',';
          append_number(text, v);
        }
        text += '\n';
      }
    }
    out << text;
  });
}

void write_error_histogram_csv(const std::string& path,
                               const std::vector<ErrorHistogram>& histograms) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "method,lower_m,upper_m,fraction\n";
    for (const ErrorHistogram& h : histograms) {
      for (std::size_t b = 0; b < h.fractions.size(); ++b) {
        text += h.method + ',';
        append_number(text, h.edges_m[b]);
        text += ',';
        append_number(text, h.edges_m[b + 1]);
        text += ',';
        append_number(text, h.fractions[b]);
        text += '\n';
      }
    }
    out << text;
  });
}

void write_montecarlo_nees_csv(const std::string& path, const std::vector<MethodSummary>& methods) {
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "method,scan,runs,mean_nees,lower,upper\n";
    for (const MethodSummary& s : methods) {
      for (std::size_t k = 0; k < s.nees.size(); ++k) {
        const AveragedNees& step = s.nees[k];
        text += s.method + ',' + std::to_string(k) + ',' + std::to_string(step.runs) + ',';
        append_number(text, step.mean);
        text += ',';
        append_number(text, step.lower);
        text += ',';
        append_number(text, step.upper);
        text += '\n';
      }
    }
    out << text;
  });
}

}  // namespace msislab::io
