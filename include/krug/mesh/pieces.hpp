#pragma once
// Connected pieces of a range of zones (a body): zones joined by shared edges, both active. A body
// that fractures or erodes may fall apart; its pieces are its fragments (the plug of a plate, the
// remaining projectile).
#include <vector>

#include "krug/core/vec2.hpp"
#include "krug/mesh/mesh.hpp"

namespace krug {

struct Fragment {
  double mass = 0.0;   // kg per radian (RZ) or per m (planar) from connected_pieces; Simulation::fragments gives whole bodies
  Vec2 velocity;       // mass-weighted (corner masses and node velocities)
  Vec2 centroid;       // mass-weighted
  Vec2 bbox_min, bbox_max;  // over the corners of its zones
  Index zones = 0;
};

// The pieces of the active zones in [zone_begin, zone_end), in the order of their first zone.
std::vector<Fragment> connected_pieces(const Mesh& mesh, Index zone_begin, Index zone_end);

}  // namespace krug
