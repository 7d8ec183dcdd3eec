#include "krug/solver/body.hpp"

#include <algorithm>
#include <limits>

namespace krug {

BodySummary summarise_body(const Mesh& mesh, const Body& body, GeometryKind geometry) {
  const NodeFields& nodes = mesh.nodes;
  BodySummary s;
  double mass = 0.0;
  Vec2 momentum, moment;
  s.bbox_min = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  s.bbox_max = -s.bbox_min;
  for (Index p = body.node_begin; p < body.node_end; ++p) {
    mass += nodes.mass[p];
    momentum += nodes.mass[p] * nodes.velocity(p);
    moment += nodes.mass[p] * nodes.position(p);
    if (nodes.mass[p] == 0.0) continue;  // a node whose zones have all left the grid: no longer the body's
    s.bbox_min = {std::min(s.bbox_min.x, nodes.x[p]), std::min(s.bbox_min.y, nodes.y[p])};
    s.bbox_max = {std::max(s.bbox_max.x, nodes.x[p]), std::max(s.bbox_max.y, nodes.y[p])};
  }
  for (Index z = body.zone_begin; z < body.zone_end; ++z) s.zones += mesh.zones.active[z] ? 1 : 0;
  s.mass = whole_body_factor(geometry) * mass;
  if (mass > 0.0) {
    s.velocity = (1.0 / mass) * momentum;
    s.centroid = (1.0 / mass) * moment;
  }
  return s;
}

double internal_energy(const ZoneFields& zones, Index zone_begin, Index zone_end) {
  double sum = 0.0;
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (zones.active[z]) sum += zones.mass[z] * zones.specific_energy[z];
  }
  return sum;
}

std::vector<Fragment> body_fragments(const Mesh& mesh, const Body& body, GeometryKind geometry) {
  std::vector<Fragment> pieces = connected_pieces(mesh, body.zone_begin, body.zone_end);
  for (Fragment& f : pieces) f.mass *= whole_body_factor(geometry);
  std::sort(pieces.begin(), pieces.end(), [](const Fragment& a, const Fragment& b) { return a.mass > b.mass; });
  return pieces;
}

Index body_of_zone(const std::vector<Body>& bodies, Index zone) {
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (zone >= bodies[b].zone_begin && zone < bodies[b].zone_end) return static_cast<Index>(b);
  }
  return -1;
}

}  // namespace krug
