#pragma once
// What the run loop tells whoever keeps a run's outputs. The loop (run.hpp) knows no file: it calls
// an observer after every cycle, when a checkpoint is due (the schedule and an interruption are the
// loop's) and once at the end. output::RunRecorder (krug/output/outputs.hpp) is the observer that
// writes history.csv, gauges.csv, the snapshots, checkpoint.bin and summary.json.
#include <filesystem>

#include "krug/run/state.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::run {

class RunObserver {
 public:
  RunObserver() = default;
  RunObserver(const RunObserver&) = delete;
  RunObserver& operator=(const RunObserver&) = delete;
  virtual ~RunObserver() = default;

  // After every cycle. The observer keeps its own schedule (history rows, snapshots, gauges) and is
  // ready before the first cycle: it has seen the starting state when it was made.
  virtual void cycle(const Simulation& simulation) = 0;
  // Keeps the state and `progress` so that the run can continue from here. The loop has filled its
  // own part of `progress` (checkpoint schedule, wall time, stop window, penetration record); the
  // observer adds its own and returns where it kept the checkpoint.
  virtual std::filesystem::path checkpoint(const Simulation& simulation, RunProgress& progress) = 0;
  // Once with the final state and the run's result, however the run ended.
  virtual void finish(const Simulation& simulation, const RunResult& result) = 0;
};

}  // namespace krug::run
