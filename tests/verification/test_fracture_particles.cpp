// E8 of verification.md (fracture and free elements): free elements in a closed box, swept by a
// moving wall. Checks the particle contacts of docs/theory.md §2 step 3 (particle-particle,
// particle-segment, particle-wall) on a crowd of particles:
//   - no particle passes through another, a wall of the box or the moving wall by more than 1e-3 of
//     its radius (direct distance checks after every step, and deepest_contact_gap());
//   - their kinetic energy never grows beyond the work done on them: from the moment the last zone
//     has converted, K_particles(t) <= K_particles(t_c) + W(t_c -> t), W the work of the moving wall
//     (a kinematically driven body: all its nodes held, so the ledger's boundary work is exactly the
//     work its contact reactions do); particle-particle and particle-wall contacts only dissipate;
//   - the energy ledger closes (relative drift < 1e-12) and contact work is dissipative overall.
//
// Planar (x, y), per metre. The box: rigid walls x = 0, x = 20 mm, y = 0, y = 10 mm. The particles:
// a 6 x 6 mm block of Wilkins aluminium (rho0 2785, K 79.06 GPa, mu 27.6 GPa, Y0 0.3 GPa), 12 x 12
// zones, every zone damaged beforehand and given a low loosening limit (chi_* = 1e-4), moving with an
// expanding and rotating field u = a (x - xc) - 2 a (y - yc), v = a (y - yc) + 2 a (x - xc),
// a = 5000 1/s (up to 36 m/s at the corners): it loosens at once and turns into 144 particles of
// radius 0.25 mm, one boundary layer per step (all converted at t = 0.23 us), which then
// fly apart, hit the walls and each other. The moving wall: a 1 x 10 mm aluminium block spanning the
// box's height at x in [0.5, 1.5] mm, every node driven at 30 m/s along x (it travels 6 mm in the
// 200 us of the run, sweeping the particles ahead of it).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "krug/krug.hpp"
#include "verification_support.hpp"

using krug::verification::body_from;

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

namespace {

constexpr double box_width = 0.02, box_height = 0.01, wall_speed = 30.0;

SimulationSetup particles_in_a_box(double end_time) {
  SimulationSetup s;
  s.geometry = GeometryKind::planar;
  const generate::Patch block = generate::rectangle(s.mesh, generate::graded_axis(0.007, {{0.013, 12, 1.0}}),
                                                    generate::graded_axis(0.002, {{0.008, 12, 1.0}}), 0);
  const generate::Patch wall = generate::rectangle(s.mesh, generate::graded_axis(0.0005, {{0.0015, 2, 1.0}}),
                                                   generate::graded_axis(0.0, {{box_height, 20, 1.0}}), 1);
  const Material aluminium{"aluminium", 2785.0, LinearBulk{7.906e10, 2785.0}, PerfectlyPlastic{2.76e10, 3.0e8}};
  s.materials = {aluminium, aluminium};
  s.materials[1].name = "wall";
  s.bodies.push_back(body_from("block", 0, block));
  s.bodies.push_back(body_from("moving wall", 1, wall));
  const double a = 5000.0, xc = 0.01, yc = 0.005;
  for (Index n = block.node_begin; n < block.node_end; ++n) {
    const double x = s.mesh.nodes.x[n] - xc, y = s.mesh.nodes.y[n] - yc;
    s.mesh.nodes.u[n] = a * x - 2.0 * a * y;
    s.mesh.nodes.v[n] = a * y + 2.0 * a * x;
  }
  for (Index n = wall.node_begin; n < wall.node_end; ++n) {
    s.mesh.nodes.u[n] = wall_speed;
    s.constraints.push_back({n, true, true});
  }
  s.zone_state.resize(s.mesh.zones.size());
  for (Index z = block.zone_begin; z < block.zone_end; ++z) s.zone_state.fracture.damaged[z] = 1;
  fracture::FractureLimits limits;
  limits.elongation = 10.0;  // enables fracture; never reached
  limits.loosening = 1e-4;
  s.fracture = {limits, fracture::FractureLimits{}};
  auto rigid_wall = [](Vec2 point, Vec2 normal) {
    contact::RigidWall w;
    w.point = point;
    w.normal = normal;
    return w;
  };
  s.contact.walls = {rigid_wall({0.0, 0.0}, {1.0, 0.0}), rigid_wall({box_width, 0.0}, {-1.0, 0.0}),
                     rigid_wall({0.0, 0.0}, {0.0, 1.0}), rigid_wall({0.0, box_height}, {0.0, -1.0})};
  s.contact.pairs = {{0, 1, 0.0}, {0, 0, 0.0}};
  s.controls.end_time = end_time;
  return s;
}

// Overlaps of the current particles, as fractions of the radius (the smaller one for a pair); > 0 is
// a penetration.
struct Overlaps {
  double particle = 0.0, box = 0.0, moving_wall = 0.0;
};

Overlaps overlaps(const Simulation& sim) {
  Overlaps o;
  const Particles& p = sim.particles();
  // The moving wall is a rectangle moving rigidly (all nodes driven): its extent is its node box.
  const BodySummary wall = sim.summarise(sim.bodies()[1]);
  for (Index i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    o.box = std::max({o.box, (r - p.x[i]) / r, (r - (box_width - p.x[i])) / r, (r - p.y[i]) / r,
                      (r - (box_height - p.y[i])) / r});
    const double dx = std::max({wall.bbox_min.x - p.x[i], 0.0, p.x[i] - wall.bbox_max.x});
    const double dy = std::max({wall.bbox_min.y - p.y[i], 0.0, p.y[i] - wall.bbox_max.y});
    const bool inside = dx == 0.0 && dy == 0.0;
    const double distance = inside ? -std::min({p.x[i] - wall.bbox_min.x, wall.bbox_max.x - p.x[i], p.y[i] - wall.bbox_min.y,
                                                wall.bbox_max.y - p.y[i]})
                                   : std::hypot(dx, dy);
    o.moving_wall = std::max(o.moving_wall, (r - distance) / r);
    for (Index j = i + 1; j < p.size(); ++j) {
      const double d = std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]);
      o.particle = std::max(o.particle, (p.radius[i] + p.radius[j] - d) / std::min(p.radius[i], p.radius[j]));
    }
  }
  return o;
}

double particle_kinetic_energy(const Particles& p) {
  double k = 0.0;
  for (Index i = 0; i < p.size(); ++i) k += 0.5 * p.mass[i] * dot(p.velocity(i), p.velocity(i));
  return k;
}

}  // namespace

TEST_CASE("E8 particles in a closed box swept by a moving wall: no pass-through, no energy gain",
          "[fracture][E8][particles]") {
  verification::Run run(particles_in_a_box(2.0e-4));
  Simulation& sim = run.simulation;
  const Index block_zones = sim.bodies()[0].zone_end - sim.bodies()[0].zone_begin;

  Overlaps worst;
  double smallest_radius = std::numeric_limits<double>::infinity();
  double converted_at = -1.0, kinetic_at_conversion = 0.0, work_at_conversion = 0.0;
  double worst_excess = -std::numeric_limits<double>::infinity(), largest_kinetic = 0.0;
  double worst_drift = 0.0;
  int most_sweeps = 0;
  verification::advance(run, [&](const Simulation& s) {
    const Overlaps o = overlaps(s);
    worst.particle = std::max(worst.particle, o.particle);
    worst.box = std::max(worst.box, o.box);
    worst.moving_wall = std::max(worst.moving_wall, o.moving_wall);
    for (double r : s.particles().radius) smallest_radius = std::min(smallest_radius, r);
    most_sweeps = std::max(most_sweeps, s.last_contact().sweeps);
    worst_drift = std::max(worst_drift, s.ledger().relative_energy_drift());
    const double kinetic = particle_kinetic_energy(s.particles());
    if (converted_at < 0.0 && s.summarise(s.bodies()[0]).zones == 0) {
      converted_at = s.time();
      kinetic_at_conversion = kinetic;
      work_at_conversion = s.ledger().energy.boundary;
    }
    if (converted_at >= 0.0) {
      largest_kinetic = std::max(largest_kinetic, kinetic);
      worst_excess = std::max(worst_excess, kinetic - kinetic_at_conversion - (s.ledger().energy.boundary - work_at_conversion));
    }
  });
  REQUIRE(run.completed());
  const Ledger& ledger = sim.ledger();
  const double work = ledger.energy.boundary - work_at_conversion;
  INFO("cycles " << sim.cycle() << ", all " << block_zones << " zones converted at " << converted_at << " s, particles "
                 << sim.particles().size() << ", smallest radius " << smallest_radius << " m; worst overlaps / radius: "
                 << "particle " << worst.particle << ", box " << worst.box << ", moving wall " << worst.moving_wall
                 << "; deepest contact gap " << sim.deepest_contact_gap() << " m; most sweeps " << most_sweeps
                 << "; K_p at conversion " << kinetic_at_conversion << " J/m, largest " << largest_kinetic
                 << ", work of the moving wall " << work << " J/m, worst excess " << worst_excess
                 << " J/m; contact " << ledger.energy.contact << " J/m, overlap " << ledger.energy.overlap
                 << "; drift " << worst_drift);
  const long zones = sim.mesh().zones.size();
  report("E8 particles in a box", "deepest particle-particle overlap / radius", "< 1e-3", worst.particle, "-", zones, run.seconds);
  report("E8 particles in a box", "deepest overlap with the moving wall / radius", "< 1e-3", worst.moving_wall, "-", zones, run.seconds);
  report("E8 particles in a box", "deepest overlap with the box / radius", "< 1e-3", worst.box, "-", zones, run.seconds);
  report("E8 particles in a box", "max (K_p - K_p(t_c) - W_wall) (J/m)", "<= 0", worst_excess,
         format_number("W_wall %.3g J/m", work), zones, run.seconds);
  report("E8 particles in a box", "energy drift, max", "< 1e-12", worst_drift, "round-off", zones, run.seconds);

  // The case: the whole block became particles, which the wall then drove (it did positive work).
  // Contacts that started a step apart only dissipate (docs/theory.md §3): the contact work less the
  // overlap line (the contacts pushing a pre-existing overlap open), to round-off.
  CHECK(ledger.energy.contact - ledger.energy.overlap <= 1e-12 * ledger.energy_scale());
  CHECK(sim.fracture_counts(0).converted == block_zones);
  CHECK(sim.particles().size() == block_zones);
  CHECK(converted_at > 0.0);
  CHECK(work > 0.0);
  // No pass-through beyond 1e-3 of a radius (the brief). Measured: particle-particle 1.0e-4,
  // moving wall 1.1e-4, box walls 1e-14; deepest_contact_gap -1.5e-8 m = 6e-5 of a radius. (A search
  // that missed pairs the solve brought together left 6.4e-4 to 1.2e-3 between particles,
  // docs/verification.md, Contact, C2. Before
  // the projected Gauss-Seidel sweeps were made to iterate, src/contact/contact.cpp, every solve stopped
  // after one sweep, and this case left overlaps of 1.6e-2 of a radius between particles and 9.3e-3
  // against the moving wall.)
  CHECK(worst.particle < 1e-3);
  CHECK(worst.box < 1e-3);
  CHECK(worst.moving_wall < 1e-3);
  CHECK(sim.deepest_contact_gap() > -1e-3 * smallest_radius);
  // Kinetic energy never above what the wall put in (measured: never above; K_p at most its 37.3 J/m
  // at conversion, while the wall did 68.2 J/m of work). Round-off allowance 1e-12 of the scale.
  CHECK(worst_excess <= 1e-12 * (kinetic_at_conversion + std::abs(work)));
  // Dissipative contact overall (measured -73.0 J/m, of which 6e-5 J/m booked overlap removal), and
  // the ledger closes (measured drift 4.9e-13: 5160 cycles of contact sweeps over 144 particles).
  CHECK(ledger.energy.contact < 0.0);
  CHECK(worst_drift < 1e-12);
}
