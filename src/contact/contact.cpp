#include "krug/contact/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace krug::contact {

double particle_escape(const Particles& particles, double dt) {
  double escape = 0.0;
  for (Index i = 0; i < particles.size(); ++i) {
    const Vec2 start = particles.position(i);
    const Vec2 searched = start + dt * Vec2{particles.u_old[i], particles.v_old[i]};
    const Vec2 end = start + dt * particles.velocity(i);
    const double beyond = std::max({std::min(start.x, searched.x) - end.x, end.x - std::max(start.x, searched.x),
                                    std::min(start.y, searched.y) - end.y, end.y - std::max(start.y, searched.y), 0.0});
    escape = std::max(escape, beyond / (particle_search_margin * particles.radius[i]));
  }
  return escape;
}

ContactSolver::ContactSolver(ContactSetup setup, const Mesh& mesh,
                             const std::vector<std::pair<Index, Index>>& body_zone_ranges)
    : setup_(std::move(setup)), zone_ranges_(body_zone_ranges) {
  reaction_x_.assign(static_cast<std::size_t>(mesh.nodes.size()), 0.0);
  reaction_y_.assign(static_cast<std::size_t>(mesh.nodes.size()), 0.0);
  overlap_x_.assign(static_cast<std::size_t>(mesh.nodes.size()), 0.0);
  overlap_y_.assign(static_cast<std::size_t>(mesh.nodes.size()), 0.0);
  touched_flag_.assign(static_cast<std::size_t>(mesh.nodes.size()), 0);
  rebuild_boundaries(mesh);
}

void ContactSolver::rebuild_boundaries(const Mesh& mesh) {
  lists_valid_ = false;  // the near lists index the old boundaries' segments and nodes
  boundaries_.assign(zone_ranges_.size(), BodyBoundary{});
  for (std::size_t b = 0; b < zone_ranges_.size(); ++b) {
    BodyBoundary& boundary = boundaries_[b];
    boundary.segments = boundary_segments(mesh, zone_ranges_[b].first, zone_ranges_[b].second);
    for (const BoundarySegment& s : boundary.segments) boundary.nodes.push_back(s.a);
    std::sort(boundary.nodes.begin(), boundary.nodes.end());
    boundary.nodes.erase(std::unique(boundary.nodes.begin(), boundary.nodes.end()), boundary.nodes.end());
  }
}

// --- points: nodes and particles -------------------------------------------------------------

Vec2 ContactSolver::reaction_force(ContactPoint point) const {
  if (point.is_particle()) return {particle_reaction_x_[point.index], particle_reaction_y_[point.index]};
  return {reaction_x_[point.index], reaction_y_[point.index]};
}
Vec2 ContactSolver::overlap_reaction_force(ContactPoint point) const {
  if (point.is_particle()) return {particle_overlap_x_[point.index], particle_overlap_y_[point.index]};
  return {overlap_x_[point.index], overlap_y_[point.index]};
}

void ContactSolver::touch(ContactPoint point, Vec2 force) {
  const Index i = point.index;
  if (point.is_particle()) {
    if (particle_reaction_x_[i] == 0.0 && particle_reaction_y_[i] == 0.0) touched_.push_back(point);
    particle_reaction_x_[i] += force.x;
    particle_reaction_y_[i] += force.y;
    if (overlapping_) {
      particle_overlap_x_[i] += force.x;
      particle_overlap_y_[i] += force.y;
    }
    if (particle_reaction_x_[i] == 0.0 && particle_reaction_y_[i] == 0.0) particle_reaction_x_[i] = 1e-300;
    return;
  }
  reaction_x_[i] += force.x;
  reaction_y_[i] += force.y;
  if (overlapping_) {
    overlap_x_[i] += force.x;
    overlap_y_[i] += force.y;
  }
  if (!touched_flag_[i]) {
    touched_flag_[i] = 1;
    touched_.push_back(point);
  }
}

void ContactSolver::apply(ContactPoint point, Vec2 direction, double force, double dt_mid) {
  if (!point.exists() || force == 0.0) return;
  const InverseMass w = inverse_mass(point);
  const Index i = point.index;
  if (point.is_particle()) {
    particles_.u[i] += dt_mid * force * direction.x * w.x;
    particles_.v[i] += dt_mid * force * direction.y * w.y;
  } else {
    nodes_.u[i] += dt_mid * force * direction.x * w.x;
    nodes_.v[i] += dt_mid * force * direction.y * w.y;
  }
  touch(point, force * direction);
}

// --- the reaction kernel ------------------------------------------------------------------------

ContactSolver::Geometry ContactSolver::contact_geometry(const Candidate& c, double dt_next) const {
  Geometry g;
  g.start_gap = c.start_gap;
  const Vec2 point = predicted(c.node, dt_next);
  switch (c.kind) {
    case Kind::wall: {
      const Vec2 origin = c.wall >= 0 ? setup_.walls[static_cast<std::size_t>(c.wall)].point : Vec2{0.0, 0.0};
      g.normal = c.wall >= 0 ? setup_.walls[static_cast<std::size_t>(c.wall)].normal : Vec2{0.0, 1.0};
      g.tangent = {-g.normal.y, g.normal.x};
      g.gap = dot(point - origin, g.normal) - radius(c.node);
      break;
    }
    case Kind::node_segment: {
      const Vec2 a = predicted(c.a, dt_next), b = predicted(c.b, dt_next);
      const SegmentProjection p = project(point, a, b, 0.0);
      const Vec2 ab = b - a;
      const double along = dot(point - a, ab) / std::max(dot(ab, ab), 1e-300);
      g.valid = along >= -end_slack && along <= 1.0 + end_slack;
      g.xi = p.xi;
      g.gap = p.gap;
      g.normal = p.normal;
      g.tangent = p.tangent;
      break;
    }
    case Kind::particle_segment: {
      // Over the face: the signed distance from its line; beside it: the distance from its end point.
      const DiscContact k = disc_segment_contact(point, predicted(c.a, dt_next), predicted(c.b, dt_next), radius(c.node));
      g.xi = k.xi;
      g.feature = k.feature;
      g.normal = k.normal;
      g.gap = k.gap;
      // The start gap on the same feature. From the face's line it is negative beside a convex corner
      // although the particle does not touch the face: taken for an overlap, it let the particle sink
      // into the corner (up to 0.96 of its radius, tests/verification/test_particle_corner.cpp).
      g.start_gap = g.feature == SegmentFeature::face    ? c.start_gap
                    : g.feature == SegmentFeature::end_a ? c.start_gap_a
                                                         : c.start_gap_b;
      g.tangent = {-g.normal.y, g.normal.x};
      break;
    }
    case Kind::particle_particle: {
      const DiscContact k = disc_disc_contact(point, radius(c.node), predicted(c.a, dt_next), radius(c.a));
      g.normal = k.normal;
      g.tangent = {-g.normal.y, g.normal.x};
      g.gap = k.gap;
      g.xi = 0.0;  // the whole reaction on the other particle
      break;
    }
  }
  return g;
}

// The gap a contact is driven to this step: 0, or for a pre-existing overlap (start gap < 0, from
// Geometry::start_gap) the start gap less what may be removed in one step (a fraction of it, at most
// overlap_speed x dt).
double ContactSolver::overlap_target(double start_gap, double dt_next) const {
  if (start_gap >= 0.0) return 0.0;
  const double removal = std::min(setup_.controls.overlap_fraction * -start_gap, setup_.controls.overlap_speed * dt_next);
  return start_gap + removal;
}

double ContactSolver::friction_total(const Candidate& c, const Geometry& g, double accumulated, double normal_total,
                                     double dt_mid) const {
  if (c.friction <= 0.0) return accumulated;
  const double wt = contact_inverse_mass(g.tangent, g.xi, inverse_mass(c.node), inverse_mass(c.a), inverse_mass(c.b));
  if (wt <= 0.0) return accumulated;
  const double slip = dot(relative_velocity(c, g.xi), g.tangent);
  return clamp_friction(accumulated, -slip / (dt_mid * wt), c.friction * normal_total);
}

Vec2 ContactSolver::relative_velocity(const Candidate& c, double xi) const {
  Vec2 relative = velocity(c.node);
  if (c.a.exists()) relative -= (1.0 - xi) * velocity(c.a);
  if (c.b.exists()) relative -= xi * velocity(c.b);
  return relative;
}

void ContactSolver::apply_reaction(const Candidate& c, Vec2 normal, double xi, double normal_force,
                                   double tangent_force, double dt_mid) {
  const Vec2 force = normal_force * normal + tangent_force * Vec2{-normal.y, normal.x};
  const double magnitude = norm(force);
  if (magnitude == 0.0) return;
  const Vec2 direction = (1.0 / magnitude) * force;
  apply(c.node, direction, magnitude, dt_mid);
  apply(c.a, direction, -(1.0 - xi) * magnitude, dt_mid);
  apply(c.b, direction, -xi * magnitude, dt_mid);
}

double ContactSolver::update(Candidate& c, double dt_mid, double dt_next) {
  const Geometry g = contact_geometry(c, dt_next);
  const InverseMass w_point = inverse_mass(c.node), w_a = inverse_mass(c.a), w_b = inverse_mass(c.b);
  const double w = contact_inverse_mass(g.normal, g.xi, w_point, w_a, w_b);
  if (w <= 0.0) return 0.0;
  const double target = overlap_target(g.start_gap, dt_next);
  const double increment = g.valid ? -c.weight * (g.gap - target) / (dt_mid * dt_next * w) : -c.normal;
  const double total = clamp_normal(c.normal, increment);
  const double gap_after = g.gap + dt_mid * dt_next * w * (total - c.normal);

  replace_reaction(c, g, total, friction_total(c, g, c.tangent, total, dt_mid), dt_mid);
  return g.valid ? gap_after - target : std::numeric_limits<double>::infinity();
}

void ContactSolver::replace_reaction(Candidate& c, const Geometry& g, double normal_total, double tangent_total,
                                     double dt_mid) {
  overlapping_ = g.start_gap < 0.0;
  if (reoriented(c)) {
    // Withdraw the reaction where it acted, and apply the new totals in the current geometry.
    apply_reaction(c, c.applied_normal, c.applied_xi, -c.normal, -c.tangent, dt_mid);
    apply_reaction(c, g.normal, g.xi, normal_total, tangent_total, dt_mid);
    c.applied_normal = g.normal;
    c.applied_xi = g.xi;
  } else {
    apply_reaction(c, g.normal, g.xi, normal_total - c.normal, tangent_total - c.tangent, dt_mid);
  }
  c.normal = normal_total;
  c.tangent = tangent_total;
}

ContactStatistics ContactSolver::solve(NodesView nodes, ParticlesView particles, double dt_mid, double dt_next,
                                       int threads) {
  nodes_ = nodes;
  particles_ = particles;
  for (const ContactPoint p : touched_) {
    if (p.is_particle()) continue;
    reaction_x_[p.index] = reaction_y_[p.index] = 0.0;
    overlap_x_[p.index] = overlap_y_[p.index] = 0.0;
    touched_flag_[p.index] = 0;
  }
  touched_.clear();
  particle_reaction_x_.assign(static_cast<std::size_t>(particles.size), 0.0);
  particle_reaction_y_.assign(static_cast<std::size_t>(particles.size), 0.0);
  particle_overlap_x_.assign(static_cast<std::size_t>(particles.size), 0.0);
  particle_overlap_y_.assign(static_cast<std::size_t>(particles.size), 0.0);
  ContactStatistics stats;
  find_candidates(dt_next, threads);
  stats.candidates = static_cast<long>(candidates_.size());
  stats.lists_rebuilt = rebuilding_;
  if (candidates_.empty()) return stats;

  if (setup_.controls.method == ReactionMethod::summation) {
    // The paper's: every reaction from the same predicted state, then all applied together.
    std::vector<Geometry>& geometry = summation_geometry_;
    geometry.clear();
    geometry.reserve(candidates_.size());
    for (Candidate& c : candidates_) {
      const Geometry g = contact_geometry(c, dt_next);
      geometry.push_back(g);
      const double w = contact_inverse_mass(g.normal, g.xi, inverse_mass(c.node), inverse_mass(c.a), inverse_mass(c.b));
      const double target = overlap_target(g.start_gap, dt_next);
      c.normal = (w > 0.0 && g.valid) ? std::max(0.0, -c.weight * (g.gap - target) / (dt_mid * dt_next * w)) : 0.0;
    }
    // Coulomb friction from the same predicted state: the tangential reaction that stops the predicted
    // slip, within f R of the contact's own normal reaction.
    for (std::size_t k = 0; k < candidates_.size(); ++k) {
      candidates_[k].tangent = friction_total(candidates_[k], geometry[k], 0.0, candidates_[k].normal, dt_mid);
    }
    for (std::size_t k = 0; k < candidates_.size(); ++k) {
      const Candidate& c = candidates_[k];
      overlapping_ = geometry[k].start_gap < 0.0;
      apply_reaction(c, geometry[k].normal, geometry[k].xi, c.normal, c.tangent, dt_mid);
    }
    stats.sweeps = 1;
  } else {
    // Projected Gauss-Seidel. The first sweep visits every candidate; later sweeps visit a working set:
    // the candidates that push (normal > 0) or whose gap is within `working_margin` of their length.
    // Visiting any other candidate changes nothing (its reaction clamps to zero), so the result is
    // that of full sweeps unless a far candidate closes meanwhile; a full check confirms every exit.
    // Convergence: the largest violation of the contact conditions relative to the contact's length,
    // measured after the whole sweep (each update closes its own gap, but the updates after it can
    // reopen it): a penetration anywhere; where a reaction still pushes, an opening (a pushing contact
    // must close to its target gap, else its reaction is too large), and the displacement over the step
    // its reaction gives off the current normal (applied along a normal, or at an xi, that the updates
    // after it have turned or moved: a frictionless contact must not give a tangential impulse).
    constexpr double working_margin = 0.1;
    working_.clear();
    const auto violation = [&](const Candidate& c, const Geometry& g, double gap) {
      if (c.normal <= 0.0) return -gap;
      if (!g.valid) return std::numeric_limits<double>::infinity();
      if (!reoriented(c)) return std::abs(gap);
      const double w = contact_inverse_mass(g.normal, g.xi, inverse_mass(c.node), inverse_mass(c.a), inverse_mass(c.b));
      const double misplaced = dt_mid * dt_next * w * c.normal *
                               (norm(c.applied_normal - g.normal) + std::abs(c.applied_xi - g.xi)) /
                               std::max(c.length, 1e-300);
      return std::max(std::abs(gap), misplaced);
    };
    // The gap left to close, relative to the candidate's length (+infinity where it does not apply).
    const auto remaining = [&](const Candidate& c, const Geometry& g) {
      return g.valid ? (g.gap - overlap_target(g.start_gap, dt_next)) / std::max(c.length, 1e-300)
                     : std::numeric_limits<double>::infinity();
    };
    const auto check = [&](std::size_t k) {
      const Candidate& c = candidates_[k];
      const Geometry g = contact_geometry(c, dt_next);
      const double gap = remaining(c, g);
      return std::pair{violation(c, g, gap), gap};
    };
    const auto full_check = [&] {
      double worst = 0.0;
      working_.clear();
      for (std::size_t k = 0; k < candidates_.size(); ++k) {
        const auto [v, gap] = check(k);
        worst = std::max(worst, v);
        if (candidates_[k].normal > 0.0 || gap < working_margin) working_.push_back(static_cast<Index>(k));
      }
      return worst;
    };
    for (Candidate& c : candidates_) update(c, dt_mid, dt_next);
    stats.sweeps = 1;
    double worst = full_check();
    while (worst > setup_.controls.gap_tolerance && stats.sweeps < setup_.controls.max_sweeps) {
      for (Index k : working_) update(candidates_[static_cast<std::size_t>(k)], dt_mid, dt_next);
      ++stats.sweeps;
      worst = 0.0;
      for (Index k : working_) worst = std::max(worst, check(static_cast<std::size_t>(k)).first);
      if (worst <= setup_.controls.gap_tolerance) worst = full_check();
    }
    // Sweeps that stalled: the pushing contacts solved together (again from the geometry that solve
    // left, at most three times: the normals turn with the reactions' velocity changes), then a sweep
    // for the contacts that open or close, until converged or a tenth of the sweep limit more.
    if (worst > setup_.controls.gap_tolerance && setup_.controls.solve_stalled) {
      for (int round = 0; round < 3 && worst > setup_.controls.gap_tolerance; ++round) {
        if (!solve_pushing_together(dt_mid, dt_next)) break;
        stats.together = round + 1;
        worst = full_check();
      }
      for (int more = 0; more < std::max(1, setup_.controls.max_sweeps / 10) && worst > setup_.controls.gap_tolerance; ++more) {
        for (Index k : working_) update(candidates_[static_cast<std::size_t>(k)], dt_mid, dt_next);
        ++stats.sweeps;
        worst = full_check();
      }
    }
    stats.converged = worst <= setup_.controls.gap_tolerance;
  }
  overlapping_ = false;
  for (const Candidate& c : candidates_) {
    if (c.normal > 0.0) ++stats.active;
    stats.total_normal += c.normal;
    const Geometry g = contact_geometry(c, dt_next);
    if (!g.valid) continue;
    stats.deepest_gap = std::min(stats.deepest_gap, g.gap - std::min(g.start_gap, 0.0));
  }
  return stats;
}

void ContactSolver::source_forces(const Mesh& mesh, SourceForces& out) const {
  out.pairs.assign(setup_.pairs.size(), Vec2{});
  out.walls.assign(setup_.walls.size(), Vec2{});
  const bool summation = setup_.controls.method == ReactionMethod::summation;
  for (std::size_t k = 0; k < candidates_.size(); ++k) {
    const Candidate& c = candidates_[k];
    if (c.kind == Kind::wall) {
      if (c.wall < 0) continue;  // the axis wall of particles
      const Vec2 n = setup_.walls[static_cast<std::size_t>(c.wall)].normal;
      out.walls[static_cast<std::size_t>(c.wall)] += c.normal * n + c.tangent * Vec2{-n.y, n.x};
    } else if (c.kind == Kind::node_segment && c.pair >= 0) {
      const BodyPair& pair = setup_.pairs[static_cast<std::size_t>(c.pair)];
      if (pair.first == pair.second) continue;
      const Vec2 n = summation ? summation_geometry_[k].normal : c.applied_normal;
      const Vec2 force = c.normal * n + c.tangent * Vec2{-n.y, n.x};  // on the node; its segment takes -force
      const bool on_first = mesh.nodes.body[c.node.index] == pair.first;
      out.pairs[static_cast<std::size_t>(c.pair)] += on_first ? force : -1.0 * force;
    }
  }
}

}  // namespace krug::contact
