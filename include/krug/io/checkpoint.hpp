#pragma once
// Checkpoint files (DIR/checkpoint.bin): the SimulationState of a run and the run loop's own
// progress (output schedule, snapshot list, length of history.csv, stop-rule window, wall time),
// so that `krug run --restart` continues the run as if it had never stopped.
//
// Format (version 4), little-endian, native doubles:
//   "KRUGCKPT"  u32 version  u32 0x01020304 (byte order)  u32 sizeof(double)  u32 sizeof(Index)
//   u64 FNV-1a hash of the resolved scenario text the run started from
//   the state and progress, field by field: a vector is a u64 count and its raw elements,
//   a string a u64 length and its bytes
//   u64 FNV-1a hash of every byte before it, then "KRUGEND!"
// The file is written under a temporary name and renamed. A file that is truncated, corrupted,
// of another version or from another machine layout is refused with an InputError.
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <deque>

#include "krug/core/vec2.hpp"
#include "krug/solver/penetration.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::io {

inline constexpr std::uint32_t checkpoint_version = 5;

// The stop rule's window as it stands (krug/run/stop_rule.hpp, StopMonitor): what a checkpoint keeps
// of it. Each component's window extremes are kept as (time, value) samples in monotonic queues.
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
  double smallest = 0.0;                  // s (0: no step yet)
  double smallest_time = 0.0;             // s, when it was taken
  std::int32_t smallest_body = -1, smallest_zone = -1;  // zone within the body; -1 when not a zone's
  std::int32_t smallest_limit = 0;        // TimeStepLimit
};

// What the run loop and the recorder need, besides the simulation, to continue their outputs.
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
  // Gauges (scenario key "gauges"; zero and empty without): the next row's time, the length of
  // gauges.csv, and the impulse of each force gauge so far (per radian or per m, two per channel).
  double next_gauge_time = 0.0;
  std::uint64_t gauge_bytes = 0;
  std::vector<double> gauge_impulses;
};

struct Checkpoint {
  SimulationState state;
  RunProgress progress;
  std::uint64_t scenario_hash = 0;
};

// FNV-1a, 64 bits.
std::uint64_t fnv1a(const std::string& bytes, std::uint64_t hash = 0xcbf29ce484222325ULL);

void write_checkpoint(const std::filesystem::path& file, const SimulationState& state, const RunProgress& progress,
                      std::uint64_t scenario_hash);
Checkpoint read_checkpoint(const std::filesystem::path& file);
// The same from the file's bytes; `name` labels the errors.
Checkpoint parse_checkpoint(const std::string& bytes, const std::string& name);

}  // namespace krug::io
