// E1 of verification.md: elastic slab impact and separation through the contact reactions
// (examples/verification/slab_impact.json, run through the library API).
#include <catch2/catch.hpp>

#include <cmath>

#include "krug/scenario/scenario.hpp"
#include "krug/krug.hpp"

using namespace krug;

TEST_CASE("E1 slab impact: plateau, peak, separation, momentum and the booked impact loss", "[contact][E1]") {
  scenario::Scenario scenario = scenario::load_scenario(KRUG_EXAMPLES_DIR "/verification/slab_impact.json");
  const contact::ReactionMethod method = GENERATE(contact::ReactionMethod::gauss_seidel, contact::ReactionMethod::summation);
  scenario.setup.contact.controls.method = method;
  Simulation sim(scenario.setup);
  const Body& flyer = sim.bodies()[0];
  const Body& target = sim.bodies()[1];

  // Wilkins aluminium (verification.md E1).
  const double rho0 = 2785.0, bulk = 7.906e10, shear = 2.76e10, impact_speed = 10.0;
  const double wave_speed = std::sqrt((bulk + 4.0 / 3.0 * shear) / rho0);  // c_L = 6449.9 m/s
  const double plateau = -rho0 * wave_speed * impact_speed / 2.0;         // -89.8 MPa
  const double flyer_thickness = 0.005, height = 2.5e-4;
  const int flyer_zones = 20;
  const double zone_transit = flyer_thickness / flyer_zones / wave_speed;
  const double separation_exact = 2.0 * flyer_thickness / wave_speed;      // 1.550 us

  // Probe: the target zone centred nearest x = 2.5 mm; plateau window after the wave has passed it,
  // clear of the front (0.3 us) and before the release from the flyer's rear arrives (2.5 mm + 10 mm path).
  Index probe = target.zone_begin;
  for (Index z = target.zone_begin; z < target.zone_end; ++z) {
    if (std::abs(quad::centre(sim.mesh().corner_positions(z)).x - 0.0025) <
        std::abs(quad::centre(sim.mesh().corner_positions(probe)).x - 0.0025)) probe = z;
  }
  const double arrival = 0.0025 / wave_speed;
  double plateau_sum = 0.0, peak = 0.0, last_loaded = 0.0;
  int plateau_samples = 0;
  while (!sim.finished()) {
    sim.step();
    const ZoneState& zone_state = sim.zone_state();
    const double stress = zone_state.strength.deviator_xx[probe] - zone_state.hydro.pressure[probe];
    peak = std::min(peak, stress);
    if (sim.time() > arrival + 0.3e-6 && sim.time() < arrival + 1.2e-6) {
      plateau_sum += stress;
      ++plateau_samples;
    }
    // Separation: the release from the flyer's rear reaches the interface; measured where the interface
    // force last carries half the plateau stress (a smeared wave's arrival at half amplitude).
    if (sim.last_contact().total_normal / height >= 0.5 * std::abs(plateau)) last_loaded = sim.time();
  }
  const double measured_plateau = plateau_sum / plateau_samples;
  INFO("plateau " << measured_plateau << " Pa, exact " << plateau << " Pa; peak " << peak << " Pa; separation "
                  << last_loaded << " s, exact " << separation_exact << " s");
  CHECK(measured_plateau == Approx(plateau).epsilon(0.005));    // within 0.5 % (verification.md E1)
  CHECK(peak >= 1.05 * plateau);                                // at most 5 % above the plateau
  CHECK(std::abs(last_loaded - separation_exact) <= 3.0 * zone_transit);  // +- 3 zone transit times

  const Ledger& ledger = sim.ledger();
  // Momentum: no boundary acts axially (slip walls hold y only): exact to round-off.
  CHECK(std::abs(ledger.axial_momentum - ledger.initial_axial_momentum) < 1e-12 * ledger.initial_axial_momentum);
  CHECK(ledger.relative_energy_drift() < 1e-12);
  // The velocity-matching contact is perfectly inelastic for the interface nodes: it dissipates about
  // 1/(4 N_f) of the flyer's kinetic energy (verification.md E1); the ledger books it (W_contact < 0).
  const double flyer_kinetic = 0.5 * rho0 * flyer_thickness * height * impact_speed * impact_speed;
  CHECK(ledger.energy.contact < 0.0);
  CHECK(-ledger.energy.contact / flyer_kinetic == Approx(1.0 / (4.0 * flyer_zones)).epsilon(0.10));
  // The flyer stops: its residual velocity is the small one the inelastic impact leaves, and the
  // target carries the momentum (5 m/s square pulse -> mean velocity impact_speed * m_f / m_t).
  const BodySummary f = sim.summarise(flyer), t = sim.summarise(target);
  CHECK(std::abs(f.velocity.x) < 0.01 * impact_speed);
  CHECK(t.velocity.x == Approx(impact_speed * 0.5).epsilon(0.01));
  // Contact never pulls and leaves no measurable penetration (1e-3 of a zone).
  CHECK(sim.deepest_contact_gap() > -1e-3 * flyer_thickness / flyer_zones);
}
