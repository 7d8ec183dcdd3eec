#include "krug/mesh/generators.hpp"

#include <cmath>

#include "krug/core/error.hpp"

namespace krug::generate {

std::vector<double> graded_axis(double from, const std::vector<AxisSegment>& segments) {
  std::vector<double> lines{from};
  for (const AxisSegment& s : segments) {
    if (s.zones < 1) throw InputError("graded axis: a segment needs at least one zone");
    if (!(s.ratio > 0.0)) throw InputError("graded axis: the zone growth ratio must be positive");
    const double start = lines.back();
    // Zone sizes h, h r, h r^2, ...: h = L (r - 1) / (r^n - 1), or L / n for r = 1.
    const double length = s.to - start;
    double weight_sum = 0.0, weight = 1.0;
    for (int k = 0; k < s.zones; ++k) { weight_sum += weight; weight *= s.ratio; }
    double position = start;
    weight = 1.0;
    for (int k = 0; k < s.zones - 1; ++k) {
      position += length * weight / weight_sum;
      lines.push_back(position);
      weight *= s.ratio;
    }
    lines.push_back(s.to);  // land exactly on the breakpoint
  }
  return lines;
}

namespace {

Patch structured_patch(Mesh& mesh, int ni, int nj, Index body, bool collapse_i_min,
                       const std::function<Vec2(int, int)>& node_position, const PositionMap& map) {
  Patch patch;
  patch.zones_i = ni;
  patch.zones_j = nj;
  patch.node_begin = mesh.nodes.size();
  // node_id(i, j); with a collapsed i_min every (0, j) is the single centre node.
  std::vector<Index> ids(static_cast<std::size_t>((ni + 1) * (nj + 1)));
  Index next_node = patch.node_begin;
  std::vector<Vec2> positions;
  for (int j = 0; j <= nj; ++j) {
    for (int i = 0; i <= ni; ++i) {
      Index& id = ids[static_cast<std::size_t>(j * (ni + 1) + i)];
      if (collapse_i_min && i == 0 && j > 0) {
        id = ids[0];
        continue;
      }
      id = next_node++;
      Vec2 x = node_position(i, j);
      if (map) x = map(x);
      positions.push_back(x);
    }
  }
  patch.node_end = next_node;
  mesh.nodes.resize(patch.node_end);
  for (Index n = patch.node_begin; n < patch.node_end; ++n) {
    mesh.nodes.x[n] = positions[static_cast<std::size_t>(n - patch.node_begin)].x;
    mesh.nodes.y[n] = positions[static_cast<std::size_t>(n - patch.node_begin)].y;
    mesh.nodes.body[n] = body;
  }
  auto id = [&](int i, int j) { return ids[static_cast<std::size_t>(j * (ni + 1) + i)]; };

  patch.zone_begin = mesh.zones.size();
  patch.zone_end = patch.zone_begin + ni * nj;
  mesh.zones.resize(patch.zone_end);
  Index z = patch.zone_begin;
  for (int j = 0; j < nj; ++j) {
    for (int i = 0; i < ni; ++i, ++z) {
      mesh.zones.corners[z] = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      mesh.zones.body[z] = body;
    }
  }
  auto side = [&](const std::string& name, auto&& node_of, int count) {
    std::vector<Index> nodes;
    for (int k = 0; k <= count; ++k) {
      const Index n = node_of(k);
      if (nodes.empty() || nodes.back() != n) nodes.push_back(n);
    }
    patch.sides[name] = std::move(nodes);
  };
  side("i_min", [&](int k) { return id(0, k); }, nj);
  side("i_max", [&](int k) { return id(ni, k); }, nj);
  side("j_min", [&](int k) { return id(k, 0); }, ni);
  side("j_max", [&](int k) { return id(k, nj); }, ni);
  return patch;
}

}  // namespace

Patch rectangle(Mesh& mesh, const std::vector<double>& xs, const std::vector<double>& ys, Index body,
                const PositionMap& map) {
  if (xs.size() < 2 || ys.size() < 2) throw InputError("rectangle: needs at least one zone each way");
  const int ni = static_cast<int>(xs.size()) - 1, nj = static_cast<int>(ys.size()) - 1;
  return structured_patch(mesh, ni, nj, body, false,
                          [&](int i, int j) { return Vec2{xs[static_cast<std::size_t>(i)], ys[static_cast<std::size_t>(j)]}; }, map);
}

Patch sector(Mesh& mesh, const std::vector<double>& radii, const std::vector<double>& angles, Index body,
             const PositionMap& map) {
  if (radii.size() < 2 || angles.size() < 2) throw InputError("sector: needs at least one zone each way");
  const int ni = static_cast<int>(radii.size()) - 1, nj = static_cast<int>(angles.size()) - 1;
  const bool centre = radii.front() == 0.0;
  return structured_patch(mesh, ni, nj, body, centre, [&](int i, int j) {
    const double r = radii[static_cast<std::size_t>(i)], a = angles[static_cast<std::size_t>(j)];
    return Vec2{r * std::cos(a), r * std::sin(a)};
  }, map);
}

}  // namespace krug::generate
