// Gauges (krug/solver/gauges.hpp) against what they must measure:
//   * the E6 Taylor bar (examples/verification/taylor_bar.json): the impact face is held (slip plane)
//     and a rigid wall stops the side nodes that roll onto it; the impulse of the two force gauges
//     (held_bar_z_min and wall0) is the bar's axial momentum change, to round-off;
//   * the E1 elastic slab impact (examples/verification/slab_impact.json): the reactions of the target's
//     two slip sides, each its own channel, against the exact lateral stress of uniaxial strain;
//   * the Sod tube (examples/verification/sod.json): tracers on either side of the membrane, against
//     the exact Riemann solution (tests/data/exact/sod_t0.25.csv) at their Eulerian position and t = 0.25,
//     and their position against the exact Lagrangian one (the same mass between tracer and contact).
//   * a Johnson-Cook block: the tracer's temperature column is the model's T of its zone.
// The spall trace (free-surface gauge) is checked in test_fracture_spall.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "krug/krug.hpp"
#include "sod_measures.hpp"
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

namespace {

double column(const GaugeSampler& gauges, const std::vector<double>& values, const std::string& name) {
  const auto& columns = gauges.columns();
  const auto found = std::find(columns.begin(), columns.end(), name);
  REQUIRE(found != columns.end());
  return values.at(static_cast<std::size_t>(found - columns.begin()));
}

// Sum of m u along the first axis over the body's nodes, for the whole body (x 2 pi in RZ).
double axial_momentum(const Simulation& sim, const Body& body) {
  double p = 0.0;
  for (Index n = body.node_begin; n < body.node_end; ++n) p += sim.mesh().nodes.mass[n] * sim.mesh().nodes.u[n];
  return sim.whole_body_factor() * p;
}

}  // namespace

// Impulse against momentum. Each step the held face takes -(F + R) on its held axial components and
// the wall applies its reactions R; the bar's internal forces sum to zero axially (the control-volume
// form conserves axial momentum, docs/theory.md), so sum_n dt^n (held + wall) is exactly the change of
// sum m u. Required to 1e-10 of the momentum change: the two sides are sums of the same terms in a
// different order over ~4 000 cycles (measured: see the INFO line and docs/verification.md).
TEST_CASE("Taylor bar: the impulse of the impact-face force gauges is the bar's momentum change",
          "[gauges][E6][strength][axisymmetric]") {
  const scenario::Scenario scenario = scenario::load_scenario(example_path("taylor_bar.json"));
  REQUIRE(scenario.gauges.forces);
  Run run(scenario.setup);
  const Simulation& sim = run.simulation;
  const Body& bar = sim.bodies().front();
  GaugeSampler gauges(scenario.gauges, sim);
  const double initial = axial_momentum(sim, bar);
  std::vector<double> values;
  double peak_force = 0.0;
  advance(run, [&](const Simulation& s) {
    gauges.accumulate(s);
    gauges.sample(s, values);
    peak_force = std::max(peak_force, std::abs(column(gauges, values, "held_bar_z_min_Fz") + column(gauges, values, "wall0_Fz")));
  });
  REQUIRE(run.completed());
  gauges.sample(sim, values);
  const double held = column(gauges, values, "held_bar_z_min_Iz"), wall = column(gauges, values, "wall0_Iz");
  const double change = axial_momentum(sim, bar) - initial;
  const double ledger_held = sim.whole_body_factor() * sim.ledger().axial_boundary_impulse;
  INFO("momentum change " << change << " N s; impulse: held face " << held << ", wall " << wall << ", sum "
                          << held + wall << " (relative difference " << std::abs(held + wall - change) / std::abs(change)
                          << "); ledger's boundary impulse " << ledger_held << "; peak force " << peak_force << " N");
  CHECK(std::abs(held + wall - change) <= 1e-10 * std::abs(change));
  // The held face's impulse is the ledger's boundary impulse (the same terms, booked in the step).
  CHECK(std::abs(held - ledger_held) <= 1e-10 * std::abs(ledger_held));
  // The bar stops: most of its momentum went into the face (227 m/s, 8930 kg/m^3, 32.4 mm x pi 3.2^2 mm^2).
  CHECK(change > 0.5 * std::abs(initial));
  report("E6 Taylor bar, force gauges", "impulse held + wall (N s)", format_number("%.9g (momentum change)", change),
         held + wall, format_number("%.1e relative", std::abs(held + wall - change) / std::abs(change)),
         bar.zone_end - bar.zone_begin, run.seconds);
}

// The reaction on each held side. In the E1 slab impact the slip sides y_min and y_max hold the
// target's lateral velocity; behind the compression wave the strain is uniaxial, and the exact
// lateral stress is sigma_yy = lambda / (lambda + 2 mu) sigma_xx, sigma_xx = -rho0 c_L v / 2 with v the
// flyer's 10 m/s (examples/verification/slab_impact.json; verification.md E1). Per m of thickness, the
// y_max side then holds the target with F_y = sigma_yy c_L t (the wave has run c_L t into the target,
// t < 2 h_f / c_L) and the y_min side with -F_y. Tolerance 3 %: the captured front (about three
// zones of 0.25 mm) against the 26 zones the wave has crossed at 1 us (measured: 0.01 %). Every node
// of the one-zone-thick target is held in y, so the target's y momentum stays 0: the two sides'
// forces and the contact's (minus the pair's force on the flyer) sum to zero, to round-off. Every
// held node belongs to a side, so there is no channel for held components outside the sides.
TEST_CASE("E1 slab impact: each held side's reaction against the exact lateral stress", "[gauges][E1][contact]") {
  nlohmann::json document = nlohmann::json::parse(read_text(example_path("slab_impact.json")));
  document["gauges"] = {{"interval", 1e-7}, {"forces", true}};
  const scenario::Scenario scenario = scenario::parse_scenario(document.dump(), "slab_impact.json with force gauges");
  Run run(scenario.setup);
  GaugeSampler gauges(scenario.gauges, run.simulation);
  const std::vector<std::string>& columns = gauges.columns();
  for (const char* side : {"held_flyer_y_min", "held_flyer_y_max", "held_target_y_min", "held_target_y_max"}) {
    CHECK(std::find(columns.begin(), columns.end(), std::string(side) + "_Fy") != columns.end());
  }
  CHECK(std::find(columns.begin(), columns.end(), "held_target_Fy") == columns.end());  // every held node has its side
  const double rho = 2785.0, bulk = 7.906e10, mu = 2.76e10, flyer_speed = 10.0;
  const double wave_speed = std::sqrt((bulk + 4.0 / 3.0 * mu) / rho);
  const double lambda = bulk - 2.0 / 3.0 * mu;
  const double sigma_yy = lambda / (lambda + 2.0 * mu) * (-rho * wave_speed * flyer_speed / 2.0);
  std::vector<double> values;
  double at = -1.0;
  advance(run, [&](const Simulation& s) {
    gauges.accumulate(s);
    if (at < 0.0 && s.time() >= 1e-6) {
      gauges.sample(s, values);
      at = s.time() - s.last_time_step();  // the forces are F^n, at t^n
    }
  });
  REQUIRE(run.completed());
  REQUIRE(at > 0.0);
  const double top = column(gauges, values, "held_target_y_max_Fy");
  const double bottom = column(gauges, values, "held_target_y_min_Fy");
  const double exact = sigma_yy * wave_speed * at;
  INFO("t = " << at << " s: y_max " << top << " N/m, y_min " << bottom << " N/m, exact " << exact << " N/m (sigma_yy "
              << sigma_yy << " Pa)");
  CHECK(top == Approx(exact).epsilon(0.03));
  const double pair = column(gauges, values, "pair_flyer_target_Fy");
  INFO("the pair's force on the flyer, y: " << pair << " N/m");
  CHECK(std::abs(top + bottom - pair) <= 1e-9 * std::abs(top));
  // The slip sides hold only y: no axial force.
  CHECK(column(gauges, values, "held_target_y_max_Fx") == 0.0);
  report("E1 slab impact, held-side gauge", "y_max reaction at 1 us (N/m)", format_number("%.6g (exact)", exact), top,
         format_number("%+.2f %%", 100.0 * (top / exact - 1.0)), 60, run.seconds);
}

// Tracers in the Sod tube, 200 x 4 zones: one starting at x = 0.47 (left gas, ends between the fan's
// tail and the contact, rho*_L), one at x = 0.6 (right gas, ends between the contact and the shock,
// rho*_R). Tolerances of test_sod.cpp: a state within 3 % at any zone of its plateau (the tracer is one
// zone) and a position within one zone (its wave tolerance). The exact Lagrangian position: the tracer
// keeps the mass between itself and the contact (x_c = 0.5 + u* t), (0.5 - 0.47) x 1 on the left,
// (0.6 - 0.5) x 0.125 on the right, integrated on the exact density profile.
TEST_CASE("Sod: tracers against the exact solution at their Lagrangian position", "[sod][gauges]") {
  nlohmann::json document = nlohmann::json::parse(read_text(example_path("sod.json")));
  document["gauges"] = {{"interval", 0.01},
                        {"tracers", {{{"name", "left"}, {"position", {0.47, 0.01}}},
                                     {{"name", "right"}, {"position", {0.6, 0.01}}}}}};
  const scenario::Scenario scenario = scenario::parse_scenario(document.dump(), "sod.json with tracers");
  Run run(scenario.setup);
  GaugeSampler gauges(scenario.gauges, run.simulation);
  advance(run);
  REQUIRE(run.completed());
  std::vector<double> values;
  gauges.sample(run.simulation, values);
  const ExactProfile exact = read_exact("sod_t0.25.csv");
  const double t = 0.25, zone = 1.0 / 200.0;
  const double contact = 0.5 + sod::star_velocity * t;
  // Where the mass `m` between the tracer and the contact puts the tracer (side -1: left of it).
  const auto lagrangian = [&](double m, int side) {
    constexpr double dx = 1e-5;
    double x = contact, mass = 0.0;
    while (mass < m) {
      const double next = x + side * dx;
      mass += 0.5 * (exact.at(exact.density, x) + exact.at(exact.density, next)) * dx;
      x = next;
    }
    return x;
  };
  struct Tracer {
    const char* name;
    double expected_position;
  };
  for (const Tracer tracer : {Tracer{"left", lagrangian((0.5 - 0.47) * 1.0, -1)},
                              Tracer{"right", lagrangian((0.6 - 0.5) * 0.125, +1)}}) {
    const std::string n = tracer.name;
    const double x = column(gauges, values, n + "_x");
    const double rho = column(gauges, values, n + "_density"), p = column(gauges, values, n + "_pressure");
    const double u = column(gauges, values, n + "_vx");
    const double rho_exact = exact.at(exact.density, x), p_exact = exact.at(exact.pressure, x);
    const double u_exact = exact.at(exact.velocity, x);
    INFO(n << " tracer at x = " << x << " (exact Lagrangian position " << tracer.expected_position << "): density " << rho
           << " (exact " << rho_exact << "), pressure " << p << " (" << p_exact << "), velocity " << u << " (" << u_exact
           << ")");
    CHECK(std::abs(x - tracer.expected_position) <= zone);
    CHECK(rho == Approx(rho_exact).epsilon(0.03));
    CHECK(p == Approx(p_exact).epsilon(0.03));
    CHECK(u == Approx(u_exact).epsilon(0.03));
    // In the plateau it was meant for, not on a wave (sod_measures.hpp gives the star densities to 6 digits).
    CHECK(rho_exact == Approx(n == "left" ? sod::star_density_left : sod::star_density_right).epsilon(1e-5));
    report("Sod tracer " + n, "density at t = 0.25", format_number("%.6f", rho_exact), rho,
           format_number("%+.2f %%", 100.0 * (rho / rho_exact - 1.0)), 800, run.seconds);
    report("Sod tracer " + n, "pressure at t = 0.25", format_number("%.6f", p_exact), p,
           format_number("%+.2f %%", 100.0 * (p / p_exact - 1.0)), 800, run.seconds);
    report("Sod tracer " + n, "velocity at t = 0.25", format_number("%.6f", u_exact), u,
           format_number("%+.2f %%", 100.0 * (u / u_exact - 1.0)), 800, run.seconds);
    report("Sod tracer " + n, "position at t = 0.25", format_number("%.5f (Lagrangian)", tracer.expected_position), x,
           format_number("%.2f zones", std::abs(x - tracer.expected_position) / zone), 800, run.seconds);
  }
}

// The temperature column exists only with a Johnson-Cook material, and is its T = T_room + max(e, 0)/c_v
// (material/strength.hpp) of the tracer's zone: the library's OFHC copper (c_v 383 J/(kg K)) at
// e = 3830 J/kg, at t = 0 and after a few cycles (a block at rest: e stays put to round-off).
TEST_CASE("tracer temperature: Johnson-Cook's T of the zone", "[gauges]") {
  const std::string text = R"({
    "geometry": "planar", "end_time": 1e-6,
    "materials": { "cu": "ofhc-copper" },
    "bodies": [ { "name": "block", "material": "cu",
                  "mesh": { "type": "rectangle", "x": { "from": 0, "to": 0.01, "zones": 4 },
                                                 "y": { "from": 0, "to": 0.01, "zones": 4 } },
                  "initial": { "specific_internal_energy": 3830.0 } } ],
    "gauges": { "interval": 1e-7, "tracers": [ { "name": "t", "position": [0.004, 0.006],
                                                 "quantities": ["temperature", "specific_energy"] } ] } })";
  const scenario::Scenario scenario = scenario::parse_scenario(text, "copper block");
  Run run(scenario.setup);
  GaugeSampler gauges(scenario.gauges, run.simulation);
  REQUIRE(gauges.columns() == std::vector<std::string>{"t_temperature", "t_specific_energy"});
  const auto& jc = std::get<JohnsonCook>(run.simulation.materials().front().strength);
  std::vector<double> values;
  gauges.sample(run.simulation, values);
  CHECK(values[0] == Approx(jc.room_temperature + 3830.0 / jc.specific_heat).epsilon(1e-12));
  CHECK(jc.specific_heat == 383.0);  // the library's OFHC copper (JC83)
  for (int k = 0; k < 5; ++k) run.simulation.step();
  gauges.sample(run.simulation, values);
  CHECK(values[0] == Approx(jc.room_temperature + std::max(values[1], 0.0) / jc.specific_heat).epsilon(1e-12));
}
