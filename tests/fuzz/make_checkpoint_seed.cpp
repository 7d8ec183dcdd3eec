// Writes the checkpoint fuzzer's seed: the seed scenario (seed_scenario.hpp) after 40 cycles, with
// its particles and damage. Usage: make_checkpoint_seed OUTPUT_FILE
#include <cstdio>

#include "krug/output/checkpoint.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/solver/simulation.hpp"
#include "seed_scenario.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_checkpoint_seed OUTPUT_FILE\n");
    return 2;
  }
  const krug::scenario::Scenario scenario = krug::scenario::parse_scenario(krug::fuzz::seed_scenario, "seed.json");
  krug::Simulation simulation(scenario.setup);
  for (int cycle = 0; cycle < 40; ++cycle) simulation.step();
  krug::output::write_checkpoint(argv[1], simulation.state(), krug::run::RunProgress{}, 1);
  return 0;
}
