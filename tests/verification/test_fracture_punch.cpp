// E8 of verification.md (fracture and free elements), whole problem built through the library API:
// a flat punch through a plate with a narrow annular band of zones damaged beforehand. The band keeps
// only compressive pressure (docs/theory.md §2 step 6), so the punch shears it; its zones become
// fully fractured (altitude below f_h x initial, or loosened past chi_*) and convert to particles one
// boundary layer per step, or sooner by the interior rules, until the plug comes free.
//
// Checked: the plug separates (fragments(plate) gives 2 pieces, the plug ahead of the punch and at
// least as fast), axial momentum changes only by the impulse of the fixed rim (to round-off), the
// energy ledger closes, and the time step does not collapse: after every step each damaged zone left
// has a stable step of at least time_step_floor_ratio x the median zone step (damaged zones below it
// convert instead, docs/theory.md §2 step 7). The band is a quarter of a zone wide, so its zones
// start at 0.25 x the median step, just above the floor 0.2: shearing takes them below it, which is
// what the rule is for. The same run with the rule off (ratio 0) is the comparison. The
// interior-conversion count is reported.
//
// Axisymmetric (z, r). Plate: 6061-T6 with the paper's constants (docs/validation.md: rho0 2700,
// K 73 GPa, mu 24.6 GPa, Y0 0.28 GPa, elongation eps_* 0.4, chi_* 0.03), 2 mm thick, 6 mm radius,
// 8 zones through the thickness; radially 8 zones to r = 2 mm, the band r in [2, 2.0625] mm, then
// 16 zones to the rim r = 6 mm, which is fixed. Punch: a very stiff elastic cylinder ("rigid-ish":
// rho 7850, K 500 GPa, mu 300 GPa, no yield, no fracture; wave speed 10.7 km/s), radius 2 mm, 4 mm
// long, 0.25 mm zones, 200 m/s onto the plate, touching it at t = 0. Contact: punch/plate and the
// plate's self-contact (the plug against its own plate); particles meet everything (docs/theory.md §2 step 7).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "krug/krug.hpp"
#include "verification_support.hpp"

using krug::verification::body_from;

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

namespace {

constexpr double plate_thickness = 0.002, plate_radius = 0.006, zone_size = 0.00025, band_width = 0.0000625;
constexpr double punch_radius = 0.002, punch_length = 0.004, punch_speed = 200.0;

SimulationSetup punch_setup(double end_time, double floor_ratio) {
  SimulationSetup s;
  s.geometry = GeometryKind::axisymmetric;
  const int through = static_cast<int>(std::lround(plate_thickness / zone_size));
  const generate::Patch plate = generate::rectangle(
      s.mesh, generate::graded_axis(-plate_thickness, {{0.0, through, 1.0}}),
      generate::graded_axis(0.0, {{punch_radius, 8, 1.0}, {punch_radius + band_width, 1, 1.0}, {plate_radius, 16, 1.0}}), 0);
  const generate::Patch punch = generate::rectangle(
      s.mesh, generate::graded_axis(0.0, {{punch_length, static_cast<int>(std::lround(punch_length / zone_size)), 1.0}}),
      generate::graded_axis(0.0, {{punch_radius, static_cast<int>(std::lround(punch_radius / zone_size)), 1.0}}), 1);
  s.materials.push_back(Material{"al6061", 2700.0, LinearBulk{7.3e10, 2700.0}, PerfectlyPlastic{2.46e10, 2.8e8}});
  s.materials.push_back(Material{"stiff", 7850.0, LinearBulk{5.0e11, 7850.0}, Elastic{3.0e11}});
  s.bodies.push_back(body_from("plate", 0, plate));
  s.bodies.push_back(body_from("punch", 1, punch));
  for (Index n = punch.node_begin; n < punch.node_end; ++n) s.mesh.nodes.u[n] = -punch_speed;
  for (Index n : plate.sides.at("j_max")) s.constraints.push_back({n, true, true});  // the rim r = 6 mm
  s.zone_state.resize(s.mesh.zones.size());
  for (Index z = plate.zone_begin; z < plate.zone_end; ++z) {
    const double r = quad::centre(s.mesh.corner_positions(z)).y;
    if (r > punch_radius && r < punch_radius + band_width) s.zone_state.fracture.damaged[z] = 1;
  }
  fracture::FractureLimits al6061;
  al6061.elongation = 0.4;
  al6061.loosening = 0.03;
  s.fracture = {al6061, fracture::FractureLimits{}};
  s.contact.pairs = {{0, 1, 0.0}, {0, 0, 0.0}};
  s.controls.end_time = end_time;
  s.controls.fracture.time_step_floor_ratio = floor_ratio;
  return s;
}

double median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

struct PunchRun {
  std::string failure;
  double separated_at = -1.0;
  double smallest_step_ratio = 1e300;  // min over steps (not the last, cut to land on end_time) of dt^{n+1/2} / dt^{1/2}
  double worst_floor_margin = 1e300;   // min over steps and damaged zones of dt_z / (floor ratio x median)
  long floor_violations = 0;
  long cycles = 0;
};

PunchRun run_punch(Simulation& sim) {
  PunchRun run;
  const Body& plate = sim.bodies()[0];
  const double floor_ratio = sim.controls().fracture.time_step_floor_ratio;
  const double first_step = sim.next_time_step();
  try {
    while (!sim.finished()) {
      const std::vector<std::uint8_t> active_before = sim.mesh().zones.active;
      sim.step();
      // The floor rule, on the zones the rule saw: those updated this step (active before it).
      const ZoneFields& zones = sim.mesh().zones;
      const ZoneState& zone_state = sim.zone_state();
      std::vector<double> steps;
      for (Index z = 0; z < zones.size(); ++z) {
        if (active_before[static_cast<std::size_t>(z)]) steps.push_back(zone_state.hydro.stable_time_step[z]);
      }
      const double median_step = median(steps);
      for (Index z = plate.zone_begin; z < plate.zone_end && floor_ratio > 0.0; ++z) {
        if (!zones.active[z] || !zone_state.fracture.damaged[z]) continue;
        const double margin = zone_state.hydro.stable_time_step[z] / (floor_ratio * median_step);
        run.worst_floor_margin = std::min(run.worst_floor_margin, margin);
        if (margin < 1.0) ++run.floor_violations;
      }
      if (!sim.finished()) run.smallest_step_ratio = std::min(run.smallest_step_ratio, sim.next_time_step() / first_step);
      if (run.separated_at < 0.0 && sim.fragments(plate).size() >= 2) run.separated_at = sim.time();
    }
  } catch (const NumericalFailure& e) {
    run.failure = e.what();
  }
  run.cycles = sim.cycle();
  return run;
}

}  // namespace

TEST_CASE("E8 punch through a plate with a damaged band: the plug separates, momentum exact, no dt collapse",
          "[fracture][E8][punch]") {
  // 20 us: the plug is free after about 2.3 us and flies on ahead of the punch.
  Simulation sim(punch_setup(2.0e-5, FractureControls{}.time_step_floor_ratio));
  const PunchRun run = run_punch(sim);
  Simulation without_floor(punch_setup(2.0e-5, 0.0));
  const PunchRun comparison = run_punch(without_floor);
  REQUIRE(run.failure.empty());
  const Body& plate = sim.bodies()[0];
  const Body& punch = sim.bodies()[1];
  const double floor_ratio = sim.controls().fracture.time_step_floor_ratio;
  const std::vector<Fragment> pieces = sim.fragments(plate);
  const BodySummary punch_state = sim.summarise(punch);
  const FractureCounts& counts = sim.fracture_counts(0);
  const Ledger& ledger = sim.ledger();
  const double momentum_scale = std::sqrt(2.0 * ledger.max_kinetic * ledger.mass);
  const double momentum_error =
      std::abs(ledger.axial_momentum - ledger.initial_axial_momentum - ledger.axial_boundary_impulse) / momentum_scale;
  INFO("cycles " << run.cycles << " (without the floor rule " << comparison.cycles << ", smallest dt/first "
                 << comparison.smallest_step_ratio << ", " << without_floor.fracture_counts(0).interior_conversions
                 << " interior conversions" << (comparison.failure.empty() ? "" : ", failed: " + comparison.failure)
                 << "), separated at " << run.separated_at << " s, fragments " << pieces.size()
                 << ", converted " << counts.converted << " (interior " << counts.interior_conversions
                 << "), newly damaged " << counts.damaged << ", particles " << sim.particles().size()
                 << "; punch " << punch_state.velocity.x << " m/s; smallest dt/first " << run.smallest_step_ratio
                 << ", worst floor margin " << run.worst_floor_margin << "; momentum " << momentum_error << ", drift "
                 << ledger.relative_energy_drift() << ", contact " << ledger.energy.contact << " J/rad, overlap "
                 << ledger.energy.overlap);
  const long zones = sim.mesh().zones.size();
  report("E8 punch", "plug free at (s)", "-", run.separated_at, format_number("%.0f fragments", static_cast<double>(pieces.size())), zones, 0.0);
  report("E8 punch", "interior conversions", "-", static_cast<double>(counts.interior_conversions),
         format_number("of %.0f converted", static_cast<double>(counts.converted)), zones, 0.0);
  report("E8 punch", "smallest dt / first dt", "-", run.smallest_step_ratio,
         format_number("floor margin %.6f", run.worst_floor_margin), zones, 0.0);
  report("E8 punch, floor rule off", "smallest dt / first dt", "-", comparison.smallest_step_ratio,
         format_number("%.0f cycles", static_cast<double>(comparison.cycles)), zones, 0.0);
  report("E8 punch", "axial momentum - rim impulse, relative", "0", momentum_error, "round-off", zones, 0.0);
  report("E8 punch", "energy drift", "< 1e-12", ledger.relative_energy_drift(), "round-off", zones, 0.0);

  // The plug separates: two pieces, the lighter on the axis, ahead of the punch and not slower than it.
  REQUIRE(pieces.size() >= 2);
  const Fragment& plug = pieces[1];
  report("E8 punch", "plug axial velocity (m/s)", format_number("punch %.1f", punch_state.velocity.x), plug.velocity.x,
         format_number("plug mass %.5g kg", plug.mass), zones, 0.0);
  // The plug is the disc inside the band: rho0 pi R_p^2 h = 2700 pi (2 mm)^2 (2 mm) = 6.786e-5 kg. No
  // plug zone converts in this run (measured: its mass exactly the disc's), so 1 % is a margin for a
  // zone or two lost at its rim in a variant of the solver, not a tolerance on a physical estimate.
  const double plug_mass = 2700.0 * std::numbers::pi * punch_radius * punch_radius * plate_thickness;
  CHECK(plug.mass == Approx(plug_mass).epsilon(0.01));
  CHECK(plug.centroid.y < punch_radius);
  // Pushed by the punch and bounced off it (an elastic impactor): measured -179 m/s against the punch's
  // -165.5 m/s. "Moving with the punch": at least the punch's speed, in the same direction, and below
  // the plate's rear face.
  CHECK(plug.velocity.x < 0.0);
  CHECK(plug.velocity.x <= punch_state.velocity.x);
  CHECK(plug.centroid.x < -plate_thickness);
  CHECK(pieces[0].centroid.y > punch_radius);  // the rest of the plate, outside the band

  // Conservation: the fixed rim is the only external axial force (the axis holds u_r only).
  // Round-off: measured 1.2e-15 (momentum), 7e-16 (drift).
  CHECK(momentum_error < 1e-12);
  CHECK(ledger.relative_energy_drift() < 1e-12);
  // Contacts that started a step apart only dissipate (docs/theory.md §3): the contact work less the
  // overlap line (the contacts pushing a pre-existing overlap open), to round-off.
  CHECK(ledger.energy.contact - ledger.energy.overlap <= 1e-12 * ledger.energy_scale());
  CHECK(ledger.relative_mass_error() < 1e-14);
  // The band's zones went to particles (measured: the 8 band zones and nothing else).
  CHECK(counts.converted >= 8);
  // The time-step floor rule held after every step: no damaged zone below floor x median, and the
  // step never near the floor. This punch no longer needs the rule: with the start gap of a particle at
  // a convex corner measured from the corner (test_particle_corner.cpp), particles no longer sink into
  // the punch's corner and shear the band, whose zones convert by the altitude rule before they reach
  // the floor (measured: 0 interior conversions; smallest dt^{n+1/2} / dt^{1/2} 0.908 with the rule and
  // without it; before that fix 1 interior conversion, 0.353 against 0.067). The next test exercises it.
  CHECK(run.floor_violations == 0);
  CHECK(run.smallest_step_ratio > floor_ratio);
  CHECK(comparison.failure.empty());
}

TEST_CASE("E8 punch with a floor above the band's step: the damaged zones below it convert at once",
          "[fracture][E8][punch]") {
  // The band's zones start at 0.25 x the median zone step (a quarter-zone-wide band); with
  // time_step_floor_ratio 0.3 every one of them is below the floor from the first step, so the rule
  // (docs/theory.md §2 step 7) converts them: a zone on the surface as a boundary zone, one below
  // it as an interior conversion (measured 4 of the 8, as the surface moves in while they go), and the
  // step is no longer held by them. Without the rule they stay and hold the step down while they last.
  constexpr double floor_ratio = 0.3;
  Simulation sim(punch_setup(5.0e-6, floor_ratio));
  const PunchRun run = run_punch(sim);
  Simulation without_floor(punch_setup(5.0e-6, 0.0));
  const PunchRun comparison = run_punch(without_floor);
  REQUIRE(run.failure.empty());
  REQUIRE(comparison.failure.empty());
  const FractureCounts& counts = sim.fracture_counts(0);
  INFO("interior conversions " << counts.interior_conversions << " of " << counts.converted << "; cycles " << run.cycles
                               << " against " << comparison.cycles << " without the rule; smallest dt/first "
                               << run.smallest_step_ratio << " against " << comparison.smallest_step_ratio
                               << "; worst floor margin " << run.worst_floor_margin);
  CHECK(run.floor_violations == 0);
  CHECK(counts.converted >= 8);
  CHECK(counts.interior_conversions >= 1);
  // What the rule is for: the step is no longer held by the band (smallest dt / first 1.1 with the
  // rule, 0.14 without). The run's cycle count is not asserted: it follows how fast the punch's surface
  // moves in, which the contact's corner rule changed (541 with the rule against 550 without it before
  // that rule, 587 against 550 after; docs/verification.md, Contact, C8).
  CHECK(run.smallest_step_ratio > comparison.smallest_step_ratio);
}
