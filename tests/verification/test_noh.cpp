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
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;
using namespace krug::verification::noh;

namespace {

void check_noh(const Run& run, const NohCase& c) {
  INFO(c.problem);
  INFO(run.failure);
  report_failure(c.problem, run);
  REQUIRE(run.completed());
  const Body& gas = run.simulation.bodies().front();
  const long zones = gas.zone_end - gas.zone_begin;
  const NohResult r = measure_noh(run, c);

  CHECK(run.simulation.ledger().relative_energy_drift() < 1e-12);  // compatible update, walls at rest
  INFO("shock on the rows: from " << r.shock.smallest << " to " << r.shock.largest << ", worst "
                                  << r.shock.worst_zones << " zones of " << r.shock.zone_size);
  CHECK(r.shock.all_found);
  if (!r.shock.all_found) {
    double peak = 0.0;
    const PatchShape shape = patch_shape(run.simulation.mesh(), gas);
    for (int j = 0; j < shape.zones_j; ++j) {
      peak = std::max(peak, peak_density(row_profile(run.simulation.mesh(), gas, j, c.coordinate)));
    }
    report(c.problem, "shock: density never reaches the mid-level (peak rho)",
           format_number("%.0f", post_shock_density(c.dimension)), peak, "shock not found", zones, run.seconds);
    return;
  }
  CHECK(r.shock.worst_zones < shock_tolerance_zones);
  report(c.problem, "shock r (mean over rows; worst row)", format_number("%.4f", shock_radius), r.shock.mean,
         format_number("%.2f zones", r.shock.worst_zones), zones, run.seconds);
  report(c.problem, "shock r spread over rows", "0", r.shock.spread(),
         format_number("%.2f zones", r.shock.spread() / r.shock.zone_size), zones, run.seconds);

  INFO("plateau: mean " << r.plateau.mean << " over " << r.plateau.zones << " zones, worst zone off by "
                        << r.plateau.largest_deviation);
  REQUIRE(r.plateau.zones > 0);
  CHECK(r.plateau.largest_deviation < plateau_tolerance);
  report(c.problem, "plateau rho on [0.1, shock) (mean; worst zone)",
         format_number("%.0f", post_shock_density(c.dimension)), r.plateau.mean,
         format_number("%.1f %%", 100.0 * r.plateau.largest_deviation), zones, run.seconds);
}

}  // namespace

TEST_CASE("Noh planar: shock position and plateau density", "[noh]") {
  check_noh(run_to_end(load_example("noh_planar.json")), {"Noh, planar", 1, Coordinate::first_axis});
}

TEST_CASE("Noh cylindrical on a polar XY quarter: shock position and plateau density", "[noh]") {
  check_noh(run_to_end(load_example("noh_cylindrical.json")), {"Noh, cylindrical (XY polar)", 2, Coordinate::radius});
}

// 100 x 40 zones (verification.md E2). At 50 x 20 the worst zone of the plateau is 12.6 % low (mean
// 57.6, 10.0 %), at 100 x 40 6.6 % (docs/verification.md, F8: the axis row's viscosity weight).
TEST_CASE("Noh spherical on an RZ equal-angle polar mesh, control-volume form", "[noh][axisymmetric]") {
  check_noh(run_to_end(load_example("noh_spherical.json")),
            {"Noh, spherical (RZ polar, control volume)", 3, Coordinate::radius});
}

// Known failure F4 (docs/verification.md): the area-weighted form now keeps the rows identical, but at
// 100 x 40 its shock runs 2.8 zones ahead and its plateau is 12.8 % low.
TEST_CASE("Noh spherical on an RZ equal-angle polar mesh, area-weighted form", "[noh][axisymmetric][!mayfail]") {
  io::Scenario scenario = load_example("noh_spherical.json");
  scenario.setup.controls.axisymmetric_form = AxisymmetricForm::area_weighted;
  check_noh(run_to_end(scenario), {"Noh, spherical (RZ polar, area weighted)", 3, Coordinate::radius});
}

// Known failure F7 (docs/verification.md): with the default controls and the edge viscosity both forms
// stop near the origin (t = 0.226 and 0.176). With heat conduction and subzonal pressures (opt-in) the
// control-volume run passes every criterion: see the last test case of this file.
TEST_CASE("Noh spherical on a rectangular RZ mesh runs to the end (robustness)", "[noh][axisymmetric][!mayfail]") {
  // verification.md E2: the rectangular mesh only for robustness: it must reach t = 0.6 without
  // tangling or a collapsing time step; its accuracy is not judged.
  for (const AxisymmetricForm form : {AxisymmetricForm::control_volume, AxisymmetricForm::area_weighted}) {
    io::Scenario scenario = load_example("noh_spherical_rectangle.json");
    scenario.setup.controls.axisymmetric_form = form;
    const Run run = run_to_end(scenario);
    const std::string problem = form == AxisymmetricForm::control_volume
                                    ? "Noh, spherical (RZ rectangle, control volume)"
                                    : "Noh, spherical (RZ rectangle, area weighted)";
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
    io::Scenario scenario = load_example("noh_spherical_rectangle.json");
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
    io::Scenario scenario = load_example("noh_planar.json");
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

namespace {

// Densest-front measure on a ray of a rectangular RZ mesh: the largest radius of a zone whose centre lies
// within 2.5 degrees of the ray (4 degrees on the axis and the z = 0 plane) and whose density exceeds 40
// (between the pre-shock 16 and the post-shock 64 of the spherical Noh at t = 0.6).
double noh_shock_on_ray(const Simulation& sim, double degrees) {
  const Mesh& mesh = sim.mesh();
  const double half_width = (degrees <= 0.0 || degrees >= 90.0) ? 4.0 : 2.5;
  double radius = 0.0;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    Vec2 c{};
    for (Index n : mesh.zones.corners[z]) c += 0.25 * mesh.nodes.position(n);
    const double angle = std::atan2(c.y, c.x) * 180.0 / std::numbers::pi;
    if (std::abs(angle - degrees) <= half_width && mesh.zones.density[z] > 40.0) radius = std::max(radius, norm(c));
  }
  return radius;
}

}  // namespace

// F7 cured by subzonal pressures (0.5) and artificial heat conduction (2) together (docs/verification.md,
// F7): the spherical Noh on the RZ rectangle, control-volume form, edge viscosity. Criteria: reaches
// t = 0.6 in at most 3 x the cycles of the scalar-q run on the same mesh; shock (density crossing 40)
// within 2 zones of 0.2 on the rays 0, 15, ..., 90 degrees, spread over the rays <= 2 zones; plateau on
// r in [0.1, r_s - 2h], rays 10-80 degrees: mean within 10 % of 64, worst zone within 20 %; energy 1e-12.
// Measured at 50 x 50: 1 234 cycles (scalar q: 543), shock -0.4 to -0.1 zones, plateau -2.2 % mean,
// 4.6 % worst. At 100 x 100 (not run here, 10 s): 2 878 cycles, shock -0.3 to 0 zones, plateau -2.0 %, 3.3 %.
TEST_CASE("Noh spherical on a rectangular RZ mesh with subzonal pressures and heat conduction", "[noh][axisymmetric][subzonal]") {
  io::Scenario scalar_q = load_example("noh_spherical_rectangle.json");
  scalar_q.setup.controls.viscosity.model = ViscosityModel::scalar;
  const Run reference = run_to_end(scalar_q);
  REQUIRE(reference.completed());

  io::Scenario scenario = load_example("noh_spherical_rectangle.json");
  scenario.setup.controls.hourglass.subzonal_pressure = 0.5;
  scenario.setup.controls.viscosity.heat_conduction = 2.0;
  const Run run = run_to_end(scenario);
  INFO(run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const double h = 1.0 / 50.0;
  const std::string problem = "Noh, spherical (RZ rectangle 50 x 50, subzonal 0.5 + heat 2)";
  CHECK(sim.cycle() <= 3 * reference.simulation.cycle());
  CHECK(sim.ledger().relative_energy_drift() < 1e-12);
  report(problem, "cycles (3 x scalar q at most)", std::to_string(3 * reference.simulation.cycle()),
         static_cast<double>(sim.cycle()), "", sim.mesh().zones.size(), run.seconds);
  double lowest = 1.0, highest = 0.0;
  for (const double ray : {0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0}) {
    const double shock = noh_shock_on_ray(sim, ray);
    INFO("ray " << ray << ": shock at " << shock);
    CHECK(std::abs(shock - shock_radius) <= 2.0 * h);
    lowest = std::min(lowest, shock);
    highest = std::max(highest, shock);
    report(problem, format_number("shock r on the %.0f degree ray", ray), "0.2000", shock,
           format_number("%+.1f zones", (shock - shock_radius) / h), sim.mesh().zones.size(), run.seconds);
  }
  CHECK(highest - lowest <= 2.0 * h);
  // Plateau: zones with centres at r in [0.1, r_s - 2h] on the rays 10-80 degrees.
  double sum = 0.0, worst = 0.0;
  int count = 0;
  for (Index z = 0; z < sim.mesh().zones.size(); ++z) {
    Vec2 c{};
    for (Index n : sim.mesh().zones.corners[z]) c += 0.25 * sim.mesh().nodes.position(n);
    const double angle = std::atan2(c.y, c.x) * 180.0 / std::numbers::pi, r = norm(c);
    if (angle < 10.0 || angle > 80.0 || r < plateau_from || r > shock_radius - 2.0 * h) continue;
    sum += sim.mesh().zones.density[z];
    worst = std::max(worst, std::abs(sim.mesh().zones.density[z] / 64.0 - 1.0));
    ++count;
  }
  REQUIRE(count > 0);
  const double mean = sum / count;
  INFO("plateau: " << count << " zones, mean " << mean << ", worst " << worst);
  CHECK(std::abs(mean / 64.0 - 1.0) < 0.10);
  CHECK(worst < 0.20);
  report(problem, "plateau rho (mean; worst zone)", "64", mean, format_number("worst %.1f %%", 100.0 * worst),
         sim.mesh().zones.size(), run.seconds);
}
