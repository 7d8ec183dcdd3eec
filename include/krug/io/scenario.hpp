#pragma once
// Scenario files (JSON, SI units) -> a SimulationSetup ready to run, plus output settings.
// The format is documented in docs/scenario-format.md. Every error is an InputError naming the
// JSON path, the value found and what was expected.
#include <filesystem>
#include <string>

#include "krug/solver/simulation.hpp"

namespace krug::io {

struct OutputSettings {
  std::string directory;          // default: "out/<scenario file stem>"; `krug run --out` overrides
  double history_interval = 0.0;  // s between rows of history.csv (0: every cycle)
  double snapshot_interval = 0.0; // s between VTK snapshots (0: initial and final state only)
};

struct Scenario {
  std::string title;
  std::filesystem::path source;
  SimulationSetup setup;
  OutputSettings output;
  std::string resolved_json;  // the scenario as read, every default filled in
};

Scenario load_scenario(const std::filesystem::path& file);
Scenario parse_scenario(const std::string& json_text, const std::string& origin);

}  // namespace krug::io
