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
  // The plane-strain modulus E' = E / (1 - nu^2) = 4 mu (3K + mu) / (3K + 4 mu) from the reference bulk
  // modulus K and the shear modulus mu (Pa): the stiffness of a zone in pure bending (the physical
  // hourglass stiffness). 0 without strength.
  double bending_modulus() const {
    const double mu = shear_modulus();
    if (!(mu > 0.0)) return 0.0;
    const double k = reference_bulk_modulus(eos);
    return 4.0 * mu * (3.0 * k + mu) / (3.0 * k + 4.0 * mu);
  }
  double shock_slope() const {
    return std::visit([](const auto& m) { return m.shock_slope(); }, eos);
  }
};

}  // namespace krug
