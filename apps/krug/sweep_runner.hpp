#pragma once
// `krug sweep`: runs the variants of a scenario (krug::io::prepare_sweep) as child processes of
// this same executable, at most `jobs` at once, and writes DIR/sweep.csv.
#include <atomic>
#include <csignal>
#include <string>
#include <vector>

namespace krug::app {

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
