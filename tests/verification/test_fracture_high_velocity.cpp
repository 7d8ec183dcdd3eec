// E8 of verification.md (fracture and free elements), whole scenario through the library API: a
// hardened-steel striker at 1.5 km/s through a 3 mm 6061-T6 plate (examples/fracture/high_velocity.json).
// Stated constants. Striker (not the paper's; a typical hardened steel): rho 7850 kg/m^3, linear EOS
// K 160 GPa, perfectly plastic mu 80 GPa, Y 1.5 GPa, no fracture; radius 2.5 mm, 10 mm long,
// hemispherical nose, 8 zones across the radius. Plate: 6061-T6 with the paper's constants
// (docs/validation.md: rho0 2700, K 73 GPa, mu 24.6 GPa, Y0 0.28 GPa, elongation eps_* 0.4,
// loosening chi_* 0.03), 12 zones through the thickness, rim r = 25 mm fixed.
//
// Checked: the run reaches its end (12 us) without a numerical failure; mass is exact; axial momentum
// changes only by the impulse of the fixed rim; the energy ledger closes; the striker perforates (it
// is below the plate's rear face, still fast, and the plate has lost zones to particles). The
// interior-conversion count (docs/theory.md §2 step 7, the documented deviation from the paper)
// is reported.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "krug/scenario/scenario.hpp"
#include "krug/krug.hpp"
#include "verification_support.hpp"

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

TEST_CASE("E8 hardened-steel striker at 1.5 km/s through a 6061-T6 plate runs to the end", "[fracture][E8][high_velocity]") {
  const scenario::Scenario scenario =
      scenario::load_scenario(std::filesystem::path(KRUG_EXAMPLES_DIR) / "fracture" / "high_velocity.json");
  verification::Run run(scenario.setup);
  verification::advance(run);
  INFO(run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const Body& striker = sim.bodies()[0];
  const Body& plate = sim.bodies()[1];
  const BodySummary s = sim.summarise(striker);
  const FractureCounts& counts = sim.fracture_counts(1);
  const std::vector<Fragment> pieces = sim.fragments(plate);
  const Ledger& ledger = sim.ledger();
  const double momentum_scale = std::sqrt(2.0 * ledger.max_kinetic * ledger.mass);
  const double momentum_error =
      std::abs(ledger.axial_momentum - ledger.initial_axial_momentum - ledger.axial_boundary_impulse) / momentum_scale;
  const double particle_mass = counts.converted_mass * sim.whole_body_factor();
  // The hole: the smallest radius of a plate zone centre left in the plate, z > -5 mm (the plate is
  // 3 mm thick and dishes by less than 2 mm). Zones torn out with the plug fly ahead of the striker,
  // 17 mm below the plate at 12 us, and are not the plate's (one axis zone, 0.13 mg, did so once the
  // particle-corner start gap was fixed).
  double hole_radius = 1e300;
  for (Index z = plate.zone_begin; z < plate.zone_end; ++z) {
    if (!sim.mesh().zones.active[z]) continue;
    const Vec2 centre = quad::centre(sim.mesh().corner_positions(z));
    if (centre.x > -0.005) hole_radius = std::min(hole_radius, centre.y);
  }
  INFO("cycles " << sim.cycle() << " (" << sim.zone_cycles() << " zone-cycles, " << run.seconds << " s); striker "
                 << s.velocity.x << " m/s, rear of the striker at z = " << s.bbox_max.x << " m; plate: damaged "
                 << counts.damaged << ", converted " << counts.converted << " (interior " << counts.interior_conversions
                 << "), particle mass " << particle_mass << " kg, fragments " << pieces.size() << ", hole radius "
                 << hole_radius << " m; momentum "
                 << momentum_error << ", drift " << ledger.relative_energy_drift() << ", contact "
                 << ledger.energy.contact * sim.whole_body_factor() << " J, overlap "
                 << ledger.energy.overlap * sim.whole_body_factor() << " J, converted "
                 << ledger.energy.converted * sim.whole_body_factor() << " J");
  const long zones = sim.mesh().zones.size();
  report("E8 high velocity", "interior conversions", "-", static_cast<double>(counts.interior_conversions),
         format_number("of %.0f converted", static_cast<double>(counts.converted)), zones, run.seconds);
  report("E8 high velocity", "striker velocity at 12 us (m/s)", "-1500 at impact", s.velocity.x,
         format_number("%.0f plate fragments", static_cast<double>(pieces.size())), zones, run.seconds);
  report("E8 high velocity", "axial momentum - rim impulse, relative", "0", momentum_error, "round-off", zones, run.seconds);
  report("E8 high velocity", "energy drift", "< 1e-12", ledger.relative_energy_drift(), "round-off", zones, run.seconds);

  // Conservation (round-off; measured 6e-16 momentum, 1.6e-15 drift).
  CHECK(ledger.relative_mass_error() < 1e-14);
  CHECK(momentum_error < 1e-12);
  CHECK(ledger.relative_energy_drift() < 1e-12);
  // Contacts that started a step apart only dissipate (docs/theory.md §3): the contact work less the
  // overlap line (the contacts pushing a pre-existing overlap open), to round-off.
  CHECK(ledger.energy.contact - ledger.energy.overlap <= 1e-12 * ledger.energy_scale());
  // Perforation: the whole striker is below the plate's rear face z = -3 mm (its rear starts at
  // z = 10.1 mm and it travels about 17 mm in the 12 us; measured -7.1 mm), still fast (measured
  // -1422 m/s, a loss of 78 m/s; for scale, a striker of 1.41 g taking along all the 0.16 g of plate
  // in its path, perfectly inelastically, would keep 1500 x 1.41 / 1.57 = 1350 m/s; 1000 m/s is a loose
  // bound that only says "perforated, not stopped"), and the plate has a hole wider than the striker
  // (measured: no zone centre left within r = 4.48 mm; 197 zones converted).
  CHECK(s.bbox_max.x < -0.003);
  CHECK(s.velocity.x < -1000.0);
  CHECK(hole_radius > 0.0025);
  CHECK(counts.converted > 0);
}
