// The contact reaction solver (krug/contact/contact.hpp; docs/theory.md §2 step 3) on tiny scenes
// built in code: one-zone bodies from generate::rectangle, single particles and rigid walls. One call
// of ContactSolver::solve with given dt^n (dt_mid) and dt^{n+1/2} (dt_next), on velocities that stand
// for the predictor's u*. Each reaction R changes a velocity by dt_mid R W and so the predicted gap
// g* = (x + dt_next u) gap by dt_mid dt_next R w (kernels.hpp), so a single contact closes with
//     R = -g* / (dt_mid dt_next w)
// and the hand values below follow from it. Asserted: reactions never pull, the predicted gaps close to
// the solver's tolerance, the reactions conserve momentum (sum of m u over everything involved), and a
// pair moving apart gets nothing.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "krug/contact/contact.hpp"
#include "krug/contact/kernels.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/particles/particles.hpp"

using namespace krug;
using namespace krug::contact;

namespace {

// dt^n and dt^{n+1/2} of the step; chosen unequal so that a swapped pair would show.
constexpr double dt_mid = 0.01, dt_next = 0.02;

struct Scene {
  Mesh mesh;
  Particles particles;
  std::vector<std::pair<Index, Index>> zone_ranges;  // per body
};

// Appends a one-zone body: the unit square mapped by `map`, every node of mass `node_mass` moving at
// `velocity`; `held` sets both inverse masses to 0 (a fixed body). The generator numbers the nodes
// (0,0), (1,0), (0,1), (1,1) of the unit square from node_begin on, and the zone's corners
// counter-clockwise, so its top edge is the boundary segment from node_begin + 3 to node_begin + 2.
generate::Patch add_body(Scene& scene, const generate::PositionMap& map, double node_mass, Vec2 velocity,
                         bool held = false) {
  const Index body = static_cast<Index>(scene.zone_ranges.size());
  generate::Patch patch = generate::rectangle(scene.mesh, {0.0, 1.0}, {0.0, 1.0}, body, map);
  NodeFields& nodes = scene.mesh.nodes;
  for (Index n = patch.node_begin; n < patch.node_end; ++n) {
    nodes.mass[n] = node_mass;
    nodes.inv_mass_x[n] = nodes.inv_mass_y[n] = held ? 0.0 : 1.0 / node_mass;
    nodes.u[n] = nodes.u_old[n] = velocity.x;
    nodes.v[n] = nodes.v_old[n] = velocity.y;
    nodes.x0[n] = nodes.x[n];
    nodes.y0[n] = nodes.y[n];
  }
  scene.zone_ranges.emplace_back(patch.zone_begin, patch.zone_end);
  return patch;
}

// The unit square [0, 1]^2: its top edge runs from (1, 1) (node 3) to (0, 1) (node 2), outward normal
// to the right of a -> b: t = (-1, 0), n = (t.y, -t.x) = (0, 1).
Vec2 identity(Vec2 p) { return p; }

// A diamond standing on its corner above the unit square: the unit square mapped by
// (x, y) -> (0.5 + 0.2 (x - y), 1.1 + 0.2 (x + y)) (determinant 0.08 > 0, still counter-clockwise):
// corners (0.5, 1.1) (its bottom, node 4), (0.7, 1.3), (0.3, 1.3), (0.5, 1.5). Only the bottom corner
// comes near the square's top face; it projects on its middle, xi = 0.5.
Vec2 diamond(Vec2 p) { return {0.5 + 0.2 * (p.x - p.y), 1.1 + 0.2 * (p.x + p.y)}; }

// Sum of m u over the nodes that move (inverse mass > 0) and the particles.
Vec2 momentum(const Scene& scene) {
  Vec2 total{0.0, 0.0};
  const NodeFields& nodes = scene.mesh.nodes;
  for (Index n = 0; n < nodes.size(); ++n) {
    if (nodes.inv_mass_x[n] > 0.0) total.x += nodes.mass[n] * nodes.u[n];
    if (nodes.inv_mass_y[n] > 0.0) total.y += nodes.mass[n] * nodes.v[n];
  }
  for (Index i = 0; i < scene.particles.size(); ++i) {
    total += scene.particles.mass[static_cast<std::size_t>(i)] * scene.particles.velocity(i);
  }
  return total;
}

Vec2 predicted_node(const Scene& scene, Index n) { return scene.mesh.nodes.position(n) + dt_next * scene.mesh.nodes.velocity(n); }

// The predicted gap of node c from the predicted segment ab (ContactSolver's node-on-segment gap).
double predicted_gap(const Scene& scene, Index c, Index a, Index b) {
  return project(predicted_node(scene, c), predicted_node(scene, a), predicted_node(scene, b), 0.0).gap;
}

ContactSolver pair_solver(const Scene& scene, ReactionMethod method = ReactionMethod::gauss_seidel,
                          double friction = 0.0) {
  ContactSetup setup;
  setup.pairs.push_back({0, 1, friction});
  setup.controls.method = method;
  return ContactSolver(setup, scene.mesh, scene.zone_ranges);
}

void check_vec(Vec2 actual, Vec2 expected, double tolerance) {
  CHECK(actual.x == Approx(expected.x).margin(tolerance).epsilon(0.0));
  CHECK(actual.y == Approx(expected.y).margin(tolerance).epsilon(0.0));
}

}  // namespace

TEST_CASE("node against a fixed segment: the reaction closes the predicted gap", "[kernels][reaction_solver]") {
  Scene scene;
  add_body(scene, identity, 1.0, {0.0, 0.0}, true);   // nodes 0-3, held
  add_body(scene, diamond, 1.0, {0.0, -10.0});        // nodes 4-7, mass 1
  ContactSolver solver = pair_solver(scene);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  // Node 4 at height 1.1 moves dt_next * 10 = 0.2 down: g* = 0.1 - 0.2 = -0.1. The segment is held, so
  // w = n.W_c n = 1 and R = 0.1 / (0.01 * 0.02 * 1) = 500 N; du = dt_mid R / m = 5: v = -10 + 5 = -5,
  // and the predicted height 1.1 - 0.02 * 5 = 1.0 lies on the face. The diamond's other corners start
  // 0.3 above it and end 0.1 above: no reaction.
  CHECK(stats.active == 1);
  CHECK(stats.total_normal == Approx(500.0).margin(1e-9));
  CHECK(scene.mesh.nodes.v[4] == Approx(-5.0).margin(1e-12));
  CHECK(scene.mesh.nodes.u[4] == 0.0);  // frictionless, normal (0, 1): no tangential change
  CHECK(predicted_gap(scene, 4, 3, 2) == Approx(0.0).margin(1e-12));
  for (Index n : {5, 6, 7}) CHECK(scene.mesh.nodes.v[n] == -10.0);
  // The recorded reaction forces: R n on the node, -(1 - xi) R n = -250 n on each end (xi = 0.5).
  check_vec(solver.reaction_force(ContactPoint::node(4)), {0.0, 500.0}, 1e-9);
  check_vec(solver.reaction_force(ContactPoint::node(3)), {0.0, -250.0}, 1e-9);
  check_vec(solver.reaction_force(ContactPoint::node(2)), {0.0, -250.0}, 1e-9);
  CHECK(scene.mesh.nodes.v[2] == 0.0);  // held: the force is booked, the velocity stays
  CHECK(stats.deepest_gap >= -1e-12);
}

TEST_CASE("node against a free segment: hand reaction and momentum conserved", "[kernels][reaction_solver]") {
  Scene scene;
  add_body(scene, identity, 1.0, {0.0, 0.0});   // nodes 0-3, mass 1 each
  add_body(scene, diamond, 2.0, {0.0, -10.0});  // nodes 4-7, mass 2 each
  const Vec2 before = momentum(scene);          // 4 x 2 x (-10) = (0, -80)
  ContactSolver solver = pair_solver(scene);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  // g* = -0.1 (as above); w = 1/2 + (1 - 0.5)^2 * 1 + 0.5^2 * 1 = 1; R = 0.1 / (2e-4 * 1) = 500.
  // Node 4: du = 0.01 * 500 / 2 = 2.5 -> v = -7.5. Ends a, b: du = -0.01 * 0.5 * 500 / 1 = -2.5.
  // Predicted: node 1.1 - 0.02 * 7.5 = 0.95, segment 1 - 0.02 * 2.5 = 0.95: closed, the segment still
  // level (both ends move alike), so the first sweep is already converged.
  CHECK(stats.active == 1);
  CHECK(stats.sweeps == 1);
  CHECK(stats.total_normal == Approx(500.0).margin(1e-9));
  CHECK(scene.mesh.nodes.v[4] == Approx(-7.5).margin(1e-12));
  CHECK(scene.mesh.nodes.v[3] == Approx(-2.5).margin(1e-12));
  CHECK(scene.mesh.nodes.v[2] == Approx(-2.5).margin(1e-12));
  CHECK(scene.mesh.nodes.v[0] == 0.0);  // the square's bottom corners are not touched
  CHECK(predicted_gap(scene, 4, 3, 2) == Approx(0.0).margin(1e-12));
  // Momentum: 2 (-7.5) + 3 x 2 (-10) + 2 x 1 (-2.5) = -15 - 60 - 5 = -80, unchanged.
  check_vec(momentum(scene), before, 1e-12);
  check_vec(momentum(scene), {0.0, -80.0}, 1e-12);
}

TEST_CASE("summation method: a two-way pair gets half the closing reaction", "[kernels][reaction_solver]") {
  // ReactionMethod::summation documents that two-way pairs are weighted 1/2 (each contact is seen from
  // both sides in the paper's scheme). Here only node 4 touches: R = 1/2 x 500 = 250 (the hand value
  // of the previous case), node 4: du = 0.01 * 250 / 2 = 1.25 -> v = -8.75; ends: du = -1.25.
  Scene scene;
  add_body(scene, identity, 1.0, {0.0, 0.0});
  add_body(scene, diamond, 2.0, {0.0, -10.0});
  const Vec2 before = momentum(scene);
  ContactSolver solver = pair_solver(scene, ReactionMethod::summation);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  CHECK(stats.sweeps == 1);
  CHECK(stats.total_normal == Approx(250.0).margin(1e-9));
  CHECK(scene.mesh.nodes.v[4] == Approx(-8.75).margin(1e-12));
  CHECK(scene.mesh.nodes.v[3] == Approx(-1.25).margin(1e-12));
  // Half the gap is left: 0.1 - 0.02 (8.75 - 1.25) = 0.1 - 0.15 = -0.05.
  CHECK(predicted_gap(scene, 4, 3, 2) == Approx(-0.05).margin(1e-12));
  check_vec(momentum(scene), before, 1e-12);
}

TEST_CASE("two nodes on one free segment: coupled reactions converge to the hand solution", "[kernels][reaction_solver]") {
  // The square [0, 1]^2 (mass 1 per node) moving up at 4 m/s, and a block [0.3, 0.7] x [1.1, 1.5]
  // (mass 1 per node) moving down at 6 m/s: its bottom corners 4 (0.3, 1.1) and 5 (0.7, 1.1) reach the
  // square's top face at xi = 0.7 and 0.3, both with g* = 0.1 - 0.02 * 10 = -0.1. The two contacts share
  // the segment's ends (Delassus matrix [[1.58, 0.42], [0.42, 1.58]] with 1.58 = 1 + 0.3^2 + 0.7^2 and
  // 0.42 = 2 * 0.3 * 0.7), so Gauss-Seidel iterates. By symmetry R_4 = R_5 = R, each end takes
  // (0.3 + 0.7) R = R and the face stays level: 2e-4 (1.58 + 0.42) R = 0.1 -> R = 250.
  // Then the block's corners: -6 + 0.01 * 250 = -3.5; the face's ends: 4 - 2.5 = 1.5; predicted heights
  // 1.1 - 0.02 * 3.5 = 1.03 and 1 + 0.02 * 1.5 = 1.03.
  Scene scene;
  add_body(scene, identity, 1.0, {0.0, 4.0});
  add_body(scene, [](Vec2 p) { return Vec2{0.3 + 0.4 * p.x, 1.1 + 0.4 * p.y}; }, 1.0, {0.0, -6.0});
  const Vec2 before = momentum(scene);  // 4 x 4 - 4 x 6 = -8
  ContactSolver solver = pair_solver(scene);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  const double tolerance = ContactControls{}.gap_tolerance;  // relative to the segment length 1
  INFO("sweeps " << stats.sweeps);
  CHECK(stats.active == 2);
  CHECK(stats.sweeps > 1);
  CHECK(stats.sweeps < ContactControls{}.max_sweeps);
  for (Index c : {4, 5}) {
    // Closed to the tolerance (a pushing contact must neither penetrate nor stay open).
    CHECK(std::abs(predicted_gap(scene, c, 3, 2)) <= tolerance);
    // A gap error of 1e-5 is an error of 1e-5 / (2e-4 * 2) = 0.025 N in R: R within 0.1 of 250.
    CHECK(solver.reaction_force(ContactPoint::node(c)).y == Approx(250.0).margin(0.1));
    CHECK(solver.reaction_force(ContactPoint::node(c)).y >= 0.0);
    CHECK(scene.mesh.nodes.v[c] == Approx(-3.5).margin(1e-3));
  }
  CHECK(scene.mesh.nodes.v[2] == Approx(1.5).margin(1e-3));
  CHECK(scene.mesh.nodes.v[3] == Approx(1.5).margin(1e-3));
  CHECK(stats.deepest_gap >= -tolerance);
  // Whatever the sweeps did, each application is balanced: momentum to round-off.
  check_vec(momentum(scene), before, 1e-12);
  check_vec(momentum(scene), {0.0, -8.0}, 1e-12);
}

TEST_CASE("oblique approach with friction: no pull, gaps closed, momentum conserved", "[kernels][reaction_solver]") {
  // No hand solution here, only the invariants: the square turned by 0.1 rad about its centre, and a
  // 0.3 x 0.3 block (node mass 0.7) turned by 0.05 rad, centred at (0.45, 1.19), approaching obliquely;
  // Coulomb friction 0.3 in the pair; Gauss-Seidel and the paper's summation (which closes gaps only
  // approximately). Worked out with the rotations: the block's bottom corners 4 and 5 start 0.049 and
  // 0.034 above the top face (at xi 0.64 and 0.34) and would end 0.16 and 0.18 inside it without
  // reactions; every block corner starts more than 0.25 (the search depth) outside the square's side
  // faces' lines, so the top face is the only one they meet.
  const ReactionMethod method = GENERATE(ReactionMethod::gauss_seidel, ReactionMethod::summation);
  const auto turned = [](double angle, Vec2 centre, double size) {
    return [=](Vec2 p) {
      const Vec2 q = size * (p - Vec2{0.5, 0.5});
      return centre + Vec2{std::cos(angle) * q.x - std::sin(angle) * q.y, std::sin(angle) * q.x + std::cos(angle) * q.y};
    };
  };
  Scene scene;
  add_body(scene, turned(0.1, {0.5, 0.5}, 1.0), 1.0, {1.0, 2.0});
  add_body(scene, turned(0.05, {0.45, 1.19}, 0.3), 0.7, {-3.0, -9.0});
  const Vec2 before = momentum(scene);
  // The top face's predicted normal before the reactions: the geometry the summation method uses.
  const auto top_normal = [&] {
    return project(predicted_node(scene, 4), predicted_node(scene, 3), predicted_node(scene, 2), 0.0).normal;
  };
  const Vec2 normal_before = top_normal();
  ContactSolver solver = pair_solver(scene, method, 0.3);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  INFO("sweeps " << stats.sweeps << ", active " << stats.active);
  CHECK(stats.active == 2);
  CHECK(stats.total_normal > 0.0);
  // Each block corner's reaction R n + T t: R >= 0 and |T| <= 0.3 R, in the geometry the reaction was
  // computed in: the predicted face before the solve (summation), or after it (Gauss-Seidel, where the
  // converged normal differs from the last applied one by the solver's tolerance: ~1e-4 here, see the
  // `misplaced` measure; 1e-3 |f| allowed).
  const Vec2 n = method == ReactionMethod::summation ? normal_before : top_normal();
  const double slack = method == ReactionMethod::summation ? 1e-9 : 1e-3;
  for (Index c = 4; c < 8; ++c) {
    const Vec2 f = solver.reaction_force(ContactPoint::node(c));
    const double normal_part = dot(f, n);
    const double tangential_part = std::abs(cross(n, f));
    CHECK(normal_part >= -slack * norm(f));
    CHECK(tangential_part <= 0.3 * normal_part + slack * norm(f));
  }
  CHECK(norm(solver.reaction_force(ContactPoint::node(4))) > 0.0);
  CHECK(norm(solver.reaction_force(ContactPoint::node(5))) > 0.0);
  check_vec(momentum(scene), before, 1e-12);
  if (method == ReactionMethod::gauss_seidel) {
    // The sweeps stop at gaps within tolerance x the candidate's segment length (1 for the top face).
    const double tolerance = ContactControls{}.gap_tolerance * 1.0;
    CHECK(stats.deepest_gap >= -tolerance);
    for (Index c : {4, 5}) CHECK(std::abs(predicted_gap(scene, c, 3, 2)) <= tolerance);
    for (Index c : {6, 7}) CHECK(predicted_gap(scene, c, 3, 2) > 0.0);
  }
}

TEST_CASE("a pair moving apart gets no reaction", "[kernels][reaction_solver]") {
  // The diamond 0.1 above the square. Separating at 10 m/s relative: the predicted gap only grows.
  const Vec2 square_velocity = GENERATE(Vec2{0.0, -10.0}, Vec2{0.0, 0.0}, Vec2{3.0, -5.0});
  const Vec2 diamond_velocity = square_velocity + Vec2{0.0, 10.0};
  Scene scene;
  add_body(scene, identity, 1.0, square_velocity);
  add_body(scene, diamond, 2.0, diamond_velocity);
  ContactSolver solver = pair_solver(scene);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  CHECK(stats.active == 0);
  CHECK(stats.total_normal == 0.0);
  CHECK(solver.touched_points().empty());
  for (Index n = 0; n < 8; ++n) {
    const Vec2 expected = n < 4 ? square_velocity : diamond_velocity;
    CHECK(scene.mesh.nodes.u[n] == expected.x);
    CHECK(scene.mesh.nodes.v[n] == expected.y);
  }
}

TEST_CASE("particle against a free segment: hand reaction and momentum", "[kernels][reaction_solver]") {
  // The square [0, 1]^2 (free, mass 1 per node) and a particle of mass 2, radius 0.1 at (0.5, 1.2)
  // falling at 20 m/s: start gap 1.2 - 1 - 0.1 = 0.1, g* = 0.1 - 0.02 * 20 = -0.3, xi = 0.5;
  // w = 1/2 + 0.25 + 0.25 = 1, R = 0.3 / (2e-4 * 1) = 1500. Particle: du = 0.01 * 1500 / 2 = 7.5 ->
  // -12.5; ends: du = -0.01 * 0.5 * 1500 = -7.5. Predicted: 1.2 - 0.25 - 0.1 = 0.85 = 1 - 0.15.
  Scene scene;
  add_body(scene, identity, 1.0, {0.0, 0.0});
  scene.particles.add({0.5, 1.2}, {0.0, -20.0}, 2.0, 0.1, 0, 0.0);
  const Vec2 before = momentum(scene);  // (0, -40)
  ContactSetup setup;
  setup.particles = true;
  ContactSolver solver(setup, scene.mesh, scene.zone_ranges);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  CHECK(stats.active == 1);
  CHECK(stats.total_normal == Approx(1500.0).margin(1e-9));
  CHECK(scene.particles.v[0] == Approx(-12.5).margin(1e-12));
  CHECK(scene.mesh.nodes.v[2] == Approx(-7.5).margin(1e-12));
  CHECK(scene.mesh.nodes.v[3] == Approx(-7.5).margin(1e-12));
  const DiscContact after = disc_segment_contact(
      scene.particles.position(0) + dt_next * scene.particles.velocity(0), predicted_node(scene, 3),
      predicted_node(scene, 2), 0.1);
  CHECK(after.gap == Approx(0.0).margin(1e-12));
  check_vec(solver.reaction_force(ContactPoint::particle(0)), {0.0, 1500.0}, 1e-9);
  check_vec(momentum(scene), before, 1e-12);
  check_vec(momentum(scene), {0.0, -40.0}, 1e-12);
}

TEST_CASE("particle off the segment's middle and at a corner: invariants", "[kernels][reaction_solver]") {
  // Off the middle (xi = 0.75) the ends move unequally and the face turns, so the sweeps iterate; near
  // the square's corner (1, 1) the particle meets the end points of two segments (the top face's a and
  // the right side's b; predicted centre (1.04, 1.04), 0.057 from the corner: 0.043 inside). Either
  // way: no pull, the predicted gap closed to the tolerance, momentum conserved.
  const auto [centre, velocity] =
      GENERATE(std::pair{Vec2{0.25, 1.2}, Vec2{0.0, -20.0}}, std::pair{Vec2{1.12, 1.12}, Vec2{-4.0, -4.0}});
  const bool held = GENERATE(false, true);
  Scene scene;
  add_body(scene, identity, 1.0, {0.0, 0.0}, held);
  const double radius = 0.1;
  scene.particles.add(centre, velocity, 2.0, radius, 0, 0.0);
  const Vec2 before = momentum(scene);
  ContactSetup setup;
  setup.particles = true;
  ContactSolver solver(setup, scene.mesh, scene.zone_ranges);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  INFO("sweeps " << stats.sweeps << (held ? ", held square" : ", free square"));
  CHECK(stats.active >= 1);
  CHECK(stats.total_normal > 0.0);
  if (!held) check_vec(momentum(scene), before, 1e-12);
  // The predicted contact with the top face (feature: the face, or its end point a at the corner),
  // and with the right side 1 -> 3 (its end point b at the corner).
  const Vec2 p = scene.particles.position(0) + dt_next * scene.particles.velocity(0);
  const DiscContact top = disc_segment_contact(p, predicted_node(scene, 3), predicted_node(scene, 2), radius);
  const DiscContact side = disc_segment_contact(p, predicted_node(scene, 1), predicted_node(scene, 3), radius);
  // The push on the particle never points into the square: positive along the final contact normal
  // (from the face, or from the corner) and along the normal before the solve ((0, 1) on the face,
  // (1, 1)/sqrt(2) at the corner). It need not be parallel to the final normal: particle contacts add
  // each change along the current normal (contact.hpp, Candidate), and off the middle the face turns
  // by ~0.13 rad in this step (its ends move by 0.02 x 0.01 x 1333 x (0.25, 0.75)).
  const Vec2 push = solver.reaction_force(ContactPoint::particle(0));
  const Vec2 normal_before = centre.x < 1.0 ? Vec2{0.0, 1.0} : std::sqrt(0.5) * Vec2{1.0, 1.0};
  CHECK(dot(push, top.normal) > 0.0);
  CHECK(dot(push, normal_before) > 0.0);
  // Closed: the pushing contact to within the tolerance x its candidate length (max(segment length,
  // radius) = 1 here), the other not penetrated beyond it.
  const double tolerance = ContactControls{}.gap_tolerance * 1.0;
  CHECK(std::abs(top.gap) <= tolerance);
  CHECK(side.gap >= -tolerance);
  CHECK(stats.deepest_gap >= -tolerance);
}

TEST_CASE("particle against particle, head on: hand reaction and momentum", "[kernels][reaction_solver]") {
  // Masses 1 and 3, radii 0.1, centres (0, 0) and (0.3, 0), velocities +5 and -5: start gap 0.1,
  // predicted centres 0.1 and 0.2 apart 0.1: g* = 0.1 - 0.2 = -0.1, normal from the second to the first
  // (-1, 0), w = 1 + 1/3 = 4/3, R = 0.1 / (2e-4 * 4/3) = 375. First: du = -0.01 * 375 / 1 = -3.75 ->
  // 1.25; second: du = +0.01 * 375 / 3 = 1.25 -> -3.75. Predicted centres 0.025 and 0.225: 0.2 apart.
  Scene scene;  // no mesh, particles only
  scene.particles.add({0.0, 0.0}, {5.0, 0.0}, 1.0, 0.1, 0, 0.0);
  scene.particles.add({0.3, 0.0}, {-5.0, 0.0}, 3.0, 0.1, 0, 0.0);
  const Vec2 before = momentum(scene);  // 5 - 15 = -10
  ContactSetup setup;
  setup.particles = true;
  ContactSolver solver(setup, scene.mesh, scene.zone_ranges);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  CHECK(stats.active == 1);
  CHECK(stats.total_normal == Approx(375.0).margin(1e-9));
  CHECK(scene.particles.u[0] == Approx(1.25).margin(1e-12));
  CHECK(scene.particles.u[1] == Approx(-3.75).margin(1e-12));
  CHECK(scene.particles.v[0] == 0.0);
  const double distance = std::abs((scene.particles.x[1] + dt_next * scene.particles.u[1]) -
                                   (scene.particles.x[0] + dt_next * scene.particles.u[0]));
  CHECK(distance == Approx(0.2).margin(1e-12));
  check_vec(momentum(scene), before, 1e-12);
  check_vec(momentum(scene), {-10.0, 0.0}, 1e-12);
  // Moving apart instead: nothing.
  Scene apart;
  apart.particles.add({0.0, 0.0}, {-5.0, 0.0}, 1.0, 0.1, 0, 0.0);
  apart.particles.add({0.3, 0.0}, {5.0, 0.0}, 3.0, 0.1, 0, 0.0);
  ContactSolver apart_solver(setup, apart.mesh, apart.zone_ranges);
  const ContactStatistics apart_stats = apart_solver.solve(nodes_view(apart.mesh.nodes), particles_view(apart.particles), dt_mid, dt_next);
  CHECK(apart_stats.total_normal == 0.0);
  CHECK(apart.particles.u[0] == -5.0);
  CHECK(apart.particles.u[1] == 5.0);
}

TEST_CASE("rigid wall: nodes stopped on it, the impulse equals the momentum change", "[kernels][reaction_solver]") {
  // The square [0, 1] x [0.1, 1.1] (mass 1 per node) falling at 20 m/s on the wall y = 0: its bottom
  // nodes have g* = 0.1 - 0.02 * 20 = -0.3, w = 1, R = 0.3 / 2e-4 = 1500 each, du = 0.01 * 1500 = 15 ->
  // v = -5 (predicted height 0.1 - 0.1 = 0). The top nodes, 1.1 up, cannot reach it in 0.4: no candidate.
  Scene scene;
  add_body(scene, [](Vec2 p) { return Vec2{p.x, p.y + 0.1}; }, 1.0, {0.0, -20.0});
  const Vec2 before = momentum(scene);
  ContactSetup setup;
  setup.walls.push_back({{0.0, 0.0}, {0.0, 1.0}, 0.0, {}});
  ContactSolver solver(setup, scene.mesh, scene.zone_ranges);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  CHECK(stats.candidates == 2);
  CHECK(stats.active == 2);
  CHECK(stats.total_normal == Approx(3000.0).margin(1e-9));
  CHECK(scene.mesh.nodes.v[0] == Approx(-5.0).margin(1e-12));
  CHECK(scene.mesh.nodes.v[1] == Approx(-5.0).margin(1e-12));
  CHECK(scene.mesh.nodes.v[2] == -20.0);
  // The wall's impulse dt_mid x sum R n = 0.01 x 3000 = 30 is the momentum gained: 2 x 15.
  const Vec2 gained = momentum(scene) - before;
  check_vec(gained, {0.0, dt_mid * stats.total_normal}, 1e-9);
  check_vec(gained, {0.0, 30.0}, 1e-9);
}

TEST_CASE("rigid wall with Coulomb friction: slip limited to f R, or stick", "[kernels][reaction_solver]") {
  // A particle (mass 1, radius 0.1) at (0, 0.15) moving (10, -10) onto the wall y = 0, dt_mid =
  // dt_next = 0.01: g* = 0.05 - 0.1 = -0.05, R = 0.05 / (1e-4 * 1) = 500, v_y = -10 + 0.01 * 500 = -5.
  // The tangent t = (-n.y, n.x) = (-1, 0); the slip u.t = -10 needs T = 10 / (0.01 * 1) = 1000 to stop.
  //   f = 0.5: T = f R = 250 -> u_x = 10 - 0.01 * 250 = 7.5 (slides; tangential impulse f x normal).
  //   f = 2:   T = 1000 <= f R = 1000 -> u_x = 0 (sticks).
  const auto [friction, expected_u] = GENERATE(std::pair{0.5, 7.5}, std::pair{2.0, 0.0});
  Scene scene;
  scene.particles.add({0.0, 0.15}, {10.0, -10.0}, 1.0, 0.1, 0, 0.0);
  ContactSetup setup;
  setup.particles = true;
  setup.walls.push_back({{0.0, 0.0}, {0.0, 1.0}, friction, {}});
  ContactSolver solver(setup, scene.mesh, scene.zone_ranges);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), 0.01, 0.01);
  CHECK(stats.total_normal == Approx(500.0).margin(1e-9));
  CHECK(scene.particles.v[0] == Approx(-5.0).margin(1e-12));
  CHECK(scene.particles.u[0] == Approx(expected_u).margin(1e-12));
  // Coulomb on the impulses (mass 1): |du_x| <= f |du_y|, with du_y = 5.
  CHECK(std::abs(scene.particles.u[0] - 10.0) <= friction * std::abs(scene.particles.v[0] + 10.0) + 1e-12);
}

TEST_CASE("pre-existing overlap: removed by the overlap fraction, at most overlap_speed x dt", "[kernels][reaction_solver]") {
  // The square [0, 1] x [-0.01, 0.99] at rest on the wall y = 0: its bottom nodes start 0.01 inside.
  // The target gap is -0.01 + min(overlap_fraction x 0.01, overlap_speed x dt_next):
  //   defaults 0.1 and 1 m/s: removal min(1e-3, 0.02) = 1e-3, R = 1e-3 / (2e-4 * 1) = 5, v = 0.01 * 5 = 0.05;
  //   overlap_speed 0.01 m/s: removal min(1e-3, 2e-4) = 2e-4, R = 2e-4 / 2e-4 = 1, v = 0.01.
  const auto [overlap_speed, expected_r] = GENERATE(std::pair{1.0, 5.0}, std::pair{0.01, 1.0});
  Scene scene;
  add_body(scene, [](Vec2 p) { return Vec2{p.x, p.y - 0.01}; }, 1.0, {0.0, 0.0});
  ContactSetup setup;
  setup.walls.push_back({{0.0, 0.0}, {0.0, 1.0}, 0.0, {}});
  setup.controls.overlap_speed = overlap_speed;
  ContactSolver solver(setup, scene.mesh, scene.zone_ranges);
  const ContactStatistics stats = solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  CHECK(stats.total_normal == Approx(2.0 * expected_r).margin(1e-9));
  for (Index n : {0, 1}) {
    CHECK(scene.mesh.nodes.v[n] == Approx(dt_mid * expected_r).margin(1e-12));
    // The whole reaction belongs to a contact with a pre-existing overlap: the ledger's overlap line.
    check_vec(solver.overlap_reaction_force(ContactPoint::node(n)), {0.0, expected_r}, 1e-9);
  }
  // deepest_gap is measured from the start gap: the removal leaves it at or above 0.
  CHECK(stats.deepest_gap >= -1e-12);
}

TEST_CASE("node landing on a face near a convex corner gets no push from the side face",
          "[kernels][reaction_solver]") {
  // A small diamond (corners (0.9, 1.05), (0.95, 1.1), (0.85, 1.1), (0.9, 1.15), node mass 1) falls at
  // 4 m/s onto the top face of the held unit square, 0.1 from its corner (1, 1). Hand solution: only
  // the bottom corner (node 4) reaches the face, g* = 0.05 - 0.02 * 4 = -0.03, w = 1,
  // R = 0.03 / 2e-4 = 150, v = -4 + 0.01 * 150 = -2.5, and nothing acts along x: the node started
  // outside the square, with no overlap to remove. The right side (1, 0) -> (1, 1) must not act: the
  // node starts beside its end and behind its line (x = 0.9 < 1), past the convex corner, where the
  // side's line distance (-0.1) is no overlap (contact.cpp, add_node_segment_candidates).
  const ReactionMethod method = GENERATE(ReactionMethod::gauss_seidel, ReactionMethod::summation);
  Scene scene;
  add_body(scene, identity, 1.0, {0.0, 0.0}, true);
  add_body(scene, [](Vec2 p) { return Vec2{0.9 + 0.05 * (p.x - p.y), 1.05 + 0.05 * (p.x + p.y)}; }, 1.0, {0.0, -4.0});
  ContactSolver solver = pair_solver(scene, method);
  solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  CHECK(scene.mesh.nodes.u[4] == Approx(0.0).margin(1e-12));
  check_vec(solver.overlap_reaction_force(ContactPoint::node(4)), {0.0, 0.0}, 1e-9);
  if (method == ReactionMethod::gauss_seidel) {
    CHECK(scene.mesh.nodes.v[4] == Approx(-2.5).margin(1e-12));
    check_vec(solver.reaction_force(ContactPoint::node(4)), {0.0, 150.0}, 1e-9);
  }
}

TEST_CASE("node sliding along a face's line past a convex corner steps onto the face",
          "[kernels][reaction_solver]") {
  // The held body: the unit square mapped by (x, y) -> (2x, 2y - xy), corners (0, 0), (2, 0), A = (2, 1),
  // (0, 2). At A its right face (node 1 -> node 3) ends and its top face (node 3 -> node 2, tangent
  // t = (-2, 1)/sqrt 5, outward normal n = (1, 2)/sqrt 5) begins: a convex corner of 116.6 degrees.
  // The moving body, a 0.1 square, has its corner (node 4) on the top face's line 0.01 of the face's
  // length beyond A, 1e-12 behind the line (grazing it): outside the body, in front of the right face
  // by 0.02. It moves at 4 t - 0.5 n, along the line into the face's span: its predicted position is
  // 0.0258 of the way along the top face and 0.01 behind it, past the right face's end (along 1.017).
  // The top face is the one it touches. A rule that drops a face the node is behind while it is in
  // front of another face it projects onto (a far side) must keep a face whose line the node is on:
  // without that, neither face acts and the node passes 0.01 into the body in one step.
  const ReactionMethod method = GENERATE(ReactionMethod::gauss_seidel, ReactionMethod::summation);
  const double root5 = std::sqrt(5.0);
  const Vec2 t{-2.0 / root5, 1.0 / root5}, n{1.0 / root5, 2.0 / root5};
  const Vec2 corner = Vec2{2.0, 1.0} - 0.01 * root5 * t - 1e-12 * n;
  Scene scene;
  add_body(scene, [](Vec2 p) { return Vec2{2.0 * p.x, 2.0 * p.y - p.x * p.y}; }, 1.0, {0.0, 0.0}, true);
  add_body(scene, [corner](Vec2 p) { return corner + 0.1 * p; }, 1.0, 4.0 * t - 0.5 * n);
  const double before = predicted_gap(scene, 4, 3, 2);
  INFO("predicted gap of node 4 from the top face before the solve " << before);
  REQUIRE(before < -0.009);  // the unconstrained step would take it 0.01 into the body
  ContactSolver solver = pair_solver(scene, method);
  solver.solve(nodes_view(scene.mesh.nodes), particles_view(scene.particles), dt_mid, dt_next);
  // Gauss-Seidel closes the gap to the grazing start (the start gap -1e-12 is kept as a pre-existing
  // overlap): R = 0.01 / (dt_mid dt_next w) = 50. The summation method weights a two-way pair's
  // reactions 1/2 (the paper's, ContactSetup), so its one pass closes half: -0.005.
  if (method == ReactionMethod::gauss_seidel) {
    CHECK(predicted_gap(scene, 4, 3, 2) > -2e-12);
    CHECK(dot(solver.reaction_force(ContactPoint::node(4)), n) == Approx(50.0).epsilon(1e-9));
  } else {
    CHECK(predicted_gap(scene, 4, 3, 2) == Approx(0.5 * before).epsilon(1e-9));
  }
  // Only the top face pushes: along n, nothing across it.
  const Vec2 reaction = solver.reaction_force(ContactPoint::node(4));
  CHECK(std::abs(reaction.x * t.x + reaction.y * t.y) < 1e-9 * norm(reaction));
  CHECK(dot(reaction, n) > 0.0);
}
