#include "krug/mesh/pieces.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace krug {

std::vector<Fragment> connected_pieces(const Mesh& mesh, Index zone_begin, Index zone_end) {
  const ZoneFields& zones = mesh.zones;
  const NodeFields& nodes = mesh.nodes;
  const Index count = zone_end - zone_begin;
  std::vector<Index> parent(static_cast<std::size_t>(count));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index i) {
    while (parent[static_cast<std::size_t>(i)] != i) {
      parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
      i = parent[static_cast<std::size_t>(i)];
    }
    return i;
  };
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!zones.active[z]) continue;
    for (int k = 0; k < 4; ++k) {
      const Index w = zones.neighbour[z][k];
      if (w >= 0 && zones.active[w]) {
        const Index a = find(z - zone_begin), c = find(w - zone_begin);
        if (a != c) parent[static_cast<std::size_t>(std::max(a, c))] = std::min(a, c);
      }
    }
  }
  std::vector<Index> slot(static_cast<std::size_t>(count), -1);
  std::vector<Fragment> pieces;
  std::vector<double> moment_mass;
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!zones.active[z]) continue;
    const Index root = find(z - zone_begin);
    Index& s = slot[static_cast<std::size_t>(root)];
    if (s < 0) {
      s = static_cast<Index>(pieces.size());
      pieces.emplace_back();
      pieces.back().bbox_min = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
      pieces.back().bbox_max = -pieces.back().bbox_min;
    }
    Fragment& f = pieces[static_cast<std::size_t>(s)];
    const double* corner_mass = &zones.corner_mass[4 * static_cast<std::size_t>(z)];
    for (int p = 0; p < 4; ++p) {
      const Index node = zones.corners[z][p];
      f.velocity += corner_mass[p] * nodes.velocity(node);
      f.centroid += corner_mass[p] * nodes.position(node);
      f.bbox_min = {std::min(f.bbox_min.x, nodes.x[node]), std::min(f.bbox_min.y, nodes.y[node])};
      f.bbox_max = {std::max(f.bbox_max.x, nodes.x[node]), std::max(f.bbox_max.y, nodes.y[node])};
    }
    f.mass += zones.mass[z];
    ++f.zones;
  }
  for (Fragment& f : pieces) {
    f.velocity = (1.0 / f.mass) * f.velocity;
    f.centroid = (1.0 / f.mass) * f.centroid;
  }
  return pieces;
}

}  // namespace krug
