#pragma once
// Run outputs: summary.json (the fixed contract of docs/outputs.md), history.csv, VTK XML snapshots
// (.vtu per snapshot with a .pvd collection) and the resolved scenario. Files are written under a
// temporary name and renamed, so a reader never sees half a file. RunRecorder is the run loop's
// observer (krug/run/observer.hpp) that writes them, and the checkpoints (checkpoint.hpp).
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "krug/scenario/scenario.hpp"
#include "krug/output/text_file.hpp"
#include "krug/run/observer.hpp"
#include "krug/run/state.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::output {

using scenario::OutputSettings;
using scenario::Scenario;
using scenario::VtkEncoding;
using run::RunProgress;
using run::RunResult;
using run::RunStatus;
using run::TimeStepRecord;

// Picture of the current state (the app draws PNGs with Cairo when it has it): called for the
// initial state ("initial", or "state_00000" with pictures.every_snapshot), every snapshot
// ("state_NNNNN", with pictures.every_snapshot) and the final state ("final").
using PictureHook = std::function<void(const Simulation& simulation, const std::filesystem::path& directory,
                                       const std::string& name)>;

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

// Writes history rows and snapshots while a run goes on, checkpoints when the loop asks, and the
// final files when it ends.
class RunRecorder final : public run::RunObserver {
 public:
  RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory,
              PictureHook picture_hook = {});
  // Continues the outputs of a run restarted from a checkpoint taken in `previous_directory`:
  // history.csv is cut back to its length at the checkpoint (copied first when the directory is
  // another one, with the snapshots listed so far) and the output schedule goes on where it was.
  RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory,
              PictureHook picture_hook, const RunProgress& resume, const std::filesystem::path& previous_directory);
  ~RunRecorder() override;

  void cycle(const Simulation& simulation) override;  // after every cycle
  // DIR/checkpoint.bin, with the recorder's part of `progress` added (history.csv is flushed first).
  std::filesystem::path checkpoint(const Simulation& simulation, RunProgress& progress) override;
  void finish(const Simulation& simulation, const RunResult& result) override;
  const std::filesystem::path& directory() const { return directory_; }

 private:
  // The directory (locked for this run: a second run into it is refused) and scenario.resolved.json;
  // a fresh run first removes the outputs an earlier run left there (snapshots, pictures, plots,
  // summary, final state, checkpoint), so that none is mistaken for this run's.
  void open(const Scenario& scenario, bool fresh);
  // The recorder's part of a checkpoint (history.csv and gauges.csv are flushed first).
  void add_progress(RunProgress& progress);
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
  std::uint64_t scenario_hash_ = 0;  // of the resolved scenario text, kept in checkpoints
  int lock_descriptor_ = -1;  // holds the directory's lock (flock on .krug-lock) while the recorder lives
  LineFile history_;
  std::uint64_t history_bytes_ = 0;  // written to history.csv so far
  double next_history_time_ = 0.0;
  double next_snapshot_time_ = 0.0;
  std::vector<std::pair<double, std::string>> snapshots_;  // time, file relative to directory_
  std::vector<std::pair<double, std::string>> particle_snapshots_;
  TimeStepRecord time_steps_;
  run::ContactRecord contact_;
  PictureHook picture_;
  // Gauges: none (no work at all) without a "gauges" block.
  std::optional<GaugeSampler> gauges_;
  double gauge_interval_ = 0.0;
  LineFile gauge_file_;
  std::uint64_t gauge_bytes_ = 0;
  double next_gauge_time_ = 0.0;
  std::vector<double> gauge_values_;  // scratch row
};

// Resuming a study (`krug sweep`, `krug ballistic`): whether `directory` holds a finished run of the
// scenario whose resolved text (every default filled in, Scenario::resolved_json) is
// `resolved_json`: a summary.json that is whole JSON with status "completed" or "failed" (a failure is
// deterministic: running it again gives the same), not stopped by an interruption or a request, next
// to a scenario.resolved.json equal to `resolved_json` (as the run wrote it). Returns its status, or
// nullopt: run it (no summary, a half-written one, an interrupted run, a run of another scenario).
// A run removes its folder's summary.json when it starts, so a summary is never older than the
// scenario.resolved.json beside it.
std::optional<RunStatus> finished_run(const std::filesystem::path& directory, const std::string& resolved_json);

}  // namespace krug::output
