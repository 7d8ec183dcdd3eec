#include "krug/fracture/damage.hpp"

#include <algorithm>
#include <cstdint>

namespace krug::fracture {

long damage_zones(Mesh& mesh, Index zone_begin, Index zone_end, const FractureLimits& limits, GeometryKind geometry,
                  double now) {
  const bool axisymmetric = geometry == GeometryKind::axisymmetric;
  ZoneFields& zones = mesh.zones;
  const NodeFields& nodes = mesh.nodes;
  long damaged = 0;
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!zones.active[z] || zones.damaged[z]) continue;
    const ZoneCorners& n = zones.corners[z];
    const quad::Corners x = mesh.corner_positions(z);
    const quad::Corners x0{Vec2{nodes.x0[n[0]], nodes.y0[n[0]]}, Vec2{nodes.x0[n[1]], nodes.y0[n[1]]},
                           Vec2{nodes.x0[n[2]], nodes.y0[n[2]]}, Vec2{nodes.x0[n[3]], nodes.y0[n[3]]}};
    const double initial_area = quad::area(x0);
    double f11, f12, f21, f22;
    deformation_gradient(x, quad::area_gradient(x0), initial_area, f11, f12, f21, f22);
    // Hoop stretch r/R with the zone's mean radii V/A (axisymmetric); 1 in planar strain.
    const double hoop = axisymmetric ? (zones.volume[z] / zones.area[z]) / (quad::axisymmetric_volume(x0) / initial_area) : 1.0;
    const Stretches stretch = principal_stretches(f11, f12, f21, f22, hoop);
    const PrincipalStress stress = principal_stress(
        zones.deviator_xx[z], zones.deviator_yy[z], zones.deviator_xy[z], zones.deviator_zz[z], zones.pressure[z]);
    const Criterion fired = exceeded(limits, stretch, stress, zones.specific_energy[z]);
    if (fired == Criterion::none) continue;
    zones.damaged[z] = 1;
    zones.damage_time[z] = now;
    zones.damage_criterion[z] = static_cast<std::uint8_t>(fired);
    zones.deviator_xx[z] = zones.deviator_yy[z] = zones.deviator_xy[z] = zones.deviator_zz[z] = 0.0;
    zones.pressure[z] = std::max(zones.pressure[z], 0.0);
    zones.hourglass_x[z] = zones.hourglass_y[z] = 0.0;
    ++damaged;
  }
  return damaged;
}

}  // namespace krug::fracture
