#pragma once
// Fracture criteria (1) of Gulidov & Shabalin (1996), point-wise, and the damaged-state rules of
// docs/theory.md §2 step 6. A criterion is enabled only when its limit is given.
//
//   |eps_1| < eps_*     eps_1 = lambda_max - 1, the largest principal elongation
//   |sigma_1| < sigma_* sigma_1 = the largest principal value of s - p I (no artificial viscosity);
//                       a compressive limit for brittle materials on the smallest principal value
//   |gamma_1| < gamma_* gamma_1 = lambda_max - lambda_min, the largest shear strain
//   e < e_*             specific internal energy
//
// lambda are the three principal stretches of the zone's deformation from its initial shape: the
// two in-plane ones from F = dx/dX (one-point quadrature on the quad) and the hoop stretch r/R in
// axisymmetric geometry (1 in planar strain). Once any limit is exceeded the zone is damaged for
// good: it resists only volumetric compression (s = 0, p = max(p, 0)). Loosening chi = 1 - rho/rho0
// for rho < rho0 measures how far it may open; chi > chi_* (or a collapsed altitude) means fully fractured.
// The paper writes the limits on absolute values; here eps_1, sigma_1 and gamma_1 are compared signed,
// as the largest stretch, the largest principal stress and the largest shear: a zone in uniform
// compression (every stretch below 1) never fails by elongation, and compression fails only through
// the separate compressive limit.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>

#include "krug/core/parameters.hpp"
#include "krug/core/vec2.hpp"
#include "krug/fracture/point_state.hpp"
#include "krug/mesh/quad.hpp"

namespace krug::fracture {

// What made a zone damaged (FractureZoneFields::damage_criterion): one of criteria (1), or a damage law's D >= 1.
enum class Criterion : std::uint8_t {
  none = 0,
  elongation,
  tensile_stress,
  compressive_stress,
  shear_strain,
  energy,
  johnson_cook,     // Johnson-Cook damage D >= 1 (johnson_cook.hpp)
  cockcroft_latham  // Cockcroft-Latham plastic work of tension W >= W_c (cockcroft_latham.hpp)
};

constexpr std::string_view criterion_name(Criterion c) {
  switch (c) {
    case Criterion::elongation: return "elongation";
    case Criterion::tensile_stress: return "tensile_stress";
    case Criterion::compressive_stress: return "compressive_stress";
    case Criterion::shear_strain: return "shear_strain";
    case Criterion::energy: return "internal_energy";
    case Criterion::johnson_cook: return "johnson_cook";
    case Criterion::cockcroft_latham: return "cockcroft_latham";
    case Criterion::none: break;
  }
  return "none";
}

constexpr double disabled = std::numeric_limits<double>::infinity();

// Criteria (1), the first failure law (failure_law.hpp): the limits of one material; infinity =
// criterion off. Its scenario model name is "criteria", the default of a `fracture` block.
struct FractureLimits {
  static constexpr std::string_view name = "criteria";
  // The zone state it reads (point_state.hpp): the principal stretches and stresses and the energy.
  static constexpr unsigned inputs = input::stretches | input::principal_stress | input::specific_energy;

  double elongation = disabled;          // eps_* (-)
  double tensile_stress = disabled;      // sigma_* (Pa), on the largest principal stress
  double compressive_stress = disabled;  // (Pa), on minus the smallest principal stress
  double shear_strain = disabled;        // gamma_* (-)
  double internal_energy = disabled;     // e_* (J/kg)
  double loosening = 0.03;               // chi_* (-)

  bool any() const {
    return std::isfinite(elongation) || std::isfinite(tensile_stress) || std::isfinite(compressive_stress) ||
           std::isfinite(shear_strain) || std::isfinite(internal_energy);
  }
};

// Erosion of a body that does not fracture (a projectile): an intact zone leaves the mesh as a free
// element when it has collapsed (smallest altitude below altitude_ratio x its initial one, or an
// inverted corner) or when its equivalent plastic strain exceeds plastic_strain. Off by default.
// Erosion is a numerical device against runaway distortion, not a failure law: its mass, momentum and
// energy are booked like any conversion, and the summary reports the eroded mass.
struct ErosionLimits {
  double altitude_ratio = 0.0;       // (-), 0: off
  double plastic_strain = disabled;  // (-), infinity: off

  bool any() const { return altitude_ratio > 0.0 || std::isfinite(plastic_strain); }
  bool collapsed(double altitude, double initial_altitude) const { return altitude < altitude_ratio * initial_altitude; }
  bool strained(double equivalent_plastic_strain) const { return equivalent_plastic_strain > plastic_strain; }
};



// In-plane principal stretches of the 2x2 deformation gradient F: the square roots of the
// eigenvalues of C = F^T F.
inline Stretches principal_stretches(double f11, double f12, double f21, double f22, double out_of_plane) {
  const double c11 = f11 * f11 + f21 * f21;
  const double c22 = f12 * f12 + f22 * f22;
  const double c12 = f11 * f12 + f21 * f22;
  const double mean = 0.5 * (c11 + c22);
  const double radius = std::sqrt(0.25 * (c11 - c22) * (c11 - c22) + c12 * c12);
  Stretches s;
  s.in_plane_max = std::sqrt(std::max(mean + radius, 0.0));
  s.in_plane_min = std::sqrt(std::max(mean - radius, 0.0));
  s.out_of_plane = out_of_plane;
  return s;
}

// Deformation gradient of a quad by one-point quadrature: F = (1/A0) sum_p x_p (x) dA0/dX_p, with the
// initial configuration's area gradients.
inline void deformation_gradient(const std::array<Vec2, 4>& current, const std::array<Vec2, 4>& initial_gradient,
                                 double initial_area, double& f11, double& f12, double& f21, double& f22) {
  const quad::Tensor2 f = quad::outer_sum(current, initial_gradient);
  const double inv = 1.0 / initial_area;
  f11 = f.xx * inv;
  f12 = f.xy * inv;
  f21 = f.yx * inv;
  f22 = f.yy * inv;
}



inline PrincipalStress principal_stress(double sxx, double syy, double sxy, double szz, double pressure) {
  const double mean = 0.5 * (sxx + syy) - pressure;
  const double radius = std::sqrt(0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy);
  const double zz = szz - pressure;
  return {std::max(mean + radius, zz), std::min(mean - radius, zz)};
}

// The first criterion exceeded, in the order of (1), or none.
inline Criterion exceeded(const FractureLimits& limits, const Stretches& stretch, const PrincipalStress& stress,
                          double specific_energy) {
  if (stretch.largest() - 1.0 > limits.elongation) return Criterion::elongation;
  if (stress.largest > limits.tensile_stress) return Criterion::tensile_stress;
  if (-stress.smallest > limits.compressive_stress) return Criterion::compressive_stress;
  if (stretch.largest() - stretch.smallest() > limits.shear_strain) return Criterion::shear_strain;
  if (specific_energy > limits.internal_energy) return Criterion::energy;
  return Criterion::none;
}

// For the driver's shortcut (damage.hpp): a zone whose principal stretches are all below this bound
// and not negative fails neither stretch criterion (the elongation's 1 + eps_* and the shear's gamma_*:
// lambda_max - lambda_min <= lambda_max), so its stretches need not be evaluated; infinity when neither
// criterion is on.
inline double stretch_bound(const FractureLimits& limits) {
  return std::min(1.0 + limits.elongation, limits.shear_strain);
}

// Whether the stress criteria are on: the principal stresses are evaluated only then (a disabled limit
// is infinite, and no stress exceeds it).
inline bool reads_principal_stress(const FractureLimits& limits) {
  return std::isfinite(limits.tensile_stress) || std::isfinite(limits.compressive_stress);
}

// Scenario parameters (krug/core/parameters.hpp), in the order they are read: each limit is optional
// and off (infinite) when absent; chi_* defaults to 0.03.
constexpr auto parameters(std::type_identity<FractureLimits>) {
  using parameter::optional;
  using parameter::positive;
  return std::array{optional(positive("elongation", &FractureLimits::elongation), disabled),
                    optional(positive("tensile_stress", &FractureLimits::tensile_stress), disabled),
                    optional(positive("compressive_stress", &FractureLimits::compressive_stress), disabled),
                    optional(positive("shear_strain", &FractureLimits::shear_strain), disabled),
                    optional(positive("internal_energy", &FractureLimits::internal_energy), disabled),
                    optional(parameter::between("loosening", &FractureLimits::loosening, 0.0, 1.0, true), 0.03)};
}

// The law's test of one zone (failure_law.hpp): criteria (1) keep no damage variable.
inline Criterion test(const FractureLimits& limits, const PointState& point, double& /*damage*/) {
  return exceeded(limits, point.stretch, point.stress, point.specific_energy);
}

// Loosening chi = 1 - rho/rho0 where the material has expanded below its reference density, else 0.
inline double loosening(double density, double reference_density) {
  return density < reference_density ? 1.0 - density / reference_density : 0.0;
}

// Fully fractured: damaged and loosened beyond chi_*, or its smallest altitude collapsed below
// f_h times the initial one (a sheared quad keeps its area, so chi alone would never trigger).
inline bool fully_fractured(double chi, double chi_limit, double altitude, double initial_altitude,
                            double altitude_ratio) {
  return chi > chi_limit || altitude < altitude_ratio * initial_altitude;
}

}  // namespace krug::fracture
