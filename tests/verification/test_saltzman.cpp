// Saltzman piston (Dukowicz & Meltz 1992; verification.md E2) through the library API: a piston
// at u = 1 drives a strong shock (gamma 5/3, rho0 = 1, cold) through 100 x 10 zones skewed by
// x' = x + (0.1 - y) sin(pi x). Exact: shock speed 4/3, behind it rho = 4, p = 4/3, u = 1, e = 1/2.
// The mesh's skew must not bend the shock or spoil the state, and the mesh must not tangle through
// the wall reflection (t = 0.75) and the re-reflection from the piston (t = 0.9), up to t = 0.925.
#include <catch2/catch.hpp>

#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

namespace {

constexpr double check_time = 0.7;
constexpr double shock_speed = 4.0 / 3.0;   // strong-shock limit, (gamma + 1)/2 x piston speed
constexpr double post_shock_density = 4.0;  // (gamma + 1)/(gamma - 1)
constexpr double zone_width = 0.01;         // 100 zones on [0, 1] before compression

// verification.md E2: "shock planar within one zone at t = 0.7": the spread of the shock position
// over the 10 rows below one initial zone width; the mean within one zone of 4/3 t as well.
constexpr double planarity_tolerance = zone_width;
// Post-shock density "away from the boundaries": rows 2 to 7 (two zones clear of each slip wall),
// x from the piston + 0.05 (20 compressed zones: the wall-heating layer on the piston is a few
// zones) to the shock - 0.025 (10 compressed zones: the smeared front). The mean over this window
// within 2 % of 4: the mass behind a shock that is within about one of the 80 compressed zones of
// its place fixes the mean density to about 1 %, plus the wall-heating deficit. Every single zone
// within 10 %, the plateau criterion verification.md uses for Noh: the skewed mesh excites
// transverse noise of a few per cent in single zones (measured: mean 0.6 %, worst zone 7.6 %;
// the wall rows 0 and 9 reached 22 % before the F5 fix, which is why they are left out).
constexpr int first_row = 2, last_row = 7;
constexpr double density_mean_tolerance = 0.02;
constexpr double density_zone_tolerance = 0.10;

}  // namespace

// F5 (docs/verification.md, fixed): without the cosine factor of CSW 1998 in the edge viscosity the
// mesh tangled at t = 0.888; with it the run reaches 0.925 (shock spread at 0.7: 0.10 zones).
TEST_CASE("Saltzman piston: planar shock at t = 0.7 and no tangling up to t = 0.925", "[saltzman]") {
  scenario::Scenario scenario = load_example("saltzman.json");
  const double end_time = scenario.setup.controls.end_time;
  REQUIRE(end_time == Approx(0.925).margin(1e-12));
  scenario.setup.controls.end_time = check_time;
  Run run(scenario.setup);
  advance(run);
  INFO(run.failure);
  report_failure("Saltzman piston", run);
  REQUIRE(run.completed());

  const Simulation& sim = run.simulation;
  const Body& gas = sim.bodies().front();
  const long zones = gas.zone_end - gas.zone_begin;
  const double exact_shock = shock_speed * check_time;
  const double piston = check_time;  // the piston started at x = 0 with u = 1

  const ShockSurvey shock = survey_shock(sim, gas, Coordinate::first_axis, exact_shock,
                                         [](const auto&) { return 0.5 * (1.0 + post_shock_density); });
  INFO("shock rows from " << shock.smallest << " to " << shock.largest);
  CHECK(shock.all_found);
  CHECK(shock.spread() < planarity_tolerance);
  CHECK(std::abs(shock.mean - exact_shock) < zone_width);
  report("Saltzman piston", "shock x at t = 0.7 (mean over rows)", format_number("%.4f", exact_shock), shock.mean,
         format_number("%.2f zones", std::abs(shock.mean - exact_shock) / zone_width), zones, run.seconds);
  report("Saltzman piston", "shock x spread over the 10 rows", "0 (< 1 zone)", shock.spread(),
         format_number("%.2f zones", shock.spread() / zone_width), zones, run.seconds);

  std::vector<ZoneSample> window;
  for (int j = first_row; j <= last_row; ++j) {
    for (const ZoneSample& z : row_profile(sim, gas, j, Coordinate::first_axis)) window.push_back(z);
  }
  const PlateauFit density = plateau(window, piston + 0.05, exact_shock - 0.025, post_shock_density, &ZoneSample::density);
  INFO("post-shock density: mean " << density.mean << " over " << density.zones << " zones, worst off by "
                                   << density.largest_deviation);
  REQUIRE(density.zones > 0);
  CHECK(std::abs(density.mean / post_shock_density - 1.0) < density_mean_tolerance);
  CHECK(density.largest_deviation < density_zone_tolerance);
  report("Saltzman piston", "post-shock rho, rows 2-7 (mean; worst zone)", "4", density.mean,
         format_number("%.1f %%", 100.0 * std::abs(density.mean / post_shock_density - 1.0)) + "; " +
             format_number("%.1f %%", 100.0 * density.largest_deviation), zones, run.seconds);

  // On through the reflections: must reach t = 0.925 without a tangled zone or a collapsed step.
  run.simulation.controls().end_time = end_time;
  advance(run);
  INFO(run.failure);
  CHECK(run.completed());
  report("Saltzman piston", "reaches t = 0.925", "0.925", run.simulation.time(),
         run.completed() ? "completed" : "FAILED", zones, run.seconds);
  // Energy: the piston's work is booked as boundary work, so the total stays constant (round-off).
  CHECK(run.simulation.ledger().relative_energy_drift() < 1e-12);
}
