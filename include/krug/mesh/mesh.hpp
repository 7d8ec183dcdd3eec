#pragma once
// The Lagrangian mesh: zones with explicit 4-node connectivity (unstructured quadrilaterals) and
// node and zone fields stored as structure-of-arrays. Several bodies share one mesh; each body owns
// a contiguous range of nodes and of zones and never shares a node with another body.
//
// Time levels (DESIGN.md section 2): positions, density, stress and energy live at t^n; velocities
// at half steps. Extensive quantities (mass, volume, force) are per radian in axisymmetric geometry
// and per unit thickness in planar geometry.
#include <array>
#include <cstdint>
#include <vector>

#include "krug/core/vec2.hpp"
#include "krug/mesh/quad.hpp"

namespace krug {

using Index = std::int32_t;
using ZoneCorners = std::array<Index, 4>;

struct NodeFields {
  std::vector<double> x, y;                      // position at t^n (m); axisymmetric: x = z, y = r
  std::vector<double> u, v;                      // velocity at t^{n+1/2} after a step (m/s)
  std::vector<double> u_old, v_old;              // velocity at t^{n-1/2}, kept during a step (m/s)
  std::vector<double> force_x, force_y;          // F^n from the zones (N per radian or per m)
  std::vector<double> mass;                      // nodal mass (kg per radian or per m); fixed until a zone converts
  std::vector<double> x0, y0;                    // initial position (m), for the deformation of fracture criteria
  std::vector<double> inv_mass_x, inv_mass_y;    // per-DOF inverse mass; 0 where a condition fixes it
  std::vector<Index> body;

  Index size() const { return static_cast<Index>(x.size()); }
  Vec2 position(Index p) const { return {x[p], y[p]}; }
  Vec2 velocity(Index p) const { return {u[p], v[p]}; }
  void resize(Index n);
};

struct ZoneFields {
  std::vector<ZoneCorners> corners;              // node indices, counter-clockwise
  std::vector<Index> body;
  std::vector<std::uint8_t> active;              // 0 once a zone has left the grid
  std::vector<double> mass;                      // fixed (kg per radian or per m)
  std::vector<double> density;                   // kg/m^3 at t^n
  std::vector<double> specific_energy;           // J/kg
  std::vector<double> pressure;                  // Pa, from the EOS (artificial viscosity not included)
  std::vector<double> sound_speed;               // m/s, stress-wave speed used by the time step
  std::vector<double> volume;                    // m^3 per radian (axisymmetric) or m^2 (planar)
  std::vector<double> area;                      // planar area in the computational plane (m^2)
  std::vector<double> viscous_speed;             // m/s, the artificial-viscosity signal speed of the last step
  std::vector<double> volume_change;             // |dV/V| over the last step
  std::vector<double> corner_force;              // 8 per zone: force on corner p = (2p, 2p+1), at t^n
  std::vector<double> deviator_xx, deviator_yy;  // deviatoric stress (Pa)
  std::vector<double> deviator_xy, deviator_zz;  // zz: hoop (axisymmetric) or out-of-plane (planar)
  std::vector<double> plastic_strain;            // equivalent plastic strain
  std::vector<double> hourglass_x, hourglass_y;  // Flanagan-Belytschko stiffness generalised forces
  // Nodes continuing each edge through the neighbouring zones (for the viscosity limiter): the edge
  // (p, p+1) continues backwards as (before[p], p) and forwards as (p+1, after[p]); -1 at a boundary.
  std::vector<ZoneCorners> edge_before, edge_after;
  std::vector<ZoneCorners> neighbour;            // zone across each edge (p, p+1); -1 on a boundary
  bool neighbours_built = false;                 // set by build_edge_continuations, cleared by resize
  std::vector<double> corner_mass;               // 4 per zone: the zone's share of each corner node's mass
  // Fracture (DESIGN.md section 2 step 6): permanent damage, when and why it started.
  std::vector<std::uint8_t> damaged;             // 0 intact, 1 damaged
  std::vector<double> damage_time;               // s; -1 while intact
  std::vector<std::uint8_t> damage_criterion;    // fracture::Criterion that fired
  std::vector<double> initial_altitude;          // smallest altitude of the initial shape (m)
  std::vector<double> stable_time_step;          // the zone's own stable step from the last update (s)

  Index size() const { return static_cast<Index>(corners.size()); }
  void resize(Index n);
};

struct Mesh {
  NodeFields nodes;
  ZoneFields zones;

  quad::Corners corner_positions(Index zone) const {
    const ZoneCorners& c = zones.corners[zone];
    return {nodes.position(c[0]), nodes.position(c[1]), nodes.position(c[2]), nodes.position(c[3])};
  }
};

// A boundary segment: an edge used by exactly one active zone, oriented so that the zone lies on its
// left (the outward normal is to the right of a -> b).
struct BoundarySegment {
  Index a, b;
  Index zone;
};

// The corners of each node: the slots 4 z + p of the zone corners on node n are
// slot[offset[n] .. offset[n + 1]), sorted by zone (then by p).
struct NodeCorners {
  std::vector<Index> offset;
  std::vector<Index> slot;
};
NodeCorners node_corners(const Mesh& mesh);

// Recomputes edge_before/edge_after for all zones from the connectivity of active zones.
void build_edge_continuations(Mesh& mesh);

// For each zone edge (slot 4 z + k): the slot 4 w + j of the same edge in the zone w < z across it,
// if w continues the edge through the same nodes as z does (edge_before and edge_after mirrored), so
// that the viscosity limiter of the edge is the same seen from either zone; -1 otherwise (a boundary
// edge, or a node where the two zones find different continuations, e.g. of valence 3).
std::vector<Index> mirrored_edge_slots(const Mesh& mesh);

// Boundary segments of the active zones in [zone_begin, zone_end), in zone order: edges without a
// neighbour (zones.neighbour, kept up to date as zones leave the grid).
std::vector<BoundarySegment> boundary_segments(const Mesh& mesh, Index zone_begin, Index zone_end);

}  // namespace krug
