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
#include <cmath>
#include <limits>

#include "krug/core/geometry_kind.hpp"
#include "krug/fracture/criteria.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/fracture/point_state.hpp"
#include "krug/mesh/mesh.hpp"

namespace krug::fracture {

// Principal stretches of zone z from its initial shape (deformation gradient by one-point quadrature;
// the hoop stretch r/R with the zone's mean radii V/A in axisymmetric geometry, 1 in planar strain).
Stretches zone_stretches(const Mesh& mesh, Index z, bool axisymmetric);

// Puts zone z into the damaged state at time `now`, recording `why`.
void damage_zone(ZoneFields& zones, Index z, Criterion why, double now);

// The temperature of a material without one (NaN: a law's thermal term is off).
struct NoTemperature {
  double operator()(Index /*zone*/) const { return std::numeric_limits<double>::quiet_NaN(); }
};

// Damages the zones of [zone_begin, zone_end) that `law` fails at time `now`; returns how many.
// `time_step` is the step just taken (dt^{n+1/2}, over which the plastic strain grew);
// `temperature(z)` gives zone z's temperature (K) when the law reads one.
template <class Law, class Temperature = NoTemperature>
long damage_zones(Mesh& mesh, Index zone_begin, Index zone_end, const Law& law, GeometryKind geometry, double now,
                  double time_step = 0.0, Temperature&& temperature = {}) {
  constexpr unsigned needs = Law::inputs;
  const bool axisymmetric = geometry == GeometryKind::axisymmetric;
  ZoneFields& zones = mesh.zones;
  long damaged = 0;
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!zones.active[z] || zones.damaged[z]) continue;
    PointState point;
    if constexpr ((needs & input::stretches) != 0) point.stretch = zone_stretches(mesh, z, axisymmetric);
    if constexpr ((needs & input::principal_stress) != 0) {
      point.stress = principal_stress(zones.deviator_xx[z], zones.deviator_yy[z], zones.deviator_xy[z],
                                      zones.deviator_zz[z], zones.pressure[z]);
    }
    if constexpr ((needs & input::specific_energy) != 0) point.specific_energy = zones.specific_energy[z];
    if constexpr ((needs & input::pressure) != 0) point.pressure = zones.pressure[z];
    if constexpr ((needs & input::equivalent_stress) != 0) {
      const double sxx = zones.deviator_xx[z], syy = zones.deviator_yy[z], sxy = zones.deviator_xy[z],
                   szz = zones.deviator_zz[z];
      point.equivalent_stress = std::sqrt(1.5 * (sxx * sxx + syy * syy + szz * szz + 2.0 * sxy * sxy));
    }
    if constexpr ((needs & input::plastic_strain) != 0) {
      const double strain = zones.plastic_strain[z];
      point.plastic_strain_increment = std::max(strain - zones.damage_plastic_strain[z], 0.0);
      point.plastic_strain_rate = time_step > 0.0 ? point.plastic_strain_increment / time_step : 0.0;
      zones.damage_plastic_strain[z] = strain;
    }
    if constexpr ((needs & input::temperature) != 0) point.temperature = temperature(z);
    const Criterion fired = test(law, point, zones.damage[z]);
    if (fired == Criterion::none) continue;
    damage_zone(zones, z, fired, now);
    ++damaged;
  }
  return damaged;
}

}  // namespace krug::fracture
