#include "krug/output/run_files.hpp"

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/output/checkpoint.hpp"

namespace krug::output {

RunResult run_scenario(const Scenario& scenario, const RunOptions& options) {
  Simulation simulation(scenario.setup);
  run::check_cycle_budget(simulation);
  RunRecorder recorder(scenario, simulation,
                       options.output_directory.empty() ? std::filesystem::path(scenario.output.directory)
                                                        : options.output_directory,
                       options.picture);
  return run::run_simulation(scenario, simulation, recorder, options);
}

RunResult restart_scenario(const std::filesystem::path& checkpoint, const RunOptions& options) {
  const std::filesystem::path resolved = checkpoint.parent_path() / "scenario.resolved.json";
  if (!std::filesystem::exists(resolved)) {
    throw InputError(fmt::format("{}: missing; a restart needs the resolved scenario written next to the checkpoint",
                                 resolved.string()));
  }
  return restart_scenario(scenario::load_scenario(resolved), checkpoint, options);
}

RunResult restart_scenario(const Scenario& scenario, const std::filesystem::path& checkpoint_file,
                           const RunOptions& options) {
  Checkpoint checkpoint = read_checkpoint(checkpoint_file);
  std::vector<std::string> warnings;
  if (checkpoint.scenario_hash != fnv1a(scenario.resolved_json)) {
    warnings.push_back(fmt::format("the scenario differs from the one {} was taken with; continuing with the "
                                   "scenario as it is now", checkpoint_file.string()));
  }
  Simulation simulation(scenario.setup);
  simulation.restore(std::move(checkpoint.state));
  const std::filesystem::path previous = checkpoint_file.parent_path().empty() ? std::filesystem::path(".")
                                                                               : checkpoint_file.parent_path();
  const std::filesystem::path directory = options.output_directory.empty() ? previous : options.output_directory;
  RunRecorder recorder(scenario, simulation, directory, options.picture, checkpoint.progress, previous);
  RunResult result = run::resume_simulation(scenario, simulation, checkpoint.progress, recorder, options);
  result.warnings.insert(result.warnings.begin(), warnings.begin(), warnings.end());
  return result;
}

}  // namespace krug::output
