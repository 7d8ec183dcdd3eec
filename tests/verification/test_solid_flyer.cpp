// E4 of verification.md: the Wilkins aluminium flyer plate at 800 m/s onto aluminium,
// examples/verification/flyer_plate.json through the library API. Equal plates are symmetric about
// their interface, which moves at 400 m/s; the scenario works in the interface's frame, so the plate
// moves at -400 m/s onto a slip plane at x = 0 and every velocity below is shifted by +400 m/s into
// the target's frame of the reference values (test_solid_measures.hpp). A front at distance d from
// the plane moves at U - 400 in this frame.
#include <catch2/catch.hpp>

#include <cmath>

#include "test_solid_measures.hpp"

using namespace krug;
using namespace krug::verification;
using namespace krug::verification::solid;

namespace {

constexpr double plate_thickness = 0.02;  // m (flyer_plate.json)
constexpr int plate_zones = 800;          // dx = 25 um
constexpr double frame_speed = flyer::interface_speed;

struct Fronts {
  double elastic = 0.0, plastic = 0.0;  // distance from the plane (m)
};

Fronts locate_fronts(const Simulation& sim) {
  const std::vector<StripZone> strip = strip_profile(sim, sim.bodies()[0]);
  const double ahead = -frame_speed, precursor = flyer::elastic.velocity - frame_speed;
  return {velocity_front(strip, 0.5 * (ahead + precursor)), velocity_front(strip, 0.5 * precursor)};
}

// History of one zone through the release.
struct Probe {
  Index zone = 0;
  std::vector<double> deviator_xx, plastic_strain, density;
};

}  // namespace

TEST_CASE("E4 Wilkins flyer plate: HEL precursor, plastic state, fronts and the elastic swing on release",
          "[E4][strength]") {
  const scenario::Scenario scenario = load_example("flyer_plate.json");
  Run run(scenario.setup);
  const double dx = plate_thickness / plate_zones;
  const double two_thirds_y = 2.0 * flyer::yield_stress / 3.0;

  // Fronts at 1.25 and 2.5 us, before the precursor reaches the free face (at 20 mm / 6090 m/s = 3.3 us).
  double first_time = 1.25e-6, second_time = 2.5e-6;
  bool first_done = false, second_done = false;
  Fronts first, second;
  std::vector<StripZone> at_second;
  // Probes at 5, 10 and 15 mm from the plane: the release from the free face sweeps them between 4
  // and 5.6 us, before it reaches the plane (where the bonded slip plane, unlike the real interface,
  // would hold tension).
  std::vector<Probe> probes;
  for (const double x : {0.005, 0.010, 0.015}) probes.push_back({static_cast<Index>(x / dx), {}, {}, {}});
  advance(run, [&](const Simulation& sim) {
    if (!first_done && sim.time() >= first_time) {
      first_done = true;
      first_time = sim.time();
      first = locate_fronts(sim);
    }
    if (!second_done && sim.time() >= second_time) {
      second_done = true;
      second_time = sim.time();
      second = locate_fronts(sim);
      at_second = strip_profile(sim, sim.bodies()[0]);
    }
    const ZoneFields& zones = sim.mesh().zones;
    const ZoneState& zone_state = sim.zone_state();
    for (Probe& p : probes) {
      p.deviator_xx.push_back(zone_state.strength.deviator_xx[p.zone]);
      p.plastic_strain.push_back(zone_state.strength.plastic_strain[p.zone]);
      p.density.push_back(zones.density[p.zone]);
    }
  });
  INFO(run.failure);
  REQUIRE(run.completed());
  REQUIRE(second_done);

  {  // fronts
    const double exact_elastic = (flyer::elastic.front_speed - frame_speed) * second_time;
    const double exact_plastic = (flyer::plastic.front_speed - frame_speed) * second_time;
    INFO("at " << second_time << " s: elastic front " << second.elastic << " m (exact " << exact_elastic
               << "), plastic front " << second.plastic << " m (exact " << exact_plastic << ")");
    // Within 2 zones (the E2 criterion; measured 1.6 and 0.4 zones).
    CHECK(std::abs(second.elastic - exact_elastic) < 2.0 * dx);
    CHECK(std::abs(second.plastic - exact_plastic) < 2.0 * dx);
    // Speeds from two times, target frame: within 0.1 % (0.25 zones of travel over 1.25 us for the
    // plastic front; measured -1.8e-4 elastic, +4.5e-5 plastic).
    const double elastic_speed = (second.elastic - first.elastic) / (second_time - first_time) + frame_speed;
    const double plastic_speed = (second.plastic - first.plastic) / (second_time - first_time) + frame_speed;
    INFO("front speeds (target frame): elastic " << elastic_speed << " m/s, plastic " << plastic_speed << " m/s");
    CHECK(elastic_speed == Approx(flyer::elastic.front_speed).epsilon(1e-3));
    CHECK(plastic_speed == Approx(flyer::plastic.front_speed).epsilon(1e-3));
    report("E4 flyer", "elastic front speed (m/s)", "6490.4", elastic_speed,
           format_number("%+.1e", elastic_speed / flyer::elastic.front_speed - 1.0), plate_zones, run.seconds);
    report("E4 flyer", "plastic front speed (m/s)", "5908.5", plastic_speed,
           format_number("%+.1e", plastic_speed / flyer::plastic.front_speed - 1.0), plate_zones, run.seconds);
  }

  {  // plateaux at 2.5 us
    // Plastic: from 20 zones off the plane (clear of the wall-heating error of the impact boundary)
    // to 15 zones behind the plastic front; precursor: between the fronts, 15 zones clear of each.
    const StripPlateau plastic =
        strip_plateau(at_second, 20 * dx, second.plastic - 15 * dx, flyer::plastic, frame_speed);
    const StripPlateau elastic =
        strip_plateau(at_second, second.plastic + 15 * dx, second.elastic - 15 * dx, flyer::elastic, frame_speed);
    REQUIRE(plastic.zones > 400);
    REQUIRE(elastic.zones >= 20);
    INFO("plastic (" << plastic.zones << " zones): rho " << plastic.mean.density << ", p " << plastic.mean.pressure
                     << ", sigma_xx " << plastic.mean.stress_xx << ", u " << plastic.mean.velocity);
    INFO("precursor (" << elastic.zones << " zones): rho " << elastic.mean.density << ", p " << elastic.mean.pressure
                       << ", sigma_xx " << elastic.mean.stress_xx << ", u " << elastic.mean.velocity);
    // The reference values carry 5-6 digits; the scheme keeps the jump conditions, and the ringing
    // averages out. Tolerances 1e-4 on density (measured < 1e-6), 5e-4 on p, sigma_xx and u
    // (measured at most 3.3e-5, and -6e-5 for the precursor's 35 m/s).
    CHECK(plastic.mean.density == Approx(flyer::plastic.density).epsilon(1e-4));
    CHECK(plastic.mean.pressure == Approx(flyer::plastic.pressure).epsilon(5e-4));
    CHECK(plastic.mean.stress_xx == Approx(flyer::plastic.stress_xx).epsilon(5e-4));
    CHECK(plastic.mean.velocity == Approx(flyer::plastic.velocity).epsilon(5e-4));
    CHECK(elastic.mean.density == Approx(flyer::elastic.density).epsilon(1e-4));
    CHECK(elastic.mean.stress_xx == Approx(flyer::elastic.stress_xx).epsilon(5e-4));  // the HEL
    CHECK(elastic.mean.velocity == Approx(flyer::elastic.velocity).epsilon(5e-4));
    report("E4 flyer", "HEL sigma_xx (Pa)", "-6.3588e8", elastic.mean.stress_xx,
           format_number("%+.1e", elastic.mean.stress_xx / flyer::elastic.stress_xx - 1.0), plate_zones, run.seconds);
    report("E4 flyer", "precursor u (m/s)", "35.18", elastic.mean.velocity,
           format_number("%+.1e", elastic.mean.velocity / flyer::elastic.velocity - 1.0), plate_zones, run.seconds);
    report("E4 flyer", "plastic density (kg/m3)", "2985.63", plastic.mean.density,
           format_number("%+.1e", plastic.mean.density / flyer::plastic.density - 1.0), plate_zones, run.seconds);
    report("E4 flyer", "plastic p (Pa)", "6.4359e9", plastic.mean.pressure,
           format_number("%+.1e", plastic.mean.pressure / flyer::plastic.pressure - 1.0), plate_zones, run.seconds);
    report("E4 flyer", "plastic sigma_xx (Pa)", "-6.6359e9", plastic.mean.stress_xx,
           format_number("%+.1e", plastic.mean.stress_xx / flyer::plastic.stress_xx - 1.0), plate_zones, run.seconds);
  }

  double worst_hooke = 0.0, worst_ends = 0.0;
  for (const Probe& p : probes) {  // the elastic swing of the deviator on release
    // The last step in which the zone yielded in compression (s_xx < 0) and the first in which it
    // yielded in tension (s_xx > 0). Between them the zone must unload elastically: no plastic strain,
    // while s_xx travels the whole 4Y/3 from -2Y/3 to +2Y/3.
    const std::size_t steps = p.plastic_strain.size();
    std::size_t last_compressive = 0, first_tensile = 0;
    for (std::size_t k = 1; k < steps; ++k) {
      const bool yielded = p.plastic_strain[k] > p.plastic_strain[k - 1];
      if (yielded && p.deviator_xx[k] < 0.0 && first_tensile == 0) last_compressive = k;
      if (yielded && p.deviator_xx[k] > 0.0 && first_tensile == 0) first_tensile = k;
    }
    INFO("probe zone " << p.zone << ": last compressive yield at step " << last_compressive << ", first tensile yield at step "
                       << first_tensile << " of " << steps);
    REQUIRE(last_compressive > 0);
    REQUIRE(first_tensile > last_compressive + 1);
    // On the surface at both ends of the swing, to round-off (the radial return; allow 1e-12).
    const double ends = std::max(std::abs(p.deviator_xx[last_compressive] / -two_thirds_y - 1.0),
                                 std::abs(p.deviator_xx[first_tensile] / two_thirds_y - 1.0));
    CHECK(ends < 1e-12);
    worst_ends = std::max(worst_ends, ends);
    // Elastic in between: the plastic strain does not move at all.
    const double strain_before = p.plastic_strain[last_compressive];
    bool elastic = true;
    for (std::size_t k = last_compressive; k < first_tensile; ++k) elastic = elastic && p.plastic_strain[k] == strain_before;
    CHECK(elastic);
    // And follows Hooke's law in uniaxial strain: ds_xx = (4/3) mu d ln(1/rho) (hypoelastic; the
    // discrete rate is the midpoint rule for the logarithm, error O(d eps^3) per step). Over the
    // elastic steps, within 1e-6 (measured 6e-9).
    const std::size_t end = first_tensile - 1;
    const double deviator_change = p.deviator_xx[end] - p.deviator_xx[last_compressive];
    const double hooke = 4.0 / 3.0 * flyer::shear_modulus * std::log(p.density[last_compressive] / p.density[end]);
    INFO("elastic part of the swing: ds_xx " << deviator_change << " Pa, (4/3) mu dln(1/rho) " << hooke << " Pa");
    CHECK(deviator_change == Approx(hooke).epsilon(1e-6));
    worst_hooke = std::max(worst_hooke, std::abs(deviator_change / hooke - 1.0));
    // The elastic part covers nearly the whole 4Y/3 (the tensile-yield step takes the rest).
    CHECK(deviator_change > 0.9 * 2.0 * two_thirds_y);
  }
  report("E4 flyer", "release swing: s_xx at its ends / (2Y/3), worst of 3 probes", "-1 -> +1", 1.0 + worst_ends,
         format_number("%.1e", worst_ends), plate_zones, run.seconds);
  report("E4 flyer", "release swing: elastic ds_xx / ((4/3) mu dln(1/rho)), worst of 3", "1", 1.0 + worst_hooke,
         format_number("%.1e", worst_hooke), plate_zones, run.seconds);

  const Ledger& ledger = run.simulation.ledger();
  CHECK(ledger.relative_mass_error() == 0.0);
  CHECK(ledger.relative_energy_drift() < 1e-12);  // with the plane's work, to round-off
}
