#pragma once
// `krug sweep`: runs the variants of a scenario (krug::io::prepare_sweep) as child processes of
// this same executable, at most `jobs` at once, and writes DIR/sweep.csv.
#include <atomic>
#include <csignal>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace krug::app {

// One `krug run` child: its scenario and output directory (the log goes to DIR/log.txt).
struct RunJob {
  std::filesystem::path scenario;
  std::filesystem::path directory;
  std::vector<std::string> extra;  // more arguments for krug run (e.g. --no-pictures)
};

// Runs every job as `krug run SCENARIO --out DIR --quiet` child processes of this executable, at
// most `jobs` at once; an interruption stops starting new ones and is passed on once to those
// running. Returns each job's exit code (127: could not start, -1: not started because interrupted);
// `on_done(index, code)` hears each as it ends.
std::vector<int> run_jobs(const std::vector<RunJob>& list, int jobs, const std::atomic<bool>& interrupted,
                          const volatile std::sig_atomic_t& signal_number,
                          const std::function<void(std::size_t, int)>& on_done = {});

struct SweepArguments {
  std::string scenario;
  std::vector<std::string> sets;  // "PATH=V1,V2,..."
  int jobs = 0;                   // 0: the number of hardware threads
  std::string out;                // default out/<scenario stem>-sweep
  bool quiet = false;
};

// Exit code: 0 when every variant completed, 1 when some did not, 128 + signal when interrupted.
int run_sweep(const SweepArguments& arguments, const std::atomic<bool>& interrupted,
              const volatile std::sig_atomic_t& signal_number);

}  // namespace krug::app
