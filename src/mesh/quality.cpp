#include "krug/mesh/quality.hpp"

#include <algorithm>

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

}  // namespace krug
