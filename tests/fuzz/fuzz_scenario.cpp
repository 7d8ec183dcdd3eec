// libFuzzer target: the scenario reader on arbitrary bytes. Every input must be read or refused with
// an InputError; one that is read must build a Simulation and take a few steps, or stop with a
// NumericalFailure. Anything else (another exception, a crash, a sanitizer report, a hang, memory
// without bound) is a finding. Scenarios are capped at 20 000 zones (scenario::ReadLimits) so that a
// large but valid mesh is not mistaken for a leak. Build and run: scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "krug/core/error.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/solver/simulation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  krug::scenario::ReadLimits limits;
  limits.max_zones = 20'000;
  try {
    krug::scenario::Scenario scenario = krug::scenario::parse_scenario(text, "fuzz.json", limits);
    krug::Simulation simulation(std::move(scenario.setup));
    for (int cycle = 0; cycle < 3 && !simulation.finished(); ++cycle) simulation.step();
  } catch (const krug::InputError&) {
  } catch (const krug::NumericalFailure&) {
  }
  return 0;
}
