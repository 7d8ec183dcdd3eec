// E8 of verification.md: spall. A Wilkins-aluminium flyer (2 mm, 1000 m/s) onto a 6 mm target of the
// same material in uniaxial strain (slip walls), the target fracturing by the tensile-stress criterion
// sigma_* = 5 GPa (examples/verification/spall.json). The free-surface velocity history of the target
// is measured every cycle; the spall plane is the zone damaged first.
//
// Acoustic predictions (verification.md E8), and how they are derived here.
//   Spall plane. In the acoustic approximation every wave, loading or unloading, runs at one speed c.
//   The flyer then puts a rectangular pulse into the target whose length is the flyer's round trip,
//   2 d (d the flyer's thickness; the same material on both sides, so c cancels). Its head reflects
//   at the free surface as a release; the net stress first turns tensile where that reflected head
//   meets the pulse's tail, at d from the free surface. Prediction: 2.000 mm, whatever c is.
//   With the elastic-plastic speeds of this impact the two heads do not run at one speed: the loading
//   front is the plastic shock, U_s = c0 + s u_p = 5997 m/s (u_p = v/2 = 500 m/s), and both releases
//   start with the elastic wave of the shocked state, Lagrangian speed (rho/rho0) sqrt((dp/drho)_s +
//   4 mu / (3 rho)) = 7659 m/s (rho = 3038 kg/m^3, from the EOS). The release heads then meet at
//   L - (L - d)(1 + c_r/U_s)/2 = 1.45 mm from the free surface, but there the tension is only the
//   overlap of two release fans; it reaches sigma_* later and deeper, and the first damaged zone lies
//   at 2.075 mm (this test, 0.05 mm zones), 2.06 mm with 0.025 mm zones. The prediction checked is
//   therefore the acoustic one, d, within 2 zones (verification.md).
//   Pull-back. At the free surface u_fs = 2 u of the incident wave. Tension at the spall plane is the
//   reflected plateau minus what is left of the incident tail, so when the tail alone builds it (a
//   sharp reflected head, a gradual tail), the part of the tail the free surface sees before the
//   spall signal arrives is sigma_*, and du_fs = 2 sigma_* / (rho0 c). With sigma_* well above the
//   elastic swing of the release (4/3 Y (K + 4/3 mu)/(2 mu) = 0.84 GPa) the tensile part is carried
//   by plastic waves, hence c = c_b = c0 = 5328 m/s (K = rho0 c0^2 = 79.06 GPa): 2 sigma_*/(rho0 c_b)
//   = 673.9 m/s. Required within 15 % (verification.md E8).
//
// Finding (measured, see docs/verification.md): the pull-back is 441.5 m/s, 0.655 of the prediction,
// and it stays at 0.64-0.69 from 0.1 mm to 0.025 mm zones. The reason is the pulse, not the solver:
// a flyer's pulse has a sharp tail as well as a sharp head, and the tension at the spall plane is then
// built by the reflected head and the tail arriving together, each bringing part of sigma_*. In the
// linear acoustic limit (linear EOS, no strength, 200 m/s, sigma_* half the pulse) Krug gives
// 0.44-0.51 of 2 sigma_*/(rho0 c) from 0.05 mm to 0.00625 mm zones, the value of two equally smeared
// fronts crossing; with a ramped flyer (velocity falling linearly to 0 at its rear: a triangular
// pulse, whose tail alone builds the tension) it gives 0.85, 0.88, 0.91, 0.91 over the same zones.
// The 15 % assertion is kept as the brief states it, in its own test case tagged [!mayfail] (the
// suite's convention for known failures, docs/verification.md).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "krug/krug.hpp"
#include "verification_support.hpp"

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

namespace {

// The free-surface pull-back of a velocity history: the peak of the first plateau (from the arrival,
// u > v/4, until u falls 5 % below its peak), then the first minimum after it (until u rises again by
// 2 % of the peak: the spall signal).
struct PullBack {
  double peak = 0.0, peak_time = 0.0;
  double minimum = 0.0, minimum_time = 0.0;
  double value() const { return peak - minimum; }
};

PullBack pull_back(const std::vector<std::pair<double, double>>& history, double impact_speed) {
  PullBack p;
  std::size_t k = 0;
  while (k < history.size() && history[k].second < 0.25 * impact_speed) ++k;
  std::size_t peak = k;
  for (; k < history.size(); ++k) {
    if (history[k].second > history[peak].second) peak = k;
    if (history[k].second < 0.95 * history[peak].second) break;
  }
  std::size_t minimum = k;
  for (; k < history.size(); ++k) {
    if (history[k].second < history[minimum].second) minimum = k;
    if (history[k].second > history[minimum].second + 0.02 * history[peak].second) break;
  }
  if (peak >= history.size() || minimum >= history.size()) return p;
  p.peak = history[peak].second;
  p.peak_time = history[peak].first;
  p.minimum = history[minimum].second;
  p.minimum_time = history[minimum].first;
  return p;
}

// One run of examples/verification/spall.json and what the two test cases below judge.
struct SpallResult {
  std::string failure;
  double depth = 0.0;              // initial distance of the first damaged zone's centre from the free surface (m)
  double spall_plane_zones = 0.0;  // |depth - flyer thickness| / zone size
  double first_damage_time = 0.0;
  long damaged = 0;
  long flyer_damaged = 0;
  PullBack pull_back;
  double predicted = 0.0;          // 2 sigma_* / (rho0 c_b)
  double axial_momentum_error = 0.0;
  double drift = 0.0;
  double seconds = 0.0;
  long zones = 0;
};

constexpr double impact_speed = 1000.0, flyer_thickness = 0.002, zone_size = 0.006 / 120;

const SpallResult& spall_run() {
  static const SpallResult result = [] {
    SpallResult r;
    const io::Scenario scenario = verification::load_example("spall.json");
    verification::Run run(scenario.setup);
    const Simulation& sim = run.simulation;
    const Body& flyer = sim.bodies()[0];
    const Body& target = sim.bodies()[1];
    const double rho0 = 2785.0, bulk_sound_speed = 5328.0;  // Wilkins aluminium (verification.md E4)
    const double sigma_star = scenario.setup.fracture[static_cast<std::size_t>(target.material)].tensile_stress;
    r.predicted = 2.0 * sigma_star / (rho0 * bulk_sound_speed);
    double free_surface = -std::numeric_limits<double>::infinity();
    for (Index n = target.node_begin; n < target.node_end; ++n) free_surface = std::max(free_surface, sim.mesh().nodes.x[n]);
    std::vector<Index> surface_nodes;
    for (Index n = target.node_begin; n < target.node_end; ++n) {
      if (sim.mesh().nodes.x[n] == free_surface) surface_nodes.push_back(n);
    }
    std::vector<std::pair<double, double>> history;  // (t, free-surface velocity)
    verification::advance(run, [&](const Simulation& s) {
      double u = 0.0;
      for (Index n : surface_nodes) u += s.mesh().nodes.u[n];
      history.emplace_back(s.time(), u / static_cast<double>(surface_nodes.size()));
    });
    r.failure = run.failure;
    r.seconds = run.seconds;
    r.zones = sim.mesh().zones.size();
    // The spall plane: the zone damaged first, by the initial position of its centre.
    const ZoneFields& zones = sim.mesh().zones;
    Index first = -1;
    for (Index z = target.zone_begin; z < target.zone_end; ++z) {
      if (!zones.damaged[z]) continue;
      ++r.damaged;
      if (first < 0 || zones.damage_time[z] < zones.damage_time[first]) first = z;
    }
    for (Index z = flyer.zone_begin; z < flyer.zone_end; ++z) r.flyer_damaged += zones.damaged[z] ? 1 : 0;
    if (first >= 0) {
      double centre = 0.0;
      for (Index n : zones.corners[first]) centre += 0.25 * sim.mesh().nodes.x0[n];
      r.depth = free_surface - centre;
      r.spall_plane_zones = std::abs(r.depth - flyer_thickness) / zone_size;
      r.first_damage_time = zones.damage_time[first];
    }
    r.pull_back = pull_back(history, impact_speed);
    const Ledger& ledger = sim.ledger();
    r.axial_momentum_error = std::abs(ledger.axial_momentum - ledger.initial_axial_momentum) / std::abs(ledger.initial_axial_momentum);
    r.drift = ledger.relative_energy_drift();
    report("E8 spall", "spall plane depth (m)", "2.000e-3 (flyer thickness)", r.depth,
           format_number("%.2f zones", r.spall_plane_zones), r.zones, r.seconds);
    report("E8 spall", "free-surface pull-back (m/s)", format_number("%.1f", r.predicted), r.pull_back.value(),
           format_number("%+.1f %%", 100.0 * (r.pull_back.value() / r.predicted - 1.0)), r.zones, r.seconds);
    return r;
  }();
  return result;
}

std::ostream& operator<<(std::ostream& out, const SpallResult& r) {
  return out << "spall plane: first damage at " << r.first_damage_time << " s, " << r.depth
             << " m from the free surface (" << r.spall_plane_zones << " zones from the flyer thickness), " << r.damaged
             << " zones damaged; free surface: peak " << r.pull_back.peak << " m/s at " << r.pull_back.peak_time
             << " s, minimum " << r.pull_back.minimum << " m/s at " << r.pull_back.minimum_time << " s, pull-back "
             << r.pull_back.value() << " m/s against 2 sigma_*/(rho0 c_b) = " << r.predicted << " m/s (ratio "
             << r.pull_back.value() / r.predicted << "); momentum " << r.axial_momentum_error << ", drift " << r.drift;
}

}  // namespace

TEST_CASE("E8 spall: the spall plane one flyer thickness from the free surface, conservation",
          "[fracture][E8][spall]") {
  const SpallResult& r = spall_run();
  INFO(r);
  REQUIRE(r.failure.empty());
  REQUIRE(r.damaged > 0);
  CHECK(r.flyer_damaged == 0);  // the flyer has no fracture limit
  // The free surface first takes about the impact speed (symmetric impact: 2 u_p = v); measured 993 m/s.
  CHECK(r.pull_back.peak == Approx(impact_speed).epsilon(0.02));
  // Spall plane within 2 zones of the acoustic prediction, d (measured 1.5 zones: 2.075 mm).
  CHECK(r.spall_plane_zones <= 2.0);
  // Conservation: slip walls hold only the transverse velocity, so axial momentum is exact; round-off
  // (measured 0 and 6e-16).
  CHECK(r.axial_momentum_error < 1e-12);
  CHECK(r.drift < 1e-12);
}

// A known failure kept in the suite ([!mayfail]: it runs and reports in every CI log; see the top of
// this file and docs/verification.md, "Fracture and free elements (E8)").
TEST_CASE("E8 spall: the free-surface pull-back within 15 % of 2 sigma_*/(rho0 c_b)", "[fracture][E8][spall][!mayfail]") {
  const SpallResult& r = spall_run();
  INFO(r);
  REQUIRE(r.failure.empty());
  // Measured 441.5 m/s against 673.9 m/s (0.655): fails, for the reason given at the top of this file.
  CHECK(r.pull_back.value() == Approx(r.predicted).epsilon(0.15));
}
