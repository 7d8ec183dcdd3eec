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
// Finding (measured, see docs/verification.md): the pull-back is 441.5 m/s, 0.655 of 2 sigma_*/(rho0 c_b),
// and it stays at 0.64-0.69 from 0.1 mm to 0.025 mm zones. That formula is the wrong reference for a
// flyer's pulse: its tail is as sharp as its head, so the tension at the spall plane is built by the
// reflected head and the tail together, and the free surface sees only part of sigma_* before the
// spall signal. (In exact linear acoustics a rectangular pulse gives no pull-back at all: the tension
// jumps from 0 to the full pulse right behind the meeting point, so any finite value there is the
// scheme's smearing.) What remains between the formula and an elastic-plastic target is Kanel's
// correction for the release running at the elastic speed ahead of the plastic tail (G. I. Kanel,
// "Spall fracture: methodological aspects, mechanisms and governing factors", Int. J. Fracture 163,
// 2010, 173-191). The references used here instead:
//   * the same model solved by an independent 1D code (uniaxial_strain_1d.hpp): pull-back within 6 %,
//     spall plane within 2 zones, at 0.05 and 0.025 mm;
//   * a case where the formula holds: linear EOS, no strength, a ramped flyer u = v0 (1 + x/d) (its
//     pulse has a gradual tail), 200 m/s, sigma_* = p/2: within 10 % at 0.0125 mm zones;
//   * the hydrodynamic limit (Y = 0) of the same impact: 0.83-0.95 of the formula at 0.0125 mm,
//     rising with refinement (the 1D reference: 0.81, 0.83, 0.87 at 0.025, 0.0125, 0.00625 mm).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <ostream>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "krug/krug.hpp"
#include "uniaxial_strain_1d.hpp"
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
// A variant of examples/verification/spall.json run by Krug: the free-surface history and the first
// damaged zone's initial depth below the free surface.
struct Variant {
  std::string failure;
  std::vector<std::pair<double, double>> history;
  // The same trace from the scenario's free-surface gauge (gauges.surfaces[0], its velocity column),
  // sampled every cycle; empty when the scenario has no surface gauge.
  std::vector<std::pair<double, double>> gauge_history;
  double depth = 0.0;  // initial distance of the first damaged zone's centre from the free surface (m)
  double first_damage_time = 0.0;
  long damaged = 0, flyer_damaged = 0;
  double axial_momentum_error = 0.0, drift = 0.0;
  long zones = 0;
  double seconds = 0.0;
};

Variant run_variant(const nlohmann::json& document) {
  Variant v;
  const scenario::Scenario scenario = scenario::parse_scenario(document.dump(), "spall variant");
  verification::Run run(scenario.setup);
  const Simulation& sim = run.simulation;
  const Body& target = sim.bodies()[1];
  double free_surface = -std::numeric_limits<double>::infinity();
  for (Index n = target.node_begin; n < target.node_end; ++n) free_surface = std::max(free_surface, sim.mesh().nodes.x[n]);
  std::vector<Index> surface;
  for (Index n = target.node_begin; n < target.node_end; ++n) {
    if (sim.mesh().nodes.x[n] == free_surface) surface.push_back(n);
  }
  std::optional<GaugeSampler> gauges;
  std::size_t visar = 0;  // the column of the first surface gauge's velocity along its direction
  if (!scenario.gauges.surfaces.empty()) {
    gauges.emplace(scenario.gauges, sim);
    const std::string column = scenario.gauges.surfaces.front().name + "_velocity";
    visar = static_cast<std::size_t>(std::find(gauges->columns().begin(), gauges->columns().end(), column) -
                                     gauges->columns().begin());
  }
  std::vector<double> values;
  verification::advance(run, [&](const Simulation& s) {
    double u = 0.0;
    for (Index n : surface) u += s.mesh().nodes.u[n];
    v.history.emplace_back(s.time(), u / static_cast<double>(surface.size()));
    if (gauges) {
      gauges->sample(s, values);
      v.gauge_history.emplace_back(s.time(), values.at(visar));
    }
  });
  v.failure = run.failure;
  v.seconds = run.seconds;
  v.zones = sim.mesh().zones.size();
  // The spall plane: the zone damaged first, by the initial position of its centre.
  const ZoneFields& zones = sim.mesh().zones;
  const ZoneState& zone_state = sim.zone_state();
  Index first = -1;
  for (Index z = target.zone_begin; z < target.zone_end; ++z) {
    if (!zone_state.fracture.damaged[z]) continue;
    ++v.damaged;
    if (first < 0 || zone_state.fracture.damage_time[z] < zone_state.fracture.damage_time[first]) first = z;
  }
  const Body& flyer = sim.bodies()[0];
  for (Index z = flyer.zone_begin; z < flyer.zone_end; ++z) v.flyer_damaged += zone_state.fracture.damaged[z] ? 1 : 0;
  if (first >= 0) {
    double centre = 0.0;
    for (Index n : zones.corners[first]) centre += 0.25 * sim.mesh().nodes.x0[n];
    v.depth = free_surface - centre;
    v.first_damage_time = zone_state.fracture.damage_time[first];
  }
  const Ledger& ledger = sim.ledger();
  v.axial_momentum_error = std::abs(ledger.axial_momentum - ledger.initial_axial_momentum) / std::abs(ledger.initial_axial_momentum);
  v.drift = ledger.relative_energy_drift();
  return v;
}

// spall.json with zones of `h` m along the impact (flyer 2 mm, target 6 mm).
nlohmann::json spall_document(double h) {
  nlohmann::json d = nlohmann::json::parse(verification::read_text(verification::example_path("spall.json")));
  d["bodies"][0]["mesh"]["x"]["zones"] = static_cast<int>(std::lround(0.002 / h));
  d["bodies"][1]["mesh"]["x"]["zones"] = static_cast<int>(std::lround(0.006 / h));
  d["bodies"][0]["mesh"]["y"]["to"] = h;
  d["bodies"][1]["mesh"]["y"]["to"] = h;
  d.erase("output");
  // The gauges stay on the strip's mid-line (the example's are at half its 0.05 mm height).
  for (const char* kind : {"tracers", "surfaces"}) {
    for (auto& gauge : d["gauges"][kind]) gauge["position"][1] = 0.5 * h;
  }
  return d;
}

struct SpallResult {
  std::string failure;
  double depth = 0.0;              // initial distance of the first damaged zone's centre from the free surface (m)
  double spall_plane_zones = 0.0;  // |depth - flyer thickness| / zone size
  double first_damage_time = 0.0;
  long damaged = 0;
  long flyer_damaged = 0;
  PullBack pull_back;
  PullBack gauge_pull_back;        // from the scenario's free-surface gauge
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
    const Variant v = run_variant(spall_document(zone_size));  // examples/verification/spall.json
    const double rho0 = 2785.0, bulk_sound_speed = 5328.0, sigma_star = 5.0e9;  // Wilkins aluminium, spall.json
    r.predicted = 2.0 * sigma_star / (rho0 * bulk_sound_speed);
    r.failure = v.failure;
    r.seconds = v.seconds;
    r.zones = v.zones;
    r.damaged = v.damaged;
    r.flyer_damaged = v.flyer_damaged;
    r.depth = v.depth;
    r.spall_plane_zones = std::abs(v.depth - flyer_thickness) / zone_size;
    r.first_damage_time = v.first_damage_time;
    r.pull_back = pull_back(v.history, impact_speed);
    r.gauge_pull_back = pull_back(v.gauge_history, impact_speed);
    r.axial_momentum_error = v.axial_momentum_error;
    r.drift = v.drift;
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

// The free-surface gauge of examples/verification/spall.json ("visar": the target's boundary node
// nearest (6 mm, 0.025 mm), velocity along +x) gives the pull-back this test measures from the nodes
// (the mean u of the two free-surface nodes; in uniaxial strain the two move together). Required equal
// to round-off, 1e-12 relative, on the peak, the minimum and their times (measured: equal, 0 difference).
TEST_CASE("E8 spall: the free-surface gauge gives the test's own pull-back", "[fracture][E8][spall][gauges]") {
  const SpallResult& r = spall_run();
  INFO(r);
  INFO("gauge: peak " << r.gauge_pull_back.peak << " m/s at " << r.gauge_pull_back.peak_time << " s, minimum "
                      << r.gauge_pull_back.minimum << " m/s at " << r.gauge_pull_back.minimum_time << " s, pull-back "
                      << r.gauge_pull_back.value() << " m/s");
  REQUIRE(r.failure.empty());
  REQUIRE(r.gauge_pull_back.value() > 0.0);
  CHECK(std::abs(r.gauge_pull_back.value() - r.pull_back.value()) <= 1e-12 * r.pull_back.value());
  CHECK(std::abs(r.gauge_pull_back.peak - r.pull_back.peak) <= 1e-12 * r.pull_back.peak);
  CHECK(r.gauge_pull_back.peak_time == r.pull_back.peak_time);
  CHECK(r.gauge_pull_back.minimum_time == r.pull_back.minimum_time);
  report("E8 spall, free-surface gauge", "pull-back (m/s)", format_number("%.4f (nodes)", r.pull_back.value()),
         r.gauge_pull_back.value(),
         format_number("%.1e relative", std::abs(r.gauge_pull_back.value() / r.pull_back.value() - 1.0)), r.zones,
         r.seconds);
}

namespace {

namespace ref = krug::verification::reference1d;

// The same impact in the independent 1D code (Wilkins aluminium as in spall.json).
ref::Result reference_run(double h, double yield_stress) {
  ref::Material aluminium{2785.0, 5328.0, 1.338, 2.0, 2.76e10, yield_stress};
  ref::Material target = aluminium;
  target.tensile_stress = 5.0e9;
  return ref::run({aluminium, -0.002, 0.0, static_cast<int>(std::lround(0.002 / h)), [](double) { return 1000.0; }},
                  {target, 0.0, 0.006, static_cast<int>(std::lround(0.006 / h)), nullptr}, 3.0e-6);
}

}  // namespace

// The same model (Mie-Grueneisen, Prandtl-Reuss, the instantaneous tensile criterion, a flyer in
// contact) solved by a 1D code written independently of Krug's kernels, with a different viscosity.
// Measured (Krug / reference): pull-back 441.5 / 453.1 m/s at 0.05 mm.
TEST_CASE("E8 spall against an independent 1D code: pull-back, spall plane, free-surface peak", "[fracture][E8][spall]") {
  for (const double h : {0.05e-3, 0.025e-3}) {
    const Variant krug_run = run_variant(spall_document(h));
    const ref::Result reference = reference_run(h, 3.0e8);
    REQUIRE(krug_run.failure.empty());
    const PullBack k = pull_back(krug_run.history, impact_speed), r = pull_back(reference.free_surface, impact_speed);
    const double reference_depth = 0.006 - reference.first_damage_position;
    INFO("zone " << h << " m: Krug pull-back " << k.value() << " m/s (peak " << k.peak << "), reference " << r.value()
                 << " m/s (peak " << r.peak << "); spall plane " << krug_run.depth << " m against " << reference_depth);
    report("E8 spall vs 1D reference", format_number("pull-back (m/s), %.4g mm zones", h * 1e3),
           format_number("%.1f", r.value()), k.value(), format_number("%+.1f %%", 100.0 * (k.value() / r.value() - 1.0)),
           krug_run.zones, krug_run.seconds);
    CHECK(k.value() == Approx(r.value()).epsilon(0.06));
    CHECK(std::abs(krug_run.depth - reference_depth) <= 2.0 * h);
    CHECK(k.peak == Approx(impact_speed).epsilon(0.02));
    CHECK(r.peak == Approx(impact_speed).epsilon(0.02));
    CHECK(std::abs(reference.final_momentum - reference.initial_momentum) < 1e-9 * reference.initial_momentum);
  }
}

// Where 2 sigma_*/(rho0 c0) holds: a linear elastic fluid (no strength, linear EOS with K = rho0 c0^2), a
// ramped flyer whose velocity falls linearly from v0 at its face to 0 at its rear (a triangular pulse,
// whose gradual tail alone builds the tension), sigma_* half the impact pressure rho0 c0 v0 / 2.
TEST_CASE("E8 spall: the pull-back formula where it holds (ramped flyer, linear acoustics)", "[fracture][E8][spall]") {
  const double h = 0.0125e-3, v0 = 200.0, rho0 = 2785.0, c0 = 5328.0;
  const double sigma_star = 0.5 * (0.5 * rho0 * c0 * v0);
  nlohmann::json d = spall_document(h);
  for (const char* name : {"aluminium", "aluminium_spall"}) {
    auto& m = d["materials"][name];
    m["eos"] = {{"model", "linear"}, {"bulk_modulus", rho0 * c0 * c0}};
    m.erase("strength");
  }
  d["materials"]["aluminium_spall"]["fracture"]["tensile_stress"] = sigma_star;
  d["bodies"][0]["initial"]["velocity"] = {fmt::format("{} * (1 + x / 0.002)", v0), 0.0};
  const Variant krug_run = run_variant(d);
  REQUIRE(krug_run.failure.empty());
  const PullBack k = pull_back(krug_run.history, v0);
  const double predicted = 2.0 * sigma_star / (rho0 * c0);
  INFO("pull-back " << k.value() << " m/s against " << predicted << " (peak " << k.peak << ")");
  report("E8 spall, ramped flyer (linear)", "pull-back (m/s), 0.0125 mm zones", format_number("%.1f", predicted),
         k.value(), format_number("%+.1f %%", 100.0 * (k.value() / predicted - 1.0)), krug_run.zones, krug_run.seconds);
  CHECK(k.value() == Approx(predicted).epsilon(0.10));
}

// The hydrodynamic limit of the E8 impact (Y = 0): the pull-back approaches the formula from below as
// the zones shrink (the 1D reference: 0.81, 0.83, 0.87 at 0.025, 0.0125, 0.00625 mm).
TEST_CASE("E8 spall: the hydrodynamic limit approaches the formula with refinement", "[fracture][E8][spall]") {
  std::vector<double> ratio;
  for (const double h : {0.025e-3, 0.0125e-3}) {
    nlohmann::json d = spall_document(h);
    for (const char* name : {"aluminium", "aluminium_spall"}) d["materials"][name].erase("strength");
    const Variant krug_run = run_variant(d);
    REQUIRE(krug_run.failure.empty());
    const double predicted = 2.0 * 5.0e9 / (2785.0 * 5328.0);
    ratio.push_back(pull_back(krug_run.history, impact_speed).value() / predicted);
    report("E8 spall, Y = 0", format_number("pull-back / formula, %.4g mm zones", h * 1e3), "0.83-0.95", ratio.back(),
           "", krug_run.zones, krug_run.seconds);
  }
  INFO("ratios at 0.025 and 0.0125 mm: " << ratio[0] << ", " << ratio[1]);
  CHECK(ratio[1] >= 0.83);
  CHECK(ratio[1] <= 0.95);
  CHECK(ratio[1] > ratio[0]);
}
