// Kernel-level invariants of the Lagrangian step on small meshes built in code (docs/theory.md §2):
// the compatible corner forces conserve mass, axial momentum and total energy to round-off.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "krug/scenario/scenario.hpp"
#include "krug/krug.hpp"

using namespace krug;

namespace {

Simulation gas_strip(GeometryKind geometry, int nx, int ny, AxisymmetricForm form) {
  SimulationSetup s;
  s.geometry = geometry;
  auto patch = generate::rectangle(s.mesh, generate::graded_axis(0.0, {{1.0, nx, 1.0}}),
                                   generate::graded_axis(0.0, {{0.05 * ny, ny, 1.0}}), 0);
  Material gas{"gas", 1.0, IdealGas{1.4}, NoStrength{}};
  s.materials.push_back(gas);
  s.bodies.push_back({"gas", 0, patch.node_begin, patch.node_end, patch.zone_begin, patch.zone_end});
  for (Index z = 0; z < s.mesh.zones.size(); ++z) {
    const double x = quad::centre(s.mesh.corner_positions(z)).x;
    s.mesh.zones.density[z] = x < 0.5 ? 1.0 : 0.125;
    s.mesh.zones.specific_energy[z] = x < 0.5 ? 2.5 : 2.0;
  }
  for (Index n : patch.sides["i_min"]) s.constraints.push_back({n, true, false});
  for (Index n : patch.sides["i_max"]) s.constraints.push_back({n, true, false});
  s.controls.end_time = 0.2;
  s.controls.axisymmetric_form = form;
  return Simulation(std::move(s));
}

}  // namespace

TEST_CASE("Sod-like strip conserves mass and total energy to round-off", "[conservation]") {
  const auto [geometry, form] = GENERATE(std::pair{GeometryKind::planar, AxisymmetricForm::control_volume},
                                         std::pair{GeometryKind::axisymmetric, AxisymmetricForm::control_volume},
                                         std::pair{GeometryKind::axisymmetric, AxisymmetricForm::area_weighted});
  Simulation sim = gas_strip(geometry, 60, 4, form);
  while (!sim.finished()) sim.step();
  CHECK(sim.ledger().relative_mass_error() < 1e-14);
  // The area-weighted RZ form is only approximately conservative (docs/theory.md §2 step 1): its
  // accelerations are Wilkins' and its internal energy is each zone's own p dV, so the books do not
  // close exactly; that form is checked in the next test case.
  if (form == AxisymmetricForm::area_weighted) return;
  // Compatible scheme: energy exact up to accumulated round-off (~1e-16 per operation, 1e2-1e3 steps).
  CHECK(sim.ledger().relative_energy_drift() < 1e-12);
  // Walls at both ends: the axial momentum changes only by the walls' impulse.
  const double scale = sim.ledger().max_kinetic > 0 ? std::sqrt(2.0 * sim.ledger().max_kinetic * sim.ledger().mass) : 1.0;
  CHECK(std::abs(sim.ledger().axial_momentum - sim.ledger().initial_axial_momentum -
                 sim.ledger().axial_boundary_impulse) < 1e-12 * scale);
}

TEST_CASE("Area-weighted RZ form: its energy error converges away with the mesh", "[conservation]") {
  // The area-weighted accelerations and the control-volume work differ by O(dr) per zone where the flow
  // is not axial (here the free outer surface). Measured drift at 60 x 4, 120 x 8, 240 x 16: 4.2e-2,
  // 1.3e-2, 3.8e-3 (orders 1.6 and 1.8). Asserted: at least first order at each refinement, so a
  // drift that stopped shrinking (an inconsistency, not a discretisation error) fails.
  std::vector<double> drift;
  for (int refinement : {1, 2, 4}) {
    Simulation sim = gas_strip(GeometryKind::axisymmetric, 60 * refinement, 4 * refinement, AxisymmetricForm::area_weighted);
    while (!sim.finished()) sim.step();
    drift.push_back(sim.ledger().relative_energy_drift());
  }
  INFO("drift " << drift[0] << ", " << drift[1] << ", " << drift[2]);
  CHECK(std::log2(drift[0] / drift[1]) > 1.0);
  CHECK(std::log2(drift[1] / drift[2]) > 1.0);
}

TEST_CASE("a run that fails part-way through a step keeps its ledger closed", "[conservation]") {
  // An aluminium disc whose far face is driven at 2000 m/s towards its own fixed near face (which
  // rests 1 um above a second, fixed plate of a contact pair), CFL 0.9: its zones tangle at cycle 880
  // (0.50 us), inside update_zones, after the step's boundary work was booked. Before the ledger went
  // back to the last completed cycle on failure, a failed state's summary drifted (4.6e-4 of its
  // energy scale was measured on a failing run of this kind).
  const std::string text = R"({
    "geometry": "axisymmetric", "end_time": 2e-5, "controls": { "cfl": 0.9 },
    "materials": { "al": { "density": 2700.0, "eos": { "model": "linear", "bulk_modulus": 7.3e10 },
                           "strength": { "model": "perfectly_plastic", "shear_modulus": 2.46e10, "yield_stress": 2.8e8 } } },
    "bodies": [
      { "name": "top", "material": "al",
        "mesh": { "type": "rectangle", "z": { "from": 1e-6, "to": 0.001, "zones": 5 }, "r": { "from": 0.0, "to": 0.005, "zones": 10 } },
        "boundary": { "z_min": "fixed", "z_max": { "type": "velocity", "velocity": [-2000.0, null] } } },
      { "name": "bottom", "material": "al",
        "mesh": { "type": "rectangle", "z": { "from": -0.001, "to": 0.0, "zones": 5 }, "r": { "from": 0.0, "to": 0.005, "zones": 10 } },
        "boundary": { "z_max": "fixed" } } ],
    "contact": { "pairs": [ { "bodies": ["top", "bottom"] } ] }
  })";
  Simulation sim(scenario::parse_scenario(text, "test.json").setup);
  bool failed = false;
  try {
    while (!sim.finished()) sim.step();
  } catch (const NumericalFailure&) {
    failed = true;
  }
  REQUIRE(failed);
  const Ledger& ledger = sim.state().ledger;
  CHECK(ledger.relative_energy_drift() < 1e-12);
  CHECK(ledger.energy_closed());
  CHECK(std::abs(ledger.initial_axial_momentum + ledger.axial_boundary_impulse - ledger.axial_momentum) <
        1e-12 * std::abs(ledger.axial_boundary_impulse));
}
