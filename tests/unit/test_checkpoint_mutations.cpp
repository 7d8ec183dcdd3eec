// A checkpoint edited and resealed with a valid checksum (so that only the reader's own checks stand
// between it and the run) is refused with an InputError, or read into a state that restores into
// the simulation without a crash: counts of 2^62, counts off by one, random bytes. Run under the
// sanitizers in CI (label unit), where an out-of-range read or a huge allocation would show.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

#include "krug/core/error.hpp"
#include "krug/output/checkpoint.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/solver/simulation.hpp"
#include "../fuzz/seed_scenario.hpp"  // the checkpoint fuzzer's scenario: a fracturing flyer and plate

namespace {


std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

// The checkpoint's trailer: the FNV-1a of the body (8 bytes), then the end marker (8 bytes).
std::string resealed(std::string bytes) {
  const std::size_t body_end = bytes.size() - 16;
  const std::uint64_t sum = krug::output::fnv1a(bytes.substr(0, body_end));
  std::memcpy(bytes.data() + body_end, &sum, sizeof sum);
  return bytes;
}

}  // namespace

TEST_CASE("resealed, edited checkpoints are refused or restore cleanly; none crashes", "[checkpoint][robustness]") {
  const krug::scenario::Scenario scenario = krug::scenario::parse_scenario(krug::fuzz::seed_scenario, "plate.json");
  krug::Simulation simulation(scenario.setup);
  for (int i = 0; i < 40; ++i) simulation.step();
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / fmt::format("krug_checkpoint_mutations_{}", ::getpid());
  std::filesystem::create_directories(dir);
  const std::filesystem::path good = dir / "good.bin", edited = dir / "edited.bin";
  krug::output::write_checkpoint(good, simulation.state(), krug::run::RunProgress{}, 1);
  const std::string bytes = read_bytes(good);
  REQUIRE(bytes.size() > 1000);
  // The unedited checkpoint reads and restores.
  krug::Simulation restored(scenario.setup);
  restored.restore(krug::output::read_checkpoint(good).state);

  std::mt19937_64 random(20261125);
  int refused = 0, accepted = 0;
  const std::size_t body_end = bytes.size() - 16;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string mutated = bytes;
    const int kind = trial % 3;
    const std::size_t at = 8 + random() % (body_end - 16);
    if (kind == 0) {  // an 8-byte word (a count, where it lands on one) set to 2^62
      const std::uint64_t huge = std::uint64_t{1} << 62;
      std::memcpy(mutated.data() + at, &huge, sizeof huge);
    } else if (kind == 1) {  // an 8-byte word off by one either way
      std::uint64_t word = 0;
      std::memcpy(&word, mutated.data() + at, sizeof word);
      word += (random() % 2 == 0) ? 1 : std::uint64_t(-1);
      std::memcpy(mutated.data() + at, &word, sizeof word);
    } else {  // one to four random bytes
      for (int k = 0, n = 1 + static_cast<int>(random() % 4); k < n; ++k) {
        mutated[8 + random() % (body_end - 8)] = static_cast<char>(random() & 0xff);
      }
    }
    write_bytes(edited, resealed(mutated));
    try {
      krug::output::Checkpoint checkpoint = krug::output::read_checkpoint(edited);
      krug::Simulation target(scenario.setup);
      target.restore(std::move(checkpoint.state));
      ++accepted;  // a value changed inside a field: a different but well-formed state
    } catch (const krug::InputError&) {
      ++refused;
    }
  }
  INFO("refused " << refused << ", accepted " << accepted);
  CHECK(refused + accepted == 3000);
  CHECK(refused > 0);
  std::filesystem::remove_all(dir);
}
