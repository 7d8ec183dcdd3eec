#pragma once
// The Lagrangian mesh: zones with explicit 4-node connectivity (unstructured quadrilaterals) and
// node and zone fields stored as structure-of-arrays. Several bodies share one mesh; each body owns
// a contiguous range of nodes and of zones and never shares a node with another body.
//
// Time levels (docs/theory.md §2): positions, density, stress and energy live at t^n; velocities
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
  std::vector<double> subzone_mass;              // 4 per zone: the mass of each corner's median-mesh region
  // Fracture (docs/theory.md §2 step 6): permanent damage, when and why it started.
  std::vector<std::uint8_t> damaged;             // 0 intact, 1 damaged
  std::vector<double> damage_time;               // s; -1 while intact
  std::vector<std::uint8_t> damage_criterion;    // fracture::Criterion that fired
  std::vector<double> damage;                    // a damage law's D (Johnson-Cook: sum d eps_p / eps_f); 0 otherwise
  std::vector<double> damage_plastic_strain;     // the plastic strain already counted in `damage`
  std::vector<double> initial_altitude;          // smallest altitude of the initial shape (m)
  std::vector<double> stable_time_step;          // the zone's own stable step from the last update (s)

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
  f("pressure", z.pressure, 1, 0.0);
  f("sound_speed", z.sound_speed, 1, 0.0);
  f("volume", z.volume, 1, 0.0);
  f("area", z.area, 1, 0.0);
  f("viscous_speed", z.viscous_speed, 1, 0.0);
  f("volume_change", z.volume_change, 1, 0.0);
  f("corner_force", z.corner_force, 8, 0.0);
  f("deviator_xx", z.deviator_xx, 1, 0.0);
  f("deviator_yy", z.deviator_yy, 1, 0.0);
  f("deviator_xy", z.deviator_xy, 1, 0.0);
  f("deviator_zz", z.deviator_zz, 1, 0.0);
  f("plastic_strain", z.plastic_strain, 1, 0.0);
  f("hourglass_x", z.hourglass_x, 1, 0.0);
  f("hourglass_y", z.hourglass_y, 1, 0.0);
  f("edge_before", z.edge_before, 1, none);
  f("edge_after", z.edge_after, 1, none);
  f("neighbour", z.neighbour, 1, none);
  f("corner_mass", z.corner_mass, 4, 0.0);
  f("subzone_mass", z.subzone_mass, 4, 0.0);
  f("damaged", z.damaged, 1, std::uint8_t{0});
  f("damage_time", z.damage_time, 1, -1.0);
  f("damage_criterion", z.damage_criterion, 1, std::uint8_t{0});
  f("damage", z.damage, 1, 0.0);
  f("damage_plastic_strain", z.damage_plastic_strain, 1, 0.0);
  f("initial_altitude", z.initial_altitude, 1, 0.0);
  f("stable_time_step", z.stable_time_step, 1, 0.0);
}

// A field added to NodeFields or ZoneFields without its registry line changes these sizes: the build
// stops here (every member is a std::vector of 24 bytes, plus ZoneFields' neighbours_built flag).
static_assert(sizeof(std::vector<double>) != 24 || sizeof(NodeFields) == 14 * 24,
              "NodeFields changed: add the field to for_each_node_field");
static_assert(sizeof(std::vector<double>) != 24 || sizeof(ZoneFields) == 32 * 24 + 8,
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
