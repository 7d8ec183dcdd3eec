// The zone and node loops run in fixed blocks of zones shared by threads (solver/parallel.hpp): a run
// must give the same bits on one thread as on several, including the ledger's sums.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <vector>

#include "krug/krug.hpp"
#include "krug/scenario/scenario.hpp"

using namespace krug;

namespace {

// Every node and zone field that the step writes, and the ledger.
std::vector<double> state_of(const Simulation& sim) {
  std::vector<double> out;
  const NodeFields& n = sim.mesh().nodes;
  const ZoneFields& z = sim.mesh().zones;
  const HydroZoneFields& h = sim.zone_state().hydro;
  const StrengthZoneFields& s = sim.zone_state().strength;
  const HourglassZoneFields& q = sim.zone_state().hourglass;
  for (const auto* f : {&n.x, &n.y, &n.u, &n.v, &n.force_x, &n.force_y}) out.insert(out.end(), f->begin(), f->end());
  for (const auto* f : {&z.density, &z.specific_energy, &h.pressure, &h.sound_speed, &z.volume, &s.deviator_xx,
                        &s.deviator_yy, &s.deviator_xy, &s.deviator_zz, &s.plastic_strain, &q.hourglass_x,
                        &q.hourglass_y, &h.corner_force, &h.viscous_speed, &h.stable_time_step}) {
    out.insert(out.end(), f->begin(), f->end());
  }
  const EnergyLedger& e = sim.ledger().energy;
  for (double v : {e.kinetic, e.internal, e.plastic, e.viscous, e.hourglass, sim.ledger().axial_momentum, sim.time()}) {
    out.push_back(v);
  }
  return out;
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// A block with a blast in one corner: 120 x 120 = 14 400 zones, four blocks of 3 600 (block_count),
// shared by the two threads.
SimulationSetup blast(GeometryKind geometry, AxisymmetricForm form, bool strength, int threads) {
  SimulationSetup s;
  s.geometry = geometry;
  const int n = 120;
  auto patch = generate::rectangle(s.mesh, generate::graded_axis(0.0, {{1.0, n, 1.0}}),
                                   generate::graded_axis(0.0, {{1.0, n, 1.0}}), 0);
  Material material{"gas", 1.0, IdealGas{1.4}, NoStrength{}};
  if (strength) material = Material{"solid", 1.0, IdealGas{1.4}, LinearHardening{0.5, 0.02, 0.1}};
  s.materials.push_back(material);
  s.bodies.push_back({"block", 0, patch.node_begin, patch.node_end, patch.zone_begin, patch.zone_end});
  for (Index z = 0; z < s.mesh.zones.size(); ++z) {
    const Vec2 c = quad::centre(s.mesh.corner_positions(z));
    s.mesh.zones.specific_energy[z] = c.x < 0.2 && c.y < 0.2 ? 10.0 : 0.1;
  }
  for (Index node : patch.sides["i_min"]) s.constraints.push_back({node, true, false});
  for (Index node : patch.sides["j_min"]) s.constraints.push_back({node, false, true});
  s.controls.end_time = 1.0;
  s.controls.max_cycles = 60;
  s.controls.axisymmetric_form = form;
  s.controls.threads = threads;
  return s;
}

// The example `file` (under examples/) on one thread and on two, stepped together for `cycles` cycles.
struct ThreadPair {
  Simulation one, two;
};
ThreadPair run_on_one_and_two_threads(const std::filesystem::path& file, int cycles) {
  const scenario::Scenario scenario = scenario::load_scenario(std::filesystem::path(KRUG_EXAMPLES_DIR) / file);
  SimulationSetup one_setup = scenario.setup, two_setup = scenario.setup;
  one_setup.controls.threads = 1;
  two_setup.controls.threads = 2;
  ThreadPair pair{Simulation(std::move(one_setup)), Simulation(std::move(two_setup))};
  for (int cycle = 0; cycle < cycles && !pair.one.finished(); ++cycle) {
    pair.one.step();
    pair.two.step();
  }
  return pair;
}

}  // namespace

TEST_CASE("One thread and two threads give bitwise the same run", "[threads]") {
  struct Case {
    const char* name;
    GeometryKind geometry;
    AxisymmetricForm form;
    bool strength;
  };
  for (const Case& c : {Case{"planar gas", GeometryKind::planar, AxisymmetricForm::control_volume, false},
                        Case{"RZ gas, control volume", GeometryKind::axisymmetric, AxisymmetricForm::control_volume, false},
                        Case{"RZ gas, area weighted", GeometryKind::axisymmetric, AxisymmetricForm::area_weighted, false},
                        Case{"RZ with strength", GeometryKind::axisymmetric, AxisymmetricForm::control_volume, true}}) {
    INFO(c.name);
    Simulation one(blast(c.geometry, c.form, c.strength, 1));
    Simulation two(blast(c.geometry, c.form, c.strength, 2));
    while (!one.finished()) one.step();
    while (!two.finished()) two.step();
    REQUIRE(one.cycle() == 60);
    CHECK(two.cycle() == one.cycle());
    CHECK(bitwise_equal(state_of(one), state_of(two)));
  }
}

// Contact, fracture and free elements on the threads too (the candidate search in fixed chunks, the
// failure laws and the choice of zones to convert in fixed blocks): a striker through a plate, 900
// cycles, by which time zones have failed and converted and particles collide.
TEST_CASE("One thread and two threads give bitwise the same run with contact and fracture", "[threads]") {
  const ThreadPair run = run_on_one_and_two_threads(std::filesystem::path("fracture") / "high_velocity.json", 900);
  const Simulation &one = run.one, &two = run.two;
  REQUIRE(one.cycle() == 900);
  CHECK(two.cycle() == one.cycle());
  // The run did convert zones into particles: the example has 184 particles at its end, cycle 1 838
  // (printed by benchmarks/state_digest); more than 50 by cycle 900 shows that particle contacts are exercised.
  CHECK(one.particles().size() > 50);
  CHECK(bitwise_equal(state_of(one), state_of(two)));
  CHECK(bitwise_equal(one.particles().x, two.particles().x));
  CHECK(bitwise_equal(one.particles().u, two.particles().u));
}

TEST_CASE("One thread and two threads give bitwise the same rezoned run", "[threads][rezone]") {
  // The rezoned 454 m/s Taylor bar (docs/verification.md E6): its remap runs after the threaded zone
  // update, and has moved nodes by cycle 6 000 (the rezone line is positive).
  const ThreadPair run = run_on_one_and_two_threads(std::filesystem::path("verification") / "taylor_bar_454_rezone.json", 6000);
  const Simulation &one = run.one, &two = run.two;
  REQUIRE(one.cycle() == 6000);
  CHECK(one.ledger().energy.rezone > 0.0);
  CHECK(bitwise_equal(state_of(one), state_of(two)));
  CHECK(one.ledger().energy.rezone == two.ledger().energy.rezone);
}

TEST_CASE("One thread and two threads give bitwise the same run with the tensor viscosity's damping bound",
          "[threads][tensor]") {
  // The spherical Noh on the polar verification mesh with the tensor viscosity and subzonal pressures
  // at shocks (docs/verification.md F7): the damping rows are written per zone by the threaded force
  // kernel and gathered per node (Simulation::limit_step_by_damping), and the bound cuts steps from the
  // first cycles on, near the centre.
  const scenario::Scenario scenario =
      scenario::load_scenario(std::filesystem::path(KRUG_EXAMPLES_DIR) / "verification" / "noh_spherical.json");
  SimulationSetup one_setup = scenario.setup;
  one_setup.controls.viscosity.model = ViscosityModel::tensor;
  one_setup.controls.hourglass.subzonal_pressure = 2.0;
  one_setup.controls.hourglass.subzonal_at_shocks = true;
  SimulationSetup two_setup = one_setup;
  one_setup.controls.threads = 1;
  two_setup.controls.threads = 2;
  Simulation one(std::move(one_setup)), two(std::move(two_setup));
  int cut = 0;
  for (int cycle = 0; cycle < 300; ++cycle) {
    one.step();
    two.step();
    cut += one.step_cut_by_damping() ? 1 : 0;
    REQUIRE(two.step_cut_by_damping() == one.step_cut_by_damping());
  }
  CHECK(cut > 0);
  CHECK(bitwise_equal(state_of(one), state_of(two)));
}

TEST_CASE("One thread and two threads give bitwise the same run with viscosity.model \"auto\"", "[threads][tensor]") {
  // A gas under "auto" takes the tensor viscosity with the corner-collapse pressure, whose kernels leave
  // a batch of zones early where none of its zones compresses (tensor_viscosity.hpp) or has a corner
  // region beyond the threshold (artificial_forces.hpp): two threads split the zones into other batches.
  // The spherical Noh (everything compresses, the centre's corners collapse) and Sedov (gas at rest
  // outside the blast) on their polar verification meshes.
  for (const char* file : {"noh_spherical.json", "sedov_spherical.json"}) {
    INFO(file);
    const scenario::Scenario scenario =
        scenario::load_scenario(std::filesystem::path(KRUG_EXAMPLES_DIR) / "verification" / file);
    SimulationSetup one_setup = scenario.setup;
    one_setup.controls.viscosity.model = ViscosityModel::automatic;
    SimulationSetup two_setup = one_setup;
    one_setup.controls.threads = 1;
    two_setup.controls.threads = 2;
    Simulation one(std::move(one_setup)), two(std::move(two_setup));
    for (int cycle = 0; cycle < 200; ++cycle) {
      one.step();
      two.step();
    }
    CHECK(bitwise_equal(state_of(one), state_of(two)));
  }
}
