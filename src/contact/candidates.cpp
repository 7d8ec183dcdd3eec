// The contact candidates of a step: the broad-phase grids, then node-segment, particle and wall
// candidates (ContactSolver::find_candidates and its parts).
#include "krug/contact/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace krug::contact {

// --- candidates ---------------------------------------------------------------------------------

void ContactSolver::add_node_segment_candidates(const BodyBoundary& slaves, const BodyBoundary& masters,
                                                double friction, double weight, bool self, double dt_next,
                                                Index pair, std::size_t search, int threads) {
  const MasterGrid& master = master_grids_[static_cast<std::size_t>(&masters - boundaries_.data())];
  const std::vector<Box>& boxes = master.boxes;
  NearLists& lists = node_segment_lists_[search];
  if (rebuilding_) lists.chunks.resize((slaves.nodes.size() + search_chunk - 1) / search_chunk);
  // A master box moves with its segment's ends (allowed_motion_ at most) and grows with its length
  // (start_depth x at most 2 sqrt(2) allowed_motion_); the node's box moves with it.
  const double margin = 1.01 * allowed_motion_ * (2.0 + 2.0 * std::sqrt(2.0) * start_depth);
  // Each slave node's candidates are gathered, then kept only where the node can touch the face: a
  // node beside a segment's end and behind its line (past a convex corner of the master) is never in
  // contact with that face, and a node behind a face's line is handled by the master's shallowest face
  // it projects onto (the closest feature, as for particles: contact_geometry). Without this, a node
  // landing on a face near a convex corner took the side face's line distance as a pre-existing
  // overlap and was pushed sideways.
  // In fixed chunks of slave nodes (on the threads), each chunk's candidates kept in node order and the
  // chunks joined in order: the same list on any number of threads.
  const auto search_chunk_nodes = [&](std::size_t first, std::size_t last, std::vector<Candidate>& out,
                                      std::vector<Found>& found) {
    NearList& list = lists.chunks[first / search_chunk];
    if (rebuilding_) list.clear();
    for (std::size_t n = first; n < last; ++n) {
      const Index c = slaves.nodes[n];
      Box swept;
      swept.include(position(c));
      swept.include(predicted(c, dt_next));
      if (rebuilding_) list.add(master.grid, swept, margin);
      found.clear();
      list.visit(n - first, boxes, swept, [&](std::size_t k) {
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
        // that face is the one it touches. A node on the line itself (within the slack) keeps the face:
        // sliding along the line beyond a convex corner's end, it steps onto the face next.
        const double slack = end_slack * f.candidate.length;
        if (f.gap < -slack && f.gap < shallowest - slack) continue;
        out.push_back(f.candidate);
      }
    }
  };
  in_chunks(slaves.nodes.size(), threads, search_chunk_nodes);
}

// Calls search(first, last, candidates, found) on fixed chunks of [0, count) (their size from count alone),
// on up to `threads` threads, and appends each chunk's candidates to candidates_ in chunk order.
template <class Search>
void ContactSolver::in_chunks(std::size_t count, int threads, Search&& search) {
  constexpr std::size_t chunk = search_chunk;
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
      if (rebuilding_) master.grid.build(master.boxes);
    } else if (k == masters) {
      segment_boxes_.clear();
      particle_segments_.clear();
      for (const BodyBoundary& boundary : boundaries_) {
        for (const BoundarySegment& s : boundary.segments) {
          segment_boxes_.push_back(swept_box(s, dt_next));
          particle_segments_.push_back(&s);
        }
      }
      if (rebuilding_) segment_grid_.build(segment_boxes_);
    } else {
      particle_boxes_.clear();
      for (Index i = 0; i < particles_.size; ++i) particle_boxes_.push_back(reach_box(ContactPoint::particle(i), dt_next));
      if (rebuilding_) particle_grid_.build(particle_boxes_);
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
  // Particles against the segments of every body, then against each other (the grids are build_grids',
  // the lists the near lists above). Each box moves by allowed_motion_ at most, so a list holds the items
  // within twice that of the point's box at the rebuild.
  const double margin = 1.01 * 2.0 * allowed_motion_;
  const std::size_t chunks = (static_cast<std::size_t>(count) + search_chunk - 1) / search_chunk;
  if (rebuilding_) {
    particle_segment_lists_.chunks.resize(chunks);
    particle_particle_lists_.chunks.resize(chunks);
  }
  const std::vector<const BoundarySegment*>& segments = particle_segments_;
  in_chunks(static_cast<std::size_t>(count), threads,
            [&](std::size_t first, std::size_t last, std::vector<Candidate>& out, std::vector<Found>&) {
    NearList& list = particle_segment_lists_.chunks[first / search_chunk];
    if (rebuilding_) list.clear();
    for (std::size_t n = first; n < last; ++n) {
      const ContactPoint point = ContactPoint::particle(static_cast<Index>(n));
      const double r = radius(point);
      const Box box = reach_box(point);
      if (rebuilding_) list.add(segment_grid_, box, margin);
      list.visit(n - first, segment_boxes_, box, [&](std::size_t k) {
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
    NearList& list = particle_particle_lists_.chunks[first / search_chunk];
    if (rebuilding_) list.clear();
    for (std::size_t n = first; n < last; ++n) {
      const Index i = static_cast<Index>(n);
      if (rebuilding_) list.add(particle_grid_, particle_boxes_[n], margin);
      list.visit(n - first, particle_boxes_, particle_boxes_[n], [&](std::size_t j) {
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

bool ContactSolver::within_allowed_motion(double dt_next) const {
  const auto within = [&](Vec2 now, Vec2 then) {
    return std::abs(now.x - then.x) <= allowed_motion_ && std::abs(now.y - then.y) <= allowed_motion_;
  };
  for (const BodyBoundary& boundary : boundaries_) {
    for (Index c : boundary.nodes) {
      const std::size_t i = static_cast<std::size_t>(c);
      if (!within(position(c), listed_position_[i]) || !within(predicted(c, dt_next), listed_predicted_[i])) return false;
    }
  }
  if (!setup_.particles) return true;
  for (Index p = 0; p < particles_.size; ++p) {
    const ContactPoint point = ContactPoint::particle(p);
    const std::size_t i = static_cast<std::size_t>(p);
    if (!within(position(point), listed_particle_position_[i]) ||
        !within(predicted(point, dt_next), listed_particle_predicted_[i])) {
      return false;
    }
  }
  return true;
}

void ContactSolver::record_listed_positions(double dt_next) {
  listed_position_.resize(reaction_x_.size());
  listed_predicted_.resize(reaction_x_.size());
  double length_sum = 0.0;
  std::size_t segments = 0;
  for (const BodyBoundary& boundary : boundaries_) {
    for (Index c : boundary.nodes) {
      listed_position_[static_cast<std::size_t>(c)] = position(c);
      listed_predicted_[static_cast<std::size_t>(c)] = predicted(c, dt_next);
    }
    for (const BoundarySegment& s : boundary.segments) length_sum += norm(position(s.b) - position(s.a));
    segments += boundary.segments.size();
  }
  listed_particles_ = setup_.particles ? particles_.size : 0;
  listed_particle_position_.resize(static_cast<std::size_t>(listed_particles_));
  listed_particle_predicted_.resize(static_cast<std::size_t>(listed_particles_));
  for (Index p = 0; p < listed_particles_; ++p) {
    listed_particle_position_[static_cast<std::size_t>(p)] = position(ContactPoint::particle(p));
    listed_particle_predicted_[static_cast<std::size_t>(p)] = predicted(ContactPoint::particle(p), dt_next);
  }
  allowed_motion_ = allowed_motion_fraction * length_sum / static_cast<double>(std::max<std::size_t>(segments, 1));
}

void ContactSolver::find_candidates(double dt_next, int threads) {
  candidates_.clear();
  const Index particles = setup_.particles ? particles_.size : 0;
  rebuilding_ = !lists_valid_ || particles != listed_particles_ || !within_allowed_motion(dt_next);
  if (rebuilding_) {
    record_listed_positions(dt_next);
    lists_valid_ = true;
  }
  build_grids(dt_next, threads);
  const bool summation = setup_.controls.method == ReactionMethod::summation;
  std::size_t search = 0;
  for (std::size_t k = 0; k < setup_.pairs.size(); ++k) {
    const BodyPair& pair = setup_.pairs[k];
    const Index index = static_cast<Index>(k);
    const BodyBoundary& first = boundaries_[static_cast<std::size_t>(pair.first)];
    const BodyBoundary& second = boundaries_[static_cast<std::size_t>(pair.second)];
    node_segment_lists_.resize(std::max(node_segment_lists_.size(), search + 2));
    const double weight = summation ? 0.5 : 1.0;
    if (pair.first == pair.second) {
      add_node_segment_candidates(first, first, pair.friction, weight, true, dt_next, index, search++, threads);
    } else {
      add_node_segment_candidates(first, second, pair.friction, weight, false, dt_next, index, search++, threads);
      add_node_segment_candidates(second, first, pair.friction, weight, false, dt_next, index, search++, threads);
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

}  // namespace krug::contact
