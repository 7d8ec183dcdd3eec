#pragma once
// Cockcroft-Latham ductile fracture (Cockcroft & Latham 1968, J. Inst. Metals 96, 33-39): a failure law
// (failure_law.hpp) that accumulates the plastic work of the largest principal stress where it is
// tensile,
//
//   W = sum <sigma_1> d(eps_p),      <x> = max(x, 0),      D = W / W_c,
//
// and fails the zone when D >= 1 (W >= W_c, the critical "plastic work per unit volume" of tension,
// Pa = J/m^3); it then follows the damaged state of criteria (1) (s = 0, p = max(p, 0), conversion to
// free elements once loosened beyond chi_*). sigma_1 is the largest principal value of s - p I at the
// end of the step (point_state.hpp), d(eps_p) the step's equivalent plastic strain increment. Damage
// grows only with plastic strain under tension: an elastic step, or plastic flow under all-round
// compression, adds nothing. In uniaxial tension of a perfectly plastic material (sigma_1 = Y) the zone
// fails at eps_p = W_c / Y.
#include <algorithm>
#include <array>
#include <string_view>
#include <type_traits>

#include "krug/core/parameters.hpp"
#include "krug/fracture/criteria.hpp"
#include "krug/fracture/point_state.hpp"

namespace krug::fracture {

struct CockcroftLatham {
  double critical_work = 0.0;  // W_c (Pa)
  double loosening = 0.03;     // chi_* of the damaged state (-)

  static constexpr std::string_view name = "cockcroft_latham";
  static constexpr unsigned inputs = input::principal_stress | input::plastic_strain;

  bool any() const { return true; }
};

constexpr auto parameters(std::type_identity<CockcroftLatham>) {
  return std::array{parameter::positive("critical_work", &CockcroftLatham::critical_work),
                    parameter::optional(parameter::between("loosening", &CockcroftLatham::loosening, 0.0, 1.0, true), 0.03)};
}

// The driver gathers sigma_1 for every zone the law tests (damage.hpp).
inline bool reads_principal_stress(const CockcroftLatham&) { return true; }

// The law's test of one zone: D += <sigma_1> d eps_p / W_c; fractured at D >= 1.
inline Criterion test(const CockcroftLatham& law, const PointState& point, double& damage) {
  if (point.plastic_strain_increment > 0.0 && point.stress.largest > 0.0) {
    damage += point.stress.largest * point.plastic_strain_increment / law.critical_work;
  }
  return damage >= 1.0 ? Criterion::cockcroft_latham : Criterion::none;
}

}  // namespace krug::fracture
