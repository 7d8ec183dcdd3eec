#pragma once
// Running a scenario to its end time with outputs: the loop the app and the tests share. The loop
// also takes checkpoints (output.checkpoint_interval, and always when interrupted), applies the
// stop rule (scenario key "stop") and continues runs from checkpoints.
#include <atomic>
#include <filesystem>
#include <functional>

#include "krug/io/outputs.hpp"
#include "krug/io/scenario.hpp"
#include "krug/run/events.hpp"

namespace krug::run {

using io::RunResult;
using io::RunStatus;
using io::Scenario;
using io::PictureHook;

struct RunOptions {
  std::filesystem::path output_directory;  // empty: the scenario's own (restart: the checkpoint's)
  // Called after each cycle with the wall time so far; return false to stop (status "failed").
  std::function<bool(const Simulation&, double elapsed_seconds)> on_cycle;
  // Set from outside (a signal handler) to interrupt: the loop writes DIR/checkpoint.bin and ends the
  // run with status "failed", message "interrupted", stopped_by "interrupted".
  const std::atomic<bool>* interrupt = nullptr;
  // Called once with the starting state (fresh or restored), before the first cycle.
  std::function<void(const Simulation&)> on_start;
  // Called as each event happens (EventWatch: first contact, first damage, conversion, erosion, perforation).
  std::function<void(const RunEvent&)> on_event;
  // Called once with the final state (however the run ended), before the final outputs are written.
  std::function<void(const Simulation&)> on_finish;
  // Pictures of the states (the app's PNG writer); none when empty.
  PictureHook picture;
};

// Checks what only the built initial state can tell: the end time must be reachable within
// controls.max_cycles at the initial CFL-stable step (a lower bound of the cycles a run needs).
// Throws InputError naming the controlling body and zone. run_scenario calls it; so does
// `krug validate`, through validate_scenario (which builds the state and discards it).
void check_cycle_budget(const Simulation& simulation);
void validate_scenario(const Scenario& scenario);

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

}  // namespace krug::run
