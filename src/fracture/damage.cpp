#include "krug/fracture/damage.hpp"

#include <algorithm>
#include <cstdint>

namespace krug::fracture {

Stretches zone_stretches(const Mesh& mesh, Index z, bool axisymmetric) {
  const ZoneFields& zones = mesh.zones;
  const quad::Corners x = mesh.corner_positions(z);
  const quad::Corners x0 = initial_corners(mesh, z);
  const double initial_area = quad::area(x0);
  double f11, f12, f21, f22;
  deformation_gradient(x, quad::area_gradient(x0), initial_area, f11, f12, f21, f22);
  // Hoop stretch r/R with the zone's mean radii V/A (axisymmetric); 1 in planar strain.
  const double hoop = axisymmetric ? (zones.volume[z] / zones.area[z]) / (quad::axisymmetric_volume(x0) / initial_area) : 1.0;
  return principal_stretches(f11, f12, f21, f22, hoop);
}

void damage_zone(ZoneFields& zones, Index z, Criterion why, double now) {
  zones.damaged[z] = 1;
  zones.damage_time[z] = now;
  zones.damage_criterion[z] = static_cast<std::uint8_t>(why);
  zones.deviator_xx[z] = zones.deviator_yy[z] = zones.deviator_xy[z] = zones.deviator_zz[z] = 0.0;
  zones.pressure[z] = std::max(zones.pressure[z], 0.0);
  zones.hourglass_x[z] = zones.hourglass_y[z] = 0.0;
}

}  // namespace krug::fracture
