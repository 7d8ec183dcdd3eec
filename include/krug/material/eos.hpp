#pragma once
// Equations of state p(rho, e). Each model is a small value type with named parameters (SI) and pure
// functions; the solver picks the model once per body (std::visit outside the zone loop).
//
//   sound_speed_squared: the adiabatic (dp/drho)_s = (dp/drho)_e + p/rho^2 (dp/de)_rho
//   shock_slope: the coefficient of the quadratic artificial viscosity, (gamma + 1)/4 for an ideal gas
//                (strong-shock limit, Caramana, Shashkov & Whalen 1998) and s/2 for a linear Us-up fit.
#include <algorithm>
#include <concepts>
#include <limits>
#include <string_view>
#include <variant>

#include "krug/material/parameters.hpp"

namespace krug {

// Ideal (gamma-law) gas: p = (gamma - 1) rho e.
struct IdealGas {
  double gamma = 1.4;  // ratio of specific heats (-), > 1

  static constexpr std::string_view name = "ideal_gas";
  double pressure(double rho, double e) const { return (gamma - 1.0) * rho * e; }
  double sound_speed_squared(double rho, double /*e*/, double p) const {
    return rho > 0.0 ? std::max(gamma * p / rho, 0.0) : 0.0;
  }
  double shock_slope() const { return 0.25 * (gamma + 1.0); }
  // A gas: no bulk modulus of condensed matter (its constants are often non-dimensional).
  double reference_bulk_modulus() const { return 0.0; }
};

// Stiffened gas (Harlow & Amsden 1971; Saurel & Abgrall, J. Comput. Phys. 150, 1999): a liquid or a
// gas under a constant attraction p_inf, p = (gamma - 1) rho e - gamma p_inf. It is the ideal gas in
// the variable p + p_inf: the same adiabats and shock jump conditions with p replaced by p + p_inf,
// and c^2 = gamma (p + p_inf) / rho. Water: gamma = 4.4, p_inf = 6e8 Pa (Saurel & Abgrall 1999), which
// gives c = 1 625 m/s at 1 000 kg/m^3 and p = 0. p_inf = 0 is the ideal gas.
struct StiffenedGas {
  double gamma = 1.4;               // (-), > 1
  double stiffness_pressure = 0.0;  // p_inf (Pa), >= 0

  static constexpr std::string_view name = "stiffened_gas";
  double pressure(double rho, double e) const { return (gamma - 1.0) * rho * e - gamma * stiffness_pressure; }
  double sound_speed_squared(double rho, double /*e*/, double p) const {
    return rho > 0.0 ? std::max(gamma * (p + stiffness_pressure) / rho, 0.0) : 0.0;
  }
  double shock_slope() const { return 0.25 * (gamma + 1.0); }
  // rho c^2 at p = 0, gamma p_inf: a liquid's (2.64e9 Pa for water); 0 for p_inf = 0, the ideal gas.
  double reference_bulk_modulus() const { return gamma * stiffness_pressure; }
};

// Linear bulk modulus (acoustic solid or liquid): p = K (rho/rho0 - 1), independent of e.
struct LinearBulk {
  double bulk_modulus = 0.0;       // K (Pa)
  double reference_density = 0.0;  // rho0 (kg/m^3)

  static constexpr std::string_view name = "linear";
  double pressure(double rho, double /*e*/) const { return bulk_modulus * (rho / reference_density - 1.0); }
  double sound_speed_squared(double /*rho*/, double /*e*/, double /*p*/) const {
    return bulk_modulus / reference_density;
  }
  double shock_slope() const { return 0.5; }
  double reference_bulk_modulus() const { return bulk_modulus; }
};

// Mie–Grüneisen solid referenced to the principal shock Hugoniot of a linear Us–up fit,
// Us = c0 + s up (Meyers 1994, "Dynamic Behavior of Materials", the shock-wave and equation-of-state chapters;
// Wilkins 1999, "Computer Simulation of Dynamic Phenomena").
// With the compression mu = rho/rho0 - 1 and eta = 1 - rho0/rho = mu / (1 + mu), the Rankine–Hugoniot
// jump conditions give on the Hugoniot
//   p_H = rho0 c0^2 mu (1 + mu) / (1 - (s - 1) mu)^2,    e_H = p_H (1/rho0 - 1/rho) / 2,
// and the Grüneisen form with rho Gamma = rho0 Gamma0 (constant) off it,
//   p = p_H + rho0 Gamma0 (e - e_H) = rho0 c0^2 mu (1 + (1 - Gamma0/2) mu) / (1 - (s - 1) mu)^2 + rho0 Gamma0 e.
// In tension (mu < 0) the linear form p = rho0 c0^2 mu + rho0 Gamma0 e; both branches and their
// first derivatives agree at mu = 0.
// Valid range: compressions well below the singularity mu* = 1/(s - 1) of the Hugoniot (rho = 3 rho0
// for copper); the fit itself is trusted up to the largest particle velocity of its data, typically
// a few km/s. Guard: beyond mu_L = max_compression_fraction * mu* the energy-independent part of p
// continues along its tangent at mu_L (C1, monotone, finite), so a zone squeezed past the singularity
// gets a large but finite, stiff pressure instead of a division by zero or a sign flip. For s <= 1
// there is no singularity and no guard.
struct MieGruneisen {
  double reference_density = 0.0;  // rho0 (kg/m^3)
  double bulk_sound_speed = 0.0;   // c0 (m/s), intercept of Us = c0 + s up
  double hugoniot_slope = 0.0;     // s (-), slope of Us = c0 + s up
  double gruneisen = 0.0;          // Gamma0 (-), Grüneisen coefficient at rho0; rho Gamma = rho0 Gamma0

  static constexpr std::string_view name = "mie_gruneisen";
  // Fraction of the singular compression 1/(s - 1) beyond which the tangent continuation takes over.
  static constexpr double max_compression_fraction = 0.9;

  // The energy-independent part of p and its derivative d/dmu at compression mu.
  struct ReferenceCurve {
    double pressure = 0.0;  // Pa
    double slope = 0.0;     // dp/dmu at constant e (Pa)
  };

  double compression(double rho) const { return rho / reference_density - 1.0; }

  // mu_L: the compression where the tangent continuation starts (infinite when s <= 1).
  double compression_limit() const {
    return hugoniot_slope > 1.0 ? max_compression_fraction / (hugoniot_slope - 1.0)
                                : std::numeric_limits<double>::infinity();
  }

  [[gnu::always_inline]] ReferenceCurve reference_curve(double mu) const {
    const double stiffness = reference_density * bulk_sound_speed * bulk_sound_speed;  // rho0 c0^2
    if (mu <= 0.0) return {stiffness * mu, stiffness};
    const double limit = compression_limit();
    const double mu_eval = std::min(mu, limit);
    const double quadratic = 1.0 - 0.5 * gruneisen;  // 1 - Gamma0/2
    const double denominator = 1.0 - (hugoniot_slope - 1.0) * mu_eval;
    const double numerator = mu_eval * (1.0 + quadratic * mu_eval);
    const double d2 = denominator * denominator;
    const double value = stiffness * numerator / d2;
    const double slope = stiffness * ((1.0 + 2.0 * quadratic * mu_eval) / d2 +
                                      2.0 * (hugoniot_slope - 1.0) * numerator / (d2 * denominator));
    if (mu <= limit) return {value, slope};
    return {value + slope * (mu - limit), slope};
  }

  // Principal Hugoniot from (rho0, e = 0, p = 0), for 0 <= mu < compression_limit(); there
  // pressure(rho, hugoniot_energy(rho)) == hugoniot_pressure(rho). For mu < 0 the acoustic value
  // rho0 c0^2 mu (no shock in tension); at or beyond the singularity, +infinity.
  double hugoniot_pressure(double rho) const {
    const double mu = compression(rho);
    const double stiffness = reference_density * bulk_sound_speed * bulk_sound_speed;
    if (mu <= 0.0) return stiffness * mu;
    const double denominator = 1.0 - (hugoniot_slope - 1.0) * mu;
    if (!(denominator > 0.0)) return std::numeric_limits<double>::infinity();
    return stiffness * mu * (1.0 + mu) / (denominator * denominator);
  }
  double hugoniot_energy(double rho) const {
    return 0.5 * hugoniot_pressure(rho) * (1.0 / reference_density - 1.0 / rho);
  }

  double pressure(double rho, double e) const {
    return reference_curve(compression(rho)).pressure + reference_density * gruneisen * e;
  }
  // (dp/drho)_s = (dp/dmu)_e / rho0 + p rho0 Gamma0 / rho^2; floored at zero (a negative value means
  // a thermodynamically unstable state, reached only in strong tension: mu < -2 + sqrt(3) = -0.27 for Gamma0 = 2 and e = 0).
  double sound_speed_squared(double rho, double /*e*/, double p) const {
    if (!(rho > 0.0)) return 0.0;
    const double isoenergetic = reference_curve(compression(rho)).slope / reference_density;
    return std::max(isoenergetic + p * reference_density * gruneisen / (rho * rho), 0.0);
  }
  double shock_slope() const { return 0.5 * hugoniot_slope; }
  // rho0 c0^2, the slope dp/dmu of the reference curve at rho0.
  double reference_bulk_modulus() const { return reference_density * bulk_sound_speed * bulk_sound_speed; }
};

// Scenario parameters (parameters.hpp); reference_density comes from the material's density.
constexpr auto parameters(std::type_identity<IdealGas>) {
  return std::array{parameter::between("gamma", &IdealGas::gamma, 1.0, 10.0, true)};
}
constexpr auto parameters(std::type_identity<StiffenedGas>) {
  return std::array{parameter::between("gamma", &StiffenedGas::gamma, 1.0, 10.0, true),
                    parameter::non_negative("stiffness_pressure", &StiffenedGas::stiffness_pressure)};
}
constexpr auto parameters(std::type_identity<LinearBulk>) {
  return std::array{parameter::positive("bulk_modulus", &LinearBulk::bulk_modulus)};
}
constexpr auto parameters(std::type_identity<MieGruneisen>) {
  return std::array{parameter::positive("bulk_sound_speed", &MieGruneisen::bulk_sound_speed),
                    parameter::between("hugoniot_slope", &MieGruneisen::hugoniot_slope, 0.0, 10.0),
                    parameter::between("gruneisen", &MieGruneisen::gruneisen, 0.0, 10.0)};
}

// The equations of state a scenario may name (`eos.model`: each model's `name`), in this order.
using Eos = std::variant<IdealGas, LinearBulk, MieGruneisen, StiffenedGas>;

// What every alternative of Eos answers. reference_bulk_modulus() (Pa) is K0 at the reference state of
// condensed matter (a solid or a liquid), which the scenario reader's plausibility checks bound by the
// ranges of real materials (density, sound speed, Poisson ratio: docs/scenario-format.md); 0 says the
// model describes a gas, whose constants are often non-dimensional and are not checked. A model without
// the member stops the build here, so that no equation of state is left out of the checks unawares.
template <class Model>
concept EquationOfState = requires(const Model& model, double value) {
  { Model::name } -> std::convertible_to<std::string_view>;
  { model.pressure(value, value) } -> std::same_as<double>;
  { model.sound_speed_squared(value, value, value) } -> std::same_as<double>;
  { model.shock_slope() } -> std::same_as<double>;
  { model.reference_bulk_modulus() } -> std::same_as<double>;
};

template <class Variant>
inline constexpr bool all_equations_of_state = false;
template <class... Models>
inline constexpr bool all_equations_of_state<std::variant<Models...>> = (EquationOfState<Models> && ...);
static_assert(all_equations_of_state<Eos>,
              "every alternative of Eos must answer the members of EquationOfState (reference_bulk_modulus among them)");

// K0 of the material's equation of state (Pa; 0 for a gas), asked of the model.
inline double reference_bulk_modulus(const Eos& eos) {
  return std::visit([](const auto& model) { return model.reference_bulk_modulus(); }, eos);
}

}  // namespace krug
