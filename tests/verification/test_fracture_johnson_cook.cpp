// E9 of verification.md: the Johnson-Cook damage law (krug/fracture/johnson_cook.hpp) in a run. A bar
// pulled at constant speed by a velocity condition on one end, its other end on a symmetry plane, with
// the initial velocity already the homogeneous stretching field (u = v x / L) so that no start-up wave
// crosses it; the bar stays homogeneous (a hardening modulus well above the flow stress keeps it short
// of necking: Considere, d sigma / d eps = H = 2 GPa stays above sigma = 0.3 + 2 eps_p <= 0.75 GPa up to
// eps_p = 0.225).
//
//   - uniaxial tension: an axisymmetric rod with a free lateral surface, triaxiality 1/3;
//   - plane-strain tension: a planar strip (no out-of-plane strain) with a free side, whose
//       triaxiality tends to 1/sqrt(3) = 0.577 once it flows (sigma_zz = sigma_xx / 2).
//
// The failing zone (the first damaged) is followed step by step: its plastic strain increment and
// strain rate, its triaxiality -p / sigma_vm as the run reaches it. The prediction integrates
// D_ref = sum d eps_p / eps_f with eps_f written here from Johnson & Cook (1985) eq. (4) and Table 1
// (2024-T351: D1 0.13, D2 0.13, D3 -1.5, D4 0.011, D5 0), at eta = 1/3 for the rod and at the measured
// triaxiality for the strip; the zone must fail within one step's plastic strain increment of the strain at
// which D_ref reaches 1. The ledgers (mass, total energy with the boundary work) close to round-off
// through the damage. The bars' damaged zones never loosen (they keep stretching at constant volume), so
// a third case, a brittle expanding block, takes damaged zones through conversion to free elements.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "krug/krug.hpp"
#include "verification_support.hpp"

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

namespace {

// JC85 Table 1, 2024-T351 aluminium.
constexpr double d1 = 0.13, d2 = 0.13, d3 = -1.5, d4 = 0.011;

double jc85_fracture_strain(double eta, double plastic_strain_rate) {
  return (d1 + d2 * std::exp(d3 * eta)) * (1.0 + d4 * std::log(std::max(plastic_strain_rate, 1.0)));
}

fracture::JohnsonCookDamage damage_law() {
  fracture::JohnsonCookDamage law;
  law.d1 = d1;
  law.d2 = d2;
  law.d3 = d3;
  law.d4 = d4;
  law.d5 = 0.0;
  return law;
}

constexpr double length = 0.01;  // m
constexpr double half_width = 0.002;  // m: the rod's radius, the strip's half width
constexpr double rate = 1000.0;  // 1/s, nominal v / L
constexpr double speed = rate * length;

// Wilkins aluminium (E1/E4 of verification.md: rho0 2785, K 79.06 GPa, mu 27.6 GPa) with linear
// hardening Y = 300 MPa + 2 GPa eps_p.
Simulation pulled_bar(GeometryKind geometry) {
  setup::SceneDescription scene;
  scene.geometry = geometry;
  scene.materials.push_back(Material{"aluminium", 2785.0, LinearBulk{7.906e10, 2785.0}, LinearHardening{2.76e10, 3.0e8, 2.0e9}});
  scene.fracture.push_back(damage_law());
  setup::BodyDescription bar;
  bar.name = "bar";
  bar.mesh.shape = setup::RectangleMesh{generate::graded_axis(0.0, {{length, 10, 1.0}}),
                                        generate::graded_axis(0.0, {{half_width, 4, 1.0}})};
  bar.initial.velocity = std::array<setup::PointFunction, 2>{[](double x, double) { return speed * x / length; },
                                                             [](double, double) { return 0.0; }};
  const bool rz = geometry == GeometryKind::axisymmetric;
  bar.boundary = {{rz ? "z_min" : "x_min", setup::SideCondition::symmetry, {}},
                  {rz ? "z_max" : "x_max", setup::SideCondition::velocity, {speed, std::nullopt}}};
  if (!rz) bar.boundary.push_back({"y_min", setup::SideCondition::symmetry, {}});
  scene.bodies.push_back(bar);
  scene.controls.end_time = 1.0;
  return Simulation(setup::build_simulation(scene));
}

struct StepRecord {
  double increment = 0.0;  // d eps_p of the step
  double rate = 0.0;       // d eps_p / dt
  double eta = 0.0;        // -p / sigma_vm at the end of the step (the previous step's on the failing step)
};

struct Outcome {
  Index zone = -1;
  double failure_strain = 0.0;  // the zone's eps_p on the step it became damaged
  double damage = 0.0;          // its D then
  std::vector<StepRecord> history;
  double worst_energy_drift = 0.0;
  double worst_mass_error = 0.0;
  long converted = 0;
};

// Mass and energy close to round-off over a run with damage (and whatever converted), reported.
void check_ledgers(const std::string& problem, const Outcome& out, const Simulation& sim) {
  report(problem, "ledgers with damage", "round-off", out.worst_energy_drift,
         "energy " + format_number("%.2e", out.worst_energy_drift) + ", mass " + format_number("%.2e", out.worst_mass_error) +
             ", converted zones " + std::to_string(out.converted),
         sim.mesh().zones.size(), 0.0);
  CHECK(out.worst_mass_error < 1e-13);
  CHECK(out.worst_energy_drift < 1e-12);
}

double triaxiality(const ZoneState& state, Index k) {
  const StrengthZoneFields& z = state.strength;
  const double vm = std::sqrt(1.5 * (z.deviator_xx[k] * z.deviator_xx[k] + z.deviator_yy[k] * z.deviator_yy[k] +
                                     z.deviator_zz[k] * z.deviator_zz[k] + 2.0 * z.deviator_xy[k] * z.deviator_xy[k]));
  return vm > 0.0 ? -state.hydro.pressure[k] / vm : 0.0;
}

// Runs until a zone is damaged, following every zone, then `after` more steps (damaged zones loosen and
// convert) watching the ledgers.
Outcome run(Simulation& sim, long after) {
  const ZoneFields& zones = sim.mesh().zones;
  const ZoneState& zone_state = sim.zone_state();
  const Index n = zones.size();
  std::vector<std::vector<StepRecord>> histories(static_cast<std::size_t>(n));
  std::vector<double> strain_before(static_cast<std::size_t>(n), 0.0);
  Outcome out;
  long extra = -1;
  for (long cycle = 0; cycle < 100000 && extra < after; ++cycle) {
    const double t0 = sim.time();
    sim.step();
    const double dt = sim.time() - t0;
    for (Index k = 0; k < n && out.zone < 0; ++k) {
      auto& h = histories[static_cast<std::size_t>(k)];
      const double increment = zone_state.strength.plastic_strain[k] - strain_before[static_cast<std::size_t>(k)];
      strain_before[static_cast<std::size_t>(k)] = zone_state.strength.plastic_strain[k];
      // On the failing step the deviator is already zeroed: keep the previous step's triaxiality.
      const double eta = zone_state.fracture.damaged[k] ? (h.empty() ? 0.0 : h.back().eta) : triaxiality(zone_state, k);
      h.push_back({increment, increment / dt, eta});
    }
    if (out.zone < 0) {
      for (Index k = 0; k < n; ++k) {
        if (zone_state.fracture.damaged[k]) {
          out.zone = k;
          out.failure_strain = zone_state.strength.plastic_strain[k];
          out.damage = zone_state.fracture.damage[k];
          out.history = histories[static_cast<std::size_t>(k)];
          extra = 0;
          break;
        }
      }
    } else {
      ++extra;
    }
    out.worst_energy_drift = std::max(out.worst_energy_drift, sim.ledger().relative_energy_drift());
    out.worst_mass_error = std::max(out.worst_mass_error, sim.ledger().relative_mass_error());
  }
  out.converted = sim.fracture_counts(0).converted;
  return out;
}

struct Prediction {
  double strain = 0.0;      // eps_p at which D_ref reaches 1 (within the step that crosses it, or past
                            // the history at its last step's fracture strain)
  double increment = 0.0;   // the plastic strain increment of the failing zone's last step
  double mean_eta = 0.0;    // plastic-strain-weighted mean triaxiality over the history
  double mean_rate = 0.0;   // plastic-strain-weighted mean plastic strain rate
};

// D_ref = sum d eps_p / eps_f(eta, rate), eta fixed (the rod) or the measured one (the strip: fixed_eta NaN).
Prediction predict(const std::vector<StepRecord>& history, double fixed_eta) {
  Prediction p;
  double d = 0.0, strain = 0.0, weighted_eta = 0.0, weighted_rate = 0.0, last_strain_limit = 0.0;
  bool reached = false;
  for (const StepRecord& s : history) {
    if (!(s.increment > 0.0)) continue;
    const double eta = std::isnan(fixed_eta) ? s.eta : fixed_eta;
    last_strain_limit = jc85_fracture_strain(eta, s.rate);
    if (!reached && d + s.increment / last_strain_limit >= 1.0) {
      reached = true;
      p.strain = strain + (1.0 - d) * last_strain_limit;  // D_ref = 1 inside this step
    }
    d += s.increment / last_strain_limit;
    strain += s.increment;
    weighted_eta += s.eta * s.increment;
    weighted_rate += s.rate * s.increment;
    p.increment = s.increment;
  }
  if (!reached) p.strain = strain + (1.0 - d) * last_strain_limit;
  p.mean_eta = weighted_eta / strain;
  p.mean_rate = weighted_rate / strain;
  return p;
}

}  // namespace

TEST_CASE("Johnson-Cook damage: a rod in uniaxial tension fails at eps_f(1/3) (RZ)", "[verification][failure_laws]") {
  Simulation sim = pulled_bar(GeometryKind::axisymmetric);
  const Outcome out = run(sim, 2000);
  REQUIRE(out.zone >= 0);
  CHECK(sim.zone_state().fracture.damage_criterion[out.zone] == static_cast<std::uint8_t>(fracture::Criterion::johnson_cook));
  const Prediction at_third = predict(out.history, 1.0 / 3.0);
  const double formula = jc85_fracture_strain(1.0 / 3.0, at_third.mean_rate);
  report("JC damage, RZ uniaxial tension", "failure plastic strain", "D_ref(eta = 1/3) = 1", out.failure_strain,
         "predicted " + format_number("%.6f", at_third.strain) + " (one step " +
             format_number("%.2e", at_third.increment) + "); eps_f(1/3, mean rate " + format_number("%.0f", at_third.mean_rate) +
             "/s) = " + format_number("%.5f", formula) + "; measured mean eta " + format_number("%.5f", at_third.mean_eta) +
             "; D at failure " + format_number("%.5f", out.damage),
         sim.mesh().zones.size(), 0.0);
  // The rod stays uniaxial: its flowing triaxiality is 1/3 (to the radial inertia of the pull, about
  // rho (rate R)^2 = 11 Pa against 300 MPa, and the radial ringing of the elastic-plastic transition).
  CHECK(at_third.mean_eta == Approx(1.0 / 3.0).margin(1e-3));
  CHECK(std::abs(out.failure_strain - at_third.strain) <= at_third.increment * (1.0 + 1e-9));
  CHECK(out.damage >= 1.0);
  // The rate factor barely moves over the run: the single-rate formula agrees to 0.1 %.
  CHECK(out.failure_strain == Approx(formula).epsilon(1e-3));
  check_ledgers("JC damage, RZ uniaxial tension", out, sim);
}

TEST_CASE("Johnson-Cook damage: a plane-strain strip fails at eps_f of its measured triaxiality",
          "[verification][failure_laws]") {
  Simulation sim = pulled_bar(GeometryKind::planar);
  const Outcome out = run(sim, 2000);
  REQUIRE(out.zone >= 0);
  const Prediction measured = predict(out.history, std::numeric_limits<double>::quiet_NaN());
  const double at_mean = jc85_fracture_strain(measured.mean_eta, measured.mean_rate);
  const double at_ideal = jc85_fracture_strain(1.0 / std::sqrt(3.0), measured.mean_rate);
  report("JC damage, planar plane-strain tension", "failure plastic strain", "D_ref(measured eta) = 1",
         out.failure_strain, "predicted " + format_number("%.6f", measured.strain) + " (one step " +
             format_number("%.2e", measured.increment) + "); measured mean eta " + format_number("%.5f", measured.mean_eta) +
             ", eps_f there " + format_number("%.5f", at_mean) + "; eps_f(1/sqrt 3) = " + format_number("%.5f", at_ideal),
         sim.mesh().zones.size(), 0.0);
  CHECK(std::abs(out.failure_strain - measured.strain) <= measured.increment * (1.0 + 1e-9));
  // Plane strain, not uniaxial: the triaxiality lies well above 1/3, near 1/sqrt(3).
  CHECK(measured.mean_eta > 0.5);
  CHECK(measured.mean_eta < 0.6);
  check_ledgers("JC damage, planar plane-strain tension", out, sim);
}

TEST_CASE("Johnson-Cook damage: damaged zones loosen and convert, ledgers close (planar and RZ)",
          "[verification][failure_laws]") {
  // An 8 x 4 block of the same aluminium (perfectly plastic, Y0 300 MPa) expanding and shearing from
  // its initial velocity u = a (x - 2 mm) + a y / 2, v = a y, a = 1e5 1/s (the field of E8's conversion
  // test, five times faster, so that it flows plastically), with a deliberately brittle Johnson-Cook law (D1 = 0.01, D2..D5 = 0: eps_f = 0.01 at every
  // triaxiality) so that the zones fail early, then loosen beyond chi_* = 0.03 and leave the grid as
  // free elements from the surface. Mass is conserved exactly and the energy ledger closes.
  for (const GeometryKind geometry : {GeometryKind::planar, GeometryKind::axisymmetric}) {
    SimulationSetup s;
    s.geometry = geometry;
    const generate::Patch patch = generate::rectangle(s.mesh, generate::graded_axis(0.0, {{0.004, 8, 1.0}}),
                                                      generate::graded_axis(0.0, {{0.002, 4, 1.0}}), 0);
    s.materials.push_back(Material{"aluminium", 2785.0, LinearBulk{7.906e10, 2785.0}, PerfectlyPlastic{2.76e10, 3.0e8}});
    s.bodies.push_back(krug::verification::body_from("block", 0, patch));
    const double a = 1e5;
    for (Index n = 0; n < s.mesh.nodes.size(); ++n) {
      s.mesh.nodes.u[n] = a * (s.mesh.nodes.x[n] - 0.002) + 0.5 * a * s.mesh.nodes.y[n];
      s.mesh.nodes.v[n] = a * s.mesh.nodes.y[n];
    }
    fracture::JohnsonCookDamage brittle;
    brittle.d1 = 0.01;
    s.fracture.push_back(brittle);
    s.controls.end_time = 6e-6;
    Simulation sim(std::move(s));
    double worst_drift = 0.0, worst_mass = 0.0;
    while (!sim.finished()) {
      sim.step();
      worst_drift = std::max(worst_drift, sim.ledger().relative_energy_drift());
      worst_mass = std::max(worst_mass, sim.ledger().relative_mass_error());
    }
    const FractureCounts& counts = sim.fracture_counts(0);
    double largest_damage = 0.0;
    for (Index z = 0; z < sim.mesh().zones.size(); ++z) largest_damage = std::max(largest_damage, sim.zone_state().fracture.damage[z]);
    const std::string name = geometry == GeometryKind::planar ? "planar" : "RZ";
    report("JC damage, expanding block " + name, "ledgers with conversion", "round-off", worst_drift,
           "damaged " + std::to_string(counts.damaged) + ", converted " + std::to_string(counts.converted) +
               ", mass error " + format_number("%.2e", worst_mass),
           sim.mesh().zones.size(), 0.0);
    CHECK(counts.damaged > 0);
    CHECK(counts.converted > 0);
    CHECK(largest_damage >= 1.0);
    CHECK(worst_mass < 1e-13);
    CHECK(worst_drift < 1e-12);
  }
}
