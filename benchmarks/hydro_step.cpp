// Cost of the hydrodynamic time step in nanoseconds per zone-cycle (docs/performance.md).
//
// For each problem (benchmarks/problems.hpp) and size, a Simulation is built and advanced to half its
// end time once, outside any timing, so that the measured cycles see a developed flow (shocks,
// rarefactions and compressing edges across the grid) rather than a grid at rest. Each benchmark
// iteration copies that state (not timed) and times `window` cycles with a steady clock (manual
// time): ns_per_zone_cycle = elapsed ns / zone-cycles. The `whole_run` benchmarks time a complete run
// from t = 0 to the end time on the small grids, to show that the window is representative of the
// whole run.
//
//   build-bench/benchmarks/hydro_step --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/solver/simulation.hpp"
#include "problems.hpp"

namespace {

using krug::Simulation;
using krug::SimulationSetup;
using Clock = std::chrono::steady_clock;

constexpr long window_cycles = 50;

struct Case {
  std::string name;  // problem/size, e.g. sedov_planar/200x200
  std::function<SimulationSetup()> setup;
};

// The state at half the end time, built once per case and reused by every repetition.
const Simulation& checkpoint(const Case& c) {
  static std::map<std::string, std::unique_ptr<Simulation>> cache;
  auto found = cache.find(c.name);
  if (found == cache.end()) {
    auto sim = std::make_unique<Simulation>(c.setup());
    const double stop = 0.5 * sim->controls().end_time;
    while (sim->time() < stop && !sim->finished()) sim->step();
    found = cache.emplace(c.name, std::move(sim)).first;
  }
  return *found->second;
}

void report(benchmark::State& state, double total_ns, long zone_cycles, long cycles, long zones) {
  state.counters["ns_per_zone_cycle"] = zone_cycles > 0 ? total_ns / static_cast<double>(zone_cycles) : 0.0;
  state.counters["zones"] = static_cast<double>(zones);
  state.counters["cycles"] = benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kAvgIterations);
  state.SetItemsProcessed(zone_cycles);
}

// Times `window_cycles` cycles from the mid-run checkpoint.
void window(benchmark::State& state, const Case& c) {
  double total_ns = 0.0;
  long zone_cycles = 0, cycles = 0;
  long zones = 0;
  try {
    const Simulation& start = checkpoint(c);
    zones = start.mesh().zones.size();
    for (auto _ : state) {
      Simulation sim = start;  // copy, not timed
      const long zone_cycles_before = sim.zone_cycles();
      const long cycle_before = sim.cycle();
      const auto t0 = Clock::now();
      for (long k = 0; k < window_cycles && !sim.finished(); ++k) sim.step();
      const auto t1 = Clock::now();
      benchmark::DoNotOptimize(sim.mesh().nodes.x.data());
      benchmark::ClobberMemory();
      const double ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
      state.SetIterationTime(1e-9 * ns);
      total_ns += ns;
      zone_cycles += sim.zone_cycles() - zone_cycles_before;
      cycles += sim.cycle() - cycle_before;
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  report(state, total_ns, zone_cycles, cycles, zones);
}

// Times a complete run, t = 0 to the end time (construction not timed).
void whole_run(benchmark::State& state, const Case& c) {
  double total_ns = 0.0;
  long zone_cycles = 0, cycles = 0;
  long zones = 0;
  try {
    const SimulationSetup setup = c.setup();
    for (auto _ : state) {
      Simulation sim(setup);  // copy of the set-up and initialisation, not timed
      zones = sim.mesh().zones.size();
      const auto t0 = Clock::now();
      while (!sim.finished()) sim.step();
      const auto t1 = Clock::now();
      benchmark::DoNotOptimize(sim.mesh().nodes.x.data());
      benchmark::ClobberMemory();
      const double ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
      state.SetIterationTime(1e-9 * ns);
      total_ns += ns;
      zone_cycles += sim.zone_cycles();
      cycles += sim.cycle();
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  report(state, total_ns, zone_cycles, cycles, zones);
}

}  // namespace

int main(int argc, char** argv) {
  namespace problems = krug::problems;
  // Sod: a strip four times longer than wide (square zones); Sedov: n x n quarters.
  const std::vector<Case> cases = {
      {"sod_planar/100x25", [] { return problems::sod_strip(100, 25); }},
      {"sod_planar/400x100", [] { return problems::sod_strip(400, 100); }},
      {"sedov_planar/50x50", [] { return problems::sedov_planar(50); }},
      {"sedov_planar/200x200", [] { return problems::sedov_planar(200); }},
      {"sedov_rz/50x50", [] { return problems::sedov_axisymmetric(50); }},
      {"sedov_rz/200x200", [] { return problems::sedov_axisymmetric(200); }},
  };
  for (const Case& c : cases) {
    benchmark::RegisterBenchmark(fmt::format("window/{}", c.name).c_str(),
                                 [c](benchmark::State& state) { window(state, c); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  for (const Case& c : {cases[0], cases[2], cases[4]}) {
    benchmark::RegisterBenchmark(fmt::format("whole_run/{}", c.name).c_str(),
                                 [c](benchmark::State& state) { whole_run(state, c); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
