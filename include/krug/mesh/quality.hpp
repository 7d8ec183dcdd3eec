#pragma once
// Zone quality measures of a quadrilateral mesh, used to accept a generated mesh and to report how
// far a running one has distorted.
//
// Corner sine (the scaled Jacobian of the bilinear map at a corner): for corner p with edges
// e1 = x_{p+1} - x_p and e2 = x_{p-1} - x_p, sin(angle) = (e1 x e2) / (|e1| |e2|). It is 1 for a
// rectangle, falls to 0 for a sliver or a repeated corner (a zero-length edge counts as 0) and is
// negative for a reflex or inverted corner of a counter-clockwise zone. A zone's value is the
// smallest over its four corners.
//
// Aspect ratio: longest edge / smallest altitude = longest edge^2 / area, the same altitude that sets
// the CFL length (quad::smallest_altitude). It is w/h for a w x h rectangle (w >= h), 1 for a square,
// and grows without bound for a sliver of either kind (thin rectangle or flat parallelogram);
// +infinity for a zone of non-positive area.
#include <limits>
#include <optional>
#include <vector>

#include "krug/mesh/mesh.hpp"
#include "krug/mesh/quad.hpp"

namespace krug {

// Smallest of the four corner sines (see above).
double min_corner_sine(const quad::Corners& c);

// Longest edge^2 / area; +infinity when the area is not positive.
double aspect_ratio(const quad::Corners& c);

// Worst values over the active zones of a range, with the zone that attains each (-1 if none).
struct ZoneQuality {
  double min_corner_sine = std::numeric_limits<double>::infinity();
  Index min_corner_sine_zone = -1;
  double max_aspect_ratio = 0.0;
  Index max_aspect_ratio_zone = -1;
  double min_area = std::numeric_limits<double>::infinity();  // planar area in the computational plane (m^2)
  Index min_area_zone = -1;
  Index zones = 0;  // active zones measured
};

// Quality of the active zones in [zone_begin, zone_end), from the current node positions.
ZoneQuality zone_quality(const Mesh& mesh, Index zone_begin, Index zone_end);

// Overlap of two bodies at set-up: a node of [node_begin, node_end) that lies inside a zone of
// [zone_begin, zone_end) deeper than `depth_fraction` x that zone's smallest altitude behind the
// zone's boundary edges (a node on an interior edge is inside both zones), with the depth the
// distance to the nearest boundary edge (at least the smallest altitude for an interior zone).
// Bodies that touch (shared or coincident boundaries) do not overlap. Needs zones.neighbour
// (build_edge_continuations).
// Found through a uniform bucket grid of the nodes: linear in the sizes of both ranges. The test is
// exact for convex zones; a non-convex zone is tested as the intersection of its edges' half-planes.
struct NodeInZone {
  Index node = -1;
  Index zone = -1;
  double depth = 0.0;  // distance from the node to the zone's nearest edge (m)
};
std::optional<NodeInZone> find_node_inside_zones(const Mesh& mesh, Index node_begin, Index node_end, Index zone_begin,
                                                 Index zone_end, double depth_fraction = 1e-3);
// The same for arbitrary points (NodeInZone::node is then the point's index in `points`).
std::optional<NodeInZone> find_point_inside_zones(const Mesh& mesh, const std::vector<Vec2>& points, Index zone_begin,
                                                  Index zone_end, double depth_fraction = 1e-3);
// The same for the centres (corner means) of the active zones of [centre_begin, centre_end)
// (NodeInZone::node is then the zone): bodies whose nodes coincide, e.g. two identical bodies, or a
// body moved whole zones into another along its zone lines, have no node strictly inside the other's
// zones, but their zone centres are.
std::optional<NodeInZone> find_zone_centre_inside_zones(const Mesh& mesh, Index centre_begin, Index centre_end,
                                                        Index zone_begin, Index zone_end, double depth_fraction = 1e-3);

}  // namespace krug
