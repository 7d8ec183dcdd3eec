// The copper Taylor bar of examples/verification/taylor_bar.json (L0 32.4 mm, R0 3.2 mm, 227 m/s onto a
// rigid wall) with its material replaced by the library's "ofhc-copper" (Mie–Grüneisen, Johnson–Cook
// strength of annealed OFHC copper, Johnson & Cook 1983). The example's own copper is an idealised
// work-hardened copper (Y0 400 MPa, linear hardening) whose converged final length, 21.42 mm, is a
// numerical reference, not a test of OFHC copper; the library's copper is not meant to match it.
// No published final length of an OFHC copper bar of this geometry and speed is used here: the run
// checks the ledgers and reports the length (docs/materials.md gives the measured figure).
// Under the `convergence` label: about 12 s of one core.
#include <catch2/catch.hpp>

#include <string>

#include "test_solid_measures.hpp"

using namespace krug;
using namespace krug::verification;
using namespace krug::verification::solid;

TEST_CASE("Taylor bar at 227 m/s with the library's OFHC copper: ledgers and the final length",
          "[taylor_library][strength][axisymmetric]") {
  std::string text = read_text(example_path("taylor_bar.json"));
  const std::string from = "\"copper\": {";
  const auto begin = text.find(from);
  REQUIRE(begin != std::string::npos);
  const auto end = text.find("}\n    }", begin);  // the closing of the strength block, then of the material
  REQUIRE(end != std::string::npos);
  text.replace(begin, end + 7 - begin, "\"copper\": \"ofhc-copper\"");
  const io::Scenario scenario = io::parse_scenario(text, "taylor_bar.json with ofhc-copper");
  Run run(scenario.setup);
  const Body& bar = run.simulation.bodies().front();
  const std::vector<Index> face = impact_face_nodes(run.simulation.mesh(), bar);
  advance(run);
  INFO(run.failure);
  REQUIRE(run.completed());
  const TaylorMeasures m = taylor_measures(run.simulation.mesh(), bar, face);
  const long zones = bar.zone_end - bar.zone_begin;
  WARN("ofhc-copper Taylor bar: length " << 1e3 * m.length << " mm, impact-face radius " << 1e3 * m.face_radius
                                         << " mm at 80 us; " << run.simulation.cycle() << " cycles, " << run.seconds
                                         << " s");
  report("Taylor bar, library ofhc-copper", "length at 80 us (mm)", "none published for this geometry", 1e3 * m.length,
         "-", zones, run.seconds);
  const Ledger& ledger = run.simulation.ledger();
  CHECK(ledger.relative_mass_error() == 0.0);
  CHECK(ledger.relative_energy_drift() < 1e-12);
  // Only what holds whatever the law: shorter than it started, and not flattened to a quarter (Taylor's
  // (1948) rigid-plastic estimate L/L0 = exp(-rho U^2 / (2 Y)) gives 0.56 L0 for Y = 400 MPa, the flow
  // stress the law reaches at a plastic strain near 0.5 and 1e4 /s). Measured: 19.10 mm, face radius 7.14 mm
  // (68 x 12 zones).
  CHECK(m.length < 32.4e-3);
  CHECK(m.length > 0.25 * 32.4e-3);
}
