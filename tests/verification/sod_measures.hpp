#pragma once
// Measures of a Sod shock-tube result (verification.md E2), shared by the default-resolution tests
// and the convergence study: wave positions, plateau states and the L1 density error.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "verification_support.hpp"

namespace krug::verification::sod {

// Exact star state and wave positions at t = 0.25 (verification.md E2; the exact Riemann solution of
// Sod's problem, gamma 1.4, left (1, 0, 1), right (0.125, 0, 0.1), membrane x = 0.5).
inline constexpr double star_pressure = 0.303130;
inline constexpr double star_velocity = 0.927453;
inline constexpr double star_density_left = 0.426319;
inline constexpr double star_density_right = 0.265574;
inline constexpr double head = 0.2042, tail = 0.4824, contact = 0.7319, shock = 0.9380;
inline constexpr double left_density = 1.0, right_density = 0.125;

// Each wave is located where density crosses a level: jumps at their mid-level (the exact jump
// position), the rarefaction's ends 10 % of the way into the fan, where the exact profile is steep
// but the numerical rounding of the kink is small. The numerical crossing is compared with the
// exact profile's crossing of the same level (tests/data/exact/sod_t0.25.csv).
struct Wave {
  const char* name;
  double level;
};
inline const std::array<Wave, 4> waves{{
    {"rarefaction head", left_density - 0.1 * (left_density - star_density_left)},
    {"rarefaction tail", star_density_left + 0.1 * (left_density - star_density_left)},
    {"contact", 0.5 * (star_density_left + star_density_right)},
    {"shock", 0.5 * (star_density_right + right_density)},
}};

struct WaveError {
  double exact = 0.0;      // exact crossing of the level
  double position = 0.0;   // numerical crossing, on the row with the largest error
  double zones = 0.0;      // largest |position - exact| over the rows, in local zone widths
};

// Largest error over the rows of the strip, in local zone sizes (the spacing of the two zone centres
// around the crossing).
inline std::array<WaveError, 4> wave_errors(const Simulation& simulation, const Body& body, const ExactProfile& exact) {
  const Mesh& mesh = simulation.mesh();
  std::array<WaveError, 4> errors{};
  const PatchShape shape = patch_shape(mesh, body);
  for (std::size_t w = 0; w < waves.size(); ++w) {
    errors[w].exact = exact.crossing_from_right(exact.density, waves[w].level);
    errors[w].zones = -1.0;
  }
  for (int j = 0; j < shape.zones_j; ++j) {
    const auto row = row_profile(simulation, body, j, Coordinate::first_axis);
    for (std::size_t w = 0; w < waves.size(); ++w) {
      const Front f = front_from_outside(row, waves[w].level);
      const double zones = f.found() ? std::abs(f.position - errors[w].exact) / f.spacing
                                     : std::numeric_limits<double>::infinity();
      if (zones > errors[w].zones) {
        errors[w].zones = zones;
        errors[w].position = f.position;
      }
    }
  }
  return errors;
}

// Plateau windows, per row, counted in zones from the measured waves: the star region between the
// rarefaction tail and the shock, split at the contact. `margin_tail` zones are left out after the
// tail (the overshoot of u and undershoot of p that a Lagrangian scheme leaves at the tail of a
// centred rarefaction, about 8 zones wide at 200 zones), `margin` zones next to the contact (wall
// heating) and the shock (its smeared profile).
struct Plateaus {
  PlateauFit pressure, velocity, density_left, density_right;
};

inline constexpr int margin_tail = 10;
inline constexpr int margin = 4;

inline Plateaus plateaus(const Simulation& simulation, const Body& body) {
  const Mesh& mesh = simulation.mesh();
  const PatchShape shape = patch_shape(mesh, body);
  std::vector<ZoneSample> star, star_left, star_right;
  for (int j = 0; j < shape.zones_j; ++j) {
    const auto row = row_profile(simulation, body, j, Coordinate::first_axis);
    const Front tail_front = front_from_outside(row, waves[1].level);
    const Front contact_front = front_from_outside(row, waves[2].level);
    const Front shock_front = front_from_outside(row, waves[3].level);
    if (!tail_front.found() || !contact_front.found() || !shock_front.found()) continue;
    const std::size_t first = tail_front.inner + 1 + margin_tail;
    const std::size_t contact_left = contact_front.inner, contact_right = contact_front.inner + 1;
    const std::size_t last = shock_front.inner;  // the zone just behind the shock
    for (std::size_t k = first; k + margin <= last; ++k) star.push_back(row[k]);
    for (std::size_t k = first; k + margin <= contact_left; ++k) star_left.push_back(row[k]);
    for (std::size_t k = contact_right + margin; k + margin <= last; ++k) star_right.push_back(row[k]);
  }
  const double everywhere = std::numeric_limits<double>::infinity();
  return {plateau(star, -everywhere, everywhere, star_pressure, &ZoneSample::pressure),
          plateau(star, -everywhere, everywhere, star_velocity, &ZoneSample::velocity),
          plateau(star_left, -everywhere, everywhere, star_density_left, &ZoneSample::density),
          plateau(star_right, -everywhere, everywhere, star_density_right, &ZoneSample::density)};
}

}  // namespace krug::verification::sod
