#pragma once
// The run loop the app and the tests share: steps the simulation to its end time, applies the stop
// rule (scenario key "stop"), keeps the penetration record, takes checkpoints on the schedule
// (output.checkpoint_interval, and always when interrupted) and continues runs from a checkpoint's
// progress. It writes no file: it tells an observer (observer.hpp), and output::run_scenario
// (krug/output/run_files.hpp) gives it the one that writes the run's files.
#include <atomic>
#include <functional>

#include "krug/scenario/scenario.hpp"
#include "krug/run/events.hpp"
#include "krug/run/observer.hpp"
#include "krug/run/state.hpp"

namespace krug::run {

using scenario::Scenario;

struct RunOptions {
  // Called after each cycle with the wall time so far; return false to stop (status "failed").
  std::function<bool(const Simulation&, double elapsed_seconds)> on_cycle;
  // Set from outside (a signal handler) to interrupt: the loop takes a checkpoint and ends the run with
  // status "failed", message "interrupted", stopped_by "interrupted".
  const std::atomic<bool>* interrupt = nullptr;
  // Called once with the starting state (fresh or restored), before the first cycle.
  std::function<void(const Simulation&)> on_start;
  // Called as each event happens (EventWatch: first contact, first damage, conversion, erosion, perforation).
  std::function<void(const RunEvent&)> on_event;
  // Called once with the final state (however the run ended), before the observer's finish.
  std::function<void(const Simulation&)> on_finish;
};

// Checks what only the built initial state can tell: the end time must be reachable within
// controls.max_cycles at the initial CFL-stable step (a lower bound of the cycles a run needs).
// Throws InputError naming the controlling body and zone. output::run_scenario calls it; so does
// `krug validate`, through validate_scenario (which builds the state and discards it).
void check_cycle_budget(const Simulation& simulation);
void validate_scenario(const Scenario& scenario);

// Runs `simulation`, freshly built from `scenario` (its cycle budget checked), to the end time, to the
// stop rule or to a numerical failure; never throws NumericalFailure (it is reported in the result).
// `observer` has seen the starting state.
RunResult run_simulation(const Scenario& scenario, Simulation& simulation, RunObserver& observer,
                         const RunOptions& options);
// The same for a simulation restored from a checkpoint, whose loop state is in `progress` (the stop
// window, the penetration record, the checkpoint schedule, the wall time so far).
RunResult resume_simulation(const Scenario& scenario, Simulation& simulation, const RunProgress& progress,
                            RunObserver& observer, const RunOptions& options);

}  // namespace krug::run
