#pragma once
// Mesh generators: structured (i, j) patches of quadrilaterals appended to a Mesh. Every patch owns
// its nodes. Sides are named by logical direction: i_min, i_max, j_min, j_max.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "krug/mesh/mesh.hpp"

namespace krug::generate {

// One stretch of a graded axis: from the previous end to `to`, `zones` zones whose sizes grow by
// `ratio` from one zone to the next (ratio 1: uniform).
struct AxisSegment {
  double to = 0.0;
  int zones = 1;
  double ratio = 1.0;
};

// Grid-line coordinates starting at `from` and running through the segments in order.
std::vector<double> graded_axis(double from, const std::vector<AxisSegment>& segments);

struct Patch {
  Index node_begin = 0, node_end = 0;
  Index zone_begin = 0, zone_end = 0;
  int zones_i = 0, zones_j = 0;
  std::map<std::string, std::vector<Index>> sides;  // i_min, i_max, j_min, j_max -> nodes
};

// Optional map applied to every generated node position (for example a skewed mesh).
using PositionMap = std::function<Vec2(Vec2)>;

// Rectangle with grid lines at xs (i direction) and ys (j direction).
Patch rectangle(Mesh& mesh, const std::vector<double>& xs, const std::vector<double>& ys, Index body,
                const PositionMap& map = {});

// Annular sector: radii (i direction, increasing) and angles in radians (j direction, increasing),
// node at (radius cos angle, radius sin angle). A first radius of 0 makes the centre one node and the
// innermost ring of zones triangles (a repeated corner).
Patch sector(Mesh& mesh, const std::vector<double>& radii, const std::vector<double>& angles, Index body,
             const PositionMap& map = {});

}  // namespace krug::generate
