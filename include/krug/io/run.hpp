#pragma once
// Running a scenario to its end time with outputs: the loop the app and the tests share.
#include <filesystem>
#include <functional>

#include "krug/io/outputs.hpp"
#include "krug/io/scenario.hpp"

namespace krug::io {

struct RunOptions {
  std::filesystem::path output_directory;  // empty: the scenario's own
  // Called after each cycle with the wall time so far; return false to stop (status "failed").
  std::function<bool(const Simulation&, double elapsed_seconds)> on_cycle;
};

// Runs to the end time or to a numerical failure; never throws NumericalFailure (it is reported in
// the result and in summary.json). InputError from the setup propagates.
RunResult run_scenario(const Scenario& scenario, const RunOptions& options);

}  // namespace krug::io
