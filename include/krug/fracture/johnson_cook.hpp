#pragma once
// Johnson-Cook damage (Johnson & Cook 1985, Eng. Fract. Mech. 21(1), 31-48, eq. (4)-(5)): a failure law
// (failure_law.hpp) that accumulates damage with plastic strain,
//
//   eps_f = [D1 + D2 exp(D3 eta)] [1 + D4 ln(rate*)] [1 + D5 T*],      D = sum d(eps_p) / eps_f,
//
// and fails the zone when D >= 1; it then follows the damaged state of criteria (1) (s = 0,
// p = max(p, 0), conversion to free elements once loosened beyond chi_*).
//
//   eta   = -p / sigma_vm, the stress triaxiality (JC85's sigma* = mean stress / von Mises stress);
//           p is the equation of state's pressure (compression positive, no artificial viscosity) and
//           sigma_vm = sqrt(3/2 s:s) at the end of the step. Where sigma_vm = 0 (no deviator: a melted
//           zone) eta is +infinity under tension, -infinity under compression and 0 at p = 0, and the
//           exponential term takes its limit (0 or infinity by the sign of D3 eta; D2 when D3 = 0).
//   rate* = (d eps_p / dt) / rate0, the plastic strain rate of the step over the reference rate (JC85:
//           "the dimensionless plastic strain rate"); the factor is 1 below the reference rate, as in
//           the Johnson-Cook strength model (strength.hpp), so that ln(rate*) >= 0.
//   T*    = (T - T_room) / (T_melt - T_room), clamped to [0, 1]; T is the strength model's temperature
//           (Johnson-Cook strength: T_room + e / c_v); without one (other strength models) T* = 0.
//
// Damage grows only with plastic strain: an elastic step adds nothing. Outside the triaxialities of
// the fit the formula can give eps_f <= 0 (e.g. 6061-T6 of L01, D1 = -0.77, beyond eta = 1.35): eps_f
// is floored at `minimum_fracture_strain` (default 0), and a plastic step at eps_f <= 0 sets D = 1.
// JC85's separate spall rule for sigma* > 1.5 is not part of this law.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string_view>
#include <type_traits>

#include "krug/core/parameters.hpp"
#include "krug/fracture/criteria.hpp"
#include "krug/fracture/point_state.hpp"

namespace krug::fracture {

struct JohnsonCookDamage {
  double d1 = 0.0;  // D1 (-)
  double d2 = 0.0;  // D2 (-)
  double d3 = 0.0;  // D3 (-)
  double d4 = 0.0;  // D4 (-)
  double d5 = 0.0;  // D5 (-)
  double reference_strain_rate = 1.0;                                  // rate0 (1/s)
  double room_temperature = 293.0;                                     // T_room (K)
  double melt_temperature = std::numeric_limits<double>::infinity();   // T_melt (K); infinite: no thermal term
  double minimum_fracture_strain = 0.0;                                // floor of eps_f (-)
  double loosening = 0.03;                                             // chi_* of the damaged state (-)

  static constexpr std::string_view name = "johnson_cook";
  static constexpr unsigned inputs =
      input::pressure | input::equivalent_stress | input::plastic_strain | input::temperature;

  bool any() const { return true; }

  // eta = -p / sigma_vm, with the limits above where sigma_vm = 0.
  static double triaxiality(double pressure, double equivalent_stress) {
    if (equivalent_stress > 0.0) return -pressure / equivalent_stress;
    if (pressure < 0.0) return std::numeric_limits<double>::infinity();
    if (pressure > 0.0) return -std::numeric_limits<double>::infinity();
    return 0.0;
  }
  // D1 + D2 exp(D3 eta).
  double stress_factor(double eta) const {
    const double exponent = d3 == 0.0 ? 0.0 : d3 * eta;
    return d1 + (d2 == 0.0 ? 0.0 : d2 * std::exp(exponent));
  }
  // 1 + D4 ln(rate*), rate* = rate / rate0, 1 at or below the reference rate.
  double rate_factor(double plastic_strain_rate) const {
    if (!(plastic_strain_rate > reference_strain_rate) || !(reference_strain_rate > 0.0)) return 1.0;
    return 1.0 + d4 * std::log(plastic_strain_rate / reference_strain_rate);
  }
  // 1 + D5 T*, T* clamped to [0, 1]; 1 without a temperature (NaN) or a melt temperature.
  double thermal_factor(double temperature) const {
    const double range = melt_temperature - room_temperature;
    if (!(range > 0.0) || !std::isfinite(range) || !(temperature > room_temperature)) return 1.0;
    return 1.0 + d5 * std::min((temperature - room_temperature) / range, 1.0);
  }
  // eps_f at a triaxiality, plastic strain rate and temperature, floored at minimum_fracture_strain.
  double fracture_strain(double eta, double plastic_strain_rate, double temperature) const {
    const double strain = stress_factor(eta) * rate_factor(plastic_strain_rate) * thermal_factor(temperature);
    return strain > minimum_fracture_strain ? strain : minimum_fracture_strain;  // NaN: the floor
  }
};

// Scenario parameters (krug/core/parameters.hpp). The reference rate and the two temperatures, when not
// given, are the Johnson-Cook strength model's (`strength.reference_strain_rate`, `room_temperature`,
// `melt_temperature`), else 1/s, 293 K and infinite (no thermal term).
constexpr auto parameters(std::type_identity<JohnsonCookDamage>) {
  using parameter::any;
  using parameter::from_strength;
  using parameter::optional;
  using parameter::positive;
  constexpr double infinity = std::numeric_limits<double>::infinity();
  return std::array{any("d1", &JohnsonCookDamage::d1),
                    any("d2", &JohnsonCookDamage::d2),
                    any("d3", &JohnsonCookDamage::d3),
                    any("d4", &JohnsonCookDamage::d4),
                    any("d5", &JohnsonCookDamage::d5),
                    from_strength(positive("reference_strain_rate", &JohnsonCookDamage::reference_strain_rate),
                                  "reference_strain_rate", 1.0),
                    from_strength(positive("room_temperature", &JohnsonCookDamage::room_temperature),
                                  "room_temperature", 293.0),
                    from_strength(positive("melt_temperature", &JohnsonCookDamage::melt_temperature),
                                  "melt_temperature", infinity),
                    optional(parameter::non_negative("minimum_fracture_strain",
                                                     &JohnsonCookDamage::minimum_fracture_strain), 0.0),
                    optional(parameter::between("loosening", &JohnsonCookDamage::loosening, 0.0, 1.0, true), 0.03)};
}

// The law's test of one zone: D += d eps_p / eps_f over a plastic step; fractured at D >= 1.
inline Criterion test(const JohnsonCookDamage& law, const PointState& point, double& damage) {
  if (point.plastic_strain_increment > 0.0) {
    const double eta = JohnsonCookDamage::triaxiality(point.pressure, point.equivalent_stress);
    const double strain = law.fracture_strain(eta, point.plastic_strain_rate, point.temperature);
    damage = strain > 0.0 ? damage + point.plastic_strain_increment / strain : std::max(damage, 1.0);
  }
  return damage >= 1.0 ? Criterion::johnson_cook : Criterion::none;
}

}  // namespace krug::fracture
