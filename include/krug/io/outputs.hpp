#pragma once
// Run outputs: summary.json (the fixed contract of docs/outputs.md), history.csv, VTK XML snapshots
// (.vtu per snapshot with a .pvd collection) and the resolved scenario. Files are written under a
// temporary name and renamed, so a reader never sees half a file.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "krug/io/checkpoint.hpp"
#include "krug/io/scenario.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::io {

enum class RunStatus { completed, failed };

struct RunResult {
  RunStatus status = RunStatus::completed;
  std::string message;
  double wall_seconds = 0.0;
  // Why the run ended: "end_time", "stop rule", "interrupted", "failure", "max_cycles" or "request"
  // (the caller's on_cycle said stop). summary.json field "stopped_by".
  std::string stopped_by = "end_time";
  std::filesystem::path checkpoint;    // the checkpoint written last, if any
  std::vector<std::string> warnings;   // for the user (e.g. a restart whose scenario was edited)
  std::optional<PenetrationReport> penetration;  // scenarios with a "penetration" block
  TimeStepRecord time_steps;           // filled by the recorder
};

// Picture of the current state (the app draws PNGs with Cairo when it has it): called for the
// initial state ("initial", or "state_00000" with pictures.every_snapshot), every snapshot
// ("state_NNNNN", with pictures.every_snapshot) and the final state ("final").
using PictureHook = std::function<void(const Simulation& simulation, const std::filesystem::path& directory,
                                       const std::string& name)>;

void write_text_atomically(const std::filesystem::path& file, const std::string& text);
// The active zones as a VTK XML UnstructuredGrid (fields: docs/outputs.md).
void write_vtu(const Simulation& simulation, const std::filesystem::path& file,
               VtkEncoding encoding = VtkEncoding::binary);
// Particles as VTK XML PolyData points (mass, radius, velocity, body of origin, birth time).
void write_vtp(const Simulation& simulation, const std::filesystem::path& file,
               VtkEncoding encoding = VtkEncoding::binary);
std::string summary_json(const Simulation& simulation, const RunResult& result);
// The penetration result in a few lines for the console (empty without a penetration block).
std::vector<std::string> penetration_lines(const RunResult& result);

// A text file appended to in whole lines: the lines are kept in memory and written with one write()
// call per batch (64 KiB or a second's worth, or at flush()), so a process killed at any moment
// leaves only whole lines.
class LineFile {
 public:
  LineFile() = default;
  ~LineFile();
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;
  // Opens (creates) the file, emptied or appended to; an InputError if it cannot be written.
  void open(const std::filesystem::path& file, bool append);
  void append(std::string_view lines);  // one or more whole lines, each ending in '\n'
  void flush();

 private:
  int descriptor_ = -1;
  std::string pending_;
  std::chrono::steady_clock::time_point last_write_{};
  std::filesystem::path file_;
};

// Writes history rows and snapshots while a run goes on, and the final files when it ends.
class RunRecorder {
 public:
  RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory,
              PictureHook picture_hook = {});
  // Continues the outputs of a run restarted from a checkpoint taken in `previous_directory`:
  // history.csv is cut back to its length at the checkpoint (copied first when the directory is
  // another one, with the snapshots listed so far) and the output schedule goes on where it was.
  RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory,
              PictureHook picture_hook, const RunProgress& resume, const std::filesystem::path& previous_directory);
  ~RunRecorder();
  RunRecorder(const RunRecorder&) = delete;
  RunRecorder& operator=(const RunRecorder&) = delete;

  void observe(const Simulation& simulation);  // after every cycle
  void finish(const Simulation& simulation, const RunResult& result);
  const std::filesystem::path& directory() const { return directory_; }
  // The recorder's part of a checkpoint (history.csv is flushed first).
  RunProgress progress();

 private:
  // The directory (locked for this run: a second run into it is refused) and scenario.resolved.json;
  // a fresh run first removes the outputs an earlier run left there (snapshots, pictures, plots,
  // summary, final state, checkpoint), so that none is mistaken for this run's.
  void open(const Scenario& scenario, bool fresh);
  static std::string history_header(const Simulation& simulation);
  void append_history(const std::string& text);
  void write_history_row(const Simulation& simulation);
  void count_time_step(const Simulation& simulation);
  void write_snapshot(const Simulation& simulation);
  void picture(const Simulation& simulation, const std::string& name);
  // gauges.csv (scenario key "gauges"): the header, and a row of the current state.
  std::string gauge_header() const;
  void write_gauge_row(const Simulation& simulation);

  std::filesystem::path directory_;
  OutputSettings settings_;
  int lock_descriptor_ = -1;  // holds the directory's lock (flock on .krug-lock) while the recorder lives
  LineFile history_;
  std::uint64_t history_bytes_ = 0;  // written to history.csv so far
  double next_history_time_ = 0.0;
  double next_snapshot_time_ = 0.0;
  std::vector<std::pair<double, std::string>> snapshots_;  // time, file relative to directory_
  std::vector<std::pair<double, std::string>> particle_snapshots_;
  TimeStepRecord time_steps_;
  PictureHook picture_;
  // Gauges: none (no work at all) without a "gauges" block.
  std::optional<GaugeSampler> gauges_;
  double gauge_interval_ = 0.0;
  LineFile gauge_file_;
  std::uint64_t gauge_bytes_ = 0;
  double next_gauge_time_ = 0.0;
  std::vector<double> gauge_values_;  // scratch row
};

}  // namespace krug::io
