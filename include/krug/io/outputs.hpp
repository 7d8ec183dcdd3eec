#pragma once
// Run outputs: summary.json (the fixed contract of docs/outputs.md), history.csv, VTK XML snapshots
// (.vtu per snapshot with a .pvd collection) and the resolved scenario. Files are written under a
// temporary name and renamed, so a reader never sees half a file.
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "krug/io/scenario.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::io {

enum class RunStatus { completed, failed };

struct RunResult {
  RunStatus status = RunStatus::completed;
  std::string message;
  double wall_seconds = 0.0;
};

void write_text_atomically(const std::filesystem::path& file, const std::string& text);
void write_vtu(const Simulation& simulation, const std::filesystem::path& file);
// Particles as VTK XML PolyData points (mass, radius, velocity, body of origin).
void write_vtp(const Simulation& simulation, const std::filesystem::path& file);
std::string summary_json(const Simulation& simulation, const RunResult& result);

// Writes history rows and snapshots while a run goes on, and the final files when it ends.
class RunRecorder {
 public:
  RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory);
  ~RunRecorder();
  RunRecorder(const RunRecorder&) = delete;
  RunRecorder& operator=(const RunRecorder&) = delete;

  void observe(const Simulation& simulation);  // after every cycle
  void finish(const Simulation& simulation, const RunResult& result);
  const std::filesystem::path& directory() const { return directory_; }

 private:
  void write_history_row(const Simulation& simulation);
  void write_snapshot(const Simulation& simulation);

  std::filesystem::path directory_;
  OutputSettings settings_;
  std::ofstream history_;
  double next_history_time_ = 0.0;
  double next_snapshot_time_ = 0.0;
  std::vector<std::pair<double, std::string>> snapshots_;  // time, file relative to directory_
  std::vector<std::pair<double, std::string>> particle_snapshots_;
};

}  // namespace krug::io
