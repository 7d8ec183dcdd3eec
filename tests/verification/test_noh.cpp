// Noh implosion (Noh 1987; verification.md E2) through the library API: planar (strip against a
// wall), cylindrical (XY quarter, polar mesh), spherical (RZ quarter, equal-angle polar mesh, both
// axisymmetric forms) and the spherical problem on a rectangular RZ mesh as a robustness run.
//
// Exact solution at t = 0.6 (tests/data/exact/noh_*_t0.6.csv): shock at r = t/3 = 0.2; behind it
// rho = 4, 16, 64 (planar, cylindrical, spherical), at rest, e = 0.5; ahead of it
// rho = (1 + t/r)^(k-1), i.e. 1, 4, 16 just outside r = 0.2.
//
// Judged as verification.md asks: the shock position within 2 local zone sizes on every row (ray),
// and the plateau density within 10 % on r in [0.1, 0.2], away from the wall-heating dip at the
// centre. The plateau window stops 2 zones inside the measured shock on each row, since those zones
// belong to the smeared front that the position criterion already judges.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "noh_measures.hpp"
#include "rz_rectangle_blasts.hpp"
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;
using namespace krug::verification::noh;


TEST_CASE("Noh planar: shock position and plateau density", "[noh]") {
  check_noh(run_to_end(load_example("noh_planar.json")), {"Noh, planar", 1, Coordinate::first_axis});
}

TEST_CASE("Noh cylindrical on a polar XY quarter: shock position and plateau density", "[noh]") {
  check_noh(run_to_end(load_example("noh_cylindrical.json")), {"Noh, cylindrical (XY polar)", 2, Coordinate::radius});
}

// 100 x 40 zones (verification.md E2), default controls: the tensor viscosity with the corner-collapse
// pressure 1 in this gas, which holds open the axis row's zone that the tensor viscosity alone lets
// collapse onto the axis (docs/verification.md F7). Within three times the cycles of the edge viscosity
// (`viscosity.model` "edge": 9 724 cycles, shock 1.0 zone out, plateau mean 60.65, worst zone 6.6 %).
// Measured: 15 287 cycles, shock 0.2028-0.2030, plateau mean 60.45, worst zone 7.6 % low.
TEST_CASE("Noh spherical on an RZ equal-angle polar mesh, control-volume form", "[noh][axisymmetric]") {
  scenario::Scenario scenario = load_example("noh_spherical.json");
  scenario.setup.controls.max_cycles = 3 * 9'724;
  check_noh(run_to_end(scenario), {"Noh, spherical (RZ polar, control volume)", 3, Coordinate::radius});
}

// Known failure F4 (docs/verification.md): the area-weighted form now keeps the rows identical, but at
// 100 x 40 its shock runs 2.9 zones ahead and its plateau is 13.1 % low (default controls).
TEST_CASE("Noh spherical on an RZ equal-angle polar mesh, area-weighted form", "[noh][axisymmetric][!mayfail]") {
  scenario::Scenario scenario = load_example("noh_spherical.json");
  scenario.setup.controls.axisymmetric_form = AxisymmetricForm::area_weighted;
  check_noh(run_to_end(scenario), {"Noh, spherical (RZ polar, area weighted)", 3, Coordinate::radius});
}

// F7 (docs/verification.md) with default controls: the gas takes the tensor viscosity with the
// corner-collapse pressure 1 (`viscosity.model` "auto"). Criteria of rz_rectangle_blasts.hpp: t = 0.6 in at
// most 3 x the scalar-q run's cycles; shock within 2 zones of 0.2 on the rays 0, 15, ..., 90 degrees,
// spread <= 2 zones; plateau mean within 10 % of 64, worst zone within 20 %; energy 1e-12. Measured at
// 50 x 50: 397 cycles (scalar q 483), shock +0.2 to +0.3 zones, spread 0.13, plateau -8.3 %, worst 11.9 %.
// The area-weighted form with the same controls is judged for robustness only (verification.md E2: it
// must reach t = 0.6; measured: it does).
TEST_CASE("Noh spherical on a rectangular RZ mesh with default controls", "[noh][axisymmetric]") {
  const long scalar_q_cycles = rz_rectangle::noh_scalar_q_cycles(50);
  REQUIRE(scalar_q_cycles > 0);
  rz_rectangle::check_noh(load_example("noh_spherical_rectangle.json"), 50, scalar_q_cycles,
                          "Noh, spherical (RZ rectangle 50 x 50, default controls)");
  scenario::Scenario area_weighted = load_example("noh_spherical_rectangle.json");
  area_weighted.setup.controls.axisymmetric_form = AxisymmetricForm::area_weighted;
  const Run run = run_to_end(area_weighted);
  INFO(run.failure);
  CHECK(run.completed());
  report("Noh, spherical (RZ rectangle, area weighted)", "reaches t = 0.6", "0.6", run.simulation.time(),
         run.completed() ? "completed" : "FAILED", run.simulation.bodies().front().zone_end, run.seconds);
}

// Known failure F7 (docs/verification.md): with the edge viscosity (`viscosity.model` "edge") both forms
// stop near the origin (t = 0.226 and 0.176), a bow-tied zone at the origin corner.
TEST_CASE("Noh spherical on a rectangular RZ mesh runs to the end (robustness) with the edge viscosity",
          "[noh][axisymmetric][!mayfail]") {
  // verification.md E2: the rectangular mesh only for robustness: it must reach t = 0.6 without
  // tangling or a collapsing time step; its accuracy is not judged.
  for (const AxisymmetricForm form : {AxisymmetricForm::control_volume, AxisymmetricForm::area_weighted}) {
    scenario::Scenario scenario = load_example("noh_spherical_rectangle.json");
    scenario.setup.controls.viscosity.model = ViscosityModel::edge;
    scenario.setup.controls.axisymmetric_form = form;
    const Run run = run_to_end(scenario);
    const std::string problem = form == AxisymmetricForm::control_volume
                                    ? "Noh, spherical (RZ rectangle, control volume, edge viscosity)"
                                    : "Noh, spherical (RZ rectangle, area weighted, edge viscosity)";
    INFO(problem << ": " << run.failure);
    CHECK(run.completed());
    report(problem, "reaches t = 0.6", "0.6", run.simulation.time(), run.completed() ? "completed" : "FAILED",
           run.simulation.bodies().front().zone_end, run.seconds);
  }
}

// F7's workaround, measured: with Wilkins' scalar q (controls.viscosity.model = "scalar") both forms
// reach the end (verification.md E2: robustness only, accuracy not judged).
TEST_CASE("Noh spherical on a rectangular RZ mesh runs to the end with the scalar viscosity", "[noh][axisymmetric]") {
  for (const AxisymmetricForm form : {AxisymmetricForm::control_volume, AxisymmetricForm::area_weighted}) {
    scenario::Scenario scenario = load_example("noh_spherical_rectangle.json");
    scenario.setup.controls.viscosity.model = ViscosityModel::scalar;
    scenario.setup.controls.axisymmetric_form = form;
    const Run run = run_to_end(scenario);
    const bool compatible = form == AxisymmetricForm::control_volume;
    const std::string problem = compatible ? "Noh, spherical (RZ rectangle, control volume, scalar q)"
                                           : "Noh, spherical (RZ rectangle, area weighted, scalar q)";
    INFO(problem << ": " << run.failure);
    CHECK(run.completed());
    if (compatible) CHECK(run.simulation.ledger().relative_energy_drift() < 1e-12);  // compatible update
    report(problem, "reaches t = 0.6", "0.6", run.simulation.time(), run.completed() ? "completed" : "FAILED",
           run.simulation.bodies().front().zone_end, run.seconds);
  }
}

// The ledger's viscous line books the artificial viscosity's dissipation with either model. The
// irreversible heating of a shock is fixed by its jump conditions, not by the damper that spreads it,
// so the planar Noh's two models must book nearly the same viscous work (an independent figure for each
// other); both are part of the internal energy, which pressure work also raises in a compression.
// Measured: edge 0.007806 J, scalar 0.007880 J of internal 0.01198 J (0.9 % apart).
TEST_CASE("Noh planar: the edge and the scalar viscosity book the same viscous work", "[noh][ledger]") {
  std::vector<double> viscous;
  for (const ViscosityModel model : {ViscosityModel::edge, ViscosityModel::scalar}) {
    scenario::Scenario scenario = load_example("noh_planar.json");
    scenario.setup.controls.viscosity.model = model;
    const Run run = run_to_end(scenario);
    REQUIRE(run.completed());
    const EnergyLedger& e = run.simulation.ledger().energy;
    CHECK(e.viscous > 0.0);
    CHECK(e.viscous < e.internal);
    CHECK(run.simulation.ledger().relative_energy_drift() < 1e-12);
    viscous.push_back(e.viscous);
  }
  CHECK(std::abs(viscous[1] - viscous[0]) < 0.05 * viscous[0]);
}


// F7 cured by subzonal pressures (0.5) and artificial heat conduction (2) together (docs/verification.md,
// F7): the spherical Noh on the RZ rectangle, control-volume form, edge viscosity. Criteria: reaches
// t = 0.6 in at most 3 x the cycles of the scalar-q run on the same mesh; shock (density crossing 40)
// within 2 zones of 0.2 on the rays 0, 15, ..., 90 degrees, spread over the rays <= 2 zones; plateau on
// r in [0.1, r_s - 2h], rays 10-80 degrees: mean within 10 % of 64, worst zone within 20 %; energy 1e-12.
// Measured at 50 x 50: 1 048 cycles (scalar q: 483), shock -0.4 to -0.1 zones, plateau -2.2 % mean,
// 4.6 % worst. 100 x 100 is in convergence_hard_cases.cpp.
TEST_CASE("Noh spherical on a rectangular RZ mesh with subzonal pressures and heat conduction", "[noh][axisymmetric][subzonal]") {
  const long scalar_q_cycles = rz_rectangle::noh_scalar_q_cycles(50);
  REQUIRE(scalar_q_cycles > 0);

  scenario::Scenario scenario = load_example("noh_spherical_rectangle.json");
  scenario.setup.controls.viscosity.model = ViscosityModel::edge;  // the default gives this gas the tensor viscosity
  scenario.setup.controls.hourglass.subzonal_pressure = 0.5;
  scenario.setup.controls.viscosity.heat_conduction = 2.0;
  rz_rectangle::check_noh(scenario, 50, scalar_q_cycles, "Noh, spherical (RZ rectangle 50 x 50, subzonal 0.5 + heat 2)");
}
