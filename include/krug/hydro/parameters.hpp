#pragma once
// Numerical parameters of the hydrodynamic step (artificial viscosity, hourglass control, the
// axisymmetric form of the corner forces), with defaults. The kernels in this module read them;
// the solver's Controls carry one copy per run, and each body's copy (body_viscosity) resolves the
// choices that depend on whether the body has strength and on the geometry.
#include <optional>

#include "krug/core/geometry_kind.hpp"

namespace krug {

enum class ViscosityModel {
  edge,    // Caramana, Shashkov & Whalen (1998) edge viscosity with a limiter
  scalar,  // Wilkins' zone-centred q added to the pressure
  tensor,  // Campbell & Shashkov (2001) corner (tensor) viscosity with a limiter
  off,
  // By body (a run's default, Controls): in axisymmetric bodies without strength the tensor viscosity with the
  // corner-collapse pressure (HourglassParams::collapse_pressure, 1 unless given), which keeps the
  // converging gas flows of docs/verification.md F7 from folding at the axis; in every other body the
  // edge viscosity (planar gas flows and solids, which it passes at a smaller cost per cycle).
  automatic
};

// A kernel takes a resolved model (zone_force_params); a run's controls default to `automatic` (Controls).
struct ViscosityParams {
  ViscosityModel model = ViscosityModel::edge;
  double quadratic = 1.0;  // c_q, multiplies the EOS shock slope ((gamma+1)/4 for a gas)
  double linear = 0.5;     // c_l, multiplies the sound speed
  bool limiter = true;     // edge and tensor models: switch off for velocity fields linear along the edge
  double heat_conduction = 0.0;  // Noh's artificial heat flux coefficient (heat_conduction.hpp), bodies
                                 // without strength; 0: off
};

// How the stiffness part of the hourglass control is sized, in bodies with strength.
enum class HourglassStiffness {
  // Flanagan & Belytschko (1981): k mu |b|^2 / A for both directions of the mode, k = `stiffness`.
  coefficient,
  // The zone's own bending stiffness (the physical stabilization of Belytschko & Bindeman 1991, in the
  // incompatible-mode form): the mode's displacement along each of the zone's axes resisted as the pure
  // bending of a rectangle of those sides, E'/3 x (the zone's extent across / along that axis), E' the
  // plane-strain modulus from the reference bulk and shear moduli. No coefficient: `stiffness` unused.
  physical
};

struct HourglassParams {
  double viscous = 0.05;    // Flanagan-Belytschko viscous coefficient (x rho c sqrt(A))
  double stiffness = 0.05;  // Flanagan-Belytschko stiffness coefficient (x shear modulus; no effect without strength)
  HourglassStiffness stiffness_form = HourglassStiffness::coefficient;
  // The stiffness state's bound in bodies that yield: |Q| <= plastic_limit x Y0 x |b| (Y0 the initial
  // flow stress, |b| the zone's area-gradient norm), the most a zone at yield can resist its
  // hourglass mode with; in the physical form plastic_limit x the zone's fully plastic bending
  // (artificial_forces.hpp, zone_bending). 0: unbounded.
  double plastic_limit = 1.0;
  // Subzonal pressures (Caramana & Shashkov 1998), in bodies without strength: each corner region of
  // the median mesh keeps its own mass, and one denser than its zone pushes with
  // dp = subzonal_pressure x c^2 (rho_corner - rho_zone). 0: off.
  double subzonal_pressure = 0.0;
  // With the tensor viscosity: the subzonal pressures of a zone scaled by 1 - psi of its most active
  // compressing corner (the tensor viscosity's own switch, batch_tensor_viscosity), so that they act at
  // shocks and not in smooth flow. False: everywhere.
  bool subzonal_at_shocks = false;
  // A corner-collapse pressure, in every body: the subzonal pressure's dead-band form. A corner region of
  // the median mesh compressed beyond `collapse_threshold` times its zone's density pushes with
  // dp = collapse_pressure x c^2 (rho_corner - collapse_threshold x rho_zone); below that it does nothing,
  // so smooth flow, affine or not, never feels it. What it stops is a corner folding into its zone (a
  // zone turning into a dart), which the one-point hourglass control does not see. 0: off. Not given:
  // 0, except in the bodies that ViscosityModel::automatic gives the tensor viscosity (body_viscosity).
  std::optional<double> collapse_pressure;
  double collapse_threshold = 1.5;
};

// What ViscosityModel::automatic gives a body without strength as its corner-collapse pressure.
inline constexpr double automatic_collapse_pressure = 1.0;

// The viscosity model and corner-collapse pressure one body takes: `viscosity.model`, and
// `hourglass.collapse_pressure` (0 if not given), unless the model is `automatic` (see there).
struct BodyViscosity {
  ViscosityModel model = ViscosityModel::edge;
  double collapse_pressure = 0.0;
};

inline BodyViscosity body_viscosity(const ViscosityParams& viscosity, const HourglassParams& hourglass,
                                    bool has_strength, GeometryKind geometry) {
  if (viscosity.model != ViscosityModel::automatic) return {viscosity.model, hourglass.collapse_pressure.value_or(0.0)};
  if (has_strength || geometry != GeometryKind::axisymmetric) {
    return {ViscosityModel::edge, hourglass.collapse_pressure.value_or(0.0)};
  }
  return {ViscosityModel::tensor, hourglass.collapse_pressure.value_or(automatic_collapse_pressure)};
}

enum class AxisymmetricForm {
  control_volume,  // compatible corner forces from dV/dx_p: exact momentum and energy (default)
  area_weighted    // Wilkins' area-weighted form: better symmetry on polar meshes, not exactly conservative
};

}  // namespace krug
