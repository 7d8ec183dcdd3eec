// Convergence studies (ctest label `convergence`; verification.md E2): the Sod L1 density error at
// four resolutions with its observed order, on the planar strip and along the RZ axis, and a finer
// run of the cylindrical Noh problem than the default-resolution tests can afford.
//
// KRUG_CONVERGENCE_SCALE (default 1: the full study) scales every resolution; CI runs a fraction
// (0.5: Sod at 50 to 400 zones and the Noh run at the default 50 x 20, a few seconds in all).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "noh_measures.hpp"
#include "sod_measures.hpp"
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

namespace {

int scaled(int zones) { return std::max(4, static_cast<int>(std::lround(zones * convergence_scale()))); }

struct Level {
  int zones = 0;
  double l1 = 0.0;
  double seconds = 0.0;
};

// Sod along x (or z) at `along` zones and 4 across, from `file` whose tube has 200 zones.
Level sod_level(const std::string& file, int along) {
  const scenario::Scenario scenario = load_example(file, {zones(200, along)});
  const Run run = run_to_end(scenario);
  INFO(file << " at " << along << " zones: " << run.failure);
  REQUIRE(run.completed());
  const Body& tube = run.simulation.bodies().front();
  return {along, density_l1_error(run.simulation, tube, read_exact("sod_t0.25.csv")), run.seconds};
}

// Observed order between successive doublings, log2(E_n / E_2n). For a flow with a shock and a
// contact the L1 error of a scheme that is first order at discontinuities falls as h^1 (the jumps
// are captured in a fixed number of zones and a Lagrangian contact does not spread), so each
// observed order must lie in [0.8, 1.2] (measured: 0.96 to 1.05 planar from 100 to 800 zones,
// docs/verification.md); the smooth parts converge faster but weigh less.
constexpr double order_low = 0.8, order_high = 1.2;

void sod_study(const std::string& problem, const std::string& file) {
  std::vector<Level> levels;
  for (const int n : {100, 200, 400, 800}) levels.push_back(sod_level(file, scaled(n)));
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const double order = k == 0 ? 0.0 : std::log2(levels[k - 1].l1 / levels[k].l1);
    report(problem, "L1 density error at " + std::to_string(levels[k].zones) + " zones",
           k == 0 ? "-" : "order 1", levels[k].l1, k == 0 ? "-" : format_number("order %.2f", order),
           4L * levels[k].zones, levels[k].seconds);
    // Below 50 zones the fan and the star region span too few zones for the asymptotic regime
    // (measured 1.59 from 25 to 50 zones), so reduced-scale runs check only the finer pairs.
    if (k == 0 || levels[k - 1].zones < 50) continue;
    INFO(problem << ": " << levels[k - 1].zones << " -> " << levels[k].zones << " zones, L1 " << levels[k - 1].l1
                 << " -> " << levels[k].l1 << ", observed order " << order);
    CHECK(order > order_low);
    CHECK(order < order_high);
  }
}

}  // namespace

TEST_CASE("Convergence: Sod L1 density error on a planar strip is first order", "[convergence][sod]") {
  sod_study("Sod convergence, planar strip", "sod.json");
}

TEST_CASE("Convergence: Sod L1 density error along the RZ axis is first order", "[convergence][sod][axisymmetric]") {
  sod_study("Sod convergence, RZ rod (control volume)", "sod_axisymmetric.json");
}

TEST_CASE("Refinement: Noh cylindrical on a finer polar mesh meets the E2 criteria", "[convergence][noh]") {
  // The default test runs 50 x 20 zones; here 100 x 40 (scaled, never below the default), judged
  // with the same verification.md criteria (noh_measures.hpp): shock within 2 zones, plateau within
  // 10 %. (200 x 80 would take about 5 minutes at 250 ns per zone-cycle: the centre zones set the step.)
  const int radial = std::max(50, scaled(100)), angular = radial * 2 / 5;
  const scenario::Scenario scenario = load_example("noh_cylindrical.json", {zones(50, radial), zones(20, angular)});
  const Run run = run_to_end(scenario);
  INFO(radial << " x " << angular << " zones: " << run.failure);
  REQUIRE(run.completed());
  const noh::NohResult r = noh::measure_noh(run, {"Noh, cylindrical", 2, Coordinate::radius});
  const long zone_count = static_cast<long>(radial) * angular;
  report("Noh refinement, cylindrical (XY polar)", "shock r (mean; worst row)", "0.2000", r.shock.mean,
         format_number("%.2f zones", r.shock.worst_zones), zone_count, run.seconds);
  report("Noh refinement, cylindrical (XY polar)", "plateau rho (mean; worst zone)", "16", r.plateau.mean,
         format_number("%.1f %%", 100.0 * r.plateau.largest_deviation), zone_count, run.seconds);
  CHECK(r.shock.worst_zones < noh::shock_tolerance_zones);
  REQUIRE(r.plateau.zones > 0);
  CHECK(r.plateau.largest_deviation < noh::plateau_tolerance);
}
