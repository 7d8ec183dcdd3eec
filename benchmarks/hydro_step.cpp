// Cost of the hydrodynamic time step in nanoseconds per zone-cycle (docs/performance.md).
//
// For each problem (benchmarks/problems.hpp) and size, a Simulation is built and advanced to a
// checkpoint once, outside any timing, so that the measured cycles see a developed flow (shocks,
// rarefactions, compressing edges) rather than a grid at rest: half the end time, except the RZ Sedov
// blast on its Cartesian quarter, which with the default controls stops at cycle 2351 at every
// resolution (axis zones tangle, see docs/performance.md) and is checkpointed at cycle 1000. Each
// benchmark iteration copies the checkpoint (not timed) and times `window_cycles` cycles (manual
// time). ns_per_zone_cycle = CPU time of the benchmark thread / zone-cycles: on a shared machine it is
// inflated far less than wall time by other processes; wall_ns_per_zone_cycle is reported as well.
// `window_at_start` times the first cycles from t = 0 instead (a grid mostly at rest), and
// `whole_run` a complete run on the small grids, to show how representative the window is.
//
//   build-bench/benchmarks/hydro_step --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/solver/simulation.hpp"
#include "problems.hpp"
#include "timing.hpp"

namespace {

using krug::Simulation;
using krug::SimulationSetup;
using krug::bench::time_it;
using krug::bench::Timing;


constexpr long window_cycles = 50;

struct Case {
  std::string name;  // problem/size, e.g. sedov_planar/200x200
  std::function<SimulationSetup()> setup;
  long checkpoint_cycles = std::numeric_limits<long>::max();  // checkpoint: half the end time or this cycle
  bool plastic = false;  // report the fraction of zones that yield during the window
  int threads = 1;       // controls.threads; above 1 the time is wall time (the thread's CPU time is a share)
};

// The same case on `threads` threads (name suffix /threads:N).
Case on_threads(Case c, int threads) {
  c.name += fmt::format("/threads:{}", threads);
  c.threads = threads;
  c.setup = [setup = c.setup, threads] {
    SimulationSetup s = setup();
    s.controls.threads = threads;
    return s;
  };
  return c;
}

// The checkpoint state, built once per case and reused by every repetition.
const Simulation& checkpoint(const Case& c) {
  static std::map<std::string, std::unique_ptr<Simulation>> cache;
  auto found = cache.find(c.name);
  if (found == cache.end()) {
    auto sim = std::make_unique<Simulation>(c.setup());
    const double stop = 0.5 * sim->controls().end_time;
    while (sim->time() < stop && sim->cycle() < c.checkpoint_cycles && !sim->finished()) sim->step();
    found = cache.emplace(c.name, std::move(sim)).first;
  }
  return *found->second;
}

// Fraction of the active zones whose plastic strain grew between two states of the same problem.
double yielding_fraction(const Simulation& before, const Simulation& after) {
  const krug::StrengthZoneFields& a = before.zone_state().strength;
  const krug::StrengthZoneFields& b = after.zone_state().strength;
  long active = 0, yielding = 0;
  for (krug::Index z = 0; z < before.mesh().zones.size(); ++z) {
    if (!after.mesh().zones.active[z]) continue;
    ++active;
    if (b.plastic_strain[z] > a.plastic_strain[z]) ++yielding;
  }
  return active > 0 ? static_cast<double>(yielding) / static_cast<double>(active) : 0.0;
}

void report(benchmark::State& state, Timing total, long zone_cycles, long cycles, long zones, int threads) {
  const double per = zone_cycles > 0 ? 1.0 / static_cast<double>(zone_cycles) : 0.0;
  state.counters["ns_per_zone_cycle"] = (threads > 1 ? total.wall_ns : total.cpu_ns) * per;
  state.counters["threads"] = threads;
  state.counters["wall_ns_per_zone_cycle"] = total.wall_ns * per;
  state.counters["zones"] = static_cast<double>(zones);
  state.counters["cycles"] = benchmark::Counter(static_cast<double>(cycles), benchmark::Counter::kAvgIterations);
  state.SetItemsProcessed(zone_cycles);
}

// Times `window_cycles` cycles from the checkpoint, or from t = 0 when `at_start`.
void window(benchmark::State& state, const Case& c, bool at_start) {
  Timing total;
  long zone_cycles = 0, cycles = 0;
  long zones = 0;
  try {
    std::unique_ptr<Simulation> initial;
    if (at_start) initial = std::make_unique<Simulation>(c.setup());
    const Simulation& start = at_start ? *initial : checkpoint(c);
    zones = start.mesh().zones.size();
    for (auto _ : state) {
      Simulation sim = start;  // copy, not timed
      const long zone_cycles_before = sim.zone_cycles();
      const long cycle_before = sim.cycle();
      const Timing t = time_it([&] {
        for (long k = 0; k < window_cycles && !sim.finished(); ++k) sim.step();
      });
      benchmark::DoNotOptimize(sim.mesh().nodes.x.data());
      benchmark::ClobberMemory();
      state.SetIterationTime(1e-9 * (c.threads > 1 ? t.wall_ns : t.cpu_ns));
      total += t;
      zone_cycles += sim.zone_cycles() - zone_cycles_before;
      cycles += sim.cycle() - cycle_before;
      if (c.plastic) state.counters["yielding_fraction"] = yielding_fraction(start, sim);
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  report(state, total, zone_cycles, cycles, zones, c.threads);
}

// Times a complete run, t = 0 to the end time (construction not timed).
void whole_run(benchmark::State& state, const Case& c) {
  Timing total;
  long zone_cycles = 0, cycles = 0;
  long zones = 0;
  try {
    const SimulationSetup setup = c.setup();
    for (auto _ : state) {
      Simulation sim(setup);  // copy of the set-up and initialisation, not timed
      zones = sim.mesh().zones.size();
      const Timing t = time_it([&] {
        while (!sim.finished()) sim.step();
      });
      benchmark::DoNotOptimize(sim.mesh().nodes.x.data());
      benchmark::ClobberMemory();
      state.SetIterationTime(1e-9 * (c.threads > 1 ? t.wall_ns : t.cpu_ns));
      total += t;
      zone_cycles += sim.zone_cycles();
      cycles += sim.cycle();
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  report(state, total, zone_cycles, cycles, zones, c.threads);
}

}  // namespace

int main(int argc, char** argv) {
  namespace problems = krug::problems;
  // Sod: a strip four times longer than wide (square zones); Sedov: n x n quarters.
  constexpr long rz_checkpoint = 1000;
  constexpr long copper_checkpoint_per_zone = 2;  // cycles per zone of the cylinder's length
  const std::vector<Case> cases = {
      {"sod_planar/100x25", [] { return problems::sod_strip(100, 25); }},
      {"sod_planar/400x100", [] { return problems::sod_strip(400, 100); }},
      {"sedov_planar/50x50", [] { return problems::sedov_planar(50); }},
      {"sedov_planar/200x200", [] { return problems::sedov_planar(200); }},
      {"sedov_rz/50x50", [] { return problems::sedov_axisymmetric(50); }, rz_checkpoint},
      {"sedov_rz/200x200", [] { return problems::sedov_axisymmetric(200); }, rz_checkpoint},
      {"copper_rz/50x50", [] { return problems::copper_cylinder_rz(50); }, copper_checkpoint_per_zone * 50, true},
      {"copper_rz/200x200", [] { return problems::copper_cylinder_rz(200); }, copper_checkpoint_per_zone * 200, true},
  };
  for (const Case& c : cases) {
    benchmark::RegisterBenchmark(fmt::format("window/{}", c.name).c_str(),
                                 [c](benchmark::State& state) { window(state, c, false); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  // The 40 000-zone windows on two threads (ten blocks of 4 096 zones: five per thread).
  for (const Case& c : {cases[1], cases[3], cases[5], cases[7]}) {
    const Case threaded = on_threads(c, 2);
    benchmark::RegisterBenchmark(fmt::format("window/{}", threaded.name).c_str(),
                                 [threaded](benchmark::State& state) { window(state, threaded, false); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  for (const Case& c : {cases[3], cases[5]}) {
    benchmark::RegisterBenchmark(fmt::format("window_at_start/{}", c.name).c_str(),
                                 [c](benchmark::State& state) { window(state, c, true); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  // The RZ blast does not reach its end time with the default controls (see above): no whole run.
  for (const Case& c : {cases[0], cases[2]}) {
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
