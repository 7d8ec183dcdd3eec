#pragma once
// Artificial heat conduction (after Noh, J. Comput. Phys. 72, 1987): across every face shared by two
// zones of one body, internal energy flows from the hotter zone to the colder at the rate
// k rho (c + w) A_f (e_a - e_b), with rho and c the two zones' mean density and sound speed, w their
// closing speed (0 when they separate) and A_f the face (its length, times its mean radius in
// axisymmetric geometry). It spreads the excess heating a converging shock leaves at a wall, an axis
// or the origin ("wall heating"), and the blast's hot core, which otherwise drive the lightest nodes of
// the mesh (the axis row; docs/verification.md, F7). It also smears contact discontinuities, so it is
// an option for implosions and blasts, off by default. Exchanges are pairwise and summed in zone
// order: a body's internal energy is conserved to round-off and the result is the same on any number
// of threads. Explicit: each face's exchange is scaled down where a zone would otherwise give or take
// more in one step than equalises it with all its neighbours (dt K / m <= 1, K its faces' sum).
#include <algorithm>
#include <cmath>
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"

namespace krug {

// Adds to energy_change[z] (J per radian or per m; sized to the mesh's zones) the heat zone z gains
// over a step of dt from its neighbours in [zone_begin, zone_end). The mesh's edge neighbours must be
// built (build_edge_continuations). Reads the mesh and hydro.sound_speed.
inline void exchange_heat(const Mesh& mesh, const HydroZoneFields& hydro, Index zone_begin, Index zone_end,
                          double coefficient, double dt, GeometryKind geometry, std::vector<double>& energy_change) {
  const ZoneFields& zones = mesh.zones;
  const NodeFields& nodes = mesh.nodes;
  const bool axisymmetric = geometry == GeometryKind::axisymmetric;
  struct Face {
    Index a, b;
    double conductance;  // kg/s: heat per unit of specific-energy difference per unit time
  };
  std::vector<Face> faces;
  const std::size_t count = static_cast<std::size_t>(zone_end - zone_begin);
  std::vector<double> total(count, 0.0);
  std::vector<Vec2> centre(count), velocity(count);  // each zone's mean corner position and velocity
  for (Index z = zone_begin; z < zone_end; ++z) {
    for (Index n : zones.corners[z]) {
      centre[static_cast<std::size_t>(z - zone_begin)] += 0.25 * nodes.position(n);
      velocity[static_cast<std::size_t>(z - zone_begin)] += 0.25 * nodes.velocity(n);
    }
  }
  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!zones.active[z]) continue;
    const ZoneCorners& n = zones.corners[z];
    for (int k = 0; k < 4; ++k) {
      const Index o = zones.neighbour[z][k];
      if (o <= z || o >= zone_end || !zones.active[o]) continue;  // each face once, inside the body
      const Vec2 a = nodes.position(n[k]), b = nodes.position(n[(k + 1) & 3]);
      const double face = norm(b - a) * (axisymmetric ? 0.5 * (a.y + b.y) : 1.0);
      const std::size_t iz = static_cast<std::size_t>(z - zone_begin), io = static_cast<std::size_t>(o - zone_begin);
      const Vec2 d = centre[io] - centre[iz];
      const double distance = norm(d);
      if (!(distance > 0.0) || !(face > 0.0)) continue;
      const double closing = -dot(velocity[io] - velocity[iz], d) / distance;
      const double rho = 0.5 * (zones.density[z] + zones.density[o]);
      const double c = 0.5 * (hydro.sound_speed[z] + hydro.sound_speed[o]);
      const double conductance = coefficient * rho * (c + std::max(closing, 0.0)) * face;
      faces.push_back({z, o, conductance});
      total[static_cast<std::size_t>(z - zone_begin)] += conductance;
      total[static_cast<std::size_t>(o - zone_begin)] += conductance;
    }
  }
  // The explicit limit: a zone of mass m exchanging with conductance sum K over dt does not overshoot
  // its neighbours while dt K / m <= 1; the faces of a zone beyond it are scaled down.
  auto scale = [&](Index z) {
    const double k = dt * total[static_cast<std::size_t>(z - zone_begin)];
    return k > zones.mass[z] ? zones.mass[z] / k : 1.0;
  };
  for (const Face& f : faces) {
    const double flux =
        dt * f.conductance * std::min(scale(f.a), scale(f.b)) * (zones.specific_energy[f.a] - zones.specific_energy[f.b]);
    energy_change[static_cast<std::size_t>(f.a)] -= flux;
    energy_change[static_cast<std::size_t>(f.b)] += flux;
  }
}

}  // namespace krug
