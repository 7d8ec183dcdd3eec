#pragma once
// A body: its ranges of nodes and zones on the shared mesh, its material and erosion limits, and what
// is measured of it (summary, internal energy), as free functions of the mesh that read only.
#include <string>
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/pieces.hpp"

namespace krug {

struct Body {
  std::string name;
  Index material = 0;
  Index node_begin = 0, node_end = 0;
  Index zone_begin = 0, zone_end = 0;
  // Erosion (off by default): an intact zone that collapses or strains past these limits becomes a
  // particle (mass and momentum exact), counted as eroded mass (fracture::ErosionLimits).
  double erosion_altitude_ratio = 0.0;
  double erosion_plastic_strain = fracture::disabled;
  // Rezoning (off by default): the interior nodes of zones flattened below this ratio of their initial
  // smallest altitude are relaxed and the zones around them remapped (solver/rezone.hpp).
  double rezone_ratio = 0.0;
  double rezone_relaxation = 0.05;  // the fraction of the way to the neighbours' mean a node moves per step

  fracture::ErosionLimits erosion() const { return {erosion_altitude_ratio, erosion_plastic_strain}; }
  void set_erosion(const fracture::ErosionLimits& e) {
    erosion_altitude_ratio = e.altitude_ratio;
    erosion_plastic_strain = e.plastic_strain;
  }
};

// Per-body summary figures (whole body: x 2 pi in RZ).
struct BodySummary {
  double mass = 0.0;
  Vec2 velocity;   // mass-weighted mean velocity
  Vec2 centroid;   // mass-weighted node centroid
  Vec2 bbox_min, bbox_max;  // over the nodes still carrying mass (not those of zones that left the grid)
  Index zones = 0; // active zones
};

// Reads the body's nodes and zones of `mesh`.
BodySummary summarise_body(const Mesh& mesh, const Body& body, GeometryKind geometry);

// Sum m e over the active zones of [zone_begin, zone_end), in zone order (per radian or per m).
double internal_energy(const ZoneFields& zones, Index zone_begin, Index zone_end);

// Connected pieces of a body's remaining zones (by shared edges; connected_pieces), heaviest first,
// masses for the whole body (x 2 pi in RZ).
std::vector<Fragment> body_fragments(const Mesh& mesh, const Body& body, GeometryKind geometry);

// The body owning a zone (its index in `bodies`), -1 for none.
Index body_of_zone(const std::vector<Body>& bodies, Index zone);

}  // namespace krug
