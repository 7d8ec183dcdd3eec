#include "krug/io/run.hpp"

#include <chrono>

#include "krug/core/error.hpp"

namespace krug::io {

RunResult run_scenario(const Scenario& scenario, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  Simulation simulation(scenario.setup);
  RunRecorder recorder(scenario, simulation,
                       options.output_directory.empty() ? std::filesystem::path(scenario.output.directory)
                                                        : options.output_directory);
  RunResult result;
  try {
    while (!simulation.finished()) {
      simulation.step();
      recorder.observe(simulation);
      if (options.on_cycle && !options.on_cycle(simulation, elapsed())) {
        result.status = RunStatus::failed;
        result.message = "stopped on request before the end time";
        break;
      }
    }
    if (result.status == RunStatus::completed && simulation.cycle() >= simulation.controls().max_cycles &&
        simulation.time() < simulation.controls().end_time) {
      result.status = RunStatus::failed;
      result.message = "reached max_cycles before the end time";
    }
  } catch (const NumericalFailure& failure) {
    result.status = RunStatus::failed;
    result.message = failure.what();
  }
  result.wall_seconds = elapsed();
  recorder.finish(simulation, result);
  return result;
}

}  // namespace krug::io
