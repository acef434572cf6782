// A simulated dataset directory (docs/formats.md): the St. Pere log formats plus calibration.yaml
// and truth/ (trajectory.tum, beams.csv), so `msislab run` reads it like the real data.
#pragma once

#include <string>
#include <vector>

#include "dataset/dataset.hpp"
#include "io/beam_truth.hpp"
#include "io/output_guard.hpp"
#include "sim/simulator.hpp"

namespace msislab::dataset {

/// Writes every file into a staging sibling of `out.path`, then puts it in place (io::StagedFolder:
/// an earlier dataset there is replaced only once the new one is complete, and only when msislab
/// wrote it). `scenario_text` is kept as scenario.yaml for provenance.
void write_simulated_dataset(const io::OutputRequest& out, const sim::Scenario& scenario,
                             const sim::SimulationResult& result, const std::string& scenario_text);

/// The records the dataset's files hold (every file but scenario.yaml and truth/beams.csv). With
/// as_stored, the values read back from the files (calibration_as_stored, yaw_as_stored), so that
/// methods given the records in memory compute what they compute from the directory; without,
/// the values the files are written from.
DatasetRecords simulated_records(const sim::Scenario& scenario, const sim::SimulationResult& result,
                                 bool as_stored = true);

/// The rows of the per-beam truth table, truth/beams.csv (io/beam_truth writes them).
std::vector<io::BeamTruthRow> beam_truth_rows(const std::vector<sim::RenderedBeam>& beams);

}  // namespace msislab::dataset
