// Per-zone kernels of the strength and fracture steps, in ns per zone (docs/performance.md, "The paper's
// case"): arrays of 4096 zones' worth of inputs, no mesh loop around them.
//
// rotation/polynomial, rotation/library: the objective rotation of a deviator by a small angle
// (krug::rotate_deviator: cos and sin of the double angle by their Taylor polynomials, krug::cos_sin)
// against the same rotation with std::cos and std::sin. Angles up to 1e-3 rad, as over one time step.
//
// stretches/exact, stretches/bound: the principal stretches of a quad from its initial shape
// (krug::fracture::zone_stretches) against the root-free test that they are below a limit
// (krug::fracture::stretches_below), on a mesh of 64 x 64 RZ zones sheared by up to 5 %;
// stretches/bound_cached: the same test with the zones' initial shapes computed once
// (krug::fracture::initial_shapes, as the Simulation keeps them).
//
// zone_update/copper_rz/200x200: step 5 of the time step alone (krug::update_zones, the batched zone
// update: geometry, compatible energy, deviator, EOS, stable step) on the 40 000 zones of the copper
// cylinder (benchmarks/problems.hpp) after 50 cycles, in the solver's blocks of zones. The zone and
// strength state is restored from a copy every 16 calls (untimed), so every call starts from nearby states.
//
// corner_forces/copper_rz/200x200, corner_forces/sedov_rz/200x200: step 1 of the time step alone
// (krug::body_corner_forces, the batched force kernel: geometry, stress, edge viscosity with its shared
// limiters, hourglass, the corner forces stored) on the 40 000 zones of the copper cylinder after 50
// cycles and of the spherical Sedov blast after 100, one thread. Besides the corner forces and the
// viscous speeds, which the next call overwrites, a call adds to the copper's stiffness hourglass state;
// the zone state is restored from a copy every 16 calls (untimed), as in zone_update.
// corner_forces/noh_rz_edge/200x200, corner_forces/noh_rz_tensor/200x200: the same kernel on the
// spherical Noh implosion (benchmarks/problems.hpp) after 20 cycles, when every zone ahead of the shock
// compresses: with the edge viscosity, and with the tensor viscosity and subzonal pressures at shocks
// (controls.viscosity.model "tensor", hourglass.subzonal_pressure 2, hourglass.subzonal_at_shocks),
// which also writes its damping rows for the time step.
//
//   build/benchmarks/zone_kernels --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "krug/fracture/damage.hpp"
#include "krug/hydro/zone_update.hpp"
#include "krug/material/strength.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/quad.hpp"
#include "krug/solver/hydro_step.hpp"
#include "krug/solver/parallel.hpp"
#include "problems.hpp"

namespace {

constexpr int zone_count = 4096;

std::vector<krug::Deviator> deviators() {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> stress(-1e8, 1e8);
  std::vector<krug::Deviator> s(zone_count);
  for (krug::Deviator& d : s) {
    d.xx = stress(random);
    d.yy = stress(random);
    d.xy = stress(random);
    d.zz = -(d.xx + d.yy);
  }
  return s;
}

std::vector<double> angles() {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> angle(-1e-3, 1e-3);
  std::vector<double> a(zone_count);
  for (double& x : a) x = angle(random);
  return a;
}

krug::Deviator rotate_with_library(const krug::Deviator& s, double angle) {
  const double mean = 0.5 * (s.xx + s.yy);
  const double half_difference = 0.5 * (s.xx - s.yy);
  const double cos2 = std::cos(2.0 * angle);
  const double sin2 = std::sin(2.0 * angle);
  const double axial = half_difference * cos2 - s.xy * sin2;
  return {mean + axial, mean - axial, half_difference * sin2 + s.xy * cos2, s.zz};
}

template <bool polynomial>
void rotation(benchmark::State& state) {
  const std::vector<krug::Deviator> s = deviators();
  const std::vector<double> a = angles();
  std::vector<krug::Deviator> out(zone_count);
  for (auto _ : state) {
    for (int z = 0; z < zone_count; ++z) {
      out[z] = polynomial ? krug::rotate_deviator(s[z], a[z]) : rotate_with_library(s[z], a[z]);
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.counters["ns_per_zone"] =
      benchmark::Counter(static_cast<double>(zone_count), benchmark::Counter::kIsIterationInvariantRate |
                                                              benchmark::Counter::kInvert);
}

krug::Mesh sheared_mesh() {
  krug::Mesh mesh;
  std::vector<double> lines(65);
  for (int i = 0; i <= 64; ++i) lines[static_cast<std::size_t>(i)] = 0.01 * i / 64.0;
  krug::generate::rectangle(mesh, lines, lines, 0);
  mesh.nodes.x0 = mesh.nodes.x;
  mesh.nodes.y0 = mesh.nodes.y;
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> shear(0.0, 0.05);
  for (krug::Index n = 0; n < mesh.nodes.size(); ++n) mesh.nodes.x[n] += shear(random) * mesh.nodes.y[n];
  for (krug::Index z = 0; z < mesh.zones.size(); ++z) {
    const krug::quad::Corners x = mesh.corner_positions(z);
    mesh.zones.area[z] = krug::quad::area(x);
    mesh.zones.volume[z] = krug::quad::axisymmetric_volume(x);
  }
  return mesh;
}

enum class StretchTest { exact, bound, bound_cached };

template <StretchTest test>
void stretches(benchmark::State& state) {
  const krug::Mesh mesh = sheared_mesh();
  const krug::Index zones = mesh.zones.size();
  const std::vector<krug::fracture::InitialShape> shapes = krug::fracture::initial_shapes(mesh);
  for (auto _ : state) {
    double sum = 0.0;
    for (krug::Index z = 0; z < zones; ++z) {
      if constexpr (test == StretchTest::bound) {
        sum += krug::fracture::stretches_below(mesh, z, true, 1.4) ? 1.0 : 0.0;
      } else if constexpr (test == StretchTest::bound_cached) {
        sum += krug::fracture::stretches_below(mesh, z, true, 1.4, shapes[static_cast<std::size_t>(z)]) ? 1.0 : 0.0;
      } else {
        sum += krug::fracture::zone_stretches(mesh, z, true).largest();
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["ns_per_zone"] = benchmark::Counter(static_cast<double>(zones), benchmark::Counter::kIsIterationInvariantRate |
                                                                                     benchmark::Counter::kInvert);
}

}  // namespace

void zone_update(benchmark::State& state) {
  krug::Simulation sim(krug::problems::copper_cylinder_rz(200));
  for (int cycle = 0; cycle < 50; ++cycle) sim.step();
  const krug::Mesh start_mesh = sim.mesh();
  const krug::ZoneState start_state = sim.zone_state();
  krug::Mesh mesh = start_mesh;
  krug::ZoneState zones = start_state;
  const krug::Material& material = sim.materials().front();
  const auto eos = std::get<krug::MieGruneisen>(material.eos);
  const auto strength = std::get<krug::LinearHardening>(material.strength);
  krug::ZoneUpdateParams params;
  params.time_step_mid = 0.5 * (sim.last_time_step() + sim.next_time_step());
  params.time_step_next = sim.next_time_step();
  params.shear_modulus = material.shear_modulus();
  const krug::Index count = mesh.zones.size();
  int calls = 0;
  double sum = 0.0;
  for (auto _ : state) {
    if (++calls % 16 == 0) {
      state.PauseTiming();
      mesh = start_mesh;
      zones = start_state;
      state.ResumeTiming();
    }
    // In the solver's blocks (krug/solver/parallel.hpp), each small enough to stay in the caches.
    krug::for_each_block(0, count, 1, [&](krug::Index, krug::Index first, krug::Index last) {
      const krug::ZoneUpdateResult r = krug::update_zones<krug::GeometryKind::axisymmetric>(
          mesh, zones.hydro, zones.strength, zones.fracture, first, last, eos, strength, params);
      sum += r.internal_energy;
    });
  }
  benchmark::DoNotOptimize(sum);
  state.counters["ns_per_zone"] = benchmark::Counter(static_cast<double>(count) * static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

enum class ForceProblem { copper, sedov, noh_edge, noh_tensor };

// The gas problems name their viscosity model (the default, "auto", gives an RZ gas the tensor viscosity).
krug::SimulationSetup force_problem(ForceProblem problem) {
  auto with_edge_viscosity = [](krug::SimulationSetup setup) {
    setup.controls.viscosity.model = krug::ViscosityModel::edge;
    return setup;
  };
  switch (problem) {
    case ForceProblem::copper: return krug::problems::copper_cylinder_rz(200);
    case ForceProblem::sedov: return with_edge_viscosity(krug::problems::sedov_axisymmetric(200));
    case ForceProblem::noh_edge: return with_edge_viscosity(krug::problems::noh_axisymmetric(200));
    case ForceProblem::noh_tensor: break;
  }
  krug::SimulationSetup setup = krug::problems::noh_axisymmetric(200);
  setup.controls.viscosity.model = krug::ViscosityModel::tensor;
  setup.controls.hourglass.subzonal_pressure = 2.0;
  setup.controls.hourglass.subzonal_at_shocks = true;
  return setup;
}

template <ForceProblem problem>
void corner_forces(benchmark::State& state) {
  krug::Simulation sim(force_problem(problem));
  const int cycles = problem == ForceProblem::copper ? 50 : problem == ForceProblem::sedov ? 100 : 20;
  for (int cycle = 0; cycle < cycles; ++cycle) sim.step();
  const krug::Mesh& mesh = sim.mesh();
  const krug::ZoneState start_state = sim.zone_state();
  krug::ZoneState zones = start_state;
  const krug::Body& body = sim.bodies().front();
  const krug::Material& material = sim.materials()[static_cast<std::size_t>(body.material)];
  const krug::ZoneForceParams params = krug::zone_force_params(material, sim.controls(), sim.geometry(), sim.last_time_step());
  const std::vector<krug::Index> mirror = krug::mirrored_edge_slots(mesh);
  std::vector<double> limiters(mirror.size(), 0.0);
  const krug::SharedEdgeLimiters shared{mirror.data(), limiters.data()};
  // The tensor viscosity's damping rows, which the time step reads in a run.
  const bool tensor = problem == ForceProblem::noh_tensor;
  std::vector<double> damping_rows(tensor ? 4 * static_cast<std::size_t>(mesh.zones.size()) : 0, 0.0);
  std::vector<double> damping_scale(tensor ? mesh.nodes.size() : 0, 0.0);
  if (tensor) krug::damping_node_scale(mesh.nodes, 0, mesh.nodes.size(), damping_scale.data());
  const krug::DampingRows damping = tensor ? krug::DampingRows{damping_scale.data(), damping_rows.data()} : krug::DampingRows{};
  double sum = 0.0;
  int calls = 0;
  for (auto _ : state) {
    if (++calls % 16 == 0) {
      state.PauseTiming();
      zones = start_state;
      state.ResumeTiming();
    }
    const krug::ArtificialPower power =
        krug::body_corner_forces(mesh, zones, body, krug::GeometryKind::axisymmetric, params, 1, {}, shared,
                                 damping);
    sum += power.viscous + power.hourglass;
  }
  benchmark::DoNotOptimize(sum);
  state.counters["ns_per_zone"] =
      benchmark::Counter(static_cast<double>(mesh.zones.size()) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK(rotation<true>)->Name("rotation/polynomial");
BENCHMARK(rotation<false>)->Name("rotation/library");
BENCHMARK(stretches<StretchTest::exact>)->Name("stretches/exact");
BENCHMARK(stretches<StretchTest::bound>)->Name("stretches/bound");
BENCHMARK(stretches<StretchTest::bound_cached>)->Name("stretches/bound_cached");
BENCHMARK(zone_update)->Name("zone_update/copper_rz/200x200")->Unit(benchmark::kMicrosecond);
BENCHMARK(corner_forces<ForceProblem::copper>)->Name("corner_forces/copper_rz/200x200")->Unit(benchmark::kMicrosecond);
BENCHMARK(corner_forces<ForceProblem::sedov>)->Name("corner_forces/sedov_rz/200x200")->Unit(benchmark::kMicrosecond);
BENCHMARK(corner_forces<ForceProblem::noh_edge>)->Name("corner_forces/noh_rz_edge/200x200")->Unit(benchmark::kMicrosecond);
BENCHMARK(corner_forces<ForceProblem::noh_tensor>)->Name("corner_forces/noh_rz_tensor/200x200")->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
