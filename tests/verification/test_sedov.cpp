// Sedov blast wave (Sedov 1959; verification.md E2) through the library API: planar (half space on
// a strip), cylindrical (XY quarter, polar mesh) and spherical (RZ quarter, polar mesh, both
// axisymmetric forms). Gamma 1.4, rho0 = 1, p0 = 0; at t = 1 the shock stands at 0.5 / 0.75 / 1.0
// for blast energies 0.0673185 per unit area (half space) / 0.311357 per unit length / 0.851072
// (tests/data/exact/sedov_*_t1.csv; Kamm & Timmes 2007).
//
// Judged as verification.md asks: the shock position on every row (ray) and total energy, which a
// compatible scheme conserves to round-off; not the peak density ratio 6, which modest resolution
// cannot reach. The shock on a row is where density crosses half-way between the undisturbed 1 and
// the row's own peak (the half-height of the numerical front), so the measure does not depend on
// how far the peak falls short of 6.
#include <catch2/catch.hpp>

#include <numbers>

#include "rz_rectangle_blasts.hpp"
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

namespace {

// Shock within 2 local zone sizes (the spacing of the zone centres around the crossing) of the
// exact radius, as for Noh (verification.md E2): a captured front spans about 3 zones and a
// half-height crossing sits within one zone of its centre. Measured values in docs/verification.md.
constexpr double shock_tolerance_zones = 2.0;
// Energy: compatible update, no boundary work (symmetry planes, free outer boundary the shock never
// reaches). About 1e3 to 1e4 steps with 1e-16 relative increments: 1e-12 is round-off.
constexpr double energy_drift_tolerance = 1e-12;

struct SedovCase {
  const char* problem;
  Coordinate coordinate;
  double shock_radius;   // exact, t = 1
  double model_energy;   // energy in the modelled region, per unit thickness or per radian
};

void check_sedov(const Run& run, const SedovCase& c) {
  INFO(c.problem);
  INFO(run.failure);
  report_failure(c.problem, run);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const Body& gas = sim.bodies().front();
  const long zones = gas.zone_end - gas.zone_begin;

  // The deposit convention of the scenario (energy_deposit: per unit thickness planar, whole body
  // in RZ) must give the model energy of the exact solution; 1e-12 of the background e0 = 1e-12 is
  // also in the total, far below this bound.
  CHECK(std::abs(sim.ledger().initial_total_energy / c.model_energy - 1.0) < 1e-9);
  const double drift = sim.ledger().relative_energy_drift();
  CHECK(drift < energy_drift_tolerance);
  report(c.problem, "total energy drift", "0 (round-off)", drift, "< 1e-12", zones, run.seconds);

  const ShockSurvey shock = survey_shock(sim, gas, c.coordinate, c.shock_radius,
                                         [](const std::vector<ZoneSample>& row) { return 0.5 * (1.0 + peak_density(row)); });
  INFO("shock on the rows: from " << shock.smallest << " to " << shock.largest << ", worst " << shock.worst_zones
                                  << " zones of " << shock.zone_size);
  CHECK(shock.all_found);
  CHECK(shock.worst_zones < shock_tolerance_zones);
  report(c.problem, "shock r (mean over rows; worst row)", format_number("%.3f", c.shock_radius), shock.mean,
         format_number("%.2f zones", shock.worst_zones), zones, run.seconds);
  report(c.problem, "shock r spread over rows", "0", shock.spread(),
         format_number("%.2f zones", shock.spread() / shock.zone_size), zones, run.seconds);
}

// Energies of the modelled regions (verification.md E2 and the scenario descriptions).
constexpr double planar_energy = 0.0673185 * 0.02;           // per unit area x the strip's height 0.02
constexpr double cylindrical_energy = 0.311357 / 4.0;        // XY quarter, per unit length
const double spherical_energy = 0.851072 / (4.0 * std::numbers::pi);  // RZ quarter (hemisphere), per radian

}  // namespace

TEST_CASE("Sedov planar: shock position and total energy", "[sedov]") {
  check_sedov(run_to_end(load_example("sedov_planar.json")),
              {"Sedov, planar", Coordinate::first_axis, 0.5, planar_energy});
}

TEST_CASE("Sedov cylindrical on a polar XY quarter: shock position and total energy", "[sedov]") {
  check_sedov(run_to_end(load_example("sedov_cylindrical.json")),
              {"Sedov, cylindrical (XY polar)", Coordinate::radius, 0.75, cylindrical_energy});
}

TEST_CASE("Sedov spherical on an RZ polar quarter, control-volume form", "[sedov][axisymmetric]") {
  check_sedov(run_to_end(load_example("sedov_spherical.json")),
              {"Sedov, spherical (RZ polar, control volume)", Coordinate::radius, 1.0, spherical_energy});
}

// The same with the tensor viscosity and subzonal pressures at shocks (hourglass.subzonal_pressure 2,
// subzonal_at_shocks; test_tensor_viscosity.cpp, docs/verification.md F7). Measured: shock 1.0016,
// spread 0.18 zones, energy to 2e-16 (the edge viscosity's 1.0014).
TEST_CASE("Sedov spherical on an RZ polar quarter, tensor viscosity with subzonal pressures at shocks",
          "[sedov][axisymmetric][tensor][subzonal]") {
  scenario::Scenario scenario = load_example("sedov_spherical.json");
  rz_rectangle::use_tensor_with_subzonal_at_shocks(scenario);
  check_sedov(run_to_end(scenario), {"Sedov, spherical (RZ polar, tensor q, subzonal 2 at shocks)", Coordinate::radius,
                                     1.0, spherical_energy});
}

// Known failure F4 (docs/verification.md): symmetric, but gains 7.1 % energy and its shock is 4.2 zones out
// (default controls).
TEST_CASE("Sedov spherical on an RZ polar quarter, area-weighted form", "[sedov][axisymmetric][!mayfail]") {
  scenario::Scenario scenario = load_example("sedov_spherical.json");
  scenario.setup.controls.axisymmetric_form = AxisymmetricForm::area_weighted;
  check_sedov(run_to_end(scenario),
              {"Sedov, spherical (RZ polar, area weighted)", Coordinate::radius, 1.0, spherical_energy});
}


// F7 (docs/verification.md) with default controls (the gas takes the tensor viscosity with the
// corner-collapse pressure 1): the spherical Sedov on the RZ rectangle reaches t = 1 with the shock within
// 2 zones of 1.0 on every ray, the axis ray included (rz_rectangle_blasts.hpp). Measured at 50 x 50: 441
// cycles, shock -0.6 to -0.1 zones.
TEST_CASE("Sedov spherical on a rectangular RZ mesh with default controls: shock on every ray", "[sedov][axisymmetric]") {
  rz_rectangle::check_sedov(load_example("sedov_spherical_rectangle.json"), 50,
                            "Sedov, spherical (RZ rectangle 50 x 50, default controls)", true);
}

// F7 (docs/verification.md): on a rectangular RZ mesh the spherical Sedov stops near the axis with the
// edge viscosity (`viscosity.model` "edge"; the default gives this gas the tensor viscosity with the
// corner-collapse pressure, which passes: test_tensor_viscosity.cpp). Subzonal pressures (Caramana &
// Shashkov 1998) let the edge-viscosity run reach t = 1, with the shock within a zone of 1.0 on the rays
// from 15 to 90 degrees, but the axis row jets outwards (measured: the densest axis zone at r = 1.107 on
// 50 x 50, 1.195 on 100 x 100, with k = 0.5): a cure for the tangle, not for the axis. The shock on the
// axis ray is reported, not asserted.
TEST_CASE("Sedov spherical on a rectangular RZ mesh reaches t = 1 with the edge viscosity and subzonal pressures",
          "[sedov][axisymmetric][subzonal]") {
  scenario::Scenario scenario = load_example("sedov_spherical_rectangle.json");
  scenario.setup.controls.viscosity.model = ViscosityModel::edge;
  {
    const Run run = run_to_end(scenario);
    report("Sedov, spherical (RZ rectangle 50 x 50), edge viscosity", "reaches t = 1", "1", run.simulation.time(),
           run.completed() ? "completed" : "stops (F7)", run.simulation.mesh().zones.size(), run.seconds);
  }
  scenario.setup.controls.hourglass.subzonal_pressure = 0.5;
  rz_rectangle::check_sedov(scenario, 50, "Sedov, spherical (RZ rectangle 50 x 50), edge viscosity, subzonal 0.5", false);
}

// F7 cured by the two options together: subzonal pressures 0.5 and artificial heat conduction 2
// (docs/verification.md, F7). Measured: 50 x 50 reaches t = 1 in 329 cycles, shock +0.2 to +1.3 zones
// on every ray, the axis ray included; finer meshes in convergence_hard_cases.cpp.
TEST_CASE("Sedov spherical on a rectangular RZ mesh with subzonal pressures and heat conduction: shock on every ray",
          "[sedov][axisymmetric][subzonal]") {
  scenario::Scenario scenario = load_example("sedov_spherical_rectangle.json");
  scenario.setup.controls.viscosity.model = ViscosityModel::edge;  // the default gives this gas the tensor viscosity
  scenario.setup.controls.hourglass.subzonal_pressure = 0.5;
  scenario.setup.controls.viscosity.heat_conduction = 2.0;
  rz_rectangle::check_sedov(scenario, 50, "Sedov, spherical (RZ rectangle 50 x 50), subzonal 0.5 + heat 2", true);
}
