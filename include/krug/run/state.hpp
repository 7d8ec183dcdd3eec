#pragma once
// The run loop's own state, besides the simulation: the stop rule's window, the record of what set the
// time step, the progress a checkpoint keeps so that a restarted run goes on as if it had never
// stopped, and the result of a run. Plain values: the loop (run.hpp) fills them, the writers above it
// (krug/output/) store them in checkpoint.bin and summary.json.
#include <cstdint>
#include <deque>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "krug/core/vec2.hpp"
#include "krug/run/penetration.hpp"

namespace krug::run {

// The stop rule's window as it stands (stop_rule.hpp, StopMonitor): what a checkpoint keeps of it.
// Each component's window extremes are kept as (time, value) samples in monotonic queues.
struct StopWindow {
  using Sample = std::pair<double, double>;
  bool started = false;
  Vec2 initial_velocity;
  double scale = 0.0;       // S
  bool armed = false;
  double armed_time = 0.0;
  std::deque<Sample> max_x, min_x, max_y, min_y;
};

// Which limit set the time step, cycle by cycle: the cycles each body's zones set it, the cycles each
// other limit did, and the smallest step with where it came from.
struct TimeStepRecord {
  std::vector<std::int64_t> zone_cycles;  // per body
  std::int64_t growth_cycles = 0, particle_cycles = 0, other_cycles = 0;  // other: max_time_step, end time
  std::int64_t damping_cycles = 0;  // the tensor viscosity's damping bound
  double smallest = 0.0;                  // s (0: no step yet)
  double smallest_time = 0.0;             // s, when it was taken
  std::int32_t smallest_body = -1, smallest_zone = -1;  // zone within the body; -1 when not a zone's
  std::int32_t smallest_limit = 0;        // TimeStepLimit
  // The count the last cycle added for the step it chose (body b's zones: b; growth -2, particles -3,
  // other -4; -1 none yet): a step that the damping bound then cut is moved from it to damping_cycles.
  std::int32_t last_counted = -1;
};

// The contact solve, cycle by cycle: the cycles with a pushing contact, those whose Gauss-Seidel
// sweeps ended at max_sweeps outside the gap tolerance, those in which contact.solve_stalled solved
// the pushing contacts together, and the most sweeps a cycle took.
struct ContactRecord {
  std::int64_t active_cycles = 0, unconverged_cycles = 0, solved_together_cycles = 0;
  std::int32_t most_sweeps = 0;
};

// What the run loop and its observer need, besides the simulation, to continue their outputs. The
// loop fills the checkpoint schedule, the wall time, the stop window and the penetration record; the
// observer (observer.hpp) the rest.
struct RunProgress {
  double next_history_time = 0.0;
  double next_snapshot_time = 0.0;
  double next_checkpoint_time = 0.0;
  std::vector<std::pair<double, std::string>> snapshots;           // time, file relative to the directory
  std::vector<std::pair<double, std::string>> particle_snapshots;
  std::uint64_t history_bytes = 0;   // length of history.csv when the checkpoint was taken
  double wall_seconds = 0.0;         // wall time of the run so far
  bool has_stop_state = false;
  StopWindow stop;
  bool has_penetration = false;
  PenetrationRecord penetration;
  TimeStepRecord time_steps;
  ContactRecord contact;
  // Gauges (scenario key "gauges"; zero and empty without): the next row's time, the length of
  // gauges.csv, and the impulse of each force gauge so far (per radian or per m, two per channel).
  double next_gauge_time = 0.0;
  std::uint64_t gauge_bytes = 0;
  std::vector<double> gauge_impulses;
};

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
  ContactRecord contact;               // filled by the recorder
};

}  // namespace krug::run
