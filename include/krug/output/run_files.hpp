#pragma once
// Running a scenario to its end time with its files: the run loop (krug/run/run.hpp) with a
// RunRecorder as its observer, as the app and the tests run it. Checkpoints are taken on
// output.checkpoint_interval and always when interrupted; a run continues from one.
#include <filesystem>

#include "krug/scenario/scenario.hpp"
#include "krug/output/outputs.hpp"
#include "krug/run/run.hpp"

namespace krug::output {

struct RunOptions : run::RunOptions {
  std::filesystem::path output_directory;  // empty: the scenario's own (restart: the checkpoint's)
  // Pictures of the states (the app's PNG writer); none when empty.
  PictureHook picture;
};

// Runs to the end time, to the stop rule or to a numerical failure; never throws NumericalFailure
// (it is reported in the result and in summary.json). InputError from the setup propagates.
RunResult run_scenario(const Scenario& scenario, const RunOptions& options);

// Continues a run from a checkpoint, with the scenario stored next to it (scenario.resolved.json,
// which may have been edited, e.g. a later end_time: the result then says so in `warnings`).
// Outputs go to options.output_directory, or by default to the checkpoint's directory.
RunResult restart_scenario(const std::filesystem::path& checkpoint, const RunOptions& options);
// The same with a scenario given by the caller (it must describe the same mesh).
RunResult restart_scenario(const Scenario& scenario, const std::filesystem::path& checkpoint,
                           const RunOptions& options);

}  // namespace krug::output
