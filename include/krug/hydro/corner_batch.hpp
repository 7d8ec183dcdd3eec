#pragma once
// Corner positions and velocities of a run of consecutive zones, gathered into arrays (one array per
// corner and component) so that the loops over the batch vectorise. Shared by the force kernel
// (zone_forces.hpp) and the zone update (zone_update.hpp).
#include <array>

#include "krug/mesh/mesh.hpp"

namespace krug::detail {

template <int Size>
struct CornerBatch {
  double x[4][Size], y[4][Size];  // corner positions
  double u[4][Size], v[4][Size];  // corner velocities

  // Zones [first, first + count) of the mesh, count <= Size (inactive zones too: their values are
  // computed and never used).
  void gather(const Mesh& mesh, Index first, int count) {
    const NodeFields& nodes = mesh.nodes;
    for (int i = 0; i < count; ++i) {
      const ZoneCorners& n = mesh.zones.corners[first + i];
      for (int p = 0; p < 4; ++p) {
        x[p][i] = nodes.x[n[p]];
        y[p][i] = nodes.y[n[p]];
        u[p][i] = nodes.u[n[p]];
        v[p][i] = nodes.v[n[p]];
      }
    }
  }
  quad::Corners corners(int i) const {
    return {Vec2{x[0][i], y[0][i]}, Vec2{x[1][i], y[1][i]}, Vec2{x[2][i], y[2][i]}, Vec2{x[3][i], y[3][i]}};
  }
  std::array<Vec2, 4> velocities(int i) const {
    return {Vec2{u[0][i], v[0][i]}, Vec2{u[1][i], v[1][i]}, Vec2{u[2][i], v[2][i]}, Vec2{u[3][i], v[3][i]}};
  }
};

}  // namespace krug::detail
