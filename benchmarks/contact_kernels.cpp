// Cost of the contact kernels (docs/performance.md, "Contact kernels"):
//
//   narrow_phase/node_segment   the node-on-segment geometry of one candidate pair (kernels.hpp:
//                               project + contact_inverse_mass), ns per candidate pair;
//   reaction_sweep/N            one projected Gauss-Seidel sweep of ContactSolver::solve over two blocks
//                               pressed together along an interface of N + 5N/8 nodes (non-matching
//                               meshes, both ways), ns per active contact and per candidate: the cost
//                               of a solve with 1 + k sweeps minus that with 1 sweep, over k;
//   reaction_solve/N            the whole solve with the default controls (candidates, sweeps, stats),
//                               the solver kept between solves: nothing moves, so its near lists are
//                               reused and no grid is built (a step between rebuilds);
//   reaction_solve_rebuilt/N    the same with a solver built (untimed) before each solve, so every solve
//                               builds the grids and the near lists (a rebuild step);
//   broad_phase/build/N         UniformGrid::build over N boxes, ns per box;
//   broad_phase/query/N         one query per box (the box itself, as a body's nodes are queried
//                               against its segments), ns per query;
//   broad_phase/build_query/N   both, N from 1e3 to 1e6: ns per entity constant means linear.
//
// Boxes: N squares of side s at uniformly random centres (fixed seed) in a square of side
// s sqrt(N) x 2, so each box overlaps about two others on average, as neighbouring boundary segments
// do; numbered in random order (`random`) or row by row (`ordered`, as a boundary is traversed).
// Time is the CPU time of the benchmark thread (CLOCK_THREAD_CPUTIME_ID; other processes on a shared
// machine do not add to it); the wall time is reported beside it.
//
//   build-contact/benchmarks/contact_kernels --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "krug/contact/broad_phase.hpp"
#include "krug/contact/contact.hpp"
#include "krug/contact/kernels.hpp"
#include "krug/krug.hpp"
#include "timing.hpp"

namespace {

using namespace krug;
using krug::bench::time_it;
using krug::bench::Timing;

void per_item(benchmark::State& state, const char* name, Timing total, double items) {
  state.counters[fmt::format("ns_per_{}", name)] = items > 0.0 ? total.cpu_ns / items : 0.0;
  state.counters[fmt::format("wall_ns_per_{}", name)] = items > 0.0 ? total.wall_ns / items : 0.0;
}

// ---- narrow phase ----------------------------------------------------------------------------------

struct PairSet {
  std::vector<Vec2> point, a, b;
  std::vector<contact::InverseMass> w_point, w_a, w_b;
};

// Candidate pairs as the broad phase hands them over: a node near a segment of about unit length.
PairSet random_pairs(std::size_t n) {
  std::mt19937 random(12345);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PairSet s;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 a{unit(random), unit(random)};
    const double angle = 3.14159265358979 * unit(random);
    const Vec2 b = a + Vec2{std::cos(angle), std::sin(angle)};
    s.a.push_back(a);
    s.b.push_back(b);
    s.point.push_back(0.5 * (a + b) + 0.3 * Vec2{unit(random), unit(random)});
    const double m = 1.0 + 0.5 * unit(random);
    s.w_point.push_back({1.0 / m, 1.0 / m});
    s.w_a.push_back({1.0 / (m + 0.2), 1.0 / (m + 0.2)});
    s.w_b.push_back({1.0 / (m + 0.1), 0.0});
  }
  return s;
}

void narrow_phase(benchmark::State& state) {
  const std::size_t n = 4096;
  const PairSet pairs = random_pairs(n);
  Timing total;
  double items = 0.0;
  for (auto _ : state) {
    double sum = 0.0;
    const Timing t = time_it([&] {
      for (std::size_t k = 0; k < n; ++k) {
        const contact::SegmentProjection p = contact::project(pairs.point[k], pairs.a[k], pairs.b[k], 0.0);
        const double w = contact::contact_inverse_mass(p.normal, p.xi, pairs.w_point[k], pairs.w_a[k], pairs.w_b[k]);
        sum += p.inside ? std::max(0.0, -p.gap / w) : 0.0;
      }
    });
    benchmark::DoNotOptimize(sum);
    state.SetIterationTime(1e-9 * t.cpu_ns);
    total += t;
    items += static_cast<double>(n);
  }
  per_item(state, "pair", total, items);
}

// ---- reaction solve --------------------------------------------------------------------------------

// Two elastic blocks, the lower [0, 1] x [0, W] with N zones across and 4 along, the upper [1, 2] x [0, W]
// with 5N/8 across, moving into each other at 1 m/s: every node of the interface is a candidate
// against the other face, both ways, and every one pushes.
struct PressedBlocks {
  Mesh mesh;
  contact::ContactSetup setup;
  std::vector<std::pair<Index, Index>> ranges;
  double dt = 0.0;
};

PressedBlocks pressed_blocks(int across) {
  SimulationSetup s;
  s.geometry = GeometryKind::planar;
  const double width = 0.01 * across / 8.0;
  const auto lower = generate::rectangle(s.mesh, generate::graded_axis(0.0, {{0.01, 4, 1.0}}),
                                         generate::graded_axis(0.0, {{width, across, 1.0}}), 0);
  const auto upper = generate::rectangle(s.mesh, generate::graded_axis(0.01, {{0.02, 4, 1.0}}),
                                         generate::graded_axis(0.0, {{width, std::max(1, 5 * across / 8), 1.0}}), 1);
  s.materials.push_back(Material{"aluminium", 2785.0, LinearBulk{7.906e10, 2785.0}, Elastic{2.76e10}});
  s.bodies.push_back({"lower", 0, lower.node_begin, lower.node_end, lower.zone_begin, lower.zone_end});
  s.bodies.push_back({"upper", 0, upper.node_begin, upper.node_end, upper.zone_begin, upper.zone_end});
  for (Index n = lower.node_begin; n < lower.node_end; ++n) s.mesh.nodes.u[n] = 1.0;
  for (Index n = upper.node_begin; n < upper.node_end; ++n) s.mesh.nodes.u[n] = -1.0;
  s.controls.end_time = 1.0;
  const Simulation sim(s);  // masses and inverse masses
  PressedBlocks p;
  p.mesh = sim.mesh();
  p.setup.pairs = {{0, 1, 0.0}};
  for (const Body& b : sim.bodies()) p.ranges.emplace_back(b.zone_begin, b.zone_end);
  p.dt = sim.next_time_step();
  return p;
}

struct SolveTiming {
  Timing total;
  long active = 0, candidates = 0, sweeps = 0, solves = 0;
};

// Solves repeatedly from the same predicted state (velocities restored, not timed); `fresh`: with a
// solver built before each solve (not timed), whose broad phase is then built in the solve.
SolveTiming time_solves(const PressedBlocks& blocks, contact::ContactControls controls, benchmark::State* state,
                        bool fresh = false) {
  contact::ContactSetup setup = blocks.setup;
  setup.controls = controls;
  Mesh mesh = blocks.mesh;
  Particles particles;
  contact::ContactSolver solver(setup, mesh, blocks.ranges);
  SolveTiming result;
  const auto one = [&] {
    mesh.nodes.u = blocks.mesh.nodes.u;
    mesh.nodes.v = blocks.mesh.nodes.v;
    if (fresh) solver = contact::ContactSolver(setup, mesh, blocks.ranges);
    contact::ContactStatistics stats;
    const Timing t = time_it([&] { stats = solver.solve(contact::nodes_view(mesh.nodes), contact::particles_view(particles), blocks.dt, blocks.dt); });
    benchmark::DoNotOptimize(mesh.nodes.u.data());
    result.total += t;
    result.active += stats.active;
    result.candidates += stats.candidates;
    result.sweeps += stats.sweeps;
    ++result.solves;
    return t;
  };
  if (state != nullptr) {
    for (auto _ : *state) state->SetIterationTime(1e-9 * one().cpu_ns);
  } else {
    for (int k = 0; k < 20; ++k) one();
  }
  return result;
}

void reaction_sweep(benchmark::State& state) {
  const PressedBlocks blocks = pressed_blocks(static_cast<int>(state.range(0)));
  constexpr int extra = 10;
  contact::ContactControls one_sweep, many;
  one_sweep.max_sweeps = 1;
  many.max_sweeps = 1 + extra;
  many.gap_tolerance = -1.0;  // never converged: every sweep runs
  const SolveTiming base = time_solves(blocks, one_sweep, nullptr);
  const SolveTiming full = time_solves(blocks, many, &state);
  const double per_solve_base = base.total.cpu_ns / static_cast<double>(base.solves);
  const double per_solve_full = full.total.cpu_ns / static_cast<double>(full.solves);
  const double sweeps = static_cast<double>(full.sweeps) / static_cast<double>(full.solves) - 1.0;
  const double active = static_cast<double>(full.active) / static_cast<double>(full.solves);
  const double candidates = static_cast<double>(full.candidates) / static_cast<double>(full.solves);
  const double per_sweep = (per_solve_full - per_solve_base) / sweeps;
  state.counters["ns_per_active_contact_per_sweep"] = per_sweep / active;
  state.counters["ns_per_candidate_per_sweep"] = per_sweep / candidates;
  state.counters["active"] = active;
  state.counters["candidates"] = candidates;
}

void reaction_solve(benchmark::State& state, bool fresh) {
  const PressedBlocks blocks = pressed_blocks(static_cast<int>(state.range(0)));
  const SolveTiming t = time_solves(blocks, contact::ContactControls{}, &state, fresh);
  const double solves = static_cast<double>(t.solves);
  state.counters["ns_per_active_contact"] = t.total.cpu_ns / static_cast<double>(t.active);
  state.counters["sweeps"] = static_cast<double>(t.sweeps) / solves;
  state.counters["active"] = static_cast<double>(t.active) / solves;
  state.counters["candidates"] = static_cast<double>(t.candidates) / solves;
}

// ---- broad phase -----------------------------------------------------------------------------------

// `ordered`: the boxes numbered row by row (bands two sides high, by x within a band), as the segments
// of a mesh boundary come in boundary order, neighbours in space close in memory; otherwise in random
// order, the worst case for the caches.
std::vector<contact::Box> random_boxes(std::size_t n, bool ordered) {
  std::mt19937 random(2024);
  const double side = 1.0, extent = 2.0 * side * std::sqrt(static_cast<double>(n));
  std::uniform_real_distribution<double> where(0.0, extent);
  std::vector<Vec2> centres(n);
  for (Vec2& c : centres) c = {where(random), where(random)};
  if (ordered) {
    std::sort(centres.begin(), centres.end(), [&](Vec2 a, Vec2 b) {
      const double band_a = std::floor(a.y / (2.0 * side)), band_b = std::floor(b.y / (2.0 * side));
      return band_a != band_b ? band_a < band_b : a.x < b.x;
    });
  }
  std::vector<contact::Box> boxes(n);
  for (std::size_t k = 0; k < n; ++k) {
    boxes[k].include(centres[k] - Vec2{0.5 * side, 0.5 * side});
    boxes[k].include(centres[k] + Vec2{0.5 * side, 0.5 * side});
  }
  return boxes;
}

enum class BroadPart { build, query, both };

void broad_phase(benchmark::State& state, BroadPart part, bool ordered) {
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::vector<contact::Box> boxes = random_boxes(n, ordered);
  contact::UniformGrid grid;
  grid.build(boxes);
  Timing total;
  double items = 0.0;
  long found = 0;
  for (auto _ : state) {
    const Timing t = time_it([&] {
      if (part != BroadPart::query) grid.build(boxes);
      if (part != BroadPart::build) {
        for (const contact::Box& b : boxes) grid.query(b, [&](std::size_t) { ++found; });
      }
    });
    state.SetIterationTime(1e-9 * t.cpu_ns);
    total += t;
    items += static_cast<double>(n);
  }
  benchmark::DoNotOptimize(found);
  per_item(state, part == BroadPart::query ? "query" : "entity", total, items);
  state.counters["overlaps_per_query"] = part == BroadPart::build ? 0.0 : static_cast<double>(found) / items;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::RegisterBenchmark("narrow_phase/node_segment", narrow_phase)->UseManualTime()->Unit(benchmark::kMicrosecond);
  for (int across : {64, 512, 4096}) {
    benchmark::RegisterBenchmark("reaction_sweep", reaction_sweep)->Arg(across)->UseManualTime()->Unit(benchmark::kMicrosecond);
  }
  for (int across : {64, 512, 4096}) {
    benchmark::RegisterBenchmark("reaction_solve", [](benchmark::State& s) { reaction_solve(s, false); })
        ->Arg(across)->UseManualTime()->Unit(benchmark::kMicrosecond);
  }
  for (int across : {64, 512, 4096}) {
    benchmark::RegisterBenchmark("reaction_solve_rebuilt", [](benchmark::State& s) { reaction_solve(s, true); })
        ->Arg(across)->UseManualTime()->Unit(benchmark::kMicrosecond);
  }
  for (bool ordered : {false, true}) {
    const std::string order = ordered ? "ordered" : "random";
    for (long n : {1000L, 10000L, 100000L, 1000000L}) {
      benchmark::RegisterBenchmark(fmt::format("broad_phase/build/{}", order).c_str(),
                                   [ordered](benchmark::State& s) { broad_phase(s, BroadPart::build, ordered); })
          ->Arg(n)->UseManualTime()->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark(fmt::format("broad_phase/query/{}", order).c_str(),
                                   [ordered](benchmark::State& s) { broad_phase(s, BroadPart::query, ordered); })
          ->Arg(n)->UseManualTime()->Unit(benchmark::kMicrosecond);
      benchmark::RegisterBenchmark(fmt::format("broad_phase/build_query/{}", order).c_str(),
                                   [ordered](benchmark::State& s) { broad_phase(s, BroadPart::both, ordered); })
          ->Arg(n)->UseManualTime()->Unit(benchmark::kMicrosecond);
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
