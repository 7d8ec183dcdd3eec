// Rezoning where the Lagrangian mesh degrades: relaxation of interior nodes and a first-order
// conservative remap of the zones they touch (krug/solver/rezone.hpp).
#include "krug/solver/rezone.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "krug/hydro/zone_update.hpp"
#include "krug/solver/hydro_step.hpp"

namespace krug {

namespace {

constexpr double sharp_corner_sine = 0.25;  // corners sharper than 14.5 degrees or wider than 165.5
constexpr double settled_distance = 0.05;   // of a zone's size: a node this close to its target stays

bool has_repeated_corner(const ZoneCorners& c) {
  for (int p = 0; p < 4; ++p) {
    if (c[p] == c[quad::next(p)]) return true;
  }
  return false;
}

// A zone flattened below `ratio` of its initial smallest altitude (area / longest edge, as
// quad::smallest_altitude) or with a corner sharper than the limit (sine below sharp_corner_sine,
// a reflex corner included); without square roots.
bool distorted(const quad::Corners& x, double area, double initial_altitude, double ratio) {
  double longest = 0.0;
  bool sharp = false;
  for (int p = 0; p < 4; ++p) {
    const Vec2 a = x[quad::next(p)] - x[p], b = x[quad::prev(p)] - x[p];
    const double aa = dot(a, a), bb = dot(b, b), turn = cross(a, b);
    longest = std::max(longest, aa);
    sharp = sharp || turn <= 0.0 || turn * turn < sharp_corner_sine * sharp_corner_sine * aa * bb;
  }
  const double limit = ratio * initial_altitude;
  return sharp || area <= 0.0 || area * area < limit * limit * longest;
}

// Every corner turns left (a zone with a corner at or beyond 180 degrees is eroded or converted).
bool convex(const quad::Corners& x) {
  for (int p = 0; p < 4; ++p) {
    if (!(cross(x[quad::next(p)] - x[p], x[quad::prev(p)] - x[p]) > 0.0)) return false;
  }
  return true;
}

// The specific quantities the remap carries with the mass, per zone.
constexpr int carried = 6;  // specific energy, deviator xx, yy, xy, zz, plastic strain

std::array<double, carried> carried_of(const ZoneFields& zones, const StrengthZoneFields& s, Index z) {
  return {zones.specific_energy[z], s.deviator_xx[z], s.deviator_yy[z], s.deviator_xy[z], s.deviator_zz[z],
          s.plastic_strain[z]};
}

void store_carried(ZoneFields& zones, StrengthZoneFields& s, Index z, const std::array<double, carried>& q) {
  zones.specific_energy[z] = q[0];
  s.deviator_xx[z] = q[1];
  s.deviator_yy[z] = q[2];
  s.deviator_xy[z] = q[3];
  s.deviator_zz[z] = q[4];
  s.plastic_strain[z] = q[5];
}

// Node marks.
constexpr std::uint8_t candidate_mark = 1, moved_mark = 2, affected_mark = 4;

// The place an interior candidate node moves to, and the old velocity field's value there; false when
// it is not interior or cannot move.
bool relax_node(const Mesh& mesh, const NodeCorners& corners, Index n, const RezoneParams& params, Vec2& to,
                Vec2& velocity_at) {
  const NodeFields& nodes = mesh.nodes;
  const ZoneFields& zones = mesh.zones;
  if (nodes.inv_mass_x[n] == 0.0 || nodes.inv_mass_y[n] == 0.0) return false;
  const Vec2 here = nodes.position(n);
  const Vec2 velocity = nodes.velocity(n);
  Vec2 position_sum{};
  // The least-squares velocity gradient from the edge neighbours, G = (sum w d^T) (sum d d^T)^-1 (d a
  // neighbour's offset, w its velocity difference), and the neighbourhood's velocity range.
  std::array<double, 3> dd{};
  std::array<double, 4> wd{};
  Vec2 low = velocity, high = velocity;
  int count = 0;
  double smallest_area = std::numeric_limits<double>::infinity();
  for (Index s = corners.offset[n]; s < corners.offset[n + 1]; ++s) {
    const Index z = corners.slot[s] / 4;
    const int p = corners.slot[s] % 4;
    const ZoneCorners& c = zones.corners[z];
    if (!zones.active[z] || has_repeated_corner(c) || zones.neighbour[z][p] < 0 || zones.neighbour[z][quad::prev(p)] < 0) {
      return false;  // on a boundary, or beside a triangle
    }
    smallest_area = std::min(smallest_area, zones.area[z]);
    for (const Index k : {c[quad::next(p)], c[quad::prev(p)]}) {
      const Vec2 d = nodes.position(k) - here;
      const Vec2 w = nodes.velocity(k) - velocity;
      position_sum += nodes.position(k);
      dd[0] += d.x * d.x;
      dd[1] += d.x * d.y;
      dd[2] += d.y * d.y;
      wd[0] += w.x * d.x;
      wd[1] += w.x * d.y;
      wd[2] += w.y * d.x;
      wd[3] += w.y * d.y;
      low = {std::min(low.x, nodes.u[k]), std::min(low.y, nodes.v[k])};
      high = {std::max(high.x, nodes.u[k]), std::max(high.y, nodes.v[k])};
      ++count;
    }
  }
  if (count == 0) return false;
  const Vec2 towards = (1.0 / count) * position_sum - here;
  // A node already within settled_distance of the square root of its smallest zone's area from the
  // neighbours' mean stays: the remap's cost and smearing are spent where the mesh is distorted.
  if (!(dot(towards, towards) > settled_distance * settled_distance * smallest_area)) return false;
  // The fraction of the way, halved until every zone at the node (this node alone moved) keeps at least
  // 1 - step_fraction of its area and convex corners.
  double fraction = params.relaxation;
  for (int halving = 0;; ++halving) {
    bool kept = true;
    for (Index s = corners.offset[n]; s < corners.offset[n + 1] && kept; ++s) {
      const Index z = corners.slot[s] / 4;
      quad::Corners x = mesh.corner_positions(z);
      x[static_cast<std::size_t>(corners.slot[s] % 4)] = here + fraction * towards;
      kept = quad::area(x) >= (1.0 - params.step_fraction) * zones.area[z] && convex(x);
    }
    if (kept) break;
    if (halving == 8) return false;
    fraction *= 0.5;
  }
  const Vec2 step = fraction * towards;
  to = here + step;
  Vec2 moved_velocity = velocity;
  const double det = dd[0] * dd[2] - dd[1] * dd[1];
  if (det > 0.0) {
    const double ix = (dd[2] * step.x - dd[1] * step.y) / det, iy = (dd[0] * step.y - dd[1] * step.x) / det;
    moved_velocity += Vec2{wd[0] * ix + wd[1] * iy, wd[2] * ix + wd[3] * iy};
  }
  velocity_at = {std::clamp(moved_velocity.x, low.x, high.x), std::clamp(moved_velocity.y, low.y, high.y)};
  return true;
}

}  // namespace

RezoneResult rezone_body(Mesh& mesh, ZoneState& state, const Body& body, const Material& material,
                         GeometryKind geometry, const NodeCorners& corners, const RezoneParams& params,
                         RezoneScratch& scratch) {
  RezoneResult result;
  if (!(body.rezone_ratio > 0.0)) return result;
  NodeFields& nodes = mesh.nodes;
  ZoneFields& zones = mesh.zones;
  const bool axisymmetric = geometry == GeometryKind::axisymmetric;
  const auto volume_of = [&](const quad::Corners& x) { return axisymmetric ? quad::axisymmetric_volume(x) : quad::area(x); };
  RezoneScratch& s = scratch;
  s.node_mark.resize(static_cast<std::size_t>(nodes.size()), 0);
  s.zone_mark.resize(static_cast<std::size_t>(zones.size()), 0);
  s.local.resize(static_cast<std::size_t>(zones.size()), -1);
  s.to.resize(static_cast<std::size_t>(nodes.size()));
  s.velocity_at.resize(static_cast<std::size_t>(nodes.size()));
  s.candidates.clear();
  s.moved_nodes.clear();
  s.touched.clear();
  s.affected.clear();
  const auto mark = [](std::vector<std::uint8_t>& marks, Index i) -> std::uint8_t& { return marks[static_cast<std::size_t>(i)]; };
  // Clears every mark this call set (the scratch is reused by the next body and step).
  const auto clear_marks = [&] {
    for (const Index n : s.candidates) mark(s.node_mark, n) = 0;
    for (const Index n : s.affected) mark(s.node_mark, n) = 0;
    for (const Index z : s.touched) {
      mark(s.zone_mark, z) = 0;
      s.local[static_cast<std::size_t>(z)] = -1;
    }
  };

  // 1. The corners of the distorted zones are the candidates (in the order the zones find them).
  for (Index z = body.zone_begin; z < body.zone_end; ++z) {
    if (!zones.active[z]) continue;
    const ZoneCorners& c = zones.corners[z];
    if (has_repeated_corner(c) || !distorted(mesh.corner_positions(z), zones.area[z], zones.initial_altitude[z], body.rezone_ratio)) {
      continue;
    }
    for (const Index n : c) {
      if (mark(s.node_mark, n) & candidate_mark) continue;
      mark(s.node_mark, n) |= candidate_mark;
      s.candidates.push_back(n);
    }
  }

  // 2. Where each interior candidate goes, and the old velocity field's value there.
  for (const Index n : s.candidates) {
    const auto i = static_cast<std::size_t>(n);
    if (!relax_node(mesh, corners, n, params, s.to[i], s.velocity_at[i])) continue;
    mark(s.node_mark, n) |= moved_mark;
    s.moved_nodes.push_back(n);
  }
  const auto new_position = [&](Index n) {
    return (mark(s.node_mark, n) & moved_mark) ? s.to[static_cast<std::size_t>(n)] : nodes.position(n);
  };

  // 3. The touched zones (those at a moved node) and their new corners; nothing is written if one would
  // not keep a positive area and volume.
  for (const Index n : s.moved_nodes) {
    for (Index k = corners.offset[n]; k < corners.offset[n + 1]; ++k) {
      const Index z = corners.slot[k] / 4;
      if (mark(s.zone_mark, z)) continue;
      mark(s.zone_mark, z) = 1;
      s.local[static_cast<std::size_t>(z)] = static_cast<Index>(s.touched.size());
      s.touched.push_back(z);
    }
  }
  const std::size_t count = s.touched.size();
  s.new_x.resize(count);
  bool positive = true;
  for (std::size_t t = 0; t < count && positive; ++t) {
    const ZoneCorners& c = zones.corners[s.touched[t]];
    s.new_x[t] = {new_position(c[0]), new_position(c[1]), new_position(c[2]), new_position(c[3])};
    positive = quad::area(s.new_x[t]) > 0.0 && volume_of(s.new_x[t]) > 0.0;
  }

  // 4. The volume each edge between touched zones sweeps, taken once (from its lower zone), with the
  // upwind zone's density and carried quantities (all of the state before the remap).
  s.mass_change.assign(count, 0.0);
  s.carried_change.assign(count, std::array<double, carried>{});
  for (std::size_t t = 0; t < count && positive; ++t) {
    const Index z = s.touched[t];
    const ZoneCorners& c = zones.corners[z];
    for (int k = 0; k < 4; ++k) {
      const Index w = zones.neighbour[z][k];
      const Index a = c[k], b = c[quad::next(k)];
      if (w < z || !((mark(s.node_mark, a) | mark(s.node_mark, b)) & moved_mark)) continue;
      const double swept = volume_of({nodes.position(a), new_position(a), new_position(b), nodes.position(b)});  // > 0: z grows
      const Index donor = swept > 0.0 ? w : z;
      const double dm = zones.density[donor] * swept;
      const std::array<double, carried> q = carried_of(zones, state.strength, donor);
      const auto u = static_cast<std::size_t>(s.local[static_cast<std::size_t>(w)]);
      s.mass_change[t] += dm;
      s.mass_change[u] -= dm;
      for (int j = 0; j < carried; ++j) {
        s.carried_change[t][static_cast<std::size_t>(j)] += dm * q[static_cast<std::size_t>(j)];
        s.carried_change[u][static_cast<std::size_t>(j)] -= dm * q[static_cast<std::size_t>(j)];
      }
    }
  }
  for (std::size_t t = 0; t < count && positive; ++t) positive = zones.mass[s.touched[t]] + s.mass_change[t] > 0.0;
  if (!positive) {
    clear_marks();
    return result;
  }

  // 5. The affected nodes (the corners of the touched zones): their momentum and kinetic energy before.
  for (const Index z : s.touched) {
    for (const Index n : zones.corners[z]) {
      if (mark(s.node_mark, n) & affected_mark) continue;
      mark(s.node_mark, n) |= affected_mark;
      s.affected.push_back(n);
    }
  }
  Vec2 momentum_before{};
  double kinetic_before = 0.0;
  for (const Index n : s.affected) {
    momentum_before += nodes.mass[n] * nodes.velocity(n);
    kinetic_before += 0.5 * nodes.mass[n] * dot(nodes.velocity(n), nodes.velocity(n));
  }

  // 6. Write: the moved nodes, the zones (mass, geometry, density, carried quantities), the corner,
  // subzone and node masses.
  for (const Index n : s.moved_nodes) {
    const auto i = static_cast<std::size_t>(n);
    nodes.x[n] = s.to[i].x;
    nodes.y[n] = s.to[i].y;
    nodes.u[n] = s.velocity_at[i].x;
    nodes.v[n] = s.velocity_at[i].y;
  }
  double touched_mass = 0.0;
  for (std::size_t t = 0; t < count; ++t) {
    const Index z = s.touched[t];
    const double old_mass = zones.mass[z];
    const double new_mass = old_mass + s.mass_change[t];
    std::array<double, carried> q = carried_of(zones, state.strength, z);
    for (std::size_t j = 0; j < carried; ++j) q[j] = (old_mass * q[j] + s.carried_change[t][j]) / new_mass;
    store_carried(zones, state.strength, z, q);
    const quad::Corners& x = s.new_x[t];
    zones.mass[z] = new_mass;
    zones.area[z] = quad::area(x);
    zones.volume[z] = volume_of(x);
    zones.density[z] = new_mass / zones.volume[z];
    touched_mass += new_mass;
    const std::array<double, 4> axisymmetric_corners = axisymmetric ? quad::axisymmetric_corner_volumes(x) : std::array<double, 4>{};
    for (int p = 0; p < 4; ++p) {
      const auto slot = 4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p);
      const quad::Corners region = quad::corner_region(x, p);
      const double corner_mass = zones.density[z] * (axisymmetric ? axisymmetric_corners[static_cast<std::size_t>(p)] : quad::area(region));
      nodes.mass[zones.corners[z][p]] += corner_mass - zones.corner_mass[slot];
      zones.corner_mass[slot] = corner_mass;
      zones.subzone_mass[slot] = zones.density[z] * volume_of(region);
    }
  }

  // 7. The momentum restored by a uniform correction of the free components (the axial one alone in RZ,
  // where a ring's radial momentum is not conserved); the change of kinetic energy to heat.
  Vec2 momentum_after{};
  double free_mass_x = 0.0, free_mass_y = 0.0;
  for (const Index n : s.affected) {
    if (nodes.inv_mass_x[n] != 0.0) nodes.inv_mass_x[n] = 1.0 / nodes.mass[n];
    if (nodes.inv_mass_y[n] != 0.0) nodes.inv_mass_y[n] = 1.0 / nodes.mass[n];
    momentum_after += nodes.mass[n] * nodes.velocity(n);
    if (nodes.inv_mass_x[n] != 0.0) free_mass_x += nodes.mass[n];
    if (nodes.inv_mass_y[n] != 0.0) free_mass_y += nodes.mass[n];
  }
  const double du = free_mass_x > 0.0 ? (momentum_before.x - momentum_after.x) / free_mass_x : 0.0;
  const double dv = !axisymmetric && free_mass_y > 0.0 ? (momentum_before.y - momentum_after.y) / free_mass_y : 0.0;
  double kinetic_after = 0.0;
  Vec2 mean{};  // the free components' mass-weighted mean velocity
  for (const Index n : s.affected) {
    if (nodes.inv_mass_x[n] != 0.0) nodes.u[n] += du;
    if (nodes.inv_mass_y[n] != 0.0) nodes.v[n] += dv;
    kinetic_after += 0.5 * nodes.mass[n] * dot(nodes.velocity(n), nodes.velocity(n));
    if (nodes.inv_mass_x[n] != 0.0) mean.x += nodes.mass[n] * nodes.u[n] / free_mass_x;
    if (nodes.inv_mass_y[n] != 0.0) mean.y += nodes.mass[n] * nodes.v[n] / free_mass_y;
  }
  // A remap may shift mass toward faster nodes; the kinetic energy it would gain is taken back by
  // scaling the free components' deviations from their mean (which keeps the momentum), so that the
  // remap never draws on the internal energy.
  if (kinetic_after > kinetic_before) {
    double deviation = 0.0;
    for (const Index n : s.affected) {
      if (nodes.inv_mass_x[n] != 0.0) deviation += 0.5 * nodes.mass[n] * (nodes.u[n] - mean.x) * (nodes.u[n] - mean.x);
      if (nodes.inv_mass_y[n] != 0.0) deviation += 0.5 * nodes.mass[n] * (nodes.v[n] - mean.y) * (nodes.v[n] - mean.y);
    }
    const double excess = kinetic_after - kinetic_before;
    if (deviation > excess) {
      const double scale = std::sqrt(1.0 - excess / deviation);
      kinetic_after = 0.0;
      for (const Index n : s.affected) {
        if (nodes.inv_mass_x[n] != 0.0) nodes.u[n] = mean.x + scale * (nodes.u[n] - mean.x);
        if (nodes.inv_mass_y[n] != 0.0) nodes.v[n] = mean.y + scale * (nodes.v[n] - mean.y);
        kinetic_after += 0.5 * nodes.mass[n] * dot(nodes.velocity(n), nodes.velocity(n));
      }
    }
  }
  const double to_internal = kinetic_before - kinetic_after;

  // 8. The touched zones' energy, EOS state and stable step (as update_zones).
  const double mu = material.shear_modulus();
  for (std::size_t t = 0; t < count; ++t) {
    const Index z = s.touched[t];
    zones.specific_energy[z] += to_internal / touched_mass;
    std::visit([&](const auto& eos) { evaluate_eos(eos, mu, zones, state.hydro, z); }, material.eos);
    state.hydro.stable_time_step[z] =
        zone_stable_step(quad::stable_length(s.new_x[t], zones.area[z]), state.hydro.sound_speed[z],
                         state.hydro.viscous_speed[z], state.hydro.volume_change[z], params.cfl,
                         params.max_volume_change, params.time_step);
  }
  result.moved_nodes = static_cast<Index>(s.moved_nodes.size());
  result.remapped_zones = static_cast<Index>(count);
  result.kinetic_to_internal = to_internal;
  clear_marks();
  return result;
}

}  // namespace krug
