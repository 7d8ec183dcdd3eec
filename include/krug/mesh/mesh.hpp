#pragma once
// The Lagrangian mesh: zones with explicit 4-node connectivity (unstructured quadrilaterals) and
// node and zone fields stored as structure-of-arrays. Several bodies share one mesh; each body owns
// a contiguous range of nodes and of zones and never shares a node with another body.
//
// Time levels (docs/theory.md §2): positions, density, stress and energy live at t^n; velocities
// at half steps. Extensive quantities (mass, volume, force) are per radian in axisymmetric geometry
// and per unit thickness in planar geometry.
//
// ZoneFields holds what describes a zone itself: its connectivity and neighbours, whether it is still
// on the grid, its mass, geometry, density and specific energy (the state a setup gives and the hydro
// update carries). The packages' per-zone state (EOS results, stress, hourglass, damage) is grouped
// in zone_state.hpp and lives in the run state beside the mesh.
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
  std::vector<double> volume;                    // m^3 per radian (axisymmetric) or m^2 (planar)
  std::vector<double> area;                      // planar area in the computational plane (m^2)
  // Nodes continuing each edge through the neighbouring zones (for the viscosity limiter): the edge
  // (p, p+1) continues backwards as (before[p], p) and forwards as (p+1, after[p]); -1 at a boundary.
  std::vector<ZoneCorners> edge_before, edge_after;
  std::vector<ZoneCorners> neighbour;            // zone across each edge (p, p+1); -1 on a boundary
  bool neighbours_built = false;                 // set by build_edge_continuations, cleared by resize
  std::vector<double> corner_mass;               // 4 per zone: the zone's share of each corner node's mass
  std::vector<double> subzone_mass;              // 4 per zone: the mass of each corner's median-mesh region
  std::vector<double> initial_altitude;          // smallest altitude of the initial shape (m)

  Index size() const { return static_cast<Index>(corners.size()); }
  void resize(Index n);
};

// The field registry: every per-node and per-zone array, once, with its name, its entries per node or
// zone and the value a new entry takes. Resizing and checkpoints (write and read, in this order) walk
// these lists, so a new field is its member above plus one line here. `f(name, array, per, fill)`.
template <class Nodes, class F>
void for_each_node_field(Nodes& n, F&& f) {
  f("x", n.x, 1, 0.0);
  f("y", n.y, 1, 0.0);
  f("u", n.u, 1, 0.0);
  f("v", n.v, 1, 0.0);
  f("u_old", n.u_old, 1, 0.0);
  f("v_old", n.v_old, 1, 0.0);
  f("force_x", n.force_x, 1, 0.0);
  f("force_y", n.force_y, 1, 0.0);
  f("mass", n.mass, 1, 0.0);
  f("x0", n.x0, 1, 0.0);
  f("y0", n.y0, 1, 0.0);
  f("inv_mass_x", n.inv_mass_x, 1, 0.0);
  f("inv_mass_y", n.inv_mass_y, 1, 0.0);
  f("body", n.body, 1, Index{-1});
}

template <class Zones, class F>
void for_each_zone_field(Zones& z, F&& f) {
  constexpr ZoneCorners none{-1, -1, -1, -1};
  f("corners", z.corners, 1, none);
  f("body", z.body, 1, Index{-1});
  f("active", z.active, 1, std::uint8_t{1});
  f("mass", z.mass, 1, 0.0);
  f("density", z.density, 1, 0.0);
  f("specific_energy", z.specific_energy, 1, 0.0);
  f("volume", z.volume, 1, 0.0);
  f("area", z.area, 1, 0.0);
  f("edge_before", z.edge_before, 1, none);
  f("edge_after", z.edge_after, 1, none);
  f("neighbour", z.neighbour, 1, none);
  f("corner_mass", z.corner_mass, 4, 0.0);
  f("subzone_mass", z.subzone_mass, 4, 0.0);
  f("initial_altitude", z.initial_altitude, 1, 0.0);
}

// A field added to NodeFields or ZoneFields without its registry line changes these sizes: the build
// stops here (every member is a std::vector of 24 bytes, plus ZoneFields' neighbours_built flag).
static_assert(sizeof(std::vector<double>) != 24 || sizeof(NodeFields) == 14 * 24,
              "NodeFields changed: add the field to for_each_node_field");
static_assert(sizeof(std::vector<double>) != 24 || sizeof(ZoneFields) == 14 * 24 + 8,
              "ZoneFields changed: add the field to for_each_zone_field");

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
