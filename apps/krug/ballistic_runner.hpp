#pragma once
// `krug ballistic`: the ballistic limit of a penetration scenario (krug::run::ballistic_search), each
// speed run as a `krug run` child process of this executable (the sweep's machinery) in
// DIR/runs/v<speed>/, then DIR/ballistic.csv, ballistic.json, ballistic.png and a closing summary.
#include <atomic>
#include <csignal>
#include <string>

#include "study.hpp"

namespace krug::app {

struct BallisticArguments {
  std::string scenario;
  std::string velocity;       // "MIN,MAX" (m/s)
  double tolerance = 10.0;    // m/s
  int points_above = 3;
  int jobs = 0;               // runs per round; 0: the workers' slots (hardware threads, or MPI ranks)
  std::string out;            // default out/<scenario stem>-ballistic
  bool quiet = false;
  bool pictures = false;      // the runs' pictures and plots (off: the study only needs summary.json)
  bool scale_end_time = true; // below the scenario's speed, end_time stretched by the speed ratio
  double end_time_factor = 1.0;  // every run's end time multiplied by this (--end-time-factor)
};

// Exit code: 0 when the limit was bracketed within the tolerance, 1 when the study ended without it
// (no limit in the range, runs inside the bracket that give no answer), 2 bad input, 128 + signal
// when interrupted (the tables so far are written). A speed whose folder already holds a finished run
// of the same variant (study.hpp, finished_run) is not run again: an interrupted study resumes.
int run_ballistic(const BallisticArguments& arguments, const Workers& workers, const std::atomic<bool>& interrupted,
                  const volatile std::sig_atomic_t& signal_number);

}  // namespace krug::app
