// Nosed cylinder generator: a structured block (flat nose) or a two-block O-grid whose nose nodes are
// placed by a discrete harmonic (Tutte) embedding. Layout and conventions: nosed_cylinder.hpp.
#include "krug/mesh/nosed_cylinder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/mesh/quality.hpp"

namespace krug::generate {

namespace {

std::size_t to_size(Index i) { return static_cast<std::size_t>(i); }

// The body in local coordinates (s from the rear face toward the tip, r), zones counter-clockwise
// in (s, r), before it is placed in the mesh.
struct LocalBody {
  std::vector<Vec2> position;
  std::vector<ZoneCorners> zones;
  std::map<std::string, std::vector<Index>> sides;
  int zones_i = 0, zones_j = 0;

  Index add_node(Vec2 p) {
    position.push_back(p);
    return static_cast<Index>(position.size() - 1);
  }
};

// How a node may move in the harmonic solve.
enum class Freedom : std::uint8_t { fixed, axial, free };

void check_counts(const NosedCylinderParams& p) {
  if (p.radial_zones < 1) throw InputError("nosed cylinder: radial_zones must be at least 1");
  if (p.shank_zones < 0 || p.core_zones < 0 || p.nose_zones < 0) {
    throw InputError("nosed cylinder: zone counts must be >= 0 (0 chooses automatically)");
  }
  if (!(p.shank_ratio > 0.0) || !std::isfinite(p.shank_ratio)) {
    throw InputError("nosed cylinder: shank_ratio must be positive");
  }
  if (p.direction != 1 && p.direction != -1) throw InputError("nosed cylinder: direction must be +1 or -1");
  if (!std::isfinite(p.tip_position)) throw InputError("nosed cylinder: tip_position must be finite");
}

// Axial grid lines of the shank from s = 0 (rear) to s = shoulder, increasing; zone lengths grow by
// `ratio` from the shoulder toward the rear. zones = 0: the count whose first zone (at the shoulder)
// is closest to `first_zone`.
std::vector<double> shank_lines(double shoulder, double first_zone, int zones, double ratio) {
  if (zones == 0) {
    const double n = std::abs(ratio - 1.0) < 1e-12
                         ? shoulder / first_zone
                         : std::log1p(shoulder * (ratio - 1.0) / first_zone) / std::log(ratio);
    zones = std::max(1, static_cast<int>(std::lround(n)));
  }
  std::vector<double> lines = graded_axis(shoulder, {AxisSegment{0.0, zones, ratio}});
  std::reverse(lines.begin(), lines.end());
  return lines;
}

LocalBody flat_body(const NosedCylinderParams& p) {
  const int n_r = p.radial_zones;
  const double length = p.length, radius = p.radius;
  const std::vector<double> s = shank_lines(length, radius / n_r, p.shank_zones, p.shank_ratio);
  const int n_z = static_cast<int>(s.size()) - 1;
  LocalBody b;
  b.zones_i = n_r;
  b.zones_j = n_z;
  auto id = [&](int i, int j) { return static_cast<Index>(j * (n_z + 1) + i); };
  for (int j = 0; j <= n_r; ++j) {
    for (int i = 0; i <= n_z; ++i) b.add_node({s[static_cast<std::size_t>(i)], radius * (static_cast<double>(j) / n_r)});
  }
  for (int j = 0; j < n_r; ++j) {
    for (int i = 0; i < n_z; ++i) b.zones.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  }
  auto& axis = b.sides["axis"];
  for (int i = 0; i <= n_z; ++i) axis.push_back(id(i, 0));
  auto& nose = b.sides["nose"];
  for (int j = 0; j <= n_r; ++j) nose.push_back(id(n_z, j));
  auto& side = b.sides["side"];
  for (int i = n_z; i >= 0; --i) side.push_back(id(i, n_r));
  auto& rear = b.sides["rear"];
  for (int j = n_r; j >= 0; --j) rear.push_back(id(0, j));
  b.sides["tip"] = {id(n_z, 0)};
  return b;
}

// Places the nodes marked `axial` or `free` at the discrete harmonic embedding of the zone-edge graph
// with the `fixed` nodes held: sum over edge neighbours q of (x_n - x_q) = 0, for x on axial and free
// nodes and for r on free nodes. Each system is a principal submatrix of the graph Laplacian with a
// held node in every component, hence symmetric positive definite.
void harmonic_placement(LocalBody& b, const std::vector<Freedom>& freedom) {
  const std::size_t n = b.position.size();
  std::vector<std::pair<Index, Index>> edges;
  for (const ZoneCorners& c : b.zones) {
    for (int k = 0; k < 4; ++k) {
      const Index a = c[k], e = c[quad::next(k)];
      edges.emplace_back(std::min(a, e), std::max(a, e));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::vector<Index>> neighbours(n);
  for (const auto& [a, e] : edges) {
    neighbours[to_size(a)].push_back(e);
    neighbours[to_size(e)].push_back(a);
  }
  for (int component = 0; component < 2; ++component) {
    std::vector<Index> unknown(n, -1);
    Index count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const bool moves = freedom[i] == Freedom::free || (component == 0 && freedom[i] == Freedom::axial);
      if (moves) unknown[i] = count++;
    }
    if (count == 0) continue;
    auto coordinate = [&](Index q) -> double& {
      Vec2& x = b.position[to_size(q)];
      return component == 0 ? x.x : x.y;
    };
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(count);
    for (std::size_t i = 0; i < n; ++i) {
      const Index row = unknown[i];
      if (row < 0) continue;
      entries.emplace_back(row, row, static_cast<double>(neighbours[i].size()));
      for (Index q : neighbours[i]) {
        if (unknown[to_size(q)] >= 0) {
          entries.emplace_back(row, unknown[to_size(q)], -1.0);
        } else {
          rhs[row] += coordinate(q);
        }
      }
    }
    Eigen::SparseMatrix<double> laplacian(count, count);
    laplacian.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplacian);
    if (solver.info() != Eigen::Success) throw InputError("nosed cylinder: the nose smoothing system is singular");
    const Eigen::VectorXd solution = solver.solve(rhs);
    for (std::size_t i = 0; i < n; ++i) {
      if (unknown[i] >= 0) coordinate(static_cast<Index>(i)) = solution[unknown[i]];
    }
  }
}

LocalBody curved_body(const NosedCylinderParams& p, const NoseGeometry& g) {
  const int n_r = p.radial_zones;
  if (n_r < 2) throw InputError("nosed cylinder: a curved nose needs radial_zones >= 2");
  const int n_c = p.core_zones > 0 ? p.core_zones : std::clamp(static_cast<int>(std::lround(0.6 * n_r)), 1, n_r - 1);
  if (n_c >= n_r) throw InputError(fmt::format("nosed cylinder: core_zones ({}) must be below radial_zones ({})", n_c, n_r));
  const int n_ring = n_r - n_c;
  const double radius = p.radius;
  const int n_cn = p.nose_zones > 0
                       ? p.nose_zones - n_c
                       : std::max(1, static_cast<int>(std::lround(g.length * n_r / radius)) - n_ring);
  if (n_cn < 1) {
    throw InputError(fmt::format("nosed cylinder: nose_zones ({}) must exceed core_zones ({})", p.nose_zones, n_c));
  }
  const int n_nose = n_cn + n_c;
  const double shoulder = p.length - g.length;
  const std::vector<double> s = shank_lines(shoulder, radius / n_r, p.shank_zones, p.shank_ratio);
  const int n_z = static_cast<int>(s.size()) - 1;
  const int n_axial = n_z + n_cn;    // core columns along the axis
  const int n_path = n_axial + n_c;  // ring zones along its path: side, core top, core front

  LocalBody b;
  b.zones_i = n_r;
  b.zones_j = n_z + n_nose;
  std::vector<Freedom> freedom;
  auto add = [&](Vec2 x, Freedom f) {
    freedom.push_back(f);
    return b.add_node(x);
  };
  auto radial_line = [&](int j) { return radius * (static_cast<double>(j) / n_r); };
  // Nose surface point q of n_nose, at equal arc length from the shoulder (q = 0) to the tip.
  auto surface = [&](int q) -> Vec2 {
    if (q == 0) return {shoulder, radius};
    if (q == n_nose) return {p.length, 0.0};
    const double phi = g.tip_angle * static_cast<double>(q) / n_nose;
    const double rho = g.profile_radius;
    return {shoulder + rho * std::sin(phi), (radius - rho) + rho * std::cos(phi)};
  };

  // Core nodes (i along the axis, j across). Ahead of the shoulder the position is a first guess
  // (a linear blend) that the harmonic placement replaces.
  std::vector<Index> core(static_cast<std::size_t>((n_axial + 1) * (n_c + 1)));
  auto core_id = [&](int i, int j) -> Index& { return core[static_cast<std::size_t>(i * (n_c + 1) + j)]; };
  for (int i = 0; i <= n_axial; ++i) {
    for (int j = 0; j <= n_c; ++j) {
      if (i <= n_z) {
        core_id(i, j) = add({s[static_cast<std::size_t>(i)], radial_line(j)}, Freedom::fixed);
      } else {
        const double t = static_cast<double>(i - n_z) / (n_axial - n_z);
        const Vec2 x{shoulder + t * 0.5 * g.length, radial_line(j) * (1.0 - 0.5 * t)};
        core_id(i, j) = add(x, j == 0 ? Freedom::axial : Freedom::free);
      }
    }
  }
  // Ring nodes (k across from the core, m along the path); k = 0 is the core's top then front face.
  std::vector<Index> ring(static_cast<std::size_t>((n_ring + 1) * (n_path + 1)));
  auto ring_id = [&](int k, int m) -> Index& { return ring[static_cast<std::size_t>(m * (n_ring + 1) + k)]; };
  for (int m = 0; m <= n_path; ++m) {
    const Index inner = m <= n_axial ? core_id(m, n_c) : core_id(n_axial, n_c - (m - n_axial));
    ring_id(0, m) = inner;
    for (int k = 1; k <= n_ring; ++k) {
      if (m <= n_z) {
        ring_id(k, m) = add({s[static_cast<std::size_t>(m)], radial_line(n_c + k)}, Freedom::fixed);
      } else if (k == n_ring) {
        ring_id(k, m) = add(surface(m - n_z), Freedom::fixed);
      } else {
        const double w = static_cast<double>(k) / n_ring;
        const Vec2 x = (1.0 - w) * b.position[to_size(inner)] + w * surface(m - n_z);
        ring_id(k, m) = add(m == n_path ? Vec2{x.x, 0.0} : x, m == n_path ? Freedom::axial : Freedom::free);
      }
    }
  }
  for (int i = 0; i < n_axial; ++i) {
    for (int j = 0; j < n_c; ++j) {
      b.zones.push_back({core_id(i, j), core_id(i + 1, j), core_id(i + 1, j + 1), core_id(i, j + 1)});
    }
  }
  for (int m = 0; m < n_path; ++m) {
    for (int k = 0; k < n_ring; ++k) {
      b.zones.push_back({ring_id(k, m), ring_id(k, m + 1), ring_id(k + 1, m + 1), ring_id(k + 1, m)});
    }
  }
  harmonic_placement(b, freedom);

  auto& axis = b.sides["axis"];
  for (int i = 0; i <= n_axial; ++i) axis.push_back(core_id(i, 0));
  for (int k = 1; k <= n_ring; ++k) axis.push_back(ring_id(k, n_path));
  auto& nose = b.sides["nose"];
  for (int m = n_path; m >= n_z; --m) nose.push_back(ring_id(n_ring, m));
  auto& side = b.sides["side"];
  for (int m = n_z; m >= 0; --m) side.push_back(ring_id(n_ring, m));
  auto& rear = b.sides["rear"];
  for (int k = n_ring; k >= 0; --k) rear.push_back(ring_id(k, 0));
  for (int j = n_c - 1; j >= 0; --j) rear.push_back(core_id(0, j));
  b.sides["tip"] = {ring_id(n_ring, n_path)};
  return b;
}

}  // namespace

NoseGeometry nose_geometry(const NosedCylinderParams& p) {
  const double radius = p.radius;
  if (!(radius > 0.0) || !std::isfinite(radius)) throw InputError("nosed cylinder: radius must be positive");
  if (!(p.length > 0.0) || !std::isfinite(p.length)) throw InputError("nosed cylinder: length must be positive");
  NoseGeometry g;
  switch (p.nose) {
    case NoseShape::flat:
    case NoseShape::hemispherical:
      if (p.nose_length != 0.0 || p.ogive_calibers != 0.0) {
        throw InputError("nosed cylinder: nose_length and ogive_calibers apply to an ogive nose only");
      }
      if (p.nose == NoseShape::flat) {
        g.arc_length = radius;
        return g;
      }
      g.length = radius;
      g.profile_radius = radius;
      break;
    case NoseShape::ogive:
      if ((p.nose_length > 0.0) == (p.ogive_calibers > 0.0) || p.nose_length < 0.0 || p.ogive_calibers < 0.0) {
        throw InputError("nosed cylinder: an ogive nose needs exactly one of nose_length and ogive_calibers");
      }
      if (p.nose_length > 0.0) {
        if (p.nose_length < radius) {
          throw InputError(fmt::format("nosed cylinder: a tangent ogive needs nose_length >= radius ({} < {})",
                                       p.nose_length, radius));
        }
        g.length = p.nose_length;
        g.profile_radius = (radius * radius + g.length * g.length) / (2.0 * radius);
      } else {
        if (p.ogive_calibers < 0.5) {
          throw InputError(fmt::format("nosed cylinder: ogive_calibers must be >= 0.5 (got {})", p.ogive_calibers));
        }
        g.profile_radius = 2.0 * radius * p.ogive_calibers;
        g.length = std::sqrt(2.0 * g.profile_radius * radius - radius * radius);
      }
      break;
  }
  g.tip_angle = std::asin(std::min(1.0, g.length / g.profile_radius));
  g.arc_length = g.profile_radius * g.tip_angle;
  if (!(p.length > g.length)) {
    throw InputError(fmt::format("nosed cylinder: length ({}) must exceed the nose length ({})", p.length, g.length));
  }
  return g;
}

double nosed_cylinder_volume(const NosedCylinderParams& p, GeometryKind geometry) {
  const NoseGeometry g = nose_geometry(p);
  const double radius = p.radius;
  const double shank = p.length - g.length;
  const bool axisymmetric = geometry == GeometryKind::axisymmetric;
  if (p.nose == NoseShape::flat) return axisymmetric ? std::numbers::pi * radius * radius * p.length : radius * p.length;
  // Nose profile f(s) = sqrt(rho^2 - s^2) - d, d = rho - R, s from the shoulder; f(Ln) = 0 gives
  // sqrt(rho^2 - Ln^2) = d, so int_0^Ln sqrt(rho^2 - s^2) ds = (Ln d + rho^2 phi_tip) / 2.
  const double rho = g.profile_radius, d = rho - radius, ln = g.length;
  const double quarter = 0.5 * (ln * d + rho * rho * g.tip_angle);
  if (axisymmetric) {
    // pi int f^2 ds = pi ((rho^2 + d^2) Ln - Ln^3 / 3 - 2 d int sqrt(rho^2 - s^2) ds)
    const double nose = std::numbers::pi * ((rho * rho + d * d) * ln - ln * ln * ln / 3.0 - 2.0 * d * quarter);
    return std::numbers::pi * radius * radius * shank + nose;
  }
  return radius * shank + (quarter - d * ln);
}

Patch nosed_cylinder(Mesh& mesh, const NosedCylinderParams& params, Index body) {
  check_counts(params);
  const NoseGeometry g = nose_geometry(params);
  if (params.nose == NoseShape::flat && (params.core_zones != 0 || params.nose_zones != 0)) {
    throw InputError("nosed cylinder: core_zones and nose_zones apply to a curved nose only");
  }
  const LocalBody local = params.nose == NoseShape::flat ? flat_body(params) : curved_body(params, g);
  // Safety net, before anything is appended: every zone convex with positive area (guaranteed by the
  // construction; a failure here is a bug or an extreme parameter set).
  for (std::size_t z = 0; z < local.zones.size(); ++z) {
    const ZoneCorners& c = local.zones[z];
    const quad::Corners x{local.position[to_size(c[0])], local.position[to_size(c[1])],
                          local.position[to_size(c[2])], local.position[to_size(c[3])]};
    const double sine = min_corner_sine(x);
    if (!(sine > 0.0) || !(quad::area(x) > 0.0)) {
      throw InputError(fmt::format("nosed cylinder: the generated zone {} is degenerate (smallest corner sine {:.3g}); "
                                   "change radial_zones, core_zones or nose_zones", z, sine));
    }
  }

  Patch patch;
  patch.zones_i = local.zones_i;
  patch.zones_j = local.zones_j;
  patch.node_begin = mesh.nodes.size();
  patch.node_end = patch.node_begin + static_cast<Index>(local.position.size());
  mesh.nodes.resize(patch.node_end);
  const double sign = static_cast<double>(params.direction);
  for (std::size_t i = 0; i < local.position.size(); ++i) {
    const Index n = patch.node_begin + static_cast<Index>(i);
    const Vec2 x = local.position[i];
    // z = tip - direction (L - s); the tip node (s = L exactly) lands exactly on tip_position.
    mesh.nodes.x[n] = params.tip_position - sign * (params.length - x.x);
    mesh.nodes.y[n] = x.y;
    mesh.nodes.body[n] = body;
  }
  patch.zone_begin = mesh.zones.size();
  patch.zone_end = patch.zone_begin + static_cast<Index>(local.zones.size());
  mesh.zones.resize(patch.zone_end);
  for (std::size_t i = 0; i < local.zones.size(); ++i) {
    const Index z = patch.zone_begin + static_cast<Index>(i);
    ZoneCorners c = local.zones[i];
    for (Index& corner : c) corner += patch.node_begin;
    // Mirroring the axial coordinate (direction -1) turns the zones clockwise: reverse them.
    if (params.direction < 0) std::swap(c[1], c[3]);
    mesh.zones.corners[z] = c;
    mesh.zones.body[z] = body;
  }
  for (const auto& [name, nodes] : local.sides) {
    std::vector<Index>& out = patch.sides[name];
    out.reserve(nodes.size());
    for (Index n : nodes) out.push_back(n + patch.node_begin);
  }

  return patch;
}

}  // namespace krug::generate
