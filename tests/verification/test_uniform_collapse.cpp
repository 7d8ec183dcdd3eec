// Uniform collapse (Noh's shock-free variant; verification.md E2) through the library API, in slab,
// cylinder (XY quarter, polar mesh) and sphere (RZ quarter, polar mesh, both axisymmetric forms).
//
// A cold gas (e0 = 0, so p = 0) with the homologous velocity u = -r coasts: a particle starting at
// r0 is at r0 (1 - t) with velocity -r0 = -r/(1 - t), and the density is rho0 (1 - t)^-d (d = 1, 2,
// 3). Nothing in the exact solution produces a force, and the velocity field is linear in space, so
// the limited edge viscosity (Caramana, Shashkov & Whalen 1998) must stay switched off: no viscous
// work, no heating, and the discrete motion is the exact one up to round-off. (The internal energy
// of the cold gas is then itself only artificial heating, so the ledger's viscous and internal
// energies are judged against the kinetic energy, the energy the flow carries.)
#include <catch2/catch.hpp>

#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

namespace {

constexpr double end_time = 0.5;  // the scenarios' end time: rho = 2, 4, 8

// Round-off bounds: the discrete motion of a linear velocity field under zero force is exact, so
// the only errors are round-off in the positions (1e-16 per step, about 120 steps) and in the
// density m/V; viscous work and heating are exactly zero when the limiter returns 1, and 1e-12 of
// the kinetic energy is many orders above round-off yet far below the 3e-5 that an unlimited
// (or wrongly limited) viscosity books here.
constexpr double density_tolerance = 1e-10;
constexpr double velocity_tolerance = 1e-10;
constexpr double heating_tolerance = 1e-12;

void check_collapse(const std::string& problem, int dimension, const Run& run) {
  INFO(problem);
  INFO(run.failure);
  report_failure(problem, run);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const Mesh& mesh = sim.mesh();
  const long zones = mesh.zones.size();
  const double t = sim.time();
  const double exact_density = std::pow(1.0 - t, -dimension);

  double worst_density = 0.0;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    worst_density = std::max(worst_density, std::abs(mesh.zones.density[z] / exact_density - 1.0));
  }
  // Velocities are at t^{n+1/2}, but the exact particle velocity -r0 does not change: compare with
  // -x(t) / (1 - t) at the positions of t^{n+1} (planar slab: x only; else both components).
  double worst_velocity = 0.0;
  for (Index n = 0; n < mesh.nodes.size(); ++n) {
    const Vec2 exact_velocity = (-1.0 / (1.0 - t)) * mesh.nodes.position(n);
    const Vec2 error = mesh.nodes.velocity(n) - (dimension == 1 ? Vec2{exact_velocity.x, 0.0} : exact_velocity);
    worst_velocity = std::max(worst_velocity, norm(error));
  }
  const EnergyLedger& energy = sim.ledger().energy;
  const double viscous_share = energy.viscous / energy.kinetic;
  const double heating_share = energy.internal / energy.kinetic;

  INFO("density " << exact_density << ": worst relative error " << worst_density);
  INFO("velocity: worst error " << worst_velocity);
  INFO("viscous work / kinetic energy " << viscous_share << ", internal / kinetic " << heating_share);
  CHECK(worst_density < density_tolerance);
  CHECK(worst_velocity < velocity_tolerance);
  CHECK(viscous_share < heating_tolerance);
  CHECK(heating_share < heating_tolerance);
  CHECK(sim.ledger().relative_energy_drift() < 1e-12);
  report(problem, "rho at t = 0.5 (worst zone)", format_number("%.0f", exact_density),
         exact_density * (1.0 + worst_density), format_number("%.1e", worst_density), zones, run.seconds);
  report(problem, "viscous work / kinetic energy", "0", viscous_share, "< 1e-12", zones, run.seconds);
  report(problem, "internal energy / kinetic energy", "0", heating_share, "< 1e-12", zones, run.seconds);
}

}  // namespace

TEST_CASE("Uniform collapse of a slab: exact coasting motion, no viscous work", "[uniform_collapse]") {
  check_collapse("Uniform collapse, slab", 1, run_to_end(load_example("uniform_collapse_planar.json")));
}

TEST_CASE("Uniform collapse of a cylinder on a polar mesh: exact coasting motion, no viscous work",
          "[uniform_collapse]") {
  check_collapse("Uniform collapse, cylinder (XY polar)", 2,
                 run_to_end(load_example("uniform_collapse_cylindrical.json")));
}

TEST_CASE("Uniform collapse of a sphere on an RZ polar mesh: exact coasting motion, no viscous work",
          "[uniform_collapse][axisymmetric]") {
  check_collapse("Uniform collapse, sphere (RZ polar, control volume)", 3,
                 run_to_end(load_example("uniform_collapse_spherical.json")));
  scenario::Scenario scenario = load_example("uniform_collapse_spherical.json");
  scenario.setup.controls.axisymmetric_form = AxisymmetricForm::area_weighted;
  check_collapse("Uniform collapse, sphere (RZ polar, area weighted)", 3, run_to_end(scenario));
}

// Subzonal pressures (controls.hourglass.subzonal_pressure) vanish for motion that keeps the corner
// regions' volume ratios, and heat conduction where the energy is uniform: a uniform collapse (a
// scaling about the origin) stays exact with both on.
TEST_CASE("Uniform collapse with subzonal pressures and heat conduction on: still exact", "[uniform_collapse][subzonal]") {
  for (const char* file : {"uniform_collapse_cylindrical.json", "uniform_collapse_spherical.json"}) {
    scenario::Scenario scenario = load_example(file);
    scenario.setup.controls.hourglass.subzonal_pressure = 1.0;
    scenario.setup.controls.viscosity.heat_conduction = 2.0;  // uniform e: nothing to conduct
    const bool spherical = std::string(file) == "uniform_collapse_spherical.json";
    check_collapse(spherical ? "Uniform collapse, sphere (RZ polar), subzonal pressures"
                             : "Uniform collapse, cylinder (XY polar), subzonal pressures",
                   spherical ? 3 : 2, run_to_end(scenario));
  }
}
