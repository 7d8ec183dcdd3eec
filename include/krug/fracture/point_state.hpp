#pragma once
// The state of one zone as a failure law sees it (failure_law.hpp): plain numbers, gathered by the
// driver (damage.hpp) after the zone update of a step, at t^{n+1}. A law names the inputs it reads
// (`Law::inputs`, a set of the flags below) and the driver computes only those; a law never sees the
// mesh or the material, so the material constants it needs are its own parameters (or, in a scenario,
// taken from the strength block: krug/core/parameters.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

namespace krug::fracture {

// Principal stretches (in-plane pair and the out-of-plane/hoop one).
struct Stretches {
  double in_plane_max = 1.0;
  double in_plane_min = 1.0;
  double out_of_plane = 1.0;
  double largest() const { return std::max(in_plane_max, out_of_plane); }
  double smallest() const { return std::min(in_plane_min, out_of_plane); }
};

// Principal values of the Cauchy stress s - p I (in-plane pair from the 2x2 block, plus the zz one).
struct PrincipalStress {
  double largest = 0.0;
  double smallest = 0.0;
};

namespace input {
inline constexpr unsigned stretches = 1u << 0;         // principal stretches from the initial shape
inline constexpr unsigned principal_stress = 1u << 1;  // principal values of s - p I
inline constexpr unsigned specific_energy = 1u << 2;   // e (J/kg)
inline constexpr unsigned pressure = 1u << 3;          // p (Pa), compression positive, no viscosity
inline constexpr unsigned equivalent_stress = 1u << 4;  // sigma_vm = sqrt(3/2 s:s) (Pa)
inline constexpr unsigned plastic_strain = 1u << 5;    // the increment of eps_p over the step and its rate
inline constexpr unsigned temperature = 1u << 6;       // T (K) from the strength model
}  // namespace input

struct PointState {
  Stretches stretch;
  PrincipalStress stress;
  double specific_energy = 0.0;           // J/kg
  double pressure = 0.0;                  // Pa
  double equivalent_stress = 0.0;         // Pa
  double plastic_strain_increment = 0.0;  // d eps_p since the law last saw the zone (-), >= 0
  double plastic_strain_rate = 0.0;       // d eps_p / dt over the step (1/s)
  // K; NaN where the material's strength model defines no temperature (only Johnson-Cook strength
  // does, from the internal energy and its specific heat): a law's thermal term is then off.
  double temperature = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace krug::fracture
