#pragma once
// Strength of isotropic elastic–plastic solids: hypoelastic Prandtl–Reuss (J2) plasticity with
// isotropic hardening, point-wise (functions of one zone's state; never a loop over a mesh).
//
// One step of the deviatoric stress s over dt (Wilkins 1964, "Calculation of elastic-plastic flow"):
//   1. objective rotation of s^n by the material spin over the step: an exact rotation by the angle
//      omega dt (default), or the Hughes–Winget (1980) midpoint rotation, which is the exact rotation
//      by 2 atan(omega dt / 2). Both are orthogonal, so s:s and det s are kept to round-off; the
//      first-order Jaumann increment dt (W s - s W) is not, and inflates |s| every step;
//   2. elastic (Hooke) trial:  s_trial = s_rotated + 2 mu dt (D - tr(D)/3 I);
//   3. radial return onto the von Mises surface sqrt(3/2 s:s) = Y(eps_p) (Wilkins 1964; the
//      closest-point projection of Simo & Hughes 1998, "Computational Inelasticity", ch. 3).
//      With linear hardening Y = Y0 + H eps_p the return is closed-form,
//        d eps_p = (sqrt(3/2) |s_trial| - Y_n) / (3 mu + H),   s = s_trial Y_{n+1} / sqrt(3/2 s_trial:s_trial);
//      Johnson–Cook (Johnson & Cook 1983) solves the same consistency condition by safeguarded Newton.
//   Plastic work density over the step: the work of the flow stress along the plastic path,
//   dW_p = integral of Y d eps_p = (Y_n + Y_{n+1}) / 2 * d eps_p (J/m^3): exact for linear hardening,
//   so the accumulated W_p is the state function Y0 eps_p + H eps_p^2 / 2; the caller multiplies by
//   the zone volume. It is a part of the internal energy, reported, never added to it (docs/theory.md §3).
//
// Components. The computational plane is (x, y) in planar geometry and (z, r) in axisymmetric
// geometry; `xx` is the first coordinate (x, or the axial z), `yy` the second (y, or r), `xy` the
// in-plane shear and `zz` the third direction: out-of-plane in planar strain, the hoop (theta theta)
// component in RZ. Strain rates are tensor components: D_xy = (dv_x/dy + dv_y/dx) / 2, not the
// engineering shear rate.
//
// Valid range: small elastic strains (|s| << mu, constant mu), any plastic strain; rate independent
// except the optional Johnson–Cook rate term. Units SI (Pa, 1/s, K, J/(kg K)).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "krug/material/parameters.hpp"

namespace krug {

// ---------------------------------------------------------------------------------------------------
// Tensors of one point
// ---------------------------------------------------------------------------------------------------

// Stress deviator (Pa), symmetric and trace-free: xx + yy + zz = 0. See the component convention above.
struct Deviator {
  double xx = 0.0;
  double yy = 0.0;
  double xy = 0.0;
  double zz = 0.0;  // out-of-plane (planar) or hoop (RZ); does not rotate in the computational plane
};

// Rate of deformation D (1/s), the symmetric part of the velocity gradient, tensor components.
struct StrainRate {
  double xx = 0.0;
  double yy = 0.0;
  double xy = 0.0;  // (dv_x/dy + dv_y/dx) / 2
  double zz = 0.0;  // hoop rate v_r / r in RZ (D_thetatheta); 0 in planar strain
};

constexpr double trace(const Deviator& s) { return s.xx + s.yy + s.zz; }

// s:t, the full double contraction of two symmetric 3x3 tensors in this storage.
constexpr double double_contraction(const Deviator& s, const Deviator& t) {
  return s.xx * t.xx + s.yy * t.yy + s.zz * t.zz + 2.0 * s.xy * t.xy;
}

// The third invariant's determinant: det [[xx, xy, 0], [xy, yy, 0], [0, 0, zz]].
constexpr double determinant(const Deviator& s) { return s.zz * (s.xx * s.yy - s.xy * s.xy); }

constexpr Deviator scaled(const Deviator& s, double factor) {
  return {factor * s.xx, factor * s.yy, factor * s.xy, factor * s.zz};
}

// von Mises equivalent stress sqrt(3 J2) = sqrt(3/2 s:s) (Pa).
inline double equivalent_stress(const Deviator& s) { return std::sqrt(1.5 * double_contraction(s, s)); }

// Equivalent (von Mises) strain rate sqrt(2/3 D':D') of the deviatoric part D' (1/s); equals
// |D_xx| in uniaxial stress of an incompressible solid. Used as the Johnson–Cook rate argument.
inline double equivalent_strain_rate(const StrainRate& rate) {
  const double mean = (rate.xx + rate.yy + rate.zz) / 3.0;
  const Deviator deviatoric{rate.xx - mean, rate.yy - mean, rate.xy, rate.zz - mean};
  return std::sqrt(2.0 / 3.0 * double_contraction(deviatoric, deviatoric));
}

// ---------------------------------------------------------------------------------------------------
// Objective rotation
// ---------------------------------------------------------------------------------------------------

// The material's angular velocity in the computational plane (rad/s, counter-clockwise from the
// first axis towards the second): omega = (dv_2/dx_1 - dv_1/dx_2) / 2. A rigid rotation
// v = Omega (-x_2, x_1) gives omega = Omega. (The spin tensor's component W_12 = (dv_1/dx_2 - dv_2/dx_1)/2
// is -omega: mind the sign.)
constexpr double in_plane_spin(double dv2_dx1, double dv1_dx2) { return 0.5 * (dv2_dx1 - dv1_dx2); }

enum class StressRotation {
  exact,         // rotation by omega dt (default)
  hughes_winget  // Q = (I - W dt/2)^-1 (I + W dt/2): rotation by 2 atan(omega dt / 2); Hughes & Winget 1980
};

// Angle (rad) by which the deviator is rotated over dt with the given scheme.
inline double rotation_angle(double spin, double dt, StressRotation method = StressRotation::exact) {
  return method == StressRotation::hughes_winget ? 2.0 * std::atan(0.5 * spin * dt) : spin * dt;
}

// cos x and sin x. Where |x| <= 1/16 (a rotation over one time step is far smaller) by the Taylor
// polynomials to x^8 and x^9, in Horner form: the first omitted terms, x^10/10! < 3e-19 and
// x^11/11! < 2e-20 |x|, are below the round-off of the results, so these are cos and sin to round-off,
// without a call to the library's; std::cos and std::sin beyond.
inline void cos_sin(double x, double& cos_x, double& sin_x) {
  if (std::abs(x) <= 0.0625) {
    const double x2 = x * x;
    cos_x = 1.0 + x2 * (-1.0 / 2.0 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0))));
    sin_x = x + x * (x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0)))));
    return;
  }
  cos_x = std::cos(x);
  sin_x = std::sin(x);
}

// s' = R s R^T, R the counter-clockwise rotation by `angle` in the computational plane; zz is unchanged.
// Written in the double angle so the in-plane trace xx + yy is kept to round-off.
inline Deviator rotate_deviator(const Deviator& s, double angle) {
  const double mean = 0.5 * (s.xx + s.yy);
  const double half_difference = 0.5 * (s.xx - s.yy);
  double cos2 = 1.0, sin2 = 0.0;
  cos_sin(2.0 * angle, cos2, sin2);
  const double axial = half_difference * cos2 - s.xy * sin2;
  return {mean + axial, mean - axial, half_difference * sin2 + s.xy * cos2, s.zz};
}

// Step 1: the deviator at t^n carried objectively with the material's spin over dt.
inline Deviator rotate_objectively(const Deviator& s, double spin, double dt,
                                   StressRotation method = StressRotation::exact) {
  return rotate_deviator(s, rotation_angle(spin, dt, method));
}

// ---------------------------------------------------------------------------------------------------
// Elastic trial and radial return
// ---------------------------------------------------------------------------------------------------

// Step 2: s_trial = s_rotated + 2 mu dt (D - tr(D)/3 I).
inline Deviator hooke_trial(const Deviator& rotated, const StrainRate& rate, double shear_modulus, double dt) {
  const double mean = (rate.xx + rate.yy + rate.zz) / 3.0;
  const double factor = 2.0 * shear_modulus * dt;
  return {rotated.xx + factor * (rate.xx - mean), rotated.yy + factor * (rate.yy - mean),
          rotated.xy + factor * rate.xy, rotated.zz + factor * (rate.zz - mean)};
}

struct PlasticReturn {
  Deviator deviator;                     // s^{n+1} (Pa), on or inside the yield surface
  double plastic_strain_increment = 0.0; // d eps_p (-), >= 0
  double plastic_work_density = 0.0;     // (Y_n + Y_{n+1}) / 2 * d eps_p (J/m^3); times zone volume
  bool yielded = false;                  // the trial lay outside the yield surface
};

// Step 3, closed form for linear isotropic hardening: Y_n = yield stress at the start of the step
// (Pa), H = dY/d eps_p (Pa, 0 for perfect plasticity). A trial on or inside the surface is returned
// unchanged. Y_n < 0 is treated as 0. If 3 mu + H <= 0 (no elastic stiffness) the deviator is
// scaled to the surface with no plastic strain.
inline PlasticReturn radial_return(const Deviator& trial, double shear_modulus, double yield_stress,
                                   double hardening_modulus = 0.0) {
  // Written without branches (a trial inside the surface is scaled by exactly 1), so that a loop over
  // zones that calls it vectorises.
  const double start_yield = std::max(yield_stress, 0.0);
  const double trial_equivalent = equivalent_stress(trial);
  const bool yielded = trial_equivalent > start_yield;
  const double stiffness = 3.0 * shear_modulus + hardening_modulus;
  const double return_increment = stiffness > 0.0 ? (trial_equivalent - start_yield) / stiffness : 0.0;
  const double increment = yielded ? return_increment : 0.0;
  const double end_yield = std::max(start_yield + hardening_modulus * increment, 0.0);
  const double factor = yielded ? end_yield / trial_equivalent : 1.0;
  const double work = yielded ? 0.5 * (start_yield + end_yield) * increment : 0.0;
  return {scaled(trial, factor), increment, work, yielded};
}

// ---------------------------------------------------------------------------------------------------
// Strength models: aggregates of named parameters. Each has the data member `shear_modulus` (Pa),
// flow_stress(eps_p, strain_rate, temperature) = the current yield stress Y (Pa), its slope
// hardening_slope = dY/d eps_p (Pa) (the last two arguments matter only for Johnson–Cook), and `name`.
// (The parameter Y0 is the data member `yield_stress`, hence the function's different name.)
// ---------------------------------------------------------------------------------------------------

// Inputs of a yield law at one point, at the start of the step.
struct PlasticState {
  double plastic_strain = 0.0;  // accumulated equivalent plastic strain eps_p (-)
  double strain_rate = 0.0;     // equivalent strain rate, equivalent_strain_rate(D) (1/s); Johnson–Cook only
  double temperature = 0.0;     // K; Johnson–Cook only (at or below room temperature: no softening)
};

// No shear strength: the deviator is zero (fluids; mu = 0 and Y = 0 reduce the solver to hydro).
struct NoStrength {
  static constexpr std::string_view name = "none";
  static constexpr double shear_modulus = 0.0;
  double flow_stress(double /*plastic_strain*/, double /*strain_rate*/ = 0.0, double /*temperature*/ = 0.0) const {
    return 0.0;
  }
  double hardening_slope(double /*plastic_strain*/, double /*strain_rate*/ = 0.0, double /*temperature*/ = 0.0) const {
    return 0.0;
  }
};

// Linear elastic deviator, never yields (Y -> infinity).
struct Elastic {
  double shear_modulus = 0.0;  // mu (Pa)

  static constexpr std::string_view name = "elastic";
  double flow_stress(double /*plastic_strain*/, double /*strain_rate*/ = 0.0, double /*temperature*/ = 0.0) const {
    return std::numeric_limits<double>::infinity();
  }
  double hardening_slope(double /*plastic_strain*/, double /*strain_rate*/ = 0.0, double /*temperature*/ = 0.0) const {
    return 0.0;
  }
};

// Prandtl–Reuss elastic–perfectly plastic: constant yield stress.
struct PerfectlyPlastic {
  double shear_modulus = 0.0;  // mu (Pa)
  double yield_stress = 0.0;   // Y0 (Pa), von Mises flow stress (uniaxial yield stress)

  static constexpr std::string_view name = "perfectly_plastic";
  double flow_stress(double /*plastic_strain*/, double /*strain_rate*/ = 0.0, double /*temperature*/ = 0.0) const {
    return yield_stress;
  }
  double hardening_slope(double /*plastic_strain*/, double /*strain_rate*/ = 0.0, double /*temperature*/ = 0.0) const {
    return 0.0;
  }
};

// Linear isotropic hardening: Y = Y0 + H eps_p, H the plastic (hardening) modulus, i.e. the slope of
// the flow stress against equivalent plastic strain (E H_t/(E - E_t) in terms of a bilinear uniaxial
// curve with tangent modulus E_t).
struct LinearHardening {
  double shear_modulus = 0.0;      // mu (Pa)
  double yield_stress = 0.0;       // Y0 (Pa), at eps_p = 0
  double hardening_modulus = 0.0;  // H = dY/d eps_p (Pa)

  static constexpr std::string_view name = "linear_hardening";
  double flow_stress(double plastic_strain, double /*strain_rate*/ = 0.0, double /*temperature*/ = 0.0) const {
    return yield_stress + hardening_modulus * plastic_strain;
  }
  double hardening_slope(double /*plastic_strain*/, double /*strain_rate*/ = 0.0, double /*temperature*/ = 0.0) const {
    return hardening_modulus;
  }
};

// Johnson & Cook (1983): Y = (A + B eps_p^n) (1 + C ln(max(rate / rate0, 1))) (1 - T*^m),
// T* = (T - T_room) / (T_melt - T_room) clamped to [0, 1] (Y = 0 at melt). The rate factor is cut off
// below the reference rate, as is usual. The rate argument is the total equivalent strain rate of the
// step and the temperature is that at the start of the step, both held fixed during the return
// (explicit in rate and temperature). Defaults switch the rate and thermal terms off.
struct JohnsonCook {
  double shear_modulus = 0.0;                // mu (Pa)
  double yield_stress = 0.0;                 // A (Pa), at eps_p = 0, reference rate, room temperature
  double hardening_coefficient = 0.0;        // B (Pa)
  double hardening_exponent = 1.0;           // n (-)
  double strain_rate_coefficient = 0.0;      // C (-)
  double reference_strain_rate = 1.0;        // rate0 (1/s)
  double thermal_softening_exponent = 1.0;   // m (-)
  double room_temperature = 293.0;           // T_room (K)
  double melt_temperature = std::numeric_limits<double>::infinity();  // T_melt (K); infinite: no softening
  double specific_heat = 0.0;                // c_v (J/(kg K)), for temperature_from_energy only

  static constexpr std::string_view name = "johnson_cook";

  double rate_factor(double strain_rate) const {
    if (!(strain_rate > reference_strain_rate) || !(reference_strain_rate > 0.0)) return 1.0;
    return 1.0 + strain_rate_coefficient * std::log(strain_rate / reference_strain_rate);
  }
  double thermal_factor(double temperature) const {
    const double range = melt_temperature - room_temperature;
    if (!(range > 0.0)) return 1.0;
    const double homologous = std::clamp((temperature - room_temperature) / range, 0.0, 1.0);
    return homologous > 0.0 ? 1.0 - std::pow(homologous, thermal_softening_exponent) : 1.0;
  }
  double flow_stress(double plastic_strain, double strain_rate = 0.0, double temperature = 0.0) const {
    const double strain = std::max(plastic_strain, 0.0);
    return (yield_stress + hardening_coefficient * std::pow(strain, hardening_exponent)) *
           rate_factor(strain_rate) * thermal_factor(temperature);
  }
  // dY/d eps_p; infinite at eps_p = 0 when n < 1 (the return handles it by bisection).
  double hardening_slope(double plastic_strain, double strain_rate = 0.0, double temperature = 0.0) const {
    const double strain = std::max(plastic_strain, 0.0);
    double slope = 0.0;
    if (hardening_coefficient != 0.0 && hardening_exponent != 0.0) {
      if (strain > 0.0) {
        slope = hardening_coefficient * hardening_exponent * std::pow(strain, hardening_exponent - 1.0);
      } else if (hardening_exponent < 1.0) {
        slope = std::copysign(std::numeric_limits<double>::infinity(), hardening_coefficient);
      } else if (hardening_exponent == 1.0) {
        slope = hardening_coefficient;
      }
    }
    return slope * rate_factor(strain_rate) * thermal_factor(temperature);
  }
  // T = T_room + max(e, 0) / c_v: all internal energy counted as heat (the cold compression energy
  // too, an overestimate in strong compression). Without a specific heat: room temperature.
  double temperature_from_energy(double specific_energy) const {
    return specific_heat > 0.0 ? room_temperature + std::max(specific_energy, 0.0) / specific_heat
                               : room_temperature;
  }
};

// Scenario parameters (parameters.hpp). Johnson–Cook's optional terms default to off; its melt
// temperature and specific heat default to 1e9 (no softening, no heating) in a scenario.
constexpr auto parameters(std::type_identity<Elastic>) {
  return std::array{parameter::positive("shear_modulus", &Elastic::shear_modulus)};
}
constexpr auto parameters(std::type_identity<PerfectlyPlastic>) {
  return std::array{parameter::positive("shear_modulus", &PerfectlyPlastic::shear_modulus),
                    parameter::non_negative("yield_stress", &PerfectlyPlastic::yield_stress)};
}
constexpr auto parameters(std::type_identity<LinearHardening>) {
  return std::array{parameter::positive("shear_modulus", &LinearHardening::shear_modulus),
                    parameter::non_negative("yield_stress", &LinearHardening::yield_stress),
                    parameter::non_negative("hardening_modulus", &LinearHardening::hardening_modulus)};
}
constexpr auto parameters(std::type_identity<JohnsonCook>) {
  using parameter::optional;
  using parameter::positive;
  using parameter::non_negative;
  return std::array{positive("shear_modulus", &JohnsonCook::shear_modulus),
                    non_negative("yield_stress", &JohnsonCook::yield_stress),
                    optional(non_negative("hardening_coefficient", &JohnsonCook::hardening_coefficient), 0.0),
                    optional(positive("hardening_exponent", &JohnsonCook::hardening_exponent), 1.0),
                    optional(non_negative("strain_rate_coefficient", &JohnsonCook::strain_rate_coefficient), 0.0),
                    optional(positive("reference_strain_rate", &JohnsonCook::reference_strain_rate), 1.0),
                    optional(positive("thermal_softening_exponent", &JohnsonCook::thermal_softening_exponent), 1.0),
                    optional(positive("room_temperature", &JohnsonCook::room_temperature), 293.0),
                    optional(positive("melt_temperature", &JohnsonCook::melt_temperature), 1.0e9),
                    optional(positive("specific_heat", &JohnsonCook::specific_heat), 1.0e9)};
}

// ---------------------------------------------------------------------------------------------------
// Radial return per model (step 3) and the whole deviator update (steps 1-3)
// ---------------------------------------------------------------------------------------------------

inline PlasticReturn radial_return(const NoStrength& /*model*/, const Deviator& /*trial*/,
                                   const PlasticState& /*state*/) {
  return {Deviator{}, 0.0, 0.0, false};
}

inline PlasticReturn radial_return(const Elastic& /*model*/, const Deviator& trial, const PlasticState& /*state*/) {
  return {trial, 0.0, 0.0, false};
}

inline PlasticReturn radial_return(const PerfectlyPlastic& model, const Deviator& trial,
                                   const PlasticState& /*state*/) {
  return radial_return(trial, model.shear_modulus, model.yield_stress, 0.0);
}

inline PlasticReturn radial_return(const LinearHardening& model, const Deviator& trial, const PlasticState& state) {
  return radial_return(trial, model.shear_modulus, model.flow_stress(state.plastic_strain),
                       model.hardening_modulus);
}

// Nonlinear hardening: solve g(d) = q_trial - 3 mu d - Y(eps_p + d) = 0 for d in [0, q_trial / (3 mu)]
// (g decreases for non-softening Y, g(0) > 0 when yielding, g(q_trial / (3 mu)) = -Y <= 0) by Newton
// steps kept inside the bracket, bisection otherwise.
inline PlasticReturn radial_return(const JohnsonCook& model, const Deviator& trial, const PlasticState& state) {
  const double strain = std::max(state.plastic_strain, 0.0);
  const auto yield_at = [&](double increment) {
    return std::max(model.flow_stress(strain + increment, state.strain_rate, state.temperature), 0.0);
  };
  const double start_yield = yield_at(0.0);
  const double trial_equivalent = equivalent_stress(trial);
  if (trial_equivalent <= start_yield) return {trial, 0.0, 0.0, false};
  const double elastic_stiffness = 3.0 * model.shear_modulus;
  if (!(elastic_stiffness > 0.0)) {
    return {scaled(trial, start_yield / trial_equivalent), 0.0, 0.0, true};
  }

  double lower = 0.0;
  double upper = trial_equivalent / elastic_stiffness;
  const double tolerance = 4.0 * std::numeric_limits<double>::epsilon() * trial_equivalent;
  // First guess: the linearised return (the closed form for linear hardening), kept in the bracket.
  const double start_slope = model.hardening_slope(strain, state.strain_rate, state.temperature);
  double increment = (trial_equivalent - start_yield) / (elastic_stiffness + start_slope);
  if (!(increment > lower && increment < upper)) increment = 0.5 * (lower + upper);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double residual = trial_equivalent - elastic_stiffness * increment - yield_at(increment);
    if (std::abs(residual) <= tolerance) break;
    if (residual > 0.0) {
      lower = increment;
    } else {
      upper = increment;
    }
    if (upper - lower <= std::numeric_limits<double>::epsilon() * upper) break;
    const double slope =
        elastic_stiffness + model.hardening_slope(strain + increment, state.strain_rate, state.temperature);
    double next = increment + residual / slope;
    if (!(next > lower && next < upper)) next = 0.5 * (lower + upper);
    increment = next;
  }
  const double end_yield = yield_at(increment);
  return {scaled(trial, end_yield / trial_equivalent), increment, 0.5 * (start_yield + end_yield) * increment,
          true};
}

// Steps 1-3 for one point: rotate s^n by spin over dt, add the Hooke increment, return to the yield
// surface. `rate` and `spin` are those of the step (from u^{n+1/2} on the mid-step geometry) and `dt`
// the step they act over. The caller adds d eps_p to the zone's plastic strain and
// plastic_work_density * volume to its plastic-work report.
template <class StrengthModel>
[[gnu::always_inline]] inline PlasticReturn update_deviator(const StrengthModel& model, const Deviator& previous, const StrainRate& rate,
                              double spin, double dt, const PlasticState& state,
                              StressRotation rotation = StressRotation::exact) {
  const Deviator rotated = rotate_objectively(previous, spin, dt, rotation);
  const Deviator trial = hooke_trial(rotated, rate, model.shear_modulus, dt);
  return radial_return(model, trial, state);
}

}  // namespace krug
