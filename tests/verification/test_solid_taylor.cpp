// E6 of verification.md: the copper Taylor bar (axisymmetric), examples/verification/taylor_bar.json
// through the library API, and the hard case at twice the speed (taylor_bar_454.json). The bar
// stands on a slip plane (its impact face, u_z = 0, as in the references) and a rigid contact wall
// at z = 0 stops the side nodes that roll onto it. The refinement study and the Richardson estimate
// of the converged length and face radius (compared with 21.43 / 7.23 mm) are in convergence_solid.cpp.
#include <catch2/catch.hpp>

#include <cmath>

#include "test_solid_measures.hpp"

using namespace krug;
using namespace krug::verification;
using namespace krug::verification::solid;

namespace {

// Smallest zone area over the body (m^2): positive for an untangled mesh.
double smallest_area(const Mesh& mesh, const Body& body) {
  double smallest = std::numeric_limits<double>::infinity();
  for (Index z = body.zone_begin; z < body.zone_end; ++z) {
    if (mesh.zones.active[z]) smallest = std::min(smallest, quad::area(mesh.corner_positions(z)));
  }
  return smallest;
}

double lowest_node(const Mesh& mesh, const Body& body) {
  double lowest = std::numeric_limits<double>::infinity();
  for (Index p = body.node_begin; p < body.node_end; ++p) lowest = std::min(lowest, mesh.nodes.x[p]);
  return lowest;
}

}  // namespace

TEST_CASE("E6 Taylor bar with the physical hourglass stiffness", "[E6][strength][axisymmetric][physical]") {
  scenario::Scenario scenario = load_example("taylor_bar.json");
  scenario.setup.controls.hourglass.stiffness_form = HourglassStiffness::physical;
  Run run(scenario.setup);
  const TaylorMeasures m = advance_taylor(run);
  const Simulation& sim = run.simulation;
  const Body& bar = sim.bodies().front();
  const long zones = bar.zone_end - bar.zone_begin;
  INFO("length " << 1e3 * m.length << " mm, impact-face radius " << 1e3 * m.face_radius << " mm; hourglass "
                 << sim.ledger().energy.hourglass << " J, plastic " << sim.ledger().energy.plastic << " J; " << sim.cycle()
                 << " cycles");
  // The band of verification.md E6, as in the next test (converged references 21.42-21.43 / 7.22-7.23 mm).
  CHECK(m.length > 21.2e-3);
  CHECK(m.length < 21.7e-3);
  CHECK(m.face_radius > 6.95e-3);
  CHECK(m.face_radius < 7.45e-3);
  CHECK(sim.ledger().relative_energy_drift() < 1e-12);
  report("E6 Taylor bar, physical hourglass", "length at 80 us (mm)", "21.42-21.43", 1e3 * m.length,
         format_number("%+.2f mm", 1e3 * m.length - 21.43), zones, run.seconds);
  report("E6 Taylor bar, physical hourglass", "impact-face radius at 80 us (mm)", "7.22-7.23", 1e3 * m.face_radius,
         format_number("%+.2f mm", 1e3 * m.face_radius - 7.23), zones, run.seconds);
}

TEST_CASE("E6 Taylor bar at 227 m/s: length and impact-face radius at 80 us", "[E6][strength][axisymmetric]") {
  const scenario::Scenario scenario = load_example("taylor_bar.json");
  Run run(scenario.setup);
  const TaylorMeasures m = advance_taylor(run);
  const Simulation& sim = run.simulation;
  const Body& bar = sim.bodies().front();
  const long zones = bar.zone_end - bar.zone_begin;
  INFO("length " << 1e3 * m.length << " mm, impact-face radius " << 1e3 * m.face_radius << " mm at " << sim.time()
                 << " s; " << zones << " zones, " << sim.cycle() << " cycles, " << run.seconds << " s");
  // verification.md E6: a one-point quadrilateral code with hourglass control at modest resolution
  // should land within [21.2, 21.7] mm and [6.95, 7.45] mm (converged references 21.42-21.43 and
  // 7.22-7.23 mm; Krug's own refinement study extrapolates to 21.42 and 7.21 mm, docs/verification.md).
  CHECK(m.length > 21.2e-3);
  CHECK(m.length < 21.7e-3);
  CHECK(m.face_radius > 6.95e-3);
  CHECK(m.face_radius < 7.45e-3);
  report("E6 Taylor bar", "length at 80 us (mm)", "21.42-21.43", 1e3 * m.length,
         format_number("%+.2f mm", 1e3 * m.length - 21.43), zones, run.seconds);
  report("E6 Taylor bar", "impact-face radius at 80 us (mm)", "7.22-7.23", 1e3 * m.face_radius,
         format_number("%+.2f mm", 1e3 * m.face_radius - 7.23), zones, run.seconds);

  const Ledger& ledger = sim.ledger();
  CHECK(ledger.relative_mass_error() == 0.0);
  // Total energy with the contact and slip-plane work booked (docs/theory.md §3): round-off.
  CHECK(ledger.relative_energy_drift() < 1e-12);
  // Nearly all the kinetic energy went into plastic work; the rest is viscous and hourglass work
  // (measured at 60 x 8: 95 %, 4 % and 1 %) and the elastic ringing left in the bar.
  CHECK(ledger.energy.plastic > 0.9 * ledger.initial_total_energy);
  // Nothing below the wall: no node deeper than 1e-3 of a 0.2 mm zone (the contact leaves no
  // measurable penetration, as in E1).
  CHECK(lowest_node(sim.mesh(), bar) > -1e-3 * 0.2e-3);
}

TEST_CASE("E6 Taylor bar at twice the speed (454 m/s) runs to the end or stops with a diagnostic",
          "[E6][strength][axisymmetric][robustness]") {
  // The bar flattens to under a third of its length: the impact-face zones become thin pancakes and
  // side nodes may roll onto the wall. Either the run reaches 80 us with a sound state, or it stops with a
  // NumericalFailure that names the body, the zone and the time. Anything else (another exception, a
  // crash, a NaN in the state) fails the test.
  const scenario::Scenario scenario = load_example("taylor_bar_454.json");
  Run run(scenario.setup);
  const Body& bar = run.simulation.bodies().front();
  const std::vector<Index> face = impact_face_nodes(run.simulation.mesh(), bar);
  advance(run);
  const Simulation& sim = run.simulation;
  const TaylorMeasures m = taylor_measures(sim.mesh(), bar, face);
  INFO("outcome: " << (run.completed() ? "completed" : run.failure) << "; t = " << sim.time() << " s, "
                   << sim.cycle() << " cycles, " << run.seconds << " s; length " << 1e3 * m.length << " mm, face radius "
                   << 1e3 * m.face_radius << " mm");
  if (run.completed()) {
    CHECK(sim.time() == Approx(scenario.setup.controls.end_time).epsilon(1e-12));
    CHECK(std::isfinite(m.length));
    CHECK(std::isfinite(m.face_radius));
    CHECK(smallest_area(sim.mesh(), bar) > 0.0);
    CHECK(sim.ledger().relative_mass_error() == 0.0);
    CHECK(sim.ledger().relative_energy_drift() < 1e-10);
    CHECK(lowest_node(sim.mesh(), bar) > -1e-3 * 0.5e-3);  // 1e-3 of a zone (0.53 mm)
    // It flattened much further than the 227 m/s bar (a length well below 21 mm, a face radius well
    // above 7.5 mm: measured 9.7 and 13.7 mm).
    CHECK(m.length < 0.018);
    CHECK(m.face_radius > 0.009);
    report("E6 Taylor bar 454 m/s", "outcome", "end or diagnostic", 1e3 * m.length, "completed; length (mm)",
           bar.zone_end - bar.zone_begin, run.seconds);
  } else {
    CHECK(run.failure.find("body 'bar'") != std::string::npos);
    CHECK(run.failure.find("zone") != std::string::npos);
    CHECK(run.failure.find("t = ") != std::string::npos);
    report("E6 Taylor bar 454 m/s", "outcome", "end or diagnostic", sim.time(), "diagnostic at t (s)",
           bar.zone_end - bar.zone_begin, run.seconds);
  }
}

TEST_CASE("E6 hard case with rezoning: the Lagrangian run's length and face radius in under a third of its cycles",
          "[E6][strength][axisymmetric][rezone]") {
  // taylor_bar_454_rezone.json is taylor_bar_454.json (40 x 6) with the bar rezoned where its zones
  // flatten below half their initial altitude. The criterion: rezoning must not be the dominant error,
  // so it moves each measure by less than half of what refining the Lagrangian mesh to 60 x 8 moves it:
  // 0.48 mm of length and 0.89 mm of face radius (the study of docs/verification.md, E6: 9.30 -> 8.82
  // mm and 13.38 -> 14.27 mm). The cycles it saves are the reason to use it.
  Run lagrangian(load_example("taylor_bar_454.json").setup);
  const TaylorMeasures l = advance_taylor(lagrangian);
  Run rezoned(load_example("taylor_bar_454_rezone.json").setup);
  const TaylorMeasures r = advance_taylor(rezoned);
  const Simulation& sim = rezoned.simulation;
  INFO("Lagrangian: " << lagrangian.simulation.cycle() << " cycles, length " << 1e3 * l.length << " mm, face radius "
                      << 1e3 * l.face_radius << " mm; rezoned: " << sim.cycle() << " cycles, " << 1e3 * r.length
                      << " mm, " << 1e3 * r.face_radius << " mm; rezone line " << sim.ledger().energy.rezone << " J/rad");
  CHECK(std::abs(r.length - l.length) < 0.5 * 0.48e-3);
  CHECK(std::abs(r.face_radius - l.face_radius) < 0.5 * 0.89e-3);
  CHECK(3 * sim.cycle() < lagrangian.simulation.cycle());
  // The books close with the remap's transfers in them, and the remap turned some kinetic energy into heat.
  CHECK(sim.ledger().relative_mass_error() < 1e-14);
  CHECK(sim.ledger().relative_energy_drift() < 1e-12);
  CHECK(sim.ledger().energy.rezone > 0.0);
  CHECK(sim.ledger().energy.rezone < 0.01 * sim.ledger().initial_total_energy);
  CHECK(smallest_area(sim.mesh(), sim.bodies().front()) > 0.0);
  report("E6 Taylor bar 454 m/s, rezoned", "length (mm) against the Lagrangian run", format_number("%.2f", 1e3 * l.length),
         1e3 * r.length, format_number("%.2f mm", 1e3 * std::abs(r.length - l.length)),
         sim.bodies().front().zone_end - sim.bodies().front().zone_begin, rezoned.seconds);
}
