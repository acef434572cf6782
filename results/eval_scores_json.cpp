#include "results/eval_scores_json.hpp"

#include <cmath>
#include <limits>

#include "geometry/angles.hpp"

namespace msislab::results {

namespace {

io::Json summary_json(const RelativePoseError& rpe, const SampleSummary& s) {
  if (rpe.pairs == 0) return io::Json();
  io::Json json = io::Json::object();
  json["mean"] = s.mean;
  json["rmse"] = s.rmse;
  json["median"] = s.median;
  json["max"] = s.max;
  return json;
}

SampleSummary read_summary(const io::JsonObject& rpe, const std::string& key) {
  SampleSummary s;
  if (!rpe.has_value(key)) return s;
  const io::JsonObject json = rpe.object(key);
  s.mean = json.number("mean");
  s.rmse = json.number("rmse");
  s.median = json.number("median");
  s.max = json.number("max");
  return s;
}

std::size_t size_count_of(const io::JsonObject& json, const std::string& key) {
  return static_cast<std::size_t>(json.integer(key, 0, std::numeric_limits<int>::max()));
}

}  // namespace

void add_eval_scores(io::Json& json, const EvalScores& scores) {
  const EstimateAlignment& a = scores.alignment;
  io::Json& alignment = json["alignment"] = io::Json::object();
  alignment["method"] = a.method;
  alignment["window_s"] = a.window_s ? io::Json(*a.window_s) : io::Json();
  alignment["positions"] = a.positions;
  alignment["t_offset_s"] = a.t_offset_s;
  alignment["rotation_deg"] = a.T_truth_estimate.yaw() * kRadToDeg;
  alignment["x_m"] = a.T_truth_estimate.x();
  alignment["y_m"] = a.T_truth_estimate.y();
  if (!scores.rpe) {
    json["rpe"] = io::Json();
    return;
  }
  io::Json& rpe = json["rpe"] = io::Json::object();
  rpe["delta_m"] = scores.rpe->delta_m;
  rpe["pairs"] = scores.rpe->pairs;
  rpe["translation_m"] = summary_json(*scores.rpe, scores.rpe->translation_m);
  rpe["rotation_deg"] = summary_json(*scores.rpe, scores.rpe->rotation_deg);
}

std::optional<EvalScores> read_eval_scores(const io::JsonObject& json) {
  if (!json.has("alignment")) return std::nullopt;
  EvalScores scores;
  const io::JsonObject alignment = json.object("alignment");
  EstimateAlignment& a = scores.alignment;
  a.method = alignment.string("method");
  a.window_s = alignment.number_or_null("window_s");
  a.positions = size_count_of(alignment, "positions");
  a.t_offset_s = alignment.number("t_offset_s");
  a.T_truth_estimate = Pose2(alignment.number("x_m"), alignment.number("y_m"),
                             alignment.number("rotation_deg") / kRadToDeg);
  if (json.has_value("rpe")) {
    const io::JsonObject rpe = json.object("rpe");
    scores.rpe = RelativePoseError{};
    scores.rpe->delta_m = rpe.number("delta_m");
    scores.rpe->pairs = size_count_of(rpe, "pairs");
    scores.rpe->translation_m = read_summary(rpe, "translation_m");
    scores.rpe->rotation_deg = read_summary(rpe, "rotation_deg");
  }
  return scores;
}

}  // namespace msislab::results
