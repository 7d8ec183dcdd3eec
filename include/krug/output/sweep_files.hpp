#pragma once
// The files of a parameter sweep (`krug sweep`): each variant written to DIR/<variant>/scenario.json,
// run by the app in its own process, and DIR/sweep.csv collecting their inputs and summary figures.
// The variants themselves are made in memory (krug/scenario/edit.hpp).
#include <filesystem>
#include <vector>

#include "krug/scenario/edit.hpp"

namespace krug::output {

// Writes every variant's scenario under `directory` (scenario::plan_sweep: each is checked first).
std::vector<scenario::SweepVariant> prepare_sweep(const std::filesystem::path& scenario_file,
                                                  const std::vector<scenario::SweepParameter>& parameters,
                                                  const std::filesystem::path& directory);

// Writes DIR/sweep.csv: variant, one column per parameter, then from each DIR/<variant>/summary.json
// status, stopped_by, time, cycles, wall_seconds, energy_drift, mass_error, particles, and per body
// velocity (both components) and active zones, then message. A variant without a summary has
// status "not run".
void write_sweep_table(const std::filesystem::path& directory, const std::vector<scenario::SweepParameter>& parameters,
                       const std::vector<scenario::SweepVariant>& variants);

}  // namespace krug::output
