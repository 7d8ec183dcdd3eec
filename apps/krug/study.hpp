#pragma once
// The runs of a study (`krug sweep`, `krug ballistic`): each a `krug run` child process of this
// executable in a directory of its own; who runs them (`Workers`: child processes on this machine,
// N at a time, or MPI ranks, mpi_workers.hpp); and resuming (a directory that already holds a
// finished run of the same scenario is not run again).
#include <atomic>
#include <csignal>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace krug::app {

// One `krug run` child: its scenario and output directory (the log goes to DIR/log.txt).
struct RunJob {
  std::filesystem::path scenario;
  std::filesystem::path directory;
  std::vector<std::string> extra;  // more arguments for krug run (e.g. --no-pictures)
};

// The arguments of a job's child after the executable: run SCENARIO --out DIR --quiet EXTRA...
std::vector<std::string> job_arguments(const RunJob& job);

// Hears each job as it ends: its index in the list, its exit code (0 completed, 1 failed, 127 could
// not start, 128 + signal interrupted) and where it ran ("" on this machine, "rank 2" under MPI).
using JobDone = std::function<void(std::size_t index, int code, const std::string& where)>;

// Who runs the jobs of a study. `run` runs a list and returns each job's exit code (-1: not started
// because interrupted); it returns when every started job has ended.
struct Workers {
  int slots = 1;            // runs at once
  std::string description;  // "2 at a time", "3 MPI ranks"
  std::function<std::vector<int>(const std::vector<RunJob>&, const JobDone&)> run;
};

// Child processes of this executable on this machine, at most `jobs` at once; an interruption stops
// starting new ones and is passed on once to those running (they lead process groups of their own).
std::vector<int> run_jobs(const std::vector<RunJob>& list, int jobs, const std::atomic<bool>& interrupted,
                          const volatile std::sig_atomic_t& signal_number, const JobDone& on_done = {});
Workers local_workers(int jobs, const std::atomic<bool>& interrupted, const volatile std::sig_atomic_t& signal_number);

// Resuming (output::finished_run): the exit code `krug run` gave the finished run of this scenario in
// `directory` (0 completed, 1 failed), or nullopt: run it.
std::optional<int> finished_run(const std::filesystem::path& directory, const std::string& resolved_json);

}  // namespace krug::app
