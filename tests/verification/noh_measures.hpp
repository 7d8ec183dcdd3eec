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
  result.shock = survey_shock(mesh, gas, c.coordinate, shock_radius, [&](const auto&) { return level; });
  std::vector<ZoneSample> window;
  const PatchShape shape = patch_shape(mesh, gas);
  for (int j = 0; j < shape.zones_j; ++j) {
    const auto row = row_profile(mesh, gas, j, c.coordinate);
    const Front f = front_from_outside(row, level);
    if (!f.found()) continue;
    for (std::size_t k = 0; k + 2 <= f.inner; ++k) {
      if (row[k].position >= plateau_from) window.push_back(row[k]);
    }
  }
  result.plateau = plateau(window, plateau_from, shock_radius, post, &ZoneSample::density);
  return result;
}

}  // namespace krug::verification::noh
