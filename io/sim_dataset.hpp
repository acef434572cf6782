// A simulated dataset directory (docs/formats.md): the St. Pere log formats plus calibration.yaml
// and truth/ (trajectory.tum, beams.csv), so `msislab run` reads it like the real data.
#pragma once

#include <string>

#include "sim/simulator.hpp"

namespace msislab::io {

/// Writes every file into a temporary sibling of `dir`, then puts it in place of `dir` (an
/// earlier dataset there is replaced only once the new one is complete). `scenario_text` is kept
/// as scenario.yaml for provenance.
void write_simulated_dataset(const std::string& dir, const sim::Scenario& scenario,
                             const sim::SimulationResult& result, const std::string& scenario_text);

/// The per-beam truth table, truth/beams.csv.
void write_beam_truth(const std::string& path, const std::vector<sim::RenderedBeam>& beams);

}  // namespace msislab::io
