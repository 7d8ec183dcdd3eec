#include "krug/contact/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace krug::contact {

namespace {

// A node counts against a segment only while it projects onto it (with this slack at the ends,
// relative to the segment length) and started the step outside it or within this depth.
constexpr double end_slack = 1e-3;
constexpr double start_depth = 0.25;

Vec2 predicted(const NodeFields& nodes, Index p, double dt) {
  return {nodes.x[p] + dt * nodes.u[p], nodes.y[p] + dt * nodes.v[p]};
}

InverseMass inverse_mass(const NodeFields& nodes, Index p) {
  return p < 0 ? InverseMass{} : InverseMass{nodes.inv_mass_x[p], nodes.inv_mass_y[p]};
}

}  // namespace

ContactSolver::ContactSolver(ContactSetup setup, const Mesh& mesh,
                             const std::vector<std::pair<Index, Index>>& body_zone_ranges)
    : setup_(std::move(setup)), zone_ranges_(body_zone_ranges) {
  reaction_x_.assign(static_cast<std::size_t>(mesh.nodes.size()), 0.0);
  reaction_y_.assign(static_cast<std::size_t>(mesh.nodes.size()), 0.0);
  touched_flag_.assign(static_cast<std::size_t>(mesh.nodes.size()), 0);
  rebuild_boundaries(mesh);
}

void ContactSolver::rebuild_boundaries(const Mesh& mesh) {
  boundaries_.assign(zone_ranges_.size(), BodyBoundary{});
  for (std::size_t b = 0; b < zone_ranges_.size(); ++b) {
    BodyBoundary& boundary = boundaries_[b];
    boundary.segments = boundary_segments(mesh, zone_ranges_[b].first, zone_ranges_[b].second);
    for (const BoundarySegment& s : boundary.segments) boundary.nodes.push_back(s.a);
    std::sort(boundary.nodes.begin(), boundary.nodes.end());
    boundary.nodes.erase(std::unique(boundary.nodes.begin(), boundary.nodes.end()), boundary.nodes.end());
  }
}

void ContactSolver::add_node_segment_candidates(const Mesh& mesh, const BodyBoundary& slaves,
                                                const BodyBoundary& masters, double friction, double weight,
                                                bool self, double dt_next) {
  const NodeFields& nodes = mesh.nodes;
  boxes_.clear();
  for (const BoundarySegment& s : masters.segments) {
    Box box;
    box.include(nodes.position(s.a));
    box.include(nodes.position(s.b));
    box.include(predicted(nodes, s.a, dt_next));
    box.include(predicted(nodes, s.b, dt_next));
    boxes_.push_back(box.expanded(start_depth * norm(nodes.position(s.b) - nodes.position(s.a))));
  }
  grid_.build(boxes_);
  for (Index c : slaves.nodes) {
    Box swept;
    swept.include(nodes.position(c));
    swept.include(predicted(nodes, c, dt_next));
    grid_.query(swept, [&](std::size_t k) {
      const BoundarySegment& s = masters.segments[k];
      if (s.a == c || s.b == c) return;
      const SegmentProjection start = project(nodes.position(c), nodes.position(s.a), nodes.position(s.b), 0.0);
      const double length = norm(nodes.position(s.b) - nodes.position(s.a));
      if (start.gap < -start_depth * length) return;  // behind the surface: the far side of a body
      if (self && start.gap < 0.0) return;             // a body's own surface is never entered from behind
      candidates_.push_back({c, s.a, s.b, -1, friction, weight, std::min(start.gap, 0.0), length, 0.0, 0.0});
    });
  }
}

void ContactSolver::find_candidates(const Mesh& mesh, double dt_next) {
  candidates_.clear();
  const bool summation = setup_.controls.method == ReactionMethod::summation;
  for (const BodyPair& pair : setup_.pairs) {
    const BodyBoundary& first = boundaries_[static_cast<std::size_t>(pair.first)];
    const BodyBoundary& second = boundaries_[static_cast<std::size_t>(pair.second)];
    if (pair.first == pair.second) {
      add_node_segment_candidates(mesh, first, first, pair.friction, summation ? 0.5 : 1.0, true, dt_next);
    } else {
      add_node_segment_candidates(mesh, first, second, pair.friction, summation ? 0.5 : 1.0, false, dt_next);
      add_node_segment_candidates(mesh, second, first, pair.friction, summation ? 0.5 : 1.0, false, dt_next);
    }
  }
  const NodeFields& nodes = mesh.nodes;
  for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
    const RigidWall& wall = setup_.walls[w];
    for (std::size_t b = 0; b < boundaries_.size(); ++b) {
      if (!wall.bodies.empty() &&
          std::find(wall.bodies.begin(), wall.bodies.end(), static_cast<Index>(b)) == wall.bodies.end()) {
        continue;
      }
      double mean_length = 0.0;
      for (const BoundarySegment& s : boundaries_[b].segments) mean_length += norm(nodes.position(s.b) - nodes.position(s.a));
      mean_length /= static_cast<double>(std::max<std::size_t>(boundaries_[b].segments.size(), 1));
      for (Index c : boundaries_[b].nodes) {
        const double start_gap = dot(nodes.position(c) - wall.point, wall.normal);
        const double reach = dt_next * norm(nodes.velocity(c));
        if (start_gap - reach > 0.0) continue;  // cannot reach the wall in this step
        candidates_.push_back({c, -1, -1, static_cast<Index>(w), wall.friction, 1.0, std::min(start_gap, 0.0),
                               mean_length, 0.0, 0.0});
      }
    }
  }
}

void ContactSolver::apply(Mesh& mesh, Index node, Vec2 direction, double force, double dt_mid) {
  if (node < 0 || force == 0.0) return;
  NodeFields& nodes = mesh.nodes;
  nodes.u[node] += dt_mid * force * direction.x * nodes.inv_mass_x[node];
  nodes.v[node] += dt_mid * force * direction.y * nodes.inv_mass_y[node];
  reaction_x_[node] += force * direction.x;
  reaction_y_[node] += force * direction.y;
  if (!touched_flag_[node]) {
    touched_flag_[node] = 1;
    touched_.push_back(node);
  }
}

double ContactSolver::update(Candidate& c, Mesh& mesh, double dt_mid, double dt_next, bool accumulate_only) {
  const NodeFields& nodes = mesh.nodes;
  const Vec2 point = predicted(nodes, c.node, dt_next);
  double xi = 0.0, gap = 0.0;
  Vec2 normal, tangent;
  bool valid = true;
  if (c.wall >= 0) {
    const RigidWall& wall = setup_.walls[static_cast<std::size_t>(c.wall)];
    normal = wall.normal;
    tangent = {-normal.y, normal.x};
    gap = dot(point - wall.point, normal);
  } else {
    const SegmentProjection p = project(point, predicted(nodes, c.a, dt_next), predicted(nodes, c.b, dt_next), 0.0);
    const double slack = end_slack;
    const Vec2 ab = predicted(nodes, c.b, dt_next) - predicted(nodes, c.a, dt_next);
    const double along = dot(point - predicted(nodes, c.a, dt_next), ab) / std::max(dot(ab, ab), 1e-300);
    valid = along >= -slack && along <= 1.0 + slack;
    xi = p.xi;
    gap = p.gap;
    normal = p.normal;
    tangent = p.tangent;
  }
  const InverseMass w_point = inverse_mass(nodes, c.node), w_a = inverse_mass(nodes, c.a),
                    w_b = inverse_mass(nodes, c.b);
  const double w = contact_inverse_mass(normal, xi, w_point, w_a, w_b);
  if (w <= 0.0) return 0.0;
  // A pre-existing overlap is removed by at most overlap_fraction of its start depth per step.
  const double target = c.start_gap < 0.0 ? (1.0 - setup_.controls.overlap_fraction) * c.start_gap : 0.0;
  double increment = valid ? -(gap - target) / (dt_mid * dt_next * w) : -c.normal;
  increment *= c.weight;
  const double total = clamp_normal(c.normal, increment);
  const double change = total - c.normal;
  if (accumulate_only) {
    c.normal = total;
    return gap;
  }
  c.normal = total;
  apply(mesh, c.node, normal, change, dt_mid);
  apply(mesh, c.a, normal, -(1.0 - xi) * change, dt_mid);
  apply(mesh, c.b, normal, -xi * change, dt_mid);
  const double gap_after = gap + dt_mid * dt_next * w * change;

  if (c.friction > 0.0) {
    const double wt = contact_inverse_mass(tangent, xi, w_point, w_a, w_b);
    if (wt > 0.0) {
      Vec2 relative = nodes.velocity(c.node);
      if (c.a >= 0) relative -= (1.0 - xi) * nodes.velocity(c.a) + xi * nodes.velocity(c.b);
      const double slip = dot(relative, tangent);
      const double friction_total = clamp_friction(c.tangent, -slip / (dt_mid * wt), c.friction * c.normal);
      const double friction_change = friction_total - c.tangent;
      c.tangent = friction_total;
      apply(mesh, c.node, tangent, friction_change, dt_mid);
      apply(mesh, c.a, tangent, -(1.0 - xi) * friction_change, dt_mid);
      apply(mesh, c.b, tangent, -xi * friction_change, dt_mid);
    }
  }
  return valid ? gap_after - target : std::numeric_limits<double>::infinity();
}

ContactStatistics ContactSolver::solve(Mesh& mesh, double dt_mid, double dt_next) {
  for (Index p : touched_) {
    reaction_x_[p] = reaction_y_[p] = 0.0;
    touched_flag_[p] = 0;
  }
  touched_.clear();
  ContactStatistics stats;
  find_candidates(mesh, dt_next);
  stats.candidates = static_cast<long>(candidates_.size());
  if (candidates_.empty()) return stats;

  if (setup_.controls.method == ReactionMethod::summation) {
    // All reactions from the same predicted state, then applied together (one pass).
    for (Candidate& c : candidates_) update(c, mesh, dt_mid, dt_next, true);
    for (Candidate& c : candidates_) {
      const double total = c.normal;
      c.normal = 0.0;
      // Re-run the application with the stored total: treat it as the whole change.
      const NodeFields& nodes = mesh.nodes;
      Vec2 normal;
      double xi = 0.0;
      if (c.wall >= 0) {
        normal = setup_.walls[static_cast<std::size_t>(c.wall)].normal;
      } else {
        const SegmentProjection p = project(predicted(nodes, c.node, dt_next), predicted(nodes, c.a, dt_next),
                                            predicted(nodes, c.b, dt_next), 0.0);
        normal = p.normal;
        xi = p.xi;
      }
      c.normal = total;
      apply(mesh, c.node, normal, total, dt_mid);
      apply(mesh, c.a, normal, -(1.0 - xi) * total, dt_mid);
      apply(mesh, c.b, normal, -xi * total, dt_mid);
    }
    stats.sweeps = 1;
  } else {
    for (int sweep = 0; sweep < setup_.controls.max_sweeps; ++sweep) {
      double worst = 0.0;  // deepest remaining penetration relative to the segment length
      for (Candidate& c : candidates_) {
        const double gap = update(c, mesh, dt_mid, dt_next, false);
        if (gap < 0.0) worst = std::max(worst, -gap / std::max(c.length, 1e-300));
      }
      stats.sweeps = sweep + 1;
      if (worst <= setup_.controls.gap_tolerance) break;
    }
  }
  for (const Candidate& c : candidates_) {
    if (c.normal > 0.0) ++stats.active;
    stats.total_normal += c.normal;
  }
  // Deepest gap left (m), measured on the final predicted positions.
  const NodeFields& nodes = mesh.nodes;
  for (const Candidate& c : candidates_) {
    double gap;
    if (c.wall >= 0) {
      const RigidWall& wall = setup_.walls[static_cast<std::size_t>(c.wall)];
      gap = dot(predicted(nodes, c.node, dt_next) - wall.point, wall.normal);
    } else {
      const SegmentProjection p = project(predicted(nodes, c.node, dt_next), predicted(nodes, c.a, dt_next),
                                          predicted(nodes, c.b, dt_next), 0.0);
      if (!p.inside) continue;
      gap = p.gap - (c.start_gap < 0.0 ? c.start_gap : 0.0);
    }
    stats.deepest_gap = std::min(stats.deepest_gap, gap);
  }
  return stats;
}

}  // namespace krug::contact
