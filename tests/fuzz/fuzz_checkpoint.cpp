// libFuzzer target: the checkpoint reader on arbitrary bytes, resealed first (the trailer's FNV-1a
// checksum recomputed) so that mutations reach the reader's own checks instead of stopping at the
// checksum. Every input must be read or refused with an InputError; one that is read must restore
// into the simulation of the scenario it was made from (the seed's: seed_scenario.json beside
// this file, built in at compile time) or be refused by it. Build and run: scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "krug/core/error.hpp"
#include "krug/output/checkpoint.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/solver/simulation.hpp"
#include "seed_scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const krug::scenario::Scenario scenario = krug::scenario::parse_scenario(krug::fuzz::seed_scenario, "seed.json");
  std::string bytes(reinterpret_cast<const char*>(data), size);
  constexpr std::size_t trailer = 16;  // checksum (8 bytes) and end marker (8 bytes)
  if (bytes.size() > trailer) {
    const std::uint64_t sum = krug::output::fnv1a(bytes.substr(0, bytes.size() - trailer));
    std::memcpy(bytes.data() + bytes.size() - trailer, &sum, sizeof sum);
  }
  try {
    krug::output::Checkpoint checkpoint = krug::output::parse_checkpoint(bytes, "fuzz.bin");
    krug::Simulation simulation(scenario.setup);
    simulation.restore(std::move(checkpoint.state));
  } catch (const krug::InputError&) {
  }
  return 0;
}
