#pragma once
// `krug sweep`: runs the variants of a scenario (krug::output::prepare_sweep) as `krug run` child
// processes of this same executable (on this machine or on MPI ranks: study.hpp), skips those a
// previous sweep into the same folder finished, and writes DIR/sweep.csv.
#include <atomic>
#include <csignal>
#include <string>
#include <vector>

#include "study.hpp"

namespace krug::app {

struct SweepArguments {
  std::string scenario;
  std::vector<std::string> sets;  // "PATH=V1,V2,..."
  std::string out;                // default out/<scenario stem>-sweep
  bool quiet = false;
};

// Runs the variants not yet finished with `workers`. Exit code: 0 when every variant completed, 1
// when some did not, 128 + signal when interrupted.
int run_sweep(const SweepArguments& arguments, const Workers& workers, const std::atomic<bool>& interrupted,
              const volatile std::sig_atomic_t& signal_number);

}  // namespace krug::app
