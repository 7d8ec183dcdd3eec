// Connectivity-derived mesh data: field sizes, edge continuations for the viscosity limiter and
// boundary segments. Edges are matched by sorting (deterministic, independent of hashing).
#include <algorithm>
#include <string_view>
#include <tuple>

#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"

namespace krug {

void NodeFields::resize(Index n) {
  for_each_node_field(*this, [n](std::string_view, auto& field, std::size_t per, auto fill) {
    field.resize(per * static_cast<std::size_t>(n), fill);
  });
}

void ZoneFields::resize(Index n) {
  for_each_zone_field(*this, [n](std::string_view, auto& field, std::size_t per, auto fill) {
    field.resize(per * static_cast<std::size_t>(n), fill);
  });
  neighbours_built = false;
}

void ZoneState::resize(Index n) {
  for_each_zone_state_field(*this, [n](std::string_view, auto& field, std::size_t per, auto fill) {
    field.resize(per * static_cast<std::size_t>(n), fill);
  });
}

namespace {

struct EdgeRecord {
  Index low, high;  // node indices, low < high
  Index zone;
  int local;        // edge (corner local, corner local+1)
  bool operator<(const EdgeRecord& o) const {
    return std::tie(low, high, zone, local) < std::tie(o.low, o.high, o.zone, o.local);
  }
};

std::vector<EdgeRecord> sorted_edges(const Mesh& mesh, Index zone_begin, Index zone_end) {
  std::vector<EdgeRecord> edges;
  edges.reserve(4 * static_cast<std::size_t>(zone_end - zone_begin));
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!mesh.zones.active[z]) continue;
    const ZoneCorners& c = mesh.zones.corners[z];
    for (int k = 0; k < 4; ++k) {
      const Index a = c[k], b = c[quad::next(k)];
      if (a == b) continue;  // degenerate edge of a triangle-like zone
      edges.push_back({std::min(a, b), std::max(a, b), z, k});
    }
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

// In zone w, the neighbour of node n other than `exclude` (-1 if none).
Index other_neighbour(const ZoneCorners& w, Index n, Index exclude) {
  for (int j = 0; j < 4; ++j) {
    if (w[j] != n) continue;
    const Index before = w[quad::prev(j)], after = w[quad::next(j)];
    if (before != exclude && before != n) return before;
    if (after != exclude && after != n) return after;
  }
  return -1;
}

}  // namespace

void build_edge_continuations(Mesh& mesh) {
  const Index n = mesh.zones.size();
  const auto edges = sorted_edges(mesh, 0, n);
  // neighbour[4 z + k]: the zone across local edge k of zone z, or -1.
  for (Index z = 0; z < n; ++z) mesh.zones.neighbour[z] = ZoneCorners{-1, -1, -1, -1};
  mesh.zones.neighbours_built = true;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const EdgeRecord& e = edges[i];
    const EdgeRecord& f = edges[i + 1];
    if (e.low == f.low && e.high == f.high) {
      mesh.zones.neighbour[e.zone][e.local] = f.zone;
      mesh.zones.neighbour[f.zone][f.local] = e.zone;
    }
  }
  auto neighbour = [&](std::size_t slot) { return mesh.zones.neighbour[static_cast<Index>(slot / 4)][slot % 4]; };
  for (Index z = 0; z < n; ++z) {
    const ZoneCorners& c = mesh.zones.corners[z];
    for (int k = 0; k < 4; ++k) {
      const Index a = c[k], b = c[quad::next(k)];
      const Index across_before = neighbour(4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(quad::prev(k)));
      const Index across_after = neighbour(4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(quad::next(k)));
      mesh.zones.edge_before[z][k] =
          across_before < 0 ? -1 : other_neighbour(mesh.zones.corners[across_before], a, c[quad::prev(k)]);
      mesh.zones.edge_after[z][k] =
          across_after < 0 ? -1 : other_neighbour(mesh.zones.corners[across_after], b, c[quad::next(quad::next(k))]);
    }
  }
}

NodeCorners node_corners(const Mesh& mesh) {
  NodeCorners corners;
  const Index zone_count = mesh.zones.size();
  corners.offset.assign(static_cast<std::size_t>(mesh.nodes.size()) + 1, 0);
  for (Index z = 0; z < zone_count; ++z) {
    for (const Index n : mesh.zones.corners[z]) ++corners.offset[static_cast<std::size_t>(n) + 1];
  }
  for (std::size_t n = 1; n < corners.offset.size(); ++n) corners.offset[n] += corners.offset[n - 1];
  corners.slot.resize(static_cast<std::size_t>(corners.offset.back()));
  std::vector<Index> next(corners.offset.begin(), corners.offset.end() - 1);
  for (Index z = 0; z < zone_count; ++z) {  // zone order, then corner order: the order of the sums
    for (int p = 0; p < 4; ++p) {
      const Index n = mesh.zones.corners[z][static_cast<std::size_t>(p)];
      corners.slot[static_cast<std::size_t>(next[static_cast<std::size_t>(n)]++)] = 4 * z + p;
    }
  }
  return corners;
}

std::vector<Index> mirrored_edge_slots(const Mesh& mesh) {
  const ZoneFields& zones = mesh.zones;
  std::vector<Index> slots(4 * static_cast<std::size_t>(zones.size()), -1);
  for (Index z = 0; z < zones.size(); ++z) {
    const ZoneCorners& c = zones.corners[z];
    for (int k = 0; k < 4; ++k) {
      const Index w = zones.neighbour[z][k];
      if (w < 0 || w >= z) continue;
      for (int j = 0; j < 4; ++j) {
        const ZoneCorners& d = zones.corners[w];
        const bool same_edge = d[j] == c[quad::next(k)] && d[quad::next(j)] == c[k];
        if (same_edge && zones.edge_before[w][j] == zones.edge_after[z][k] &&
            zones.edge_after[w][j] == zones.edge_before[z][k]) {
          slots[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(k)] = 4 * w + j;
        }
      }
    }
  }
  return slots;
}

std::vector<BoundarySegment> boundary_segments(const Mesh& mesh, Index zone_begin, Index zone_end) {
  std::vector<BoundarySegment> segments;
  if (!mesh.zones.neighbours_built) {
    // A mesh fresh from the generators: match edges by sorting.
    const auto edges = sorted_edges(mesh, zone_begin, zone_end);
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const bool shared = (i > 0 && edges[i - 1].low == edges[i].low && edges[i - 1].high == edges[i].high) ||
                          (i + 1 < edges.size() && edges[i + 1].low == edges[i].low && edges[i + 1].high == edges[i].high);
      if (shared) continue;
      const ZoneCorners& c = mesh.zones.corners[edges[i].zone];
      segments.push_back({c[edges[i].local], c[quad::next(edges[i].local)], edges[i].zone});
    }
    std::sort(segments.begin(), segments.end(),
              [](const BoundarySegment& s, const BoundarySegment& t) { return std::tie(s.zone, s.a) < std::tie(t.zone, t.a); });
    return segments;
  }
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!mesh.zones.active[z]) continue;
    const ZoneCorners& c = mesh.zones.corners[z];
    for (int k = 0; k < 4; ++k) {
      const Index a = c[k], b = c[quad::next(k)];
      if (a != b && mesh.zones.neighbour[z][k] < 0) segments.push_back({a, b, z});
    }
  }
  return segments;
}

}  // namespace krug
