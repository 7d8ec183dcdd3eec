#pragma once
// A material: reference density, equation of state and strength model, chosen per material block
// (the solver dispatches with std::visit once per block, outside the zone loop).
#include <string>
#include <variant>

#include "krug/material/eos.hpp"
#include "krug/material/strength.hpp"

namespace krug {

// The strength models a scenario may name (`strength.model`: each model's `name`; the first is the
// default), in this order.
using Strength = std::variant<NoStrength, Elastic, PerfectlyPlastic, LinearHardening, JohnsonCook>;

struct Material {
  std::string name;
  double reference_density = 0.0;  // rho0 (kg/m^3)
  Eos eos = IdealGas{};
  Strength strength = NoStrength{};

  double shear_modulus() const {
    return std::visit([](const auto& s) { return s.shear_modulus; }, strength);
  }
  // The flow stress at zero plastic strain, reference rate and room temperature (Pa); 0 without
  // strength, infinite for an elastic body.
  double initial_flow_stress() const {
    return std::visit([](const auto& s) { return s.flow_stress(0.0); }, strength);
  }
  double shock_slope() const {
    return std::visit([](const auto& m) { return m.shock_slope(); }, eos);
  }
};

}  // namespace krug
