#pragma once
// Contact by reaction forces (docs/theory.md §2 step 3): node-on-segment between the bodies a
// scenario pairs (both ways), self-contact of a body's own boundary, and rigid walls that push but
// never pull. Works on the velocities after the predictor: each reaction changes velocities by
// dt^n R W, and the predicted positions x* = x^n + dt^{n+1/2} u follow.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "krug/contact/broad_phase.hpp"
#include "krug/contact/kernels.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/particles/particles.hpp"

namespace krug::contact {

struct BodyPair {
  Index first = 0;
  Index second = 0;       // == first: self-contact of the body's boundary
  double friction = 0.0;  // Coulomb coefficient
};

// A rigid plane: points x with (x - point) . normal >= 0 are allowed; `normal` is a unit vector.
struct RigidWall {
  Vec2 point;
  Vec2 normal{1.0, 0.0};
  double friction = 0.0;
  std::vector<Index> bodies;  // empty: every body
};

enum class ReactionMethod {
  gauss_seidel,  // projected Gauss-Seidel with accumulated-impulse clamping (default)
  summation      // the paper's: all reactions from the same predicted state, summed; two-way pairs weighted 1/2
};

struct ContactControls {
  ReactionMethod method = ReactionMethod::gauss_seidel;
  int max_sweeps = 50;
  // After sweeps that reach max_sweeps unconverged, solve the pushing frictionless contacts together
  // (ContactSolver::solve_pushing_together): without it a pre-stressed stack of non-matching blocks
  // crawls at the sweep limit (docs/verification.md, Contact, C2). False: the sweeps alone.
  bool solve_stalled = true;
  double gap_tolerance = 1e-5;  // sweeps stop when no gap is below -tolerance x segment length
  double overlap_fraction = 0.1;  // a pre-existing overlap is removed by at most this fraction per step,
  double overlap_speed = 1.0;     // and no faster than this (m/s): a fraction per step alone is a speed
                                  // fraction x depth / dt, which grows without bound as dt shrinks
};

struct ContactSetup {
  std::vector<BodyPair> pairs;
  std::vector<RigidWall> walls;
  ContactControls controls;
  bool particles = false;     // free elements may exist: particles against every body, each other and the walls
  bool axis_wall = false;     // axisymmetric: the axis is a rigid wall at r = radius for particles (rings)
  bool empty() const { return pairs.empty() && walls.empty() && !particles; }
};

struct ContactStatistics {
  long candidates = 0;
  long active = 0;               // candidates with a positive normal reaction at the end
  int sweeps = 0;
  bool converged = true;         // the sweeps ended within gap_tolerance (false: at max_sweeps)
  int together = 0;              // times the stalled sweeps' pushing contacts were solved together (solve_stalled)
  double deepest_gap = 0.0;      // most negative predicted gap left after the sweeps (m)
  double total_normal = 0.0;     // sum of normal reactions (N per radian or per m)
  bool lists_rebuilt = false;    // the broad phase's grids and near lists were rebuilt for this solve
};

// Per-body boundary description, rebuilt when the topology changes.
struct BodyBoundary {
  std::vector<BoundarySegment> segments;
  std::vector<Index> nodes;      // unique boundary nodes
};

// A point that takes part in a contact: a mesh node or a free particle (or none: the missing end of a
// wall contact, or the second end of a particle-particle contact).
struct ContactPoint {
  enum class Kind : std::uint8_t { none, node, particle };
  Kind kind = Kind::none;
  Index index = -1;  // the node's or the particle's index

  static constexpr ContactPoint node(Index n) { return {Kind::node, n}; }
  static constexpr ContactPoint particle(Index i) { return {Kind::particle, i}; }
  constexpr bool exists() const { return kind != Kind::none; }
  constexpr bool is_node() const { return kind == Kind::node; }
  constexpr bool is_particle() const { return kind == Kind::particle; }
  friend constexpr bool operator==(ContactPoint, ContactPoint) = default;
};

// A particle's candidates are searched over its swept path at the velocity before the solve, widened
// by this fraction of its radius beyond its size: the reactions change its velocity during the solve,
// and a pair the search missed is never seen (docs/verification.md, E8).
inline constexpr double particle_search_margin = 0.1;

// How far the last solve moved a particle beyond the reach its candidates were searched over, in
// units of the search margin (its path over dt at u_old, the velocity before the solve: a particle
// feels no other force), the largest over the particles; 0 when every particle stayed within it.
// Above 1 a particle may have met another, or a face, that is not among its candidates.
double particle_escape(const Particles& particles, double dt);

// What a contact solve reads and writes of the mesh's nodes: positions x^n and per-DOF inverse masses
// (0 where a condition holds the component) read; the predicted velocities u* written, each reaction
// applied to them as the sweeps go (u^{n+1/2} = u* + dt^n R / M).
struct NodesView {
  const double* x = nullptr;
  const double* y = nullptr;
  double* u = nullptr;
  double* v = nullptr;
  const double* inverse_mass_x = nullptr;
  const double* inverse_mass_y = nullptr;
};
inline NodesView nodes_view(NodeFields& nodes) {
  return {nodes.x.data(), nodes.y.data(), nodes.u.data(), nodes.v.data(), nodes.inv_mass_x.data(),
          nodes.inv_mass_y.data()};
}

// The same of the free particles, with their masses, radii and the bodies they came from (read).
struct ParticlesView {
  Index size = 0;
  const double* x = nullptr;
  const double* y = nullptr;
  double* u = nullptr;
  double* v = nullptr;
  const double* mass = nullptr;
  const double* radius = nullptr;
  const std::int32_t* body = nullptr;
};
inline ParticlesView particles_view(Particles& particles) {
  return {particles.size(),       particles.x.data(),    particles.y.data(),      particles.u.data(),
          particles.v.data(),     particles.mass.data(), particles.radius.data(), particles.body.data()};
}

class ContactSolver {
 public:
  ContactSolver() = default;
  ContactSolver(ContactSetup setup, const Mesh& mesh, const std::vector<std::pair<Index, Index>>& body_zone_ranges);

  bool empty() const { return setup_.empty(); }
  void rebuild_boundaries(const Mesh& mesh);

  // Applies the reactions to the velocities of nodes and particles (which hold the predicted
  // velocities u*). Records the reaction force on each touched point for the ledger. The boundaries
  // (rebuild_boundaries) are those of the mesh the node view shows.
  ContactStatistics solve(NodesView nodes, ParticlesView particles, double dt_mid, double dt_next, int threads = 1);

  // The points that received a reaction in the last solve, in the order they first did.
  const std::vector<ContactPoint>& touched_points() const { return touched_; }
  Vec2 reaction_force(ContactPoint point) const;
  // The part of reaction_force(point) applied by contacts that carry a pre-existing overlap (a start gap
  // < 0, driven open by the overlap rule): its work is the ledger's overlap line.
  Vec2 overlap_reaction_force(ContactPoint point) const;
  const ContactSetup& setup() const { return setup_; }

  // The reactions of the last solve by where they came from (for gauges; nothing in the step computes
  // them): `pairs[k]` the force pair k's node-on-segment contacts applied to its first body (zero for a
  // self-contact pair), `walls[w]` the force wall w applied to the nodes and particles it touched
  // (N per radian or per m). Each contact's reaction is its accumulated total along the direction it
  // was applied in, so the sums equal those of reaction_force() to round-off. Contacts of particles
  // with body segments or with each other belong to no pair.
  struct SourceForces {
    std::vector<Vec2> pairs, walls;
  };
  void source_forces(const Mesh& mesh, SourceForces& out) const;

 private:
  enum class Kind : std::uint8_t { node_segment, particle_segment, particle_particle, wall };
  struct Candidate {
    ContactPoint node, a, b;  // the point; the segment's end nodes, or the other particle in a; none where absent
    Index wall = -1;       // wall index (Kind::wall; -2 is the axis)
    Index pair = -1;       // setup_.pairs index of a node-segment candidate
    Kind kind = Kind::node_segment;
    double friction = 0.0;
    double weight = 1.0;   // 1/2 for two-way pairs in the summation method
    double start_gap = 0.0;     // gap at x^n, <= 0 (pre-existing overlap); particle-segment: from the face's line
    double start_gap_a = 0.0;   // particle-segment: from the end points a and b (the feature is chosen
    double start_gap_b = 0.0;   // in contact_geometry, from the predicted positions)
    double length = 0.0;   // segment length (m), for tolerances
    double normal = 0.0;   // accumulated normal reaction (N per radian or per m)
    double tangent = 0.0;  // accumulated tangential reaction
    // Gauss-Seidel, node-segment candidates: where the accumulated reaction now acts. Each update
    // withdraws it and applies the new total along the current normal at the current xi, so the
    // candidate's impulse is always normal x n + tangent x t of one geometry (a frictionless contact
    // gives no tangential impulse). The other kinds (particles) add each change along the current
    // normal: re-applying their whole reactions gave energy in a run with erosion particles
    // (docs/verification.md, Contact, C2).
    Vec2 applied_normal{0.0, 0.0};
    double applied_xi = 0.0;
  };
  static bool reoriented(const Candidate& c) { return c.kind == Kind::node_segment; }
  // A node counts against a segment only while it projects onto it (with this slack at the ends,
  // relative to the segment length) and started the step outside it or within this depth.
  static constexpr double end_slack = 1e-3;
  static constexpr double start_depth = 0.25;

  struct Geometry {
    Vec2 normal, tangent;
    double xi = 0.0, gap = 0.0;
    double start_gap = 0.0;  // the candidate's start gap on the same feature as `gap` (<= 0)
    SegmentFeature feature = SegmentFeature::face;  // particle-segment: what `gap` is measured from
    bool valid = true;
  };
  // After sweeps that stalled: the pushing frictionless contacts' reactions solved together. The
  // change of reactions dR that closes every pushing contact to its target gap in the current geometry
  // solves W dR = -(gap - target) / (dt^{n+1/2} dt^{n+1}), W = J M^-1 J^T over those contacts (J: a
  // contact's normal on its point, -(1 - xi) and -xi of it on the segment's ends), by conjugate
  // gradients on W as an operator (W is symmetric and semi-definite: two-way contacts of non-matching
  // faces are redundant, and the sweeps crawl along its near-null directions, docs/verification.md C2).
  // The new totals (clamped at zero) are applied as a sweep applies them. Returns whether it ran.
  bool solve_pushing_together(double dt_mid, double dt_next);
  // Sets candidate c's reactions to these totals, as every update does: a node-segment candidate's
  // accumulated reaction is withdrawn where it acted and the totals applied along g's normal at g's xi;
  // the other kinds add the change along g's normal. Books the overlap flag from g's start gap.
  void replace_reaction(Candidate& c, const Geometry& g, double normal_total, double tangent_total, double dt_mid);
  std::vector<Index> together_;                          // its scratch: the contacts,
  std::vector<double> together_rhs_, together_x_, together_r_, together_p_, together_q_;  // the vectors,
  std::vector<Vec2> together_point_;                     // and a force per point (nodes, then particles)
  // The candidate search runs on up to `threads` threads (in_chunks) with the same list on any number.
  void find_candidates(double dt_next, int threads);
  // `search`: which node-segment search of find_candidates this is (the index of its near lists).
  void add_node_segment_candidates(const BodyBoundary& slaves, const BodyBoundary& masters, double friction,
                                   double weight, bool self, double dt_next, Index pair, std::size_t search,
                                   int threads);
  void add_particle_candidates(double dt_next, int threads);
  Geometry contact_geometry(const Candidate& c, double dt_next) const;
  // Coulomb: the tangential reaction that stops the slip at xi, from `accumulated`, within f x
  // normal_total (unchanged without friction).
  double friction_total(const Candidate& c, const Geometry& g, double accumulated, double normal_total,
                        double dt_mid) const;
  // Velocity of the contact's point relative to the other side at xi (a wall stands still).
  Vec2 relative_velocity(const Candidate& c, double xi) const;
  // Returns the gap after this update (for the convergence check).
  double update(Candidate& c, double dt_mid, double dt_next);
  double overlap_target(double start_gap, double dt_next) const;
  void apply(ContactPoint point, Vec2 direction, double force, double dt_mid);
  // The reaction normal x n + tangent x t at xi: on the point, and shared by the segment's ends.
  void apply_reaction(const Candidate& c, Vec2 normal, double xi, double normal_force, double tangent_force,
                      double dt_mid);
  // A point's state (node or particle), inline: the reaction loops call them for every candidate and
  // sweep. The Index forms are for mesh nodes (segment ends, boundary nodes).
  Vec2 position(Index node) const { return {nodes_.x[node], nodes_.y[node]}; }
  Vec2 velocity(Index node) const { return {nodes_.u[node], nodes_.v[node]}; }
  Vec2 predicted(Index node, double dt) const { return position(node) + dt * velocity(node); }
  Vec2 position(ContactPoint point) const {
    return point.is_particle() ? Vec2{particles_.x[point.index], particles_.y[point.index]} : position(point.index);
  }
  Vec2 velocity(ContactPoint point) const {
    return point.is_particle() ? Vec2{particles_.u[point.index], particles_.v[point.index]} : velocity(point.index);
  }
  Vec2 predicted(ContactPoint point, double dt) const { return position(point) + dt * velocity(point); }
  // The box a segment sweeps over the step: its ends at x^n and at the predicted positions.
  Box swept_box(const BoundarySegment& s, double dt) const {
    Box box;
    box.include(position(s.a));
    box.include(position(s.b));
    box.include(predicted(s.a, dt));
    box.include(predicted(s.b, dt));
    return box;
  }
  InverseMass inverse_mass(ContactPoint point) const {
    if (!point.exists()) return {};
    if (point.is_particle()) {
      const double inverse = 1.0 / particles_.mass[point.index];
      return {inverse, inverse};
    }
    return {nodes_.inverse_mass_x[point.index], nodes_.inverse_mass_y[point.index]};
  }
  double radius(ContactPoint point) const { return point.is_particle() ? particles_.radius[point.index] : 0.0; }
  void touch(ContactPoint point, Vec2 force);

  NodesView nodes_;          // of the current solve
  ParticlesView particles_;
  std::vector<double> particle_reaction_x_, particle_reaction_y_;
  std::vector<double> particle_overlap_x_, particle_overlap_y_;
  bool overlapping_ = false;  // the reaction being applied is that of a contact with a pre-existing overlap

  ContactSetup setup_;
  std::vector<std::pair<Index, Index>> zone_ranges_;
  std::vector<BodyBoundary> boundaries_;
  std::vector<Candidate> candidates_;
  std::vector<Geometry> summation_geometry_;  // the summation method's geometry of each candidate, as applied
  std::vector<Index> working_;  // candidates the later Gauss-Seidel sweeps visit
  // The particles' broad phases: against the segments of every body, and against each other.
  std::vector<Box> segment_boxes_, particle_boxes_;
  UniformGrid segment_grid_, particle_grid_;
  // Builds every broad phase this step's search uses (the masters' node-segment grids and the particles'
  // two), each on its own thread when there are several: a grid is the same whichever thread builds it.
  void build_grids(double dt_next, int threads);
  std::vector<std::size_t> build_order_;  // build_grids' scratch
  // A particle's search box: the box its disc sweeps over the step, grown by the search margin.
  Box reach_box(ContactPoint point, double dt_next) const;
  // The node-segment broad phase of each body as a master, built at most once per find_candidates (a
  // body that is the master of two pairs, as in a two-body pair beside a self-contact pair, shares it).
  struct MasterGrid {
    std::vector<Box> boxes;
    UniformGrid grid;
    bool used = false;  // the master of some pair this step (its grid is then built)
  };
  std::vector<MasterGrid> master_grids_;
  struct Found {
    Candidate candidate;
    double gap;  // signed distance from the face's line at x^n
    bool over;   // projects onto the segment at x^n (within end_slack)
  };
  // Calls search(first, last, candidates, found) on fixed chunks of search_chunk points.
  static constexpr std::size_t search_chunk = 64;
  template <class Search>
  void in_chunks(std::size_t count, int threads, Search&& search);

  // The broad phase reused across steps (near lists, as Verlet lists in molecular dynamics). At a
  // rebuild each query point keeps, sorted, the items whose boxes overlap its own box grown by the
  // margin that covers what the points may move before the next rebuild; each step its candidates are
  // the items of its list whose current boxes overlap its current box: the same items, in the same
  // order (by item), as a query of a grid built that step. The lists are rebuilt when a boundary node
  // or particle (its position or its predicted position) has moved further than allowed_motion_ since
  // the last rebuild, when the boundaries were rebuilt and when the particles changed in number.
  struct NearList {
    std::vector<std::uint32_t> start;  // point first + i of the chunk has items[start[i] .. start[i + 1])
    std::vector<std::uint32_t> items;
    void clear() {
      start.assign(1, 0);
      items.clear();
    }
    // Appends the next point's list: the items of `grid` whose boxes overlap `box` grown by `margin`, sorted.
    void add(const UniformGrid& grid, const Box& box, double margin) {
      const std::size_t begin = items.size();
      grid.query(box.expanded(margin), [&](std::size_t k) { items.push_back(static_cast<std::uint32_t>(k)); });
      std::sort(items.begin() + static_cast<std::ptrdiff_t>(begin), items.end());
      start.push_back(static_cast<std::uint32_t>(items.size()));
    }
    // Calls visit(item) for the items of the chunk's point i whose current `boxes` overlap `box`, in order.
    template <class Visit>
    void visit(std::size_t i, const std::vector<Box>& boxes, const Box& box, Visit&& each) const {
      for (std::uint32_t k = start[i]; k < start[i + 1]; ++k) {
        if (boxes[items[k]].overlaps(box)) each(static_cast<std::size_t>(items[k]));
      }
    }
  };
  struct NearLists {
    std::vector<NearList> chunks;  // one per in_chunks chunk of the search's points
  };
  std::vector<NearLists> node_segment_lists_;   // one per node-segment search, in find_candidates' order
  NearLists particle_segment_lists_, particle_particle_lists_;
  // The motion a list allows, as a fraction of the boundaries' mean segment length at the rebuild.
  static constexpr double allowed_motion_fraction = 0.2;
  bool lists_valid_ = false;
  bool rebuilding_ = false;        // this step's search rebuilds the grids and the lists
  double allowed_motion_ = 0.0;    // m, per coordinate
  std::vector<Vec2> listed_position_, listed_predicted_;                    // mesh nodes, at the rebuild
  std::vector<Vec2> listed_particle_position_, listed_particle_predicted_;   // particles, at the rebuild
  Index listed_particles_ = 0;
  // Whether every boundary node and particle is within allowed_motion_ (in x and in y) of where it
  // and its predicted position were at the last rebuild.
  bool within_allowed_motion(double dt_next) const;
  void record_listed_positions(double dt_next);
  std::vector<std::vector<Candidate>> chunk_candidates_;   // in_chunks: each chunk's candidates (scratch)
  std::vector<std::vector<Found>> chunk_found_;            // and one slave node's candidates in the chunk
  std::vector<const BoundarySegment*> particle_segments_;  // the segments of the particles' broad phase
  std::vector<double> reaction_x_, reaction_y_;
  std::vector<double> overlap_x_, overlap_y_;
  std::vector<ContactPoint> touched_;
  std::vector<std::uint8_t> touched_flag_;
};

}  // namespace krug::contact
