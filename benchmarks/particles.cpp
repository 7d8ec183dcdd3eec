// Cost of free elements (particles) in nanoseconds (docs/performance.md, "Particles").
//
// box/<N>: N particles in a closed box of four rigid walls, one Simulation::step() per benchmark
// iteration, reported as ns per particle-step. Planar, radius 0.25 mm, Wilkins aluminium density
// (2785 kg/m^3), on a jittered square lattice at an area fraction of 0.3, random velocities up to
// 10 m/s (fixed seed). The scene has no zones: the step is the particles' part of the recipe (the
// predictor's copies, contact: candidates, broad phase and Gauss-Seidel sweeps, the mover, the ledger
// and the particle time-step limit). It is advanced untimed for `warm_up` steps (the step grows to the
// particle limit, 0.5 r per step at the fastest particle, and the particles meet each other and the
// walls), then each iteration times one step; every `window` steps the state is reset (untimed) to that
// checkpoint, and the iteration count is a whole number of windows, so that every repetition times
// the same steps. Counters: candidates and active contacts per particle and Gauss-Seidel sweeps per step.
//
// kernel/particle_segment, kernel/particle_particle: the narrow-phase arithmetic of one Gauss-Seidel
// update (docs/theory.md §2 step 3), in ns per candidate pair: predicted positions, the contact
// geometry (krug::contact::disc_segment_contact / disc_disc_contact, the functions the solver calls),
// the effective inverse mass, the clamped normal reaction and the velocity changes of the points, over
// 4096 pairs in arrays (no broad phase, no bookkeeping). Half of the pairs touch.
//
// solve/particle_segment, solve/particle_particle: ContactSolver::solve() alone on N isolated contacts
// of one kind (particles resting on the top face of a strip of zones; pairs of particles closing on
// each other), in ns per candidate pair: candidate search (broad phase) included.
//
// Time is the CPU time of the benchmark thread (CLOCK_THREAD_CPUTIME_ID); the wall time is reported
// beside it (equal on an idle machine).
//
//   build/benchmarks/particles --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "krug/contact/contact.hpp"
#include "krug/contact/kernels.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/solver/simulation.hpp"
#include "timing.hpp"

namespace {

using krug::Index;
using krug::Particles;
using krug::Simulation;
using krug::Vec2;
using krug::bench::time_it;
using krug::bench::Timing;

constexpr double radius = 0.25e-3;        // m
constexpr double density = 2785.0;        // kg/m^3 (planar: mass per metre = density x pi r^2)
constexpr double area_fraction = 0.3;
constexpr double max_speed = 10.0;        // m/s
constexpr int warm_up = 60;
constexpr int window = 20;


double particle_mass() { return density * std::numbers::pi * radius * radius; }

// --- particles in a closed box ---------------------------------------------------------------------

krug::contact::RigidWall wall(Vec2 point, Vec2 normal) {
  krug::contact::RigidWall w;
  w.point = point;
  w.normal = normal;
  return w;
}

// N particles (rounded up to a square lattice) in a box, advanced `warm_up` steps.
std::unique_ptr<Simulation> box(long count) {
  const long per_side = static_cast<long>(std::ceil(std::sqrt(static_cast<double>(count))));
  const double spacing = radius * std::sqrt(std::numbers::pi / area_fraction);
  const double side = static_cast<double>(per_side) * spacing;
  krug::SimulationSetup setup;
  setup.geometry = krug::GeometryKind::planar;
  setup.controls.end_time = 1.0;
  setup.contact.particles = true;
  setup.contact.walls = {wall({0.0, 0.0}, {1.0, 0.0}), wall({side, 0.0}, {-1.0, 0.0}), wall({0.0, 0.0}, {0.0, 1.0}),
                         wall({0.0, side}, {0.0, -1.0})};
  auto sim = std::make_unique<Simulation>(setup);

  krug::SimulationState state = sim->state();
  std::mt19937_64 random(20261122);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double jitter = 0.5 * (spacing - 2.0 * radius);
  for (long k = 0; k < per_side * per_side; ++k) {
    const double x = (static_cast<double>(k % per_side) + 0.5) * spacing + jitter * (2.0 * unit(random) - 1.0);
    const double y = (static_cast<double>(k / per_side) + 0.5) * spacing + jitter * (2.0 * unit(random) - 1.0);
    const double speed = max_speed * unit(random), angle = 2.0 * std::numbers::pi * unit(random);
    state.particles.add({x, y}, {speed * std::cos(angle), speed * std::sin(angle)}, particle_mass(), radius, 0, 0.0);
  }
  sim->restore(std::move(state));
  for (int k = 0; k < warm_up; ++k) sim->step();
  return sim;
}

const Simulation& box_checkpoint(long count) {
  static std::map<long, std::unique_ptr<Simulation>> cache;
  auto found = cache.find(count);
  if (found == cache.end()) found = cache.emplace(count, box(count)).first;
  return *found->second;
}

void box_step(benchmark::State& state) {
  const long count = state.range(0);
  Timing total;
  double particle_steps = 0.0, candidates = 0.0, active = 0.0, sweeps = 0.0, steps = 0.0;
  long particles = 0;
  try {
    const Simulation& start = box_checkpoint(count);
    particles = start.particles().size();
    std::unique_ptr<Simulation> sim;
    int since_reset = window;
    for (auto _ : state) {
      if (since_reset == window) {
        sim = std::make_unique<Simulation>(start);  // not timed
        since_reset = 0;
      }
      const Timing t = time_it([&] { sim->step(); });
      ++since_reset;
      benchmark::DoNotOptimize(sim->particles().x.data());
      benchmark::ClobberMemory();
      state.SetIterationTime(1e-9 * t.cpu_ns);
      total += t;
      particle_steps += static_cast<double>(particles);
      candidates += static_cast<double>(sim->last_contact().candidates);
      active += static_cast<double>(sim->last_contact().active);
      sweeps += sim->last_contact().sweeps;
      steps += 1.0;
    }
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  state.counters["ns_per_particle_step"] = total.cpu_ns / particle_steps;
  state.counters["wall_ns_per_particle_step"] = total.wall_ns / particle_steps;
  state.counters["ns_per_candidate"] = total.cpu_ns / candidates;
  state.counters["particles"] = static_cast<double>(particles);
  state.counters["candidates_per_particle"] = candidates / particle_steps;
  state.counters["active_per_particle"] = active / particle_steps;
  state.counters["sweeps"] = sweeps / steps;
  state.SetItemsProcessed(static_cast<std::int64_t>(particle_steps));
}

// --- the narrow-phase kernels alone ----------------------------------------------------------------

// One Gauss-Seidel update of a candidate (ContactSolver::update without friction): the reaction that
// closes the predicted gap, clamped, and the velocity changes it makes.
struct Point {
  std::vector<double> x, y, u, v, inverse_mass;
  void add(Vec2 position, Vec2 velocity, double w) {
    x.push_back(position.x);
    y.push_back(position.y);
    u.push_back(velocity.x);
    v.push_back(velocity.y);
    inverse_mass.push_back(w);
  }
  Vec2 predicted(std::size_t i, double dt) const { return {x[i] + dt * u[i], y[i] + dt * v[i]}; }
  void push(std::size_t i, Vec2 direction, double impulse) {
    u[i] += impulse * direction.x * inverse_mass[i];
    v[i] += impulse * direction.y * inverse_mass[i];
  }
};

constexpr std::size_t kernel_pairs = 4096;
constexpr double kernel_dt = 1e-6;

// Particle i against the segment (2i, 2i+1) of `nodes`: a segment of length 2 r in a random direction,
// the particle beside or over it (along -0.3 .. 1.3), its centre 0.5 r to 1.5 r from the line, moving
// towards it.
void kernel_particle_segment(benchmark::State& state) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Point particles, nodes;
  const double node_inverse_mass = 1.0 / (4.0 * particle_mass());
  for (std::size_t k = 0; k < kernel_pairs; ++k) {
    const double angle = 2.0 * std::numbers::pi * unit(random);
    const Vec2 tangent{std::cos(angle), std::sin(angle)}, normal{tangent.y, -tangent.x};
    const Vec2 a{unit(random), unit(random)};
    const Vec2 b = a + 2.0 * radius * tangent;
    const double along = -0.3 + 1.6 * unit(random), height = radius * (0.5 + unit(random));
    nodes.add(a, {}, node_inverse_mass);
    nodes.add(b, {}, node_inverse_mass);
    particles.add(a + 2.0 * radius * along * tangent + height * normal, -(10.0 * unit(random)) * normal, 1.0 / particle_mass());
  }
  std::vector<double> accumulated(kernel_pairs, 0.0);
  Timing total;
  double pairs = 0.0;
  for (auto _ : state) {
    const Timing t = time_it([&] {
      for (std::size_t k = 0; k < kernel_pairs; ++k) {
        const krug::contact::DiscContact c = krug::contact::disc_segment_contact(
            particles.predicted(k, kernel_dt), nodes.predicted(2 * k, kernel_dt), nodes.predicted(2 * k + 1, kernel_dt), radius);
        const double wc = particles.inverse_mass[k], wa = nodes.inverse_mass[2 * k], wb = nodes.inverse_mass[2 * k + 1];
        const double w = krug::contact::contact_inverse_mass(c.normal, c.xi, {wc, wc}, {wa, wa}, {wb, wb});
        const double total_normal = krug::contact::clamp_normal(accumulated[k], -c.gap / (kernel_dt * kernel_dt * w));
        const double change = kernel_dt * (total_normal - accumulated[k]);
        accumulated[k] = total_normal;
        particles.push(k, c.normal, change);
        nodes.push(2 * k, c.normal, -(1.0 - c.xi) * change);
        nodes.push(2 * k + 1, c.normal, -c.xi * change);
      }
    });
    benchmark::DoNotOptimize(particles.u.data());
    benchmark::ClobberMemory();
    state.SetIterationTime(1e-9 * t.cpu_ns);
    total += t;
    pairs += static_cast<double>(kernel_pairs);
  }
  state.counters["ns_per_pair"] = total.cpu_ns / pairs;
  state.counters["wall_ns_per_pair"] = total.wall_ns / pairs;
  state.SetItemsProcessed(static_cast<std::int64_t>(pairs));
}

// Particles 2i and 2i+1: centres 1.5 r to 2.5 r apart in a random direction, closing.
void kernel_particle_particle(benchmark::State& state) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Point particles;
  for (std::size_t k = 0; k < kernel_pairs; ++k) {
    const double angle = 2.0 * std::numbers::pi * unit(random);
    const Vec2 direction{std::cos(angle), std::sin(angle)};
    const Vec2 a{unit(random), unit(random)};
    const double distance = radius * (1.5 + unit(random)), speed = 10.0 * unit(random);
    particles.add(a, speed * direction, 1.0 / particle_mass());
    particles.add(a + distance * direction, -speed * direction, 1.0 / particle_mass());
  }
  std::vector<double> accumulated(kernel_pairs, 0.0);
  Timing total;
  double pairs = 0.0;
  for (auto _ : state) {
    const Timing t = time_it([&] {
      for (std::size_t k = 0; k < kernel_pairs; ++k) {
        const krug::contact::DiscContact c = krug::contact::disc_disc_contact(
            particles.predicted(2 * k, kernel_dt), radius, particles.predicted(2 * k + 1, kernel_dt), radius);
        const double wc = particles.inverse_mass[2 * k], wo = particles.inverse_mass[2 * k + 1];
        const double w = krug::contact::contact_inverse_mass(c.normal, 0.0, {wc, wc}, {wo, wo}, {});
        const double total_normal = krug::contact::clamp_normal(accumulated[k], -c.gap / (kernel_dt * kernel_dt * w));
        const double change = kernel_dt * (total_normal - accumulated[k]);
        accumulated[k] = total_normal;
        particles.push(2 * k, c.normal, change);
        particles.push(2 * k + 1, c.normal, -change);
      }
    });
    benchmark::DoNotOptimize(particles.u.data());
    benchmark::ClobberMemory();
    state.SetIterationTime(1e-9 * t.cpu_ns);
    total += t;
    pairs += static_cast<double>(kernel_pairs);
  }
  state.counters["ns_per_pair"] = total.cpu_ns / pairs;
  state.counters["wall_ns_per_pair"] = total.wall_ns / pairs;
  state.SetItemsProcessed(static_cast<std::int64_t>(pairs));
}

// --- ContactSolver::solve on isolated contacts of one kind ---------------------------------------

// Times solve() on `particles` (velocities reset before each call, not timed).
void time_solve(benchmark::State& state, krug::contact::ContactSolver& solver, krug::Mesh& mesh, Particles& particles) {
  const std::vector<double> u = particles.u, v = particles.v;
  const std::vector<double> node_u = mesh.nodes.u, node_v = mesh.nodes.v;
  Timing total;
  double candidates = 0.0, active = 0.0, sweeps = 0.0, calls = 0.0;
  for (auto _ : state) {
    particles.u = u;
    particles.v = v;
    mesh.nodes.u = node_u;
    mesh.nodes.v = node_v;
    krug::contact::ContactStatistics stats;
    const Timing t = time_it([&] { stats = solver.solve(krug::contact::nodes_view(mesh.nodes), krug::contact::particles_view(particles), kernel_dt, kernel_dt); });
    benchmark::DoNotOptimize(particles.u.data());
    benchmark::ClobberMemory();
    state.SetIterationTime(1e-9 * t.cpu_ns);
    total += t;
    candidates += static_cast<double>(stats.candidates);
    active += static_cast<double>(stats.active);
    sweeps += stats.sweeps;
    calls += 1.0;
  }
  state.counters["ns_per_candidate"] = total.cpu_ns / candidates;
  state.counters["wall_ns_per_candidate"] = total.wall_ns / candidates;
  state.counters["candidates"] = candidates / calls;
  state.counters["active"] = active / calls;
  state.counters["sweeps"] = sweeps / calls;
  state.SetItemsProcessed(static_cast<std::int64_t>(candidates));
}

// N particles, each over the middle of one top segment (length 2 r) of a strip of N zones 2 r x 2 r,
// 0.01 r from touching and closing at 5 m/s (within the step: every contact is active).
void solve_particle_segment(benchmark::State& state) {
  const long count = state.range(0);
  krug::Mesh mesh;
  const double length = 2.0 * radius * static_cast<double>(count);
  const krug::generate::Patch strip = krug::generate::rectangle(
      mesh, krug::generate::graded_axis(0.0, {{length, static_cast<int>(count), 1.0}}),
      krug::generate::graded_axis(-2.0 * radius, {{0.0, 1, 1.0}}), 0);
  for (Index n = 0; n < mesh.nodes.size(); ++n) {
    mesh.nodes.mass[n] = particle_mass();
    mesh.nodes.inv_mass_x[n] = mesh.nodes.inv_mass_y[n] = 1.0 / particle_mass();
  }
  Particles particles;
  for (long k = 0; k < count; ++k) {
    particles.add({(2.0 * static_cast<double>(k) + 1.0) * radius, 1.01 * radius}, {0.0, -5.0}, particle_mass(), radius, 0, 0.0);
  }
  krug::contact::ContactSetup setup;
  setup.particles = true;
  krug::contact::ContactSolver solver(setup, mesh, {{strip.zone_begin, strip.zone_end}});
  time_solve(state, solver, mesh, particles);
}

// N particles in pairs 2.01 r apart, closing at 5 m/s each; pairs 6 r apart.
void solve_particle_particle(benchmark::State& state) {
  const long count = state.range(0);
  krug::Mesh mesh;
  Particles particles;
  const long per_side = static_cast<long>(std::ceil(std::sqrt(static_cast<double>(count / 2))));
  for (long k = 0; k < count / 2; ++k) {
    const Vec2 centre{6.0 * radius * static_cast<double>(k % per_side), 6.0 * radius * static_cast<double>(k / per_side)};
    particles.add(centre, {5.0, 0.0}, particle_mass(), radius, 0, 0.0);
    particles.add(centre + Vec2{2.01 * radius, 0.0}, {-5.0, 0.0}, particle_mass(), radius, 0, 0.0);
  }
  krug::contact::ContactSetup setup;
  setup.particles = true;
  krug::contact::ContactSolver solver(setup, mesh, {});
  time_solve(state, solver, mesh, particles);
}

}  // namespace

int main(int argc, char** argv) {
  // Whole windows of steps (20 windows at 1e3 particles, 2 at 1e4, 1 at 1e5), so that every
  // repetition times the same steps.
  for (const auto& [count, windows] : {std::pair{1000L, 20L}, std::pair{10000L, 2L}, std::pair{100000L, 1L}}) {
    benchmark::RegisterBenchmark(fmt::format("box/{}", count).c_str(), box_step)
        ->Arg(count)
        ->Iterations(windows * window)
        ->UseManualTime()
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark("kernel/particle_segment", kernel_particle_segment)->UseManualTime()->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("kernel/particle_particle", kernel_particle_particle)->UseManualTime()->Unit(benchmark::kMicrosecond);
  for (long count : {1000L, 100000L}) {
    benchmark::RegisterBenchmark(fmt::format("solve/particle_segment/{}", count).c_str(), solve_particle_segment)
        ->Arg(count)
        ->UseManualTime()
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(fmt::format("solve/particle_particle/{}", count).c_str(), solve_particle_particle)
        ->Arg(count)
        ->UseManualTime()
        ->Unit(benchmark::kMicrosecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
