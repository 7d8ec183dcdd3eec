#pragma once
// The driver of a failure law over a mesh (step 6 of the time step): every intact active zone of a
// range gives the law its point state (point_state.hpp; only the inputs the law names: the principal
// stretches from the initial shape, with the hoop stretch r/R in axisymmetric geometry, the principal
// stresses, the energy, the pressure, the von Mises stress, the plastic strain increment since the law
// last saw the zone and its rate, the temperature) and its damage variable. A zone the law fails
// becomes damaged for good: it keeps only compressive pressure (s = 0, p = max(p, 0)) and loses its
// hourglass stiffness, and its damage time and criterion are recorded. The law is a template argument:
// the caller chooses it once per body (std::visit on FailureLaw, failure_law.hpp), never per zone.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/fracture/criteria.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/fracture/point_state.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"

namespace krug::fracture {

// Principal stretches of zone z from its initial shape (deformation gradient by one-point quadrature;
// the hoop stretch r/R with the zone's mean radii V/A in axisymmetric geometry, 1 in planar strain).
Stretches zone_stretches(const Mesh& mesh, Index z, bool axisymmetric);

// The corners of zone z where the run started (the reference of its stretches).
inline quad::Corners initial_corners(const Mesh& mesh, Index z) {
  const NodeFields& nodes = mesh.nodes;
  const ZoneCorners& n = mesh.zones.corners[z];
  return {Vec2{nodes.x0[n[0]], nodes.y0[n[0]]}, Vec2{nodes.x0[n[1]], nodes.y0[n[1]]},
          Vec2{nodes.x0[n[2]], nodes.y0[n[2]]}, Vec2{nodes.x0[n[3]], nodes.y0[n[3]]}};
}

// The initial shape of a zone as the stretch test reads it: the area gradients of its corners where
// the run started, its area and the inverse of that area, and six times its volume per radian (as
// quad::axisymmetric_volume sums it). x0 never changes, so a caller may compute these once per zone
// (initial_shapes) and pass them to damage_zones.
struct InitialShape {
  std::array<Vec2, 4> gradient{};
  double area = 0.0;
  double inverse_area = 0.0;
  double sixfold_volume = 0.0;
};

inline InitialShape initial_shape(const Mesh& mesh, Index z) {
  const quad::Corners x0 = initial_corners(mesh, z);
  InitialShape shape;
  shape.gradient = quad::area_gradient(x0);
  shape.area = quad::area(x0);
  shape.inverse_area = 1.0 / shape.area;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = x0[i];
    const Vec2 b = x0[quad::next(i)];
    shape.sixfold_volume += cross(a, b) * (a.y + b.y);
  }
  return shape;
}

// Every zone's initial shape, in zone order.
std::vector<InitialShape> initial_shapes(const Mesh& mesh);

// True when every principal stretch of zone z (as zone_stretches gives them) is certainly below
// `limit` and none is negative, decided without a square root: with s = limit^2 (less a relative margin
// of 1e-9, far above the rounding of either evaluation), lambda_max^2 < s exactly when s lies above
// the mean tr(C)/2 of the two squared stretches and (s - lambda_max^2)(s - lambda_min^2) =
// s^2 - tr(C) s + det(F)^2 > 0 (here required above a bound on its rounding error); the hoop stretch
// (V/A) / (V0/A0) is compared multiplied out. A zone near the limit, inverted or degenerate gives false.
// `shape` is the zone's initial_shape.
inline bool stretches_below(const Mesh& mesh, Index z, bool axisymmetric, double limit, const InitialShape& shape) {
  const ZoneFields& zones = mesh.zones;
  const quad::Corners x = mesh.corner_positions(z);
  const double initial_area = shape.area;
  const double bound = limit * (1.0 - 1e-9);
  if (!(initial_area > 0.0)) return false;
  const quad::Tensor2 a0f = quad::outer_sum(x, shape.gradient);  // A0 F
  const double inv = shape.inverse_area;
  const double f11 = a0f.xx * inv, f12 = a0f.xy * inv, f21 = a0f.yx * inv, f22 = a0f.yy * inv;
  const double trace = f11 * f11 + f12 * f12 + f21 * f21 + f22 * f22;  // tr(C), C = F^T F
  const double det = f11 * f22 - f12 * f21;
  const double s = bound * bound;
  if (!(0.5 * trace < s)) return false;
  const double product = (s - trace) * s + det * det;
  if (!(product > 1e-12 * (s * s + trace * s + det * det))) return false;
  if (!axisymmetric) return 1.0 < bound;
  const double sixfold_volume = shape.sixfold_volume;  // 6 V0
  const double volume = zones.volume[z], area = zones.area[z];
  if (!(area > 0.0 && volume >= 0.0 && sixfold_volume > 0.0)) return false;
  return 6.0 * volume * initial_area < bound * area * sixfold_volume;
}

inline bool stretches_below(const Mesh& mesh, Index z, bool axisymmetric, double limit) {
  return stretches_below(mesh, z, axisymmetric, limit, initial_shape(mesh, z));
}

// Puts zone z into the damaged state at time `now`, recording `why`: writes its fracture fields, zeroes
// its deviatoric stress and hourglass state and keeps only compressive pressure.
void damage_zone(ZoneState& state, Index z, Criterion why, double now);

// The temperature of a material without one (NaN: a law's thermal term is off).
struct NoTemperature {
  double operator()(Index /*zone*/) const { return std::numeric_limits<double>::quiet_NaN(); }
};

// Damages the zones of [zone_begin, zone_end) that `law` fails at time `now`; returns how many. Reads
// the mesh and the hydro and strength state; writes `state.fracture` (and damage_zone's fields).
// `time_step` is the step just taken (dt^{n+1/2}, over which the plastic strain grew);
// `temperature(z)` gives zone z's temperature (K) when the law reads one.
// `shapes`: every zone's initial_shape (indexed by zone), or null to compute them as needed.
template <class Law, class Temperature = NoTemperature>
long damage_zones(const Mesh& mesh, ZoneState& state, Index zone_begin, Index zone_end, const Law& law,
                  GeometryKind geometry, double now, double time_step = 0.0, Temperature&& temperature = {},
                  const InitialShape* shapes = nullptr) {
  constexpr unsigned needs = Law::inputs;
  const bool axisymmetric = geometry == GeometryKind::axisymmetric;
  const ZoneFields& zones = mesh.zones;
  [[maybe_unused]] const HydroZoneFields& hydro = state.hydro;
  [[maybe_unused]] const StrengthZoneFields& strength = state.strength;
  FractureZoneFields& record = state.fracture;
  long damaged = 0;
  double stretch_limit = std::numeric_limits<double>::infinity();
  bool stress_read = true;
  if constexpr ((needs & input::stretches) != 0) stretch_limit = stretch_bound(law);
  if constexpr ((needs & input::principal_stress) != 0) stress_read = reads_principal_stress(law);
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!zones.active[z] || record.damaged[z]) continue;
    PointState point;
    if constexpr ((needs & input::stretches) != 0) {
      // Below the law's stretch bound the stretches cannot fire and stay at the identity (which fires
      // nothing either): the same criterion fires as with the exact stretches.
      const bool below = stretch_limit == std::numeric_limits<double>::infinity() ||
                         (shapes != nullptr ? stretches_below(mesh, z, axisymmetric, stretch_limit, shapes[z])
                                            : stretches_below(mesh, z, axisymmetric, stretch_limit));
      if (!below) {
        point.stretch = zone_stretches(mesh, z, axisymmetric);
      }
    }
    if constexpr ((needs & input::principal_stress) != 0) {
      if (stress_read) {
        point.stress = principal_stress(strength.deviator_xx[z], strength.deviator_yy[z], strength.deviator_xy[z],
                                        strength.deviator_zz[z], hydro.pressure[z]);
      }
    }
    if constexpr ((needs & input::specific_energy) != 0) point.specific_energy = zones.specific_energy[z];
    if constexpr ((needs & input::pressure) != 0) point.pressure = hydro.pressure[z];
    if constexpr ((needs & input::equivalent_stress) != 0) {
      const double sxx = strength.deviator_xx[z], syy = strength.deviator_yy[z], sxy = strength.deviator_xy[z],
                   szz = strength.deviator_zz[z];
      point.equivalent_stress = std::sqrt(1.5 * (sxx * sxx + syy * syy + szz * szz + 2.0 * sxy * sxy));
    }
    if constexpr ((needs & input::plastic_strain) != 0) {
      const double strain = strength.plastic_strain[z];
      point.plastic_strain_increment = std::max(strain - record.damage_plastic_strain[z], 0.0);
      point.plastic_strain_rate = time_step > 0.0 ? point.plastic_strain_increment / time_step : 0.0;
      record.damage_plastic_strain[z] = strain;
    }
    if constexpr ((needs & input::temperature) != 0) point.temperature = temperature(z);
    const Criterion fired = test(law, point, record.damage[z]);
    if (fired == Criterion::none) continue;
    damage_zone(state, z, fired, now);
    ++damaged;
  }
  return damaged;
}

}  // namespace krug::fracture
