// metrics.json's members that only `msislab eval` writes (docs/formats.md): "alignment", how the
// estimate was put onto the truth, and "rpe", its relative pose error.
#pragma once

#include <optional>

#include "eval/evaluation.hpp"
#include "io/json.hpp"

namespace msislab::results {

/// Adds "alignment" and "rpe" (null when the truth has no headings) to a metrics.json object.
void add_eval_scores(io::Json& json, const EvalScores& scores);

/// Reads them back (the rotation through degrees, so its last bits may differ); nullopt when the
/// file has no "alignment" (a record written by `msislab run`).
std::optional<EvalScores> read_eval_scores(const io::JsonObject& json);

}  // namespace msislab::results
