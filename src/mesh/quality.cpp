#include "krug/mesh/quality.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace krug {

double min_corner_sine(const quad::Corners& c) {
  double smallest = 1.0;
  for (int p = 0; p < 4; ++p) {
    const Vec2 e1 = c[quad::next(p)] - c[p];
    const Vec2 e2 = c[quad::prev(p)] - c[p];
    const double lengths = norm(e1) * norm(e2);
    const double sine = lengths > 0.0 ? cross(e1, e2) / lengths : 0.0;  // repeated corner: degenerate
    smallest = std::min(smallest, sine);
  }
  return smallest;
}

double aspect_ratio(const quad::Corners& c) {
  const double zone_area = quad::area(c);
  if (!(zone_area > 0.0)) return std::numeric_limits<double>::infinity();
  double longest = 0.0;
  for (int p = 0; p < 4; ++p) {
    const Vec2 e = c[quad::next(p)] - c[p];
    longest = std::max(longest, dot(e, e));
  }
  return longest / zone_area;
}

ZoneQuality zone_quality(const Mesh& mesh, Index zone_begin, Index zone_end) {
  ZoneQuality q;
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!mesh.zones.active[z]) continue;
    ++q.zones;
    const quad::Corners c = mesh.corner_positions(z);
    const double sine = min_corner_sine(c);
    if (sine < q.min_corner_sine) { q.min_corner_sine = sine; q.min_corner_sine_zone = z; }
    const double aspect = aspect_ratio(c);
    if (aspect > q.max_aspect_ratio || q.max_aspect_ratio_zone < 0) {
      q.max_aspect_ratio = aspect;
      q.max_aspect_ratio_zone = z;
    }
    const double zone_area = quad::area(c);
    if (zone_area < q.min_area) { q.min_area = zone_area; q.min_area_zone = z; }
  }
  return q;
}

std::optional<NodeInZone> find_node_inside_zones(const Mesh& mesh, Index node_begin, Index node_end, Index zone_begin,
                                                 Index zone_end, double depth_fraction) {
  std::vector<Vec2> points;
  points.reserve(static_cast<std::size_t>(std::max<Index>(node_end - node_begin, 0)));
  for (Index n = node_begin; n < node_end; ++n) points.push_back(mesh.nodes.position(n));
  std::optional<NodeInZone> found = find_point_inside_zones(mesh, points, zone_begin, zone_end, depth_fraction);
  if (found) found->node += node_begin;
  return found;
}

std::optional<NodeInZone> find_zone_centre_inside_zones(const Mesh& mesh, Index centre_begin, Index centre_end,
                                                        Index zone_begin, Index zone_end, double depth_fraction) {
  std::vector<Vec2> points;
  std::vector<Index> zone_of;
  for (Index z = centre_begin; z < centre_end; ++z) {
    if (!mesh.zones.active[z]) continue;
    Vec2 centre{0.0, 0.0};
    for (const Vec2& c : mesh.corner_positions(z)) centre += 0.25 * c;
    points.push_back(centre);
    zone_of.push_back(z);
  }
  std::optional<NodeInZone> found = find_point_inside_zones(mesh, points, zone_begin, zone_end, depth_fraction);
  if (found) found->node = zone_of[static_cast<std::size_t>(found->node)];
  return found;
}

std::optional<NodeInZone> find_point_inside_zones(const Mesh& mesh, const std::vector<Vec2>& points, Index zone_begin,
                                                  Index zone_end, double depth_fraction) {
  // Bounding box of the zones, and their mean size for the bucket width.
  Vec2 low{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 high = -low;
  double size_sum = 0.0;
  Index zone_count = 0;
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!mesh.zones.active[z]) continue;
    for (const Vec2& c : mesh.corner_positions(z)) {
      low = {std::min(low.x, c.x), std::min(low.y, c.y)};
      high = {std::max(high.x, c.x), std::max(high.y, c.y)};
    }
    size_sum += std::sqrt(std::abs(quad::area(mesh.corner_positions(z))));
    ++zone_count;
  }
  if (zone_count == 0) return std::nullopt;
  if (!mesh.zones.neighbours_built) throw std::logic_error("find_point_inside_zones: build_edge_continuations first");
  std::vector<Index> candidates;
  for (Index n = 0; n < static_cast<Index>(points.size()); ++n) {
    const Vec2 p = points[static_cast<std::size_t>(n)];
    if (p.x > low.x && p.x < high.x && p.y > low.y && p.y < high.y) candidates.push_back(n);
  }
  if (candidates.empty()) return std::nullopt;
  const double width = std::max(size_sum / static_cast<double>(zone_count), 1e-12 * std::max(high.x - low.x, high.y - low.y));
  const auto cells = [&](double extent) {
    return static_cast<Index>(std::clamp(std::ceil(extent / width), 1.0, 4096.0));
  };
  const Index nx = cells(high.x - low.x);
  const Index ny = cells(high.y - low.y);
  const auto cell_of = [&](double v, double origin, double extent, Index count) {
    return std::clamp(static_cast<Index>((v - origin) / extent * static_cast<double>(count)), Index{0}, count - 1);
  };
  // Counting sort of the candidate nodes into cells.
  std::vector<Index> start(static_cast<std::size_t>(nx * ny + 1), 0);
  std::vector<Index> cell_of_node(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Vec2 p = points[static_cast<std::size_t>(candidates[i])];
    cell_of_node[i] = cell_of(p.x, low.x, high.x - low.x, nx) + nx * cell_of(p.y, low.y, high.y - low.y, ny);
    ++start[static_cast<std::size_t>(cell_of_node[i] + 1)];
  }
  for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  std::vector<Index> sorted(candidates.size());
  {
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      sorted[static_cast<std::size_t>(fill[static_cast<std::size_t>(cell_of_node[i])]++)] = candidates[i];
    }
  }
  std::optional<NodeInZone> deepest;
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!mesh.zones.active[z]) continue;
    const quad::Corners c = mesh.corner_positions(z);
    const double zone_area = quad::area(c);
    if (!(zone_area > 0.0)) continue;
    const double margin = depth_fraction * quad::smallest_altitude(c, zone_area);
    Vec2 zl = c[0], zh = c[0];
    for (const Vec2& q : c) {
      zl = {std::min(zl.x, q.x), std::min(zl.y, q.y)};
      zh = {std::max(zh.x, q.x), std::max(zh.y, q.y)};
    }
    const Index i0 = cell_of(zl.x, low.x, high.x - low.x, nx), i1 = cell_of(zh.x, low.x, high.x - low.x, nx);
    const Index j0 = cell_of(zl.y, low.y, high.y - low.y, ny), j1 = cell_of(zh.y, low.y, high.y - low.y, ny);
    for (Index j = j0; j <= j1; ++j) {
      for (Index i = i0; i <= i1; ++i) {
        const Index cell = i + nx * j;
        for (Index k = start[static_cast<std::size_t>(cell)]; k < start[static_cast<std::size_t>(cell + 1)]; ++k) {
          const Index n = sorted[static_cast<std::size_t>(k)];
          const Vec2 p = points[static_cast<std::size_t>(n)];
          // Inside (or on) every interior edge, and deeper than the margin behind every boundary edge.
          double depth = std::numeric_limits<double>::infinity();
          bool inside = true;
          for (int e = 0; e < 4 && inside; ++e) {
            const Vec2 edge = c[quad::next(e)] - c[e];
            const double length = norm(edge);
            if (length == 0.0) continue;  // a repeated corner (triangle)
            const double distance = cross(edge, p - c[e]) / length;
            if (mesh.zones.neighbour[z][e] >= 0) {
              inside = distance >= -1e-12 * length;
            } else {
              inside = distance > margin;
              depth = std::min(depth, distance);
            }
          }
          if (!inside) continue;
          if (!std::isfinite(depth)) depth = quad::smallest_altitude(c, zone_area);  // an interior zone: at least this
          if (!deepest || depth > deepest->depth) deepest = NodeInZone{n, z, depth};
        }
      }
    }
  }
  return deepest;
}

}  // namespace krug
