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
}  // namespace

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

// --- candidates ---------------------------------------------------------------------------------

void ContactSolver::add_node_segment_candidates(const BodyBoundary& slaves, const BodyBoundary& masters,
                                                double friction, double weight, bool self, double dt_next,
                                                Index pair, int threads) {
  const UniformGrid& grid = master_grids_[static_cast<std::size_t>(&masters - boundaries_.data())].grid;
  // Each slave node's candidates are gathered, then kept only where the node can touch the face: a
  // node beside a segment's end and behind its line (past a convex corner of the master) is never in
  // contact with that face, and a node behind a face's line is handled by the master's shallowest face
  // it projects onto (the closest feature, as for particles: contact_geometry). Without this, a node
  // landing on a face near a convex corner took the side face's line distance as a pre-existing
  // overlap and was pushed sideways.
  // In fixed chunks of slave nodes (on the threads), each chunk's candidates kept in node order and the
  // chunks joined in order: the same list on any number of threads.
  const auto search = [&](std::size_t first, std::size_t last, std::vector<Candidate>& out, std::vector<Found>& found) {
    for (std::size_t n = first; n < last; ++n) {
      const Index c = slaves.nodes[n];
      found.clear();
      Box swept;
      swept.include(position(c));
      swept.include(predicted(c, dt_next));
      grid.query(swept, [&](std::size_t k) {
        const BoundarySegment& s = masters.segments[k];
        if (s.a == c || s.b == c) return;
        const Vec2 a = position(s.a), b = position(s.b);
        const SegmentProjection start = project(position(c), a, b, 0.0);
        const double length = norm(b - a);
        if (start.gap < -start_depth * length) return;  // behind the surface: the far side of a body
        if (self && start.gap < 0.0) return;             // a body's own surface is never entered from behind
        const double along = dot(position(c) - a, b - a) / std::max(length * length, 1e-300);
        const bool over = along >= -end_slack && along <= 1.0 + end_slack;
        // Beside the end and further behind the line than past the end: past a convex corner, on the
        // far side of the corner's bisector (a right angle's; a node grazing the line keeps its contact).
        const double beside = length * std::max(-along, along - 1.0);
        if (!over && start.gap < 0.0 && -start.gap > beside) return;
        Candidate candidate{ContactPoint::node(c), ContactPoint::node(s.a), ContactPoint::node(s.b)};
        candidate.kind = Kind::node_segment;
        candidate.friction = friction;
        candidate.weight = weight;
        candidate.pair = pair;
        candidate.start_gap = std::min(start.gap, 0.0);
        candidate.length = length;
        found.push_back({candidate, start.gap, over});
      });
      double shallowest = -std::numeric_limits<double>::infinity();
      for (const Found& f : found) {
        if (f.over) shallowest = std::max(shallowest, f.gap);
      }
      for (const Found& f : found) {
        // Behind this face's line but deeper than behind (or in front of) another face it projects onto:
        // that face is the one it touches.
        if (f.gap < 0.0 && f.gap < shallowest - end_slack * f.candidate.length) continue;
        out.push_back(f.candidate);
      }
    }
  };
  in_chunks(slaves.nodes.size(), threads, search);
}

// Calls search(first, last, candidates, found) on fixed chunks of [0, count) (their size from count alone),
// on up to `threads` threads, and appends each chunk's candidates to candidates_ in chunk order.
template <class Search>
void ContactSolver::in_chunks(std::size_t count, int threads, Search&& search) {
  constexpr std::size_t chunk = 64;
  const std::size_t chunks = (count + chunk - 1) / chunk;
  if (chunk_candidates_.size() < chunks) chunk_candidates_.resize(chunks);
  if (chunk_found_.size() < chunks) chunk_found_.resize(chunks);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && chunks >= 2)
  for (std::size_t k = 0; k < chunks; ++k) {
    chunk_candidates_[k].clear();
    search(k * chunk, std::min(count, (k + 1) * chunk), chunk_candidates_[k], chunk_found_[k]);
  }
  for (std::size_t k = 0; k < chunks; ++k) {
    candidates_.insert(candidates_.end(), chunk_candidates_[k].begin(), chunk_candidates_[k].end());
  }
}

Box ContactSolver::reach_box(ContactPoint point, double dt_next) const {
  Box box;
  box.include(position(point));
  box.include(predicted(point, dt_next));
  return box.expanded((1.0 + particle_search_margin) * radius(point));
}

void ContactSolver::build_grids(double dt_next, int threads) {
  master_grids_.resize(boundaries_.size());
  for (MasterGrid& m : master_grids_) m.used = false;
  for (const BodyPair& pair : setup_.pairs) {
    master_grids_[static_cast<std::size_t>(pair.first)].used = true;
    master_grids_[static_cast<std::size_t>(pair.second)].used = true;
  }
  // The builds to make: one per master body, then the particles' two.
  const std::size_t masters = master_grids_.size();
  const bool particles = setup_.particles && particles_.size > 0;
  const auto build = [&](std::size_t k) {
    if (k < masters) {
      MasterGrid& master = master_grids_[k];
      master.boxes.clear();
      for (const BoundarySegment& s : boundaries_[k].segments) {
        master.boxes.push_back(swept_box(s, dt_next).expanded(start_depth * norm(position(s.b) - position(s.a))));
      }
      master.grid.build(master.boxes);
    } else if (k == masters) {
      segment_boxes_.clear();
      particle_segments_.clear();
      for (const BodyBoundary& boundary : boundaries_) {
        for (const BoundarySegment& s : boundary.segments) {
          segment_boxes_.push_back(swept_box(s, dt_next));
          particle_segments_.push_back(&s);
        }
      }
      segment_grid_.build(segment_boxes_);
    } else {
      particle_boxes_.clear();
      for (Index i = 0; i < particles_.size; ++i) particle_boxes_.push_back(reach_box(ContactPoint::particle(i), dt_next));
      particle_grid_.build(particle_boxes_);
    }
  };
  // The particles' segment grid first: it holds every body's segments, the largest build.
  std::vector<std::size_t>& order = build_order_;
  order.clear();
  if (particles) order.push_back(masters);
  for (std::size_t k = 0; k < masters; ++k) {
    if (master_grids_[k].used) order.push_back(k);
  }
  if (particles) order.push_back(masters + 1);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1 && order.size() >= 2)
  for (std::size_t k = 0; k < order.size(); ++k) build(order[k]);
}

void ContactSolver::add_particle_candidates(double dt_next, int threads) {
  const Index count = particles_.size;
  if (count == 0) return;
  const auto reach_box = [&](ContactPoint point) { return this->reach_box(point, dt_next); };
  // Particles against the segments of every body (the grids are build_grids').
  const std::vector<const BoundarySegment*>& segments = particle_segments_;
  in_chunks(static_cast<std::size_t>(count), threads,
            [&](std::size_t first, std::size_t last, std::vector<Candidate>& out, std::vector<Found>&) {
    for (std::size_t n = first; n < last; ++n) {
      const ContactPoint point = ContactPoint::particle(static_cast<Index>(n));
      const double r = radius(point);
      segment_grid_.query(reach_box(point), [&](std::size_t k) {
        const BoundarySegment& s = *segments[k];
        const SegmentProjection start = project(position(point), position(s.a), position(s.b), r);
        const double length = norm(position(s.b) - position(s.a));
        if (start.inside && start.gap < -2.0 * r) return;  // centre behind the face: the far side of a body
        Candidate candidate{point, ContactPoint::node(s.a), ContactPoint::node(s.b)};
        candidate.kind = Kind::particle_segment;
        // The start gap on each feature of the segment: contact_geometry takes the one of the feature its
        // predicted gap is measured on (the face's line, or an end point).
        candidate.start_gap = std::min(start.gap, 0.0);
        candidate.start_gap_a = std::min(norm(position(point) - position(s.a)) - r, 0.0);
        candidate.start_gap_b = std::min(norm(position(point) - position(s.b)) - r, 0.0);
        candidate.length = std::max(length, r);
        out.push_back(candidate);
      });
    }
  });
  // Particles against each other.
  in_chunks(static_cast<std::size_t>(count), threads,
            [&](std::size_t first, std::size_t last, std::vector<Candidate>& out, std::vector<Found>&) {
    for (std::size_t n = first; n < last; ++n) {
      const Index i = static_cast<Index>(n);
      particle_grid_.query(particle_boxes_[n], [&](std::size_t j) {
        if (static_cast<Index>(j) <= i) return;
        const ContactPoint a = ContactPoint::particle(i), b = ContactPoint::particle(static_cast<Index>(j));
        const double start_gap = norm(position(a) - position(b)) - radius(a) - radius(b);
        Candidate candidate{a, b, {}};
        candidate.kind = Kind::particle_particle;
        candidate.start_gap = std::min(start_gap, 0.0);
        candidate.length = std::max(radius(a), radius(b));
        out.push_back(candidate);
      });
    }
  });
  // Particles against the walls and the axis.
  for (Index i = 0; i < count; ++i) {
    const ContactPoint point = ContactPoint::particle(i);
    const double reach = dt_next * norm(velocity(point)) + (1.0 + particle_search_margin) * radius(point);
    for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
      const RigidWall& wall = setup_.walls[w];
      const Index origin = particles_.body[i];
      if (!wall.bodies.empty() && std::find(wall.bodies.begin(), wall.bodies.end(), origin) == wall.bodies.end()) continue;
      const double start_gap = dot(position(point) - wall.point, wall.normal) - radius(point);
      if (start_gap + radius(point) - reach > 0.0) continue;
      Candidate candidate{point, {}, {}, static_cast<Index>(w)};
      candidate.kind = Kind::wall;
      candidate.friction = wall.friction;
      candidate.start_gap = std::min(start_gap, 0.0);
      candidate.length = radius(point);
      candidates_.push_back(candidate);
    }
    if (setup_.axis_wall && position(point).y - reach <= 0.0) {
      Candidate candidate{point, {}, {}, -2};
      candidate.kind = Kind::wall;
      candidate.start_gap = std::min(position(point).y - radius(point), 0.0);
      candidate.length = radius(point);
      candidates_.push_back(candidate);
    }
  }
}

void ContactSolver::find_candidates(double dt_next, int threads) {
  candidates_.clear();
  build_grids(dt_next, threads);
  const bool summation = setup_.controls.method == ReactionMethod::summation;
  for (std::size_t k = 0; k < setup_.pairs.size(); ++k) {
    const BodyPair& pair = setup_.pairs[k];
    const Index index = static_cast<Index>(k);
    const BodyBoundary& first = boundaries_[static_cast<std::size_t>(pair.first)];
    const BodyBoundary& second = boundaries_[static_cast<std::size_t>(pair.second)];
    if (pair.first == pair.second) {
      add_node_segment_candidates(first, first, pair.friction, summation ? 0.5 : 1.0, true, dt_next, index, threads);
    } else {
      add_node_segment_candidates(first, second, pair.friction, summation ? 0.5 : 1.0, false, dt_next, index, threads);
      add_node_segment_candidates(second, first, pair.friction, summation ? 0.5 : 1.0, false, dt_next, index, threads);
    }
  }
  for (std::size_t w = 0; w < setup_.walls.size(); ++w) {
    const RigidWall& wall = setup_.walls[w];
    for (std::size_t b = 0; b < boundaries_.size(); ++b) {
      if (!wall.bodies.empty() &&
          std::find(wall.bodies.begin(), wall.bodies.end(), static_cast<Index>(b)) == wall.bodies.end()) {
        continue;
      }
      double mean_length = 0.0;
      for (const BoundarySegment& s : boundaries_[b].segments) mean_length += norm(position(s.b) - position(s.a));
      mean_length /= static_cast<double>(std::max<std::size_t>(boundaries_[b].segments.size(), 1));
      for (Index c : boundaries_[b].nodes) {
        const double start_gap = dot(position(c) - wall.point, wall.normal);
        const double reach = dt_next * norm(velocity(c));
        if (start_gap - reach > 0.0) continue;  // cannot reach the wall in this step
        Candidate candidate{ContactPoint::node(c), {}, {}, static_cast<Index>(w)};
        candidate.kind = Kind::wall;
        candidate.friction = wall.friction;
        candidate.start_gap = std::min(start_gap, 0.0);
        candidate.length = mean_length;
        candidates_.push_back(candidate);
      }
    }
  }
  if (setup_.particles) add_particle_candidates(dt_next, threads);
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

bool ContactSolver::solve_pushing_together(double dt_mid, double dt_next) {
  std::vector<Index>& set = together_;
  set.clear();
  for (Index k : working_) {
    const Candidate& c = candidates_[static_cast<std::size_t>(k)];
    if (c.friction > 0.0 && c.normal > 0.0) return false;  // Coulomb's bound is not linear: left to the sweeps
    if (c.normal > 0.0 && c.kind != Kind::wall) set.push_back(k);
  }
  if (set.empty()) return false;
  const std::size_t n = set.size();
  const std::size_t nodes = reaction_x_.size();  // one per mesh node
  together_point_.assign(nodes + static_cast<std::size_t>(particles_.size), Vec2{});
  const auto slot = [&](ContactPoint p) {
    return p.is_particle() ? nodes + static_cast<std::size_t>(p.index) : static_cast<std::size_t>(p.index);
  };
  std::vector<Geometry> geometry(n);
  together_rhs_.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
    geometry[i] = contact_geometry(c, dt_next);
    if (!geometry[i].valid) return false;
    together_rhs_[i] = -(geometry[i].gap - overlap_target(geometry[i].start_gap, dt_next)) / (dt_mid * dt_next);
  }
  // q = W v: the forces v along the normals, to the points, through the inverse masses, back along the normals.
  const auto apply_w = [&](const std::vector<double>& v, std::vector<double>& q) {
    for (std::size_t i = 0; i < n; ++i) {
      const Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
      const Vec2 f = v[i] * geometry[i].normal;
      together_point_[slot(c.node)] += f;
      if (c.a.exists()) together_point_[slot(c.a)] -= (1.0 - geometry[i].xi) * f;
      if (c.b.exists()) together_point_[slot(c.b)] -= geometry[i].xi * f;
    }
    const auto velocity_change = [&](ContactPoint p) {
      const InverseMass w = inverse_mass(p);
      const Vec2 f = together_point_[slot(p)];
      return Vec2{w.x * f.x, w.y * f.y};
    };
    for (std::size_t i = 0; i < n; ++i) {
      const Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
      Vec2 du = velocity_change(c.node);
      if (c.a.exists()) du -= (1.0 - geometry[i].xi) * velocity_change(c.a);
      if (c.b.exists()) du -= geometry[i].xi * velocity_change(c.b);
      q[i] = dot(geometry[i].normal, du);
    }
    for (std::size_t i = 0; i < n; ++i) {  // clear the points touched
      const Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
      together_point_[slot(c.node)] = {};
      if (c.a.exists()) together_point_[slot(c.a)] = {};
      if (c.b.exists()) together_point_[slot(c.b)] = {};
    }
  };
  // The largest violation, relative to the contact's length, of gaps missing their targets by
  // `residual` (in the units of the right-hand side) where reactions push; of penetrations elsewhere.
  const auto worst_of = [&](const std::vector<double>& residual, const std::vector<double>& totals) {
    double worst = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double length = std::max(candidates_[static_cast<std::size_t>(set[i])].length, 1e-300);
      const double miss = residual[i] * dt_mid * dt_next / length;  // target - gap, relative
      worst = std::max(worst, totals[i] > 0.0 ? std::abs(miss) : miss);
    }
    return worst;
  };
  // Conjugate gradients from dR = 0 until the residual is 1e-13 of the first (far below the gap
  // tolerance: a loose stop here is the tolerance's residue in every later step), W sees no more of
  // the search direction, or the residual grows (a right-hand side W cannot meet: contacts that ask
  // for gaps no reactions give); the iterate with the smallest violation is kept.
  std::vector<double>&x = together_x_, &r = together_r_, &p = together_p_, &q = together_q_;
  x.assign(n, 0.0);
  r = together_rhs_;
  p = r;
  q.assign(n, 0.0);
  std::vector<double> best(n, 0.0), ones(n, 1.0);
  double best_worst = worst_of(r, ones);
  double rr = 0.0;
  for (double v : r) rr += v * v;
  const double stop = 1e-26 * rr;
  const int limit = static_cast<int>(std::min<std::size_t>(4 * n + 10, 2000));
  for (int iteration = 0; iteration < limit && rr > stop; ++iteration) {
    apply_w(p, q);
    double pq = 0.0;
    for (std::size_t i = 0; i < n; ++i) pq += p[i] * q[i];
    if (!(pq > 0.0)) break;
    const double alpha = rr / pq;
    double next = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      next += r[i] * r[i];
    }
    const double worst = worst_of(r, ones);
    if (worst < best_worst) {
      best_worst = worst;
      best = x;
    } else if (worst > 100.0 * best_worst) {
      break;
    }
    const double beta = next / rr;
    rr = next;
    for (std::size_t i = 0; i < n; ++i) p[i] = r[i] + beta * p[i];
  }
  // The changes, clamped where a total would pull, and kept only if the linear model says they at
  // least halve the largest violation of these contacts.
  std::vector<double> change(n), totals(n), current(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double normal = candidates_[static_cast<std::size_t>(set[i])].normal;
    totals[i] = std::max(0.0, normal + best[i]);
    change[i] = totals[i] - normal;
    current[i] = normal;
  }
  apply_w(change, q);
  for (std::size_t i = 0; i < n; ++i) r[i] = together_rhs_[i] - q[i];
  if (!(worst_of(r, totals) < 0.5 * worst_of(together_rhs_, current))) return false;
  // The new totals, applied as a sweep applies them (frictionless: the tangential reaction stays 0).
  for (std::size_t i = 0; i < n; ++i) {
    Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
    replace_reaction(c, geometry[i], totals[i], c.tangent, dt_mid);
  }
  return true;
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
