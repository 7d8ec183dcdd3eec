#include "krug/particles/conversion.hpp"

#include <algorithm>
#include <cmath>

#include "krug/mesh/quad.hpp"

namespace krug {

ConversionEnergy convert_zone_to_particles(Mesh& mesh, Particles& particles, Index z, int particles_per_zone,
                                           double time, std::vector<Index>& zones_per_node,
                                           const std::vector<std::uint8_t>& held_x,
                                           const std::vector<std::uint8_t>& held_y) {
  ZoneFields& zones = mesh.zones;
  NodeFields& nodes = mesh.nodes;
  const ZoneCorners n = zones.corners[z];
  const double* corner_mass = &zones.corner_mass[4 * static_cast<std::size_t>(z)];
  const double mass = zones.mass[z];
  const quad::Corners x = mesh.corner_positions(z);
  const double area = zones.area[z];
  // The disc inscribed in the zone: of diameter sqrt(A) in a square, but never wider than the zone's
  // smallest altitude (A over its longest edge, the inscribed diameter of a parallelogram), so that a
  // flattened zone does not leave a disc that reaches through its faces into its neighbours.
  const double inscribed_diameter = std::min(std::sqrt(area), quad::smallest_altitude(x, area));

  double corner_total = 0.0;
  Vec2 momentum;
  for (int p = 0; p < 4; ++p) {
    corner_total += corner_mass[p];
    momentum += corner_mass[p] * nodes.velocity(n[p]);
  }
  const Vec2 mean_velocity = (1.0 / corner_total) * momentum;
  const std::int32_t origin = nodes.body[n[0]];
  double kinetic_defect = 0.0;
  if (particles_per_zone == 4) {
    // 2 x 2 sub-particles: each corner's mass with its node's velocity (kinetic energy exact).
    for (int p = 0; p < 4; ++p) {
      const quad::Corners region = quad::corner_region(x, p);
      particles.add(quad::centre(region), nodes.velocity(n[p]), corner_mass[p] * mass / corner_total,
                    0.25 * inscribed_diameter, origin, time);
    }
  } else {
    // One particle inscribed in the zone, the zone's mass and momentum.
    for (int p = 0; p < 4; ++p) {
      const Vec2 d = nodes.velocity(n[p]) - mean_velocity;
      kinetic_defect += 0.5 * corner_mass[p] * dot(d, d);
    }
    particles.add(quad::centre(x), mean_velocity, mass, 0.5 * inscribed_diameter, origin, time);
  }
  ConversionEnergy energy;
  energy.internal = mass * zones.specific_energy[z];
  energy.kinetic_defect = kinetic_defect;

  // The zone's share of each corner node leaves with it; a node left without zones is removed.
  for (int p = 0; p < 4; ++p) {
    nodes.mass[n[p]] -= corner_mass[p];
  }
  for (int p = 0; p < 4; ++p) {
    if (p > 0 && n[p] == n[p - 1]) continue;
    if (p == 3 && n[3] == n[0]) continue;
    const auto node = static_cast<std::size_t>(n[p]);
    if (--zones_per_node[node] == 0) nodes.mass[n[p]] = 0.0;
    const double inverse = nodes.mass[n[p]] > 0.0 ? 1.0 / nodes.mass[n[p]] : 0.0;
    nodes.inv_mass_x[n[p]] = held_x[node] ? 0.0 : inverse;
    nodes.inv_mass_y[n[p]] = held_y[node] ? 0.0 : inverse;
  }
  zones.active[z] = 0;
  for (int k = 0; k < 4; ++k) {
    const Index w = zones.neighbour[z][k];
    if (w < 0) continue;
    for (int j = 0; j < 4; ++j) {
      if (zones.neighbour[w][j] == z) zones.neighbour[w][j] = -1;
    }
    zones.neighbour[z][k] = -1;
  }
  return energy;
}

}  // namespace krug
