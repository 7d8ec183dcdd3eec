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

std::vector<InitialShape> initial_shapes(const Mesh& mesh) {
  std::vector<InitialShape> shapes(static_cast<std::size_t>(mesh.zones.size()));
  for (Index z = 0; z < mesh.zones.size(); ++z) shapes[static_cast<std::size_t>(z)] = initial_shape(mesh, z);
  return shapes;
}

void damage_zone(ZoneState& state, Index z, Criterion why, double now) {
  state.fracture.damaged[z] = 1;
  state.fracture.damage_time[z] = now;
  state.fracture.damage_criterion[z] = static_cast<std::uint8_t>(why);
  StrengthZoneFields& strength = state.strength;
  strength.deviator_xx[z] = strength.deviator_yy[z] = strength.deviator_xy[z] = strength.deviator_zz[z] = 0.0;
  state.hydro.pressure[z] = std::max(state.hydro.pressure[z], 0.0);
  state.hourglass.hourglass_x[z] = state.hourglass.hourglass_y[z] = 0.0;
}

}  // namespace krug::fracture
