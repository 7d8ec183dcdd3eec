#pragma once
// Checkpoint files (DIR/checkpoint.bin): the SimulationState of a run and the run loop's own
// progress (output schedule, snapshot list, length of history.csv, stop-rule window, wall time;
// krug/run/state.hpp, RunProgress), so that `krug run --restart` continues the run as if it had never
// stopped.
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

#include "krug/run/state.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::output {

using run::RunProgress;

inline constexpr std::uint32_t checkpoint_version = 10;

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

}  // namespace krug::output
