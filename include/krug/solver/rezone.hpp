#pragma once
// Rezoning where the Lagrangian mesh degrades (docs/theory.md §2, step 5c): the interior nodes of a
// body's distorted zones are relaxed toward the mean of their edge neighbours, and the zones they touch
// are remapped conservatively onto the moved mesh. Off unless a body asks for it (Body::rezone_ratio).
//
// What moves: an interior node of the body (every edge at it has an active zone on both sides, both
// components free, no triangle at it) that is a corner of a distorted zone: one whose smallest altitude
// is below rezone_ratio x its initial altitude, or one with a corner sharper than 14.5 degrees or wider
// than 165.5. It moves `relaxation` of the way to the mean of its edge neighbours; the fraction is
// halved until every zone at the node keeps at least 1 - step_fraction of its area and all its corners
// convex (the node moved alone). Boundary nodes never move: the body's shape, its contact surfaces and
// its held nodes stay as they are.
//
// The remap (first order, donor cell; Benson 1992): every edge between two zones sweeps a volume
// (r-weighted in RZ) as its nodes move; the mass of that volume, at the upwind zone's density, passes
// with the upwind zone's specific energy, deviatoric stress and plastic strain. Mass and internal energy
// are conserved (to round-off); the corner and subzone masses of the touched zones are derived again
// from their new density. A moved node takes the old velocity field's value at its new place, from the
// least-squares gradient of its neighbours' velocities, kept within their range. The body's axial
// momentum (both components in planar geometry) is then restored exactly by a uniform correction of the
// touched nodes, and the change of kinetic energy goes into the internal energy of the touched zones
// (booked as the ledger's `rezone` line), so that the energy ledger closes. The hourglass stiffness state
// stays with its zone.
#include <array>
#include <cstdint>
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/material/material.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/solver/body.hpp"

namespace krug {

struct RezoneParams {
  double time_step = 0.0;          // dt^{n+1/2}, for the |dV/V| limit of the touched zones' stable step
  double max_volume_change = 0.1;  // as update_zones
  double cfl = 0.5;                // for the touched zones' new stable step (as update_zones)
  double step_fraction = 0.1;      // largest share of a zone's area one node's move may take
  double relaxation = 0.05;        // fraction of the way to the neighbours' mean per step (Body::rezone_relaxation)
};

// Work arrays kept from step to step (sized to the mesh on first use; the marks are cleared after use).
struct RezoneScratch {
  std::vector<std::uint8_t> node_mark, zone_mark;
  std::vector<Index> local;  // a touched zone's place in `touched`
  std::vector<Vec2> to, velocity_at;
  std::vector<Index> candidates, moved_nodes, touched, affected;
  std::vector<quad::Corners> new_x;
  std::vector<double> mass_change;
  std::vector<std::array<double, 6>> carried_change;
};

struct RezoneResult {
  Index moved_nodes = 0;
  Index remapped_zones = 0;
  double kinetic_to_internal = 0.0;  // kinetic energy the remap moved into internal energy (J per radian or per m)
};

// Rezones one body (a no-op when body.rezone_ratio <= 0), after the zone update of the step. Reads
// `corners` (node_corners of the mesh), the inverse masses (held components), the zones' initial
// altitudes and viscous speeds; writes the positions and velocities of the moved nodes, the masses,
// inverse masses and velocities of the nodes of the touched zones, and the touched zones' mass,
// geometry, density, energy, corner and subzone masses, pressure, sound speed, stable step, deviator
// and plastic strain. Nothing is written when a touched zone would not keep a positive area, volume
// and mass. Deterministic and serial (the touched set is small).
RezoneResult rezone_body(Mesh& mesh, ZoneState& state, const Body& body, const Material& material,
                         GeometryKind geometry, const NodeCorners& corners, const RezoneParams& params,
                         RezoneScratch& scratch);

}  // namespace krug
