#pragma once
// Measures of a Noh implosion result (verification.md E2), shared by the default-resolution tests
// and the refinement study: the shock on every row (ray) and the post-shock plateau.
//
// Exact solution at t = 0.6 (tests/data/exact/noh_*_t0.6.csv): shock at r = t/3 = 0.2; behind it
// rho = 4, 16, 64 (planar, cylindrical, spherical), at rest, e = 0.5; ahead of it
// rho = (1 + t/r)^(k-1), i.e. 1, 4, 16 just outside r = 0.2. The shock on a row is where density
// crosses half-way between the exact pre- and post-shock values. The plateau window is r >= 0.1
// (verification.md: clear of the wall-heating dip) up to 2 zones inside the measured shock on each
// row: those zones belong to the smeared front, which the position criterion judges.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "verification_support.hpp"

namespace krug::verification::noh {

inline constexpr double noh_time = 0.6;
inline constexpr double shock_radius = noh_time / 3.0;  // shock speed 1/3 (gamma 5/3, u0 = -1)
inline constexpr double shock_tolerance_zones = 2.0;     // verification.md E2
inline constexpr double plateau_tolerance = 0.10;        // verification.md E2
inline constexpr double plateau_from = 0.1;              // verification.md E2: clear of the wall-heating dip

struct NohCase {
  const char* problem;
  int dimension;        // 1 planar, 2 cylindrical, 3 spherical
  Coordinate coordinate;
};

inline double post_shock_density(int dimension) { return std::pow(4.0, dimension); }                     // 4, 16, 64
inline double pre_shock_density(int dimension) { return std::pow(1.0 + noh_time / shock_radius, dimension - 1); }  // 1, 4, 16

struct NohResult {
  ShockSurvey shock;
  PlateauFit plateau;
};

inline NohResult measure_noh(const Run& run, const NohCase& c) {
  const Mesh& mesh = run.simulation.mesh();
  const Body& gas = run.simulation.bodies().front();
  const double post = post_shock_density(c.dimension);
  const double level = 0.5 * (pre_shock_density(c.dimension) + post);
  NohResult result;
  result.shock = survey_shock(run.simulation, gas, c.coordinate, shock_radius, [&](const auto&) { return level; });
  std::vector<ZoneSample> window;
  const PatchShape shape = patch_shape(mesh, gas);
  for (int j = 0; j < shape.zones_j; ++j) {
    const auto row = row_profile(run.simulation, gas, j, c.coordinate);
    const Front f = front_from_outside(row, level);
    if (!f.found()) continue;
    for (std::size_t k = 0; k + 2 <= f.inner; ++k) {
      if (row[k].position >= plateau_from) window.push_back(row[k]);
    }
  }
  result.plateau = plateau(window, plateau_from, shock_radius, post, &ZoneSample::density);
  return result;
}

// Runs the verification.md E2 checks on a finished run and reports them: completed, energy to
// 1e-12, the shock found on every row and within 2 zones, the plateau's worst zone within 10 %.
inline void check_noh(const Run& run, const NohCase& c) {
  INFO(c.problem);
  INFO(run.failure);
  report_failure(c.problem, run);
  REQUIRE(run.completed());
  const Body& gas = run.simulation.bodies().front();
  const long zones = gas.zone_end - gas.zone_begin;
  const NohResult r = measure_noh(run, c);

  CHECK(run.simulation.ledger().relative_energy_drift() < 1e-12);  // compatible update, walls at rest
  INFO("shock on the rows: from " << r.shock.smallest << " to " << r.shock.largest << ", worst "
                                  << r.shock.worst_zones << " zones of " << r.shock.zone_size);
  CHECK(r.shock.all_found);
  if (!r.shock.all_found) {
    double peak = 0.0;
    const PatchShape shape = patch_shape(run.simulation.mesh(), gas);
    for (int j = 0; j < shape.zones_j; ++j) {
      peak = std::max(peak, peak_density(row_profile(run.simulation, gas, j, c.coordinate)));
    }
    report(c.problem, "shock: density never reaches the mid-level (peak rho)",
           format_number("%.0f", post_shock_density(c.dimension)), peak, "shock not found", zones, run.seconds);
    return;
  }
  CHECK(r.shock.worst_zones < shock_tolerance_zones);
  report(c.problem, "shock r (mean over rows; worst row)", format_number("%.4f", shock_radius), r.shock.mean,
         format_number("%.2f zones", r.shock.worst_zones), zones, run.seconds);
  report(c.problem, "shock r spread over rows", "0", r.shock.spread(),
         format_number("%.2f zones", r.shock.spread() / r.shock.zone_size), zones, run.seconds);

  INFO("plateau: mean " << r.plateau.mean << " over " << r.plateau.zones << " zones, worst zone off by "
                        << r.plateau.largest_deviation);
  REQUIRE(r.plateau.zones > 0);
  CHECK(r.plateau.largest_deviation < plateau_tolerance);
  report(c.problem, "plateau rho on [0.1, shock) (mean; worst zone)",
         format_number("%.0f", post_shock_density(c.dimension)), r.plateau.mean,
         format_number("%.1f %%", 100.0 * r.plateau.largest_deviation), zones, run.seconds);
}

}  // namespace krug::verification::noh
