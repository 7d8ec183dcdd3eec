#pragma once
// The failure laws a material may name (`fracture.model`: each law's `name`; the first, criteria (1),
// is the default, so a `fracture` block without "model" reads as before), in this order.
//
// A failure law is a value type in this module with
//   - `static constexpr std::string_view name`, its scenario model name;
//   - `static constexpr unsigned inputs`, the zone state it reads (point_state.hpp, input::...);
//   - `double loosening`, the chi_* of the damaged state it leads to, and `bool any() const` (enabled);
//   - a free function `Criterion test(const Law&, const PointState&, double& damage)`: the criterion
//     that fired (Criterion::none if the zone stays intact), updating the zone's damage variable
//     (FractureZoneFields::damage) if the law has one;
//   - `parameters(std::type_identity<Law>)`, its scenario parameters (krug/core/parameters.hpp).
// The driver (damage.hpp) dispatches once per body (std::visit outside the zone loop) and gathers
// only the inputs the law names; a failed zone takes the same damaged state whatever the law.
#include <variant>

#include "krug/fracture/cockcroft_latham.hpp"
#include "krug/fracture/criteria.hpp"
#include "krug/fracture/johnson_cook.hpp"

namespace krug::fracture {

using FailureLaw = std::variant<FractureLimits, JohnsonCookDamage, CockcroftLatham>;

// The law is on (criteria (1) with at least one limit; every other law).
inline bool enabled(const FailureLaw& law) {
  return std::visit([](const auto& l) { return l.any(); }, law);
}

// chi_* of the damaged state.
inline double loosening_limit(const FailureLaw& law) {
  return std::visit([](const auto& l) { return l.loosening; }, law);
}

}  // namespace krug::fracture
