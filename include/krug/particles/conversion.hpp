#pragma once
// A zone leaves the mesh as free elements (Gulidov & Shabalin 1996; step 7 of the time step): one
// particle inscribed in the zone (radius min(sqrt(A), h)/2 with h the zone's smallest altitude, A over
// its longest edge: sqrt(A)/2 in a square, h/2 in a flattened zone; the zone's mass and momentum) or
// 2 x 2 sub-particles of half that radius (each corner's mass with its node's velocity, which also
// keeps kinetic energy exact).
// Mass and momentum pass exactly. The zone's share of each corner node's mass leaves with it; a node
// left without zones keeps no mass; the inverse masses are renewed (0 on a held degree of freedom);
// the zone is deactivated and unlinked from its neighbours. Which zones convert, and why, is the
// solver's choice (fracture and erosion rules); what the conversion does to the energy ledger is
// returned for the caller to book.
#include <cstdint>
#include <vector>

#include "krug/mesh/mesh.hpp"
#include "krug/particles/particles.hpp"

namespace krug {

// The energy that leaves the mesh with a zone (J per radian or per m).
struct ConversionEnergy {
  double internal = 0.0;        // the zone's internal energy (leaves the internal line)
  double kinetic_defect = 0.0;  // 1/2 sum m_p |u_p - u_mean|^2 of a single particle (0 for 2 x 2)
  double converted() const { return internal + kinetic_defect; }  // the converted line gains this
};

// Converts zone `zone` of `mesh` into `particles_per_zone` (1 or 4) particles born at `time`.
// `zones_per_node`: active zones touching each node (decremented); `held_x`, `held_y`: per node, the
// degrees of freedom a boundary condition holds.
ConversionEnergy convert_zone_to_particles(Mesh& mesh, Particles& particles, Index zone, int particles_per_zone,
                                           double time, std::vector<Index>& zones_per_node,
                                           const std::vector<std::uint8_t>& held_x,
                                           const std::vector<std::uint8_t>& held_y);

}  // namespace krug
