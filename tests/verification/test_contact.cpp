// Contact by reaction forces (docs/theory.md §2 step 3; docs/verification.md, "Contact"): problems
// with known answers for the node-on-segment and wall contacts, run through the library API.
//
//   1. Patch test (Taylor & Papadopoulos 1991): two elastic blocks (planar) and two elastic cylinders
//      (RZ) stacked, with matching and with non-matching meshes across the interface, squeezed by a
//      slowly ramped velocity. Once the load is held, the exact state is uniform uniaxial stress; the
//      contact must pass it across the interface within 1 %, with no gap, no velocity jump and no
//      hourglass there. A stack at rest must stay at rest, unloaded and pre-stressed between walls.
//   2. Friction: a block striking a rigid wall obliquely loses tangential momentum f x (normal
//      impulse) while it slides, and sticks (tangential velocity 0 at the contact) when f is large.
//   3. The lead bullet into a 3 mm plate without fracture (examples/contact/striker_dishing.json at a
//      coarse resolution): no interpenetration at any step, momentum against the rim impulse, energy;
//      with Gauss-Seidel and with the paper's summation.
//   4. Three plates in contact struck by a flyer (planar, exact acoustic answer: the last plate takes
//      the whole pulse and separates), and the paper's layered target struck by the bullet (RZ).
//
// The tests marked [!mayfail] are known failures of the contact solver, with the measured values and
// their causes (C1-C5 of docs/verification.md) beside them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "krug/mesh/quality.hpp"
#include "krug/krug.hpp"
#include "verification_support.hpp"

using krug::verification::body_from;

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

namespace {

// Wilkins aluminium, Y -> infinity (verification.md E1): rho0 2785 kg/m^3, K 79.06 GPa, mu 27.6 GPa.
constexpr double rho0 = 2785.0, bulk = 7.906e10, shear = 2.76e10;
Material elastic_aluminium() { return Material{"aluminium", rho0, LinearBulk{bulk, rho0}, Elastic{shear}}; }
const double longitudinal_speed = std::sqrt((bulk + 4.0 / 3.0 * shear) / rho0);  // c_L = 6449.9 m/s
// Poisson's ratio and Young's modulus from K and mu.
const double poisson = (3.0 * bulk - 2.0 * shear) / (2.0 * (3.0 * bulk + shear));  // 0.3437
const double young = 9.0 * bulk * shear / (3.0 * bulk + shear);                     // 74.17 GPa

// ---- geometric measures, independent of the contact solver -------------------------------------

// Crossing-number test of a point against an active zone (any quad, convex or not; a repeated corner
// is an edge of length 0 and never crosses).
bool inside_zone(const Mesh& mesh, Index z, Vec2 p) {
  const quad::Corners c = mesh.corner_positions(z);
  bool inside = false;
  for (int k = 0, j = 3; k < 4; j = k++) {
    if ((c[k].y > p.y) != (c[j].y > p.y) && p.x < (c[j].x - c[k].x) * (p.y - c[k].y) / (c[j].y - c[k].y) + c[k].x) {
      inside = !inside;
    }
  }
  return inside;
}

double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double length_squared = dot(ab, ab);
  const double t = length_squared > 0.0 ? std::clamp(dot(p - a, ab) / length_squared, 0.0, 1.0) : 0.0;
  return norm(p - (a + t * ab));
}

// The deepest penetration of a boundary node of `a` into `b`: a node lying inside an active zone of b,
// by its distance to b's nearest boundary segment. In RZ, segments on the axis are not surfaces (a node
// of a on the axis lies on b's axis edge without entering b), so they are left out of the distance.
double deepest_penetration(const Simulation& sim, const Body& a, const Body& b) {
  const Mesh& mesh = sim.mesh();
  const bool axisymmetric = sim.geometry() == GeometryKind::axisymmetric;
  const std::vector<BoundarySegment> own = boundary_segments(mesh, a.zone_begin, a.zone_end);
  std::vector<BoundarySegment> surface;
  for (const BoundarySegment& s : boundary_segments(mesh, b.zone_begin, b.zone_end)) {
    if (axisymmetric && mesh.nodes.y[s.a] == 0.0 && mesh.nodes.y[s.b] == 0.0) continue;
    surface.push_back(s);
  }
  Vec2 low{1e300, 1e300}, high{-1e300, -1e300};
  for (Index p = b.node_begin; p < b.node_end; ++p) {
    low = {std::min(low.x, mesh.nodes.x[p]), std::min(low.y, mesh.nodes.y[p])};
    high = {std::max(high.x, mesh.nodes.x[p]), std::max(high.y, mesh.nodes.y[p])};
  }
  double deepest = 0.0;
  for (const BoundarySegment& s : own) {
    const Vec2 p = mesh.nodes.position(s.a);
    if (p.x < low.x || p.x > high.x || p.y < low.y || p.y > high.y) continue;
    bool inside = false;
    for (Index z = b.zone_begin; z < b.zone_end && !inside; ++z) inside = mesh.zones.active[z] && inside_zone(mesh, z, p);
    if (!inside) continue;
    double depth = std::numeric_limits<double>::infinity();
    for (const BoundarySegment& t : surface) {
      depth = std::min(depth, distance_to_segment(p, mesh.nodes.position(t.a), mesh.nodes.position(t.b)));
    }
    deepest = std::max(deepest, depth);
  }
  return deepest;
}

// Smallest initial altitude of the zones of the given bodies: "a zone size" for penetration limits.
double smallest_zone(const Simulation& sim, const std::vector<Index>& bodies) {
  double smallest = std::numeric_limits<double>::infinity();
  for (Index b : bodies) {
    const Body& body = sim.bodies()[static_cast<std::size_t>(b)];
    for (Index z = body.zone_begin; z < body.zone_end; ++z) smallest = std::min(smallest, sim.mesh().zones.initial_altitude[z]);
  }
  return smallest;
}

// Position of the line through the nodes of a straight side at a transverse coordinate (the nodes
// sorted by their second coordinate; linear interpolation), and likewise its first velocity component.
struct SideLine {
  std::vector<Index> nodes;  // sorted by the second coordinate
  double at(const Mesh& mesh, double y, const std::vector<double>& field) const {
    for (std::size_t k = 1; k < nodes.size(); ++k) {
      const Index a = nodes[k - 1], b = nodes[k];
      if (y <= mesh.nodes.y[b] || k + 1 == nodes.size()) {
        const double w = std::clamp((y - mesh.nodes.y[a]) / (mesh.nodes.y[b] - mesh.nodes.y[a]), 0.0, 1.0);
        return (1.0 - w) * field[a] + w * field[b];
      }
    }
    return field[nodes.front()];
  }
};

SideLine side_line(const Mesh& mesh, std::vector<Index> nodes) {
  std::sort(nodes.begin(), nodes.end(), [&](Index a, Index b) { return mesh.nodes.y[a] < mesh.nodes.y[b]; });
  return {nodes};
}

// ---- 1. patch test ---------------------------------------------------------------------------------

// Two elastic blocks (planar; plane strain) or cylinders (RZ), each L long along the first axis and H
// wide (planar) or of radius H (RZ), stacked along the first axis: the lower on [0, L], the upper on
// [L, 2L]; 8 zones along, 8 across the lower block and `upper_across` across the upper one (8: the nodes
// meet at the interface; 5: they do not, the real contact patch test, where a node-on-segment contact
// must pass a uniform stress between non-matching meshes). The lower block's far face (first = 0) is
// held axially, the upper block's far face is driven axially, the side second = 0 is a symmetry plane
// (planar) or the axis (RZ), the outer side is free. Uniform uniaxial stress is then the exact state:
// sigma_11 = -E_eff eps, sigma_22 = 0, with E_eff = E / (1 - nu^2) in plane strain and E in RZ
// (sigma_rr = sigma_tt = 0). Contact: lower/upper, both ways, frictionless, default controls.
struct Stack {
  SimulationSetup setup;
  std::vector<Index> driven;           // nodes of the upper block's far face
  SideLine lower_face, upper_face;     // the two faces of the interface
  std::vector<Index> interface_zones[2];
};

constexpr double stack_length = 0.01, stack_width = 0.01;
constexpr int lower_across = 8, along = 8;

Stack make_stack(GeometryKind geometry, int upper_across) {
  Stack s;
  s.setup.geometry = geometry;
  const auto lower = generate::rectangle(s.setup.mesh, generate::graded_axis(0.0, {{stack_length, along, 1.0}}),
                                         generate::graded_axis(0.0, {{stack_width, lower_across, 1.0}}), 0);
  const auto upper = generate::rectangle(s.setup.mesh, generate::graded_axis(stack_length, {{2.0 * stack_length, along, 1.0}}),
                                         generate::graded_axis(0.0, {{stack_width, upper_across, 1.0}}), 1);
  s.setup.materials.push_back(elastic_aluminium());
  s.setup.bodies.push_back(body_from("lower", 0, lower));
  s.setup.bodies.push_back(body_from("upper", 0, upper));
  for (Index n : lower.sides.at("i_min")) s.setup.constraints.push_back({n, true, false});
  for (Index n : upper.sides.at("i_max")) s.setup.constraints.push_back({n, true, false});
  s.driven = upper.sides.at("i_max");
  if (geometry == GeometryKind::planar) {  // RZ: the axis holds u_r by itself
    for (Index n : lower.sides.at("j_min")) s.setup.constraints.push_back({n, false, true});
    for (Index n : upper.sides.at("j_min")) s.setup.constraints.push_back({n, false, true});
  }
  s.lower_face = side_line(s.setup.mesh, lower.sides.at("i_max"));
  s.upper_face = side_line(s.setup.mesh, upper.sides.at("i_min"));
  for (int j = 0; j < lower_across; ++j) s.interface_zones[0].push_back(lower.zone_begin + j * along + (along - 1));
  for (int j = 0; j < upper_across; ++j) s.interface_zones[1].push_back(upper.zone_begin + j * along);
  s.setup.contact.pairs = {{0, 1, 0.0}};
  return s;
}

std::string stack_name(GeometryKind g, int upper_across) {
  return std::string(g == GeometryKind::planar ? "planar blocks" : "RZ cylinders") + ", " + std::to_string(lower_across) +
         " against " + std::to_string(upper_across) + " zones";
}

// The squeeze: the driven face moves at v(t) = -v0 sin^2(pi t / T) for t < T, then is held. The
// stack's slowest mode (a fixed-fixed bar of length 2L, bar speed sqrt(E_eff/rho0) = 5.2-5.5 km/s) has
// a period P = 4 L / c_bar of about 7.5 us; T = 10 P makes the ramp quasi-static: the ringing a smooth
// ramp leaves behind is of order (P/T)^3 / pi ~ 3e-4 of the load, inside the 1 % judged. The hold
// lasts 2 P. The displacement v0 T / 2 = 1e-5 m is a strain of 5e-4 over the 20 mm stack: small, so
// the finite-strain terms (linear EOS in rho, logarithmic strain) are ~2.5e-4 relative.
struct Squeeze {
  double exact_stress = 0.0;     // Pa, for the measured end displacement
  double mean[2] = {0.0, 0.0};   // sigma_11 of the zones on each side of the interface (Pa)
  double worst_zone = 0.0;       // largest |sigma_11 / exact - 1| of those zones
  double interface_stress = 0.0; // the contact's force over the interface area (Pa)
  double worst_gap = 0.0;        // largest |gap| across the interface, any step (m)
  double worst_jump = 0.0;       // largest normal velocity jump across it, any step (m/s)
  double worst_field = 0.0;      // largest node displacement off the exact linear field / end displacement
  double v0 = 0.0, zone = 0.0;
  long zones = 0;
  double dissipation_excess = 0.0;  // (W_contact - overlap line) / energy scale at the end, <= 0
};

Squeeze squeeze(GeometryKind geometry, int upper_across, double gap_tolerance) {
  const bool planar = geometry == GeometryKind::planar;
  Stack stack = make_stack(geometry, upper_across);
  const double effective_modulus = planar ? young / (1.0 - poisson * poisson) : young;
  const double period = 4.0 * stack_length / std::sqrt(effective_modulus / rho0);
  const double ramp = 10.0 * period, displacement = 1e-5;
  Squeeze q;
  q.v0 = 2.0 * displacement / ramp;
  q.zone = stack_width / lower_across;
  stack.setup.controls.end_time = ramp + 2.0 * period;
  if (gap_tolerance > 0.0) stack.setup.contact.controls.gap_tolerance = gap_tolerance;
  Simulation sim(stack.setup);
  const Mesh& mesh = sim.mesh();
  const ZoneState& zone_state = sim.zone_state();
  q.zones = mesh.zones.size();
  while (!sim.finished()) {
    const double t_mid = sim.time() + 0.5 * sim.next_time_step();
    const double s = t_mid < ramp ? std::sin(std::numbers::pi * t_mid / ramp) : 0.0;
    for (Index n : stack.driven) sim.mesh().nodes.u[n] = -q.v0 * s * s;  // a held DOF keeps the velocity set
    sim.step();
    // Gap and normal velocity jump across the interface, both ways: each face's nodes against the other
    // face's line, interpolated at the node's transverse position.
    for (int side = 0; side < 2; ++side) {
      const SideLine& own = side == 0 ? stack.lower_face : stack.upper_face;
      const SideLine& other = side == 0 ? stack.upper_face : stack.lower_face;
      for (Index n : own.nodes) {
        const double y = mesh.nodes.y[n];
        if (y > mesh.nodes.y[other.nodes.back()]) continue;  // beyond the other face's end
        q.worst_gap = std::max(q.worst_gap, std::abs(other.at(mesh, y, mesh.nodes.x) - mesh.nodes.x[n]));
        q.worst_jump = std::max(q.worst_jump, std::abs(other.at(mesh, y, mesh.nodes.u) - mesh.nodes.u[n]));
      }
    }
  }
  double end_displacement = 0.0;
  for (Index n : stack.driven) end_displacement += (mesh.nodes.x0[n] - mesh.nodes.x[n]) / static_cast<double>(stack.driven.size());
  const double strain = end_displacement / (2.0 * stack_length);
  q.exact_stress = -effective_modulus * strain;
  for (int side = 0; side < 2; ++side) {
    for (Index z : stack.interface_zones[side]) {
      const double stress = zone_state.strength.deviator_xx[z] - zone_state.hydro.pressure[z];
      q.mean[side] += stress / static_cast<double>(stack.interface_zones[side].size());
      q.worst_zone = std::max(q.worst_zone, std::abs(stress / q.exact_stress - 1.0));
    }
  }
  // The force the contact passes is the sum of the normal reactions (every reaction pushes the lower
  // block back and the upper one on), per unit thickness or per radian.
  const double width = mesh.nodes.y[stack.lower_face.nodes.back()];
  q.interface_stress = -sim.last_contact().total_normal / (planar ? width : 0.5 * width * width);
  // Displacement field: exactly linear, u_1 = -eps x_1, u_2 = lateral eps x_2 (eps_22 = -lateral eps_11).
  const double lateral = planar ? poisson / (1.0 - poisson) : poisson;
  for (Index p = 0; p < mesh.nodes.size(); ++p) {
    const double u1 = mesh.nodes.x[p] - mesh.nodes.x0[p], u2 = mesh.nodes.y[p] - mesh.nodes.y0[p];
    q.worst_field = std::max({q.worst_field, std::abs(u1 + strain * mesh.nodes.x0[p]) / end_displacement,
                              std::abs(u2 - lateral * strain * mesh.nodes.y0[p]) / end_displacement});
  }
  q.dissipation_excess = (sim.ledger().energy.contact - sim.ledger().energy.overlap) / sim.ledger().energy_scale();
  return q;
}

// gap_tolerance 0: the solver's default.
void check_squeeze(GeometryKind geometry, int upper_across, double gap_tolerance = 0.0) {
  const Squeeze q = squeeze(geometry, upper_across, gap_tolerance);
  const std::string name = "Contact patch test, " + stack_name(geometry, upper_across);
  const double error[2] = {std::abs(q.mean[0] / q.exact_stress - 1.0), std::abs(q.mean[1] / q.exact_stress - 1.0)};
  const double force_error = std::abs(q.interface_stress / q.exact_stress - 1.0);
  // A velocity jump dv across the interface is a stress rho0 c_L dv riding on the wave it launches.
  const double jump_stress = rho0 * longitudinal_speed * q.worst_jump / std::abs(q.exact_stress);
  INFO(name << ": exact stress " << q.exact_stress << " Pa; interface zones " << q.mean[0] << " / " << q.mean[1]
            << " Pa, worst zone " << q.worst_zone << "; contact force / area " << q.interface_stress << " Pa; worst gap "
            << q.worst_gap << " m; worst jump " << q.worst_jump << " m/s (v0 " << q.v0 << ", as stress " << jump_stress
            << "); displacement field " << q.worst_field << "; (W_contact - overlap) / scale " << q.dissipation_excess);
  report(name, "interface zones sigma_11 (mean, lower / upper)", format_number("%.4g Pa", q.exact_stress), q.mean[0],
         format_number("%.1e", error[0]) + " / " + format_number("%.1e", error[1]), q.zones, 0.0);
  report(name, "worst interface zone; contact force / area", "exact", q.worst_zone, format_number("%.1e", force_error),
         q.zones, 0.0);
  report(name, "worst gap / zone; rho0 c_L x worst velocity jump / stress", "0", q.worst_gap / q.zone,
         format_number("%.1e", jump_stress), q.zones, 0.0);
  report(name, "node displacement off the exact linear field / end displacement", "0", q.worst_field, "-", q.zones, 0.0);
  report(name, "(W_contact - overlap line) / energy scale", "<= 0", q.dissipation_excess, "-", q.zones, 0.0);
  // Uniform stress within 1 % (the acceptance bar): both sides' interface zones, each of them, and the force the
  // contact carries. The exact value is for the measured end displacement.
  CHECK(error[0] < 0.01);
  CHECK(error[1] < 0.01);
  CHECK(q.worst_zone < 0.01);
  CHECK(force_error < 0.01);
  // No gap: the faces stay together within 1e-3 of a zone at every step (the penetration limit of the
  // issue, used for opening too).
  CHECK(q.worst_gap < 1e-3 * q.zone);
  // No velocity jump: the stress a jump would carry, rho0 c_L dv, below 1 % of the load at every step.
  CHECK(jump_stress < 0.01);
  // No hourglass and no kink at the interface: every node within 1 % of the end displacement of the
  // exact linear field.
  CHECK(q.worst_field < 0.01);
  // W_contact - overlap is reported, not asserted: in this slow squeeze the contact is closed for
  // hundreds of steps while the blocks' elastic forces act on the same nodes, and the reaction's
  // time-centred work R . (u^{n-1/2} + u^{n+1/2}) / 2 dt, which the ledger needs to close exactly,
  // carries a part of theirs that vanishes with dt but is not round-off: +1.2e-7 of the energy
  // scale with the matching planar meshes at cfl 0.5, 1.0e-8, 2.6e-9, 4.1e-10 at 0.25, 0.125,
  // 0.0625; +5.0e-5, 9.8e-6, 5.2e-6, 6.0e-7 with the non-matching ones (docs/verification.md, C10).
}

}  // namespace

TEST_CASE("Contact patch test, matching meshes: a slowly squeezed stack passes uniform stress across the interface",
          "[contact][patch]") {
  // The nodes of the two faces coincide: each node meets the other face at a segment's end. Measured:
  // stress within 3.5e-4 (the finite-strain terms), gaps 5e-10 of a zone, displacement field 2.6e-4.
  check_squeeze(GENERATE(GeometryKind::planar, GeometryKind::axisymmetric), 8);
}

TEST_CASE("Contact patch test, non-matching planar meshes, converged solve: uniform stress",
          "[contact][patch]") {
  // Each node of either face meets a segment of the other face at an interior point (two-way pairs).
  // The patch test judges the discretisation, so the Gauss-Seidel solve is converged (gap tolerance
  // 1e-12 instead of the default 1e-5): the constraints of the two passes are coupled and the default
  // tolerance leaves a worst zone 3.4 % off (docs/verification.md, Contact, C1). Measured converged:
  // within 4e-4.
  check_squeeze(GeometryKind::planar, 5, 1e-12);
}

TEST_CASE("Contact patch test, non-matching RZ meshes, converged solve: uniform stress",
          "[contact][patch]") {
  // Once a known failure (docs/verification.md, Contact, C3): converged, the worst interface zone was
  // 2.5 % off, then 1.6 % after the RZ deviatoric force took the r-weighted operator B_p, with a
  // radial gradient of opposite sign on the two sides (the grid's RZ nodal forces of a uniform stress
  // then had different moments sum(f r) on the two meshes, which node-on-segment contact carries
  // unchanged). Measured now: 3.3e-4, as the planar stack (3.6e-4).
  check_squeeze(GeometryKind::axisymmetric, 5, 1e-12);
}

TEST_CASE("Contact patch test: an unloaded stack at rest stays at rest and the contact never acts", "[contact][patch]") {
  // Touching faces (gap exactly 0), no stress, 1000 steps, both meshes and geometries: nothing should
  // happen beyond round-off. The zone update recomputes areas with round-off (relative 1e-16, a pressure
  // of K x 1e-16 ~ 1e-5 Pa), which moves nodes at 1e-12 m/s (planar, measured 9.8e-13; the contact
  // then never acts: its reaction is exactly 0) to 1e-10 m/s (RZ, 9.5e-11, where the contact answers
  // with reactions of the same round-off size). Judged: nodes below 1e-9 m/s, and the contact's
  // reaction at every step below 1 Pa over the interface (the loads of interest here are 1e7 Pa).
  const GeometryKind geometry = GENERATE(GeometryKind::planar, GeometryKind::axisymmetric);
  const int upper_across = GENERATE(8, 5);
  Stack stack = make_stack(geometry, upper_across);
  stack.setup.controls.end_time = 1.0;
  stack.setup.controls.max_cycles = 1000;
  Simulation sim(stack.setup);
  const double area = geometry == GeometryKind::planar ? stack_width : 0.5 * stack_width * stack_width;
  double fastest = 0.0, largest_stress = 0.0;
  while (!sim.finished()) {
    sim.step();
    for (Index p = 0; p < sim.mesh().nodes.size(); ++p) fastest = std::max(fastest, norm(sim.mesh().nodes.velocity(p)));
    largest_stress = std::max(largest_stress, sim.last_contact().total_normal / area);
  }
  INFO(stack_name(geometry, upper_across) << ": fastest node " << fastest << " m/s, largest contact stress "
                                          << largest_stress << " Pa");
  report("Contact stack at rest, unloaded, " + stack_name(geometry, upper_across), "fastest node (m/s); largest contact stress (Pa)",
         "< 1e-9; < 1", fastest, format_number("%.1e", largest_stress), sim.mesh().zones.size(), 0.0);
  CHECK(sim.cycle() == 1000);
  CHECK(fastest < 1e-9);
  CHECK(largest_stress < 1.0);
}

namespace {

// Both blocks at rho = rho0 (1 + p0/K): pressure p0 = 50 MPa with the linear EOS, no deviator. All four
// sides held normally (the outer side too), so the hydrostatic state is an exact equilibrium in which
// the contact alone holds the blocks apart (without it each face would spring into the other at
// p0 / (rho0 c_L) = 2.8 m/s). Judged: velocities at round-off (below 1e-9 of that speed), no drift
// (nodes within 1e-9 of a zone of where they started), the contact carrying p0 x area at every step
// (within 1e-9), over 20 transits of the stack (62 us, 640 steps). The solve is converged (gap
// tolerance 1e-12): the test judges the discretisation, not the solver's tolerance (with the default
// 1e-5 the matching stacks keep 5.3e-4 of the release speed along the interface, docs/verification.md,
// Contact, C2).
void check_prestressed_stack(GeometryKind geometry, int upper_across) {
  Stack stack = make_stack(geometry, upper_across);
  const double p0 = 5.0e7;
  for (Index z = 0; z < stack.setup.mesh.zones.size(); ++z) stack.setup.mesh.zones.density[z] = rho0 * (1.0 + p0 / bulk);
  for (Index p = 0; p < stack.setup.mesh.nodes.size(); ++p) {
    if (std::abs(stack.setup.mesh.nodes.y[p] - stack_width) < 1e-12) stack.setup.constraints.push_back({p, false, true});
  }
  stack.setup.controls.end_time = 20.0 * 2.0 * stack_length / longitudinal_speed;
  stack.setup.contact.controls.gap_tolerance = 1e-12;
  Simulation sim(stack.setup);
  double fastest = 0.0, drift = 0.0, worst_force = 0.0;
  int most_sweeps = 0;
  const double area = geometry == GeometryKind::planar ? stack_width : 0.5 * stack_width * stack_width;
  while (!sim.finished()) {
    sim.step();
    const Mesh& mesh = sim.mesh();
    for (Index p = 0; p < mesh.nodes.size(); ++p) {
      fastest = std::max(fastest, norm(mesh.nodes.velocity(p)));
      drift = std::max(drift, norm(mesh.nodes.position(p) - Vec2{mesh.nodes.x0[p], mesh.nodes.y0[p]}));
    }
    worst_force = std::max(worst_force, std::abs(sim.last_contact().total_normal / (p0 * area) - 1.0));
    most_sweeps = std::max(most_sweeps, sim.last_contact().sweeps);
  }
  const double release_speed = p0 / (rho0 * longitudinal_speed);
  const double zone = stack_width / lower_across;
  const std::string name = "Contact stack at rest, pre-stressed, " + stack_name(geometry, upper_across);
  INFO(name << ": fastest node " << fastest << " m/s (release speed " << release_speed << "); drift " << drift
            << " m; contact force off p0 x area by " << worst_force << "; most sweeps " << most_sweeps << "; cycles "
            << sim.cycle());
  report(name, "fastest node / (p0 / rho0 c_L); largest drift / zone", "< 1e-9", fastest / release_speed,
         format_number("%.1e", drift / zone), sim.mesh().zones.size(), 0.0);
  report(name, "contact force / (p0 x area) - 1, worst step", "< 1e-9", worst_force, "-", sim.mesh().zones.size(), 0.0);
  CHECK(fastest < 1e-9 * release_speed);
  CHECK(drift < 1e-9 * zone);
  CHECK(worst_force < 1e-9);
}

}  // namespace

TEST_CASE("Contact patch test: a pre-stressed stack stays at rest, matching meshes", "[contact][patch]") {
  // Each reaction acts along the normal and at the xi of its last update, and a pushing contact whose
  // reaction the later updates have turned off its normal is not converged (C2 fixed). Measured:
  // fastest node 1.4e-11 (planar) / 2.9e-11 (RZ) of the release speed, drift 1e-17 m, the contact
  // force within 8e-12 of p0 x area, 4 sweeps per step.
  check_prestressed_stack(GENERATE(GeometryKind::planar, GeometryKind::axisymmetric), 8);
}

TEST_CASE("Contact patch test: a pre-stressed stack stays at rest, non-matching meshes", "[contact][patch]") {
  // The Gauss-Seidel sweeps over the two-way constraints of non-matching faces stall near 1e-6 of a
  // segment length and every step reaches the 50-sweep limit; the pushing contacts are then solved
  // together (ContactSolver::solve_pushing_together, docs/verification.md, Contact, C2). Before that,
  // measured: fastest node 0.017 (planar) / 0.041 (RZ) of the release speed.
  check_prestressed_stack(GENERATE(GeometryKind::planar, GeometryKind::axisymmetric), 5);
}

// ---- 2. friction ---------------------------------------------------------------------------------

namespace {

// A 4 mm square elastic block (Wilkins aluminium, 8 x 8 zones, no boundary condition) touching a rigid
// wall x = 0 at t = 0 with velocity (-v_n, v_t) = (-10, 10) m/s, and the wall's Coulomb coefficient f.
// The wall is the only external force: the block's momentum change is the wall's impulse, normal (x)
// and tangential (y). The contact lasts about two longitudinal transits of the block (1.2 us); the run
// goes to 3 us, after the block has left the wall.
constexpr double block_size = 0.004, normal_speed = 10.0, tangential_speed = 10.0;

SimulationSetup oblique_block(double friction, contact::ReactionMethod method) {
  SimulationSetup s;
  s.geometry = GeometryKind::planar;
  const auto axis = generate::graded_axis(0.0, {{block_size, 8, 1.0}});
  const auto block = generate::rectangle(s.mesh, axis, axis, 0);
  s.materials.push_back(elastic_aluminium());
  s.bodies.push_back(body_from("block", 0, block));
  for (Index p = block.node_begin; p < block.node_end; ++p) {
    s.mesh.nodes.u[p] = -normal_speed;
    s.mesh.nodes.v[p] = tangential_speed;
  }
  contact::RigidWall wall;
  wall.point = {0.0, 0.0};
  wall.normal = {1.0, 0.0};
  wall.friction = friction;
  s.contact.walls = {wall};
  s.contact.controls.method = method;
  s.controls.end_time = 3e-6;
  return s;
}

struct ObliqueRun {
  double normal_impulse = 0.0;      // change of the block's x momentum (N s per m)
  double tangential_impulse = 0.0;  // change of its y momentum
  // Largest |v_y| of a node on the wall (x = 0) after a step while the block is pressed, where the
  // node's friction is below its Coulomb limit (|R_t| < f R_n): Coulomb's law says it sticks there.
  double stuck_slip = 0.0;
  long stuck_samples = 0;           // (node, step) pairs of that kind
  double saturated_slip = 0.0;      // the same where |R_t| = f R_n (a node unloading: it may slide)
  long saturated_samples = 0;
  double coulomb_excess = 0.0;      // largest (|R_t| - f R_n) / (f R_n) of a node on the wall (<= round-off)
  double peel_slip = 0.0;           // largest |v_y| on the wall once the block lifts off
  long contact_steps = 0;
  double drift = 0.0;
};

ObliqueRun run_oblique(double friction, contact::ReactionMethod method) {
  Simulation sim(oblique_block(friction, method));
  const auto momentum = [&] {
    Vec2 p;
    for (Index n = 0; n < sim.mesh().nodes.size(); ++n) p += sim.mesh().nodes.mass[n] * sim.mesh().nodes.velocity(n);
    return p;
  };
  const Vec2 before = momentum();
  ObliqueRun run;
  while (!sim.finished()) {
    sim.step();
    if (sim.last_contact().active == 0) continue;
    ++run.contact_steps;
    // Nodes the wall holds: the closed contact puts them on the wall exactly (predicted gap driven to 0).
    // The block is pressed until the release from its rear face returns to the wall, 2 L / c_L = 1.24 us;
    // after that it peels off, node by node, each with a normal reaction falling to zero.
    // Near the block's sides the release from its free sides unloads the wall's nodes earlier: a node
    // whose normal reaction has fallen far enough reaches its Coulomb limit and may slide, so sticking
    // is checked where the friction is below that limit.
    const bool pressed = sim.time() < 2.0 * block_size / longitudinal_speed;
    for (Index n = 0; n < sim.mesh().nodes.size(); ++n) {
      if (std::abs(sim.mesh().nodes.x[n]) >= 1e-9 * block_size) continue;
      const double slip = std::abs(sim.mesh().nodes.v[n]);
      if (!pressed) {
        run.peel_slip = std::max(run.peel_slip, slip);
        continue;
      }
      const Vec2 reaction = sim.contact().reaction_force(contact::ContactPoint::node(n));  // wall normal +x
      const double limit = friction * reaction.x;
      if (limit > 0.0) run.coulomb_excess = std::max(run.coulomb_excess, (std::abs(reaction.y) - limit) / limit);
      if (std::abs(reaction.y) < limit * (1.0 - 1e-9)) {
        run.stuck_slip = std::max(run.stuck_slip, slip);
        ++run.stuck_samples;
      } else {
        run.saturated_slip = std::max(run.saturated_slip, slip);
        ++run.saturated_samples;
      }
    }
  }
  const Vec2 after = momentum();
  run.normal_impulse = after.x - before.x;
  run.tangential_impulse = after.y - before.y;
  run.drift = sim.ledger().relative_energy_drift();
  return run;
}

}  // namespace

TEST_CASE("Contact friction: a block sliding on a rigid wall loses tangential momentum f x the normal impulse",
          "[contact][friction]") {
  // Coulomb (docs/theory.md §2 step 3): while a contact slides, its tangential reaction is f R. Each
  // node meets the wall in its own contact, solved exactly in one Gauss-Seidel pass, so if every node
  // slides at every step the tangential impulse is f x the normal impulse to round-off. Sliding holds
  // here: f = 0.1 takes at most f x (twice the normal speed) = 2 m/s from a node's 10 m/s.
  const double friction = 0.1;
  const ObliqueRun run = run_oblique(friction, contact::ReactionMethod::gauss_seidel);
  const double mass = rho0 * block_size * block_size;
  INFO("normal impulse " << run.normal_impulse << " N s/m (m v_n " << mass * normal_speed << "); tangential "
                         << run.tangential_impulse << "; ratio " << -run.tangential_impulse / run.normal_impulse
                         << "; contact steps " << run.contact_steps << "; drift " << run.drift);
  report("Contact friction, sliding (f = 0.1)", "-tangential / normal impulse", "0.1",
         -run.tangential_impulse / run.normal_impulse,
         format_number("%.1e", std::abs(-run.tangential_impulse / run.normal_impulse / friction - 1.0)), 64, 0.0);
  // The block bounces: the normal impulse lies between m v_n (perfectly inelastic) and 2 m v_n.
  CHECK(run.normal_impulse > mass * normal_speed);
  CHECK(run.normal_impulse < 2.0 * mass * normal_speed);
  // Tangential impulse = -f x normal impulse within 1e-9 (round-off of a sum over ~100 steps of
  // impulses of one sign; any node that stuck would make the ratio smaller by its share).
  CHECK(-run.tangential_impulse == Approx(friction * run.normal_impulse).epsilon(1e-9));
  // Friction dissipates; the ledger books it with the contact work: energy closes to round-off.
  CHECK(run.drift < 1e-12);
}

TEST_CASE("Contact friction: with a large coefficient the block sticks, no slip at the wall", "[contact][friction]") {
  // f = 5: stopping a node's 10 m/s of slip needs a tangential impulse m v_t, while the normal impulse
  // that stops it is at least m v_n = m v_t, so f >= 1 already sticks it on its first contact step;
  // 5 leaves margin for the elastic waves. Coulomb's law: a node held on the wall whose friction is
  // below f R_n sticks (its tangential velocity after the step is zero: the friction update drives the
  // slip to zero exactly), and the friction never exceeds f R_n. Checked at every node and step while
  // the block is pressed (t < 2 L / c_L). A node whose normal reaction falls (the release from the
  // block's free sides reaches the wall's nodes next to them before 2 L / c_L) may reach f R_n and
  // slide, as Coulomb's law says: reported only, as is the slip while the block peels off (measured:
  // up to 4.0 m/s).
  const ObliqueRun stick = run_oblique(5.0, contact::ReactionMethod::gauss_seidel);
  const ObliqueRun slide = run_oblique(0.1, contact::ReactionMethod::gauss_seidel);
  INFO("largest slip at the wall below the Coulomb limit " << stick.stuck_slip << " m/s (" << stick.stuck_samples
       << " node-steps); at the limit " << stick.saturated_slip << " m/s (" << stick.saturated_samples
       << " node-steps); while peeling off " << stick.peel_slip << "; Coulomb excess " << stick.coulomb_excess
       << "; tangential impulse " << stick.tangential_impulse << " (sliding, f = 0.1: " << slide.tangential_impulse
       << "); normal impulse " << stick.normal_impulse);
  report("Contact friction, sticking (f = 5)", "largest slip of a node on the wall below f R_n / v_t, pressed (at f R_n; peeling off)",
         "0", stick.stuck_slip / tangential_speed,
         format_number("(%.2f; ", stick.saturated_slip / tangential_speed) +
             format_number("%.2f)", stick.peel_slip / tangential_speed),
         64, 0.0);
  CHECK(stick.contact_steps > 0);
  CHECK(stick.stuck_slip < 1e-9 * tangential_speed);  // round-off of a 10 m/s slip
  // Not vacuous: most of the wall's node-steps while pressed stick below the limit (measured: 273 below
  // it and none at it; with the opt-in physical hourglass stiffness 272 and one).
  CHECK(stick.stuck_samples > 10 * stick.saturated_samples);
  CHECK(stick.coulomb_excess < 1e-9);  // |R_t| <= f R_n to round-off
  // Coulomb bound on the whole: the tangential impulse never exceeds f x normal impulse, and sticking
  // takes more tangential momentum than sliding at f = 0.1.
  CHECK(std::abs(stick.tangential_impulse) <= 5.0 * stick.normal_impulse);
  CHECK(stick.tangential_impulse < slide.tangential_impulse);
  CHECK(stick.drift < 1e-12);
}

TEST_CASE("Contact friction with the summation method: tangential impulse f x normal impulse",
          "[contact][friction]") {
  // The summation method takes every tangential reaction from the same predicted state as the normal
  // ones (C4 in docs/verification.md: it used to apply none). Each node meets the wall in its own
  // contact, and with f = 0.1 every contact slides, so the tangential impulse is f x the normal impulse
  // to round-off, as with Gauss-Seidel above.
  const double friction = 0.1;
  const ObliqueRun run = run_oblique(friction, contact::ReactionMethod::summation);
  INFO("normal impulse " << run.normal_impulse << "; tangential " << run.tangential_impulse << "; drift " << run.drift);
  report("Contact friction, sliding, summation method", "-tangential / normal impulse", "0.1",
         -run.tangential_impulse / run.normal_impulse,
         format_number("%.1e", std::abs(-run.tangential_impulse / run.normal_impulse / friction - 1.0)), 64, 0.0);
  CHECK(run.normal_impulse > 0.0);
  CHECK(-run.tangential_impulse == Approx(friction * run.normal_impulse).epsilon(1e-9));
  CHECK(run.drift < 1e-12);  // friction work is booked with the contact work
}

// ---- 3. the bullet into the plate ------------------------------------------------------------------

namespace {

// A contact example (examples/contact/<file>) with textual substitutions (each must occur once).
scenario::Scenario load_contact_example(const std::string& file, const std::vector<verification::Substitution>& substitutions) {
  const std::filesystem::path path = std::filesystem::path(KRUG_EXAMPLES_DIR) / "contact" / file;
  return scenario::parse_scenario(verification::substitute(verification::read_text(path), substitutions), path.string());
}

// Measures of a run with contact, sampled after every step.
struct ContactRun {
  std::string failure;
  double seconds = 0.0;
  long cycles = 0, zone_cycles = 0, sweeps = 0, contact_steps = 0;
  double deepest_penetration = 0.0;   // m, geometric (deepest_penetration over the watched pairs), worst step
  double deepest_solver_gap = 0.0;    // m, Simulation::deepest_contact_gap at the end (<= 0)
  double zone = 0.0;                  // smallest initial zone altitude of the watched bodies (m)
  double momentum_error = 0.0;        // |P - P0 - boundary impulse| / |P0|
  double energy_drift = 0.0;
  double contact_work = 0.0;          // W_contact, whole body (J)
  // (W_contact - overlap line) / the ledger's energy scale: contacts that start apart only dissipate,
  // so <= 0 up to round-off (docs/outputs.md, the ledger).
  double dissipation_excess = 0.0;
};

// Runs to the end time, measuring after every step the deepest penetration of every ordered pair of
// `watched` bodies that the scenario pairs for contact, and whatever `observe` wants.
ContactRun run_with_contact(const SimulationSetup& setup, const std::function<void(const Simulation&)>& observe = {}) {
  ContactRun run;
  Simulation sim(setup);
  std::vector<std::pair<Index, Index>> watched;
  std::vector<Index> bodies;
  for (const contact::BodyPair& pair : setup.contact.pairs) {
    if (pair.first == pair.second) continue;
    watched.emplace_back(pair.first, pair.second);
    watched.emplace_back(pair.second, pair.first);
    bodies.push_back(pair.first);
    bodies.push_back(pair.second);
  }
  run.zone = smallest_zone(sim, bodies);
  const auto start = std::chrono::steady_clock::now();
  double penetration_seconds = 0.0;
  try {
    while (!sim.finished()) {
      sim.step();
      run.sweeps += sim.last_contact().sweeps;
      if (sim.last_contact().active > 0) ++run.contact_steps;
      const auto measure = std::chrono::steady_clock::now();
      for (const auto& [a, b] : watched) {
        run.deepest_penetration = std::max(run.deepest_penetration,
                                           deepest_penetration(sim, sim.bodies()[static_cast<std::size_t>(a)],
                                                               sim.bodies()[static_cast<std::size_t>(b)]));
      }
      if (observe) observe(sim);
      penetration_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - measure).count();
    }
  } catch (const NumericalFailure& failure) {
    run.failure = failure.what();
  }
  // The cost of the run itself, without the measurements made after each step.
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - penetration_seconds;
  run.cycles = sim.cycle();
  run.zone_cycles = sim.zone_cycles();
  run.deepest_solver_gap = sim.deepest_contact_gap();
  const Ledger& ledger = sim.ledger();
  run.momentum_error = std::abs(ledger.axial_momentum - ledger.initial_axial_momentum - ledger.axial_boundary_impulse) /
                       std::abs(ledger.initial_axial_momentum);
  run.energy_drift = ledger.relative_energy_drift();
  run.contact_work = sim.whole_body_factor() * ledger.energy.contact;
  run.dissipation_excess = (ledger.energy.contact - ledger.energy.overlap) / ledger.energy_scale();
  return run;
}

// examples/contact/striker_dishing.json at a coarse resolution: the bullet 8 zones across its radius
// (0.35 mm) instead of 28, the plate 6 zones through its 3 mm (0.5 mm) instead of 30 and 11 + 8 radially
// instead of 56 + 32, so that a run takes about a second. The contact checks are resolution-free (a
// penetration limit relative to the zone size, conservation laws), and at this zoning the run already
// has what makes contact hard: a nose that mushrooms at several GPa, a plate that dishes and wraps
// it, contacts sliding along curved surfaces. 30 us: the plate is dished about 5 mm and the bullet
// has lost 10 % of its speed. No erosion, as in the example: the test is of node-on-segment contact
// alone (erosion 0.1 would convert 12 zones of the nose's lips to particles by 30 us at this zoning).
SimulationSetup coarse_striker(contact::ReactionMethod method) {
  scenario::Scenario scenario = load_contact_example(
      "striker_dishing.json",
      {{"\"radial_zones\": 28", "\"radial_zones\": 8"}, verification::zones(30, 6), verification::zones(56, 11),
       verification::zones(32, 8)});
  scenario.setup.controls.end_time = 30e-6;                                    // the example's
  for (Body& body : scenario.setup.bodies) body.set_erosion({});  // as the example
  scenario.setup.contact.controls.method = method;
  return scenario.setup;
}

std::string method_name(contact::ReactionMethod m) {
  return m == contact::ReactionMethod::gauss_seidel ? "Gauss-Seidel" : "summation";
}

void report_striker(const ContactRun& run, contact::ReactionMethod method, long zones) {
  const std::string name = "Contact striker (coarse), " + method_name(method);
  report(name, "deepest penetration / zone (geometric, any step)", "< 1e-3", run.deepest_penetration / run.zone,
         format_number("solver gap %.2e zone", -run.deepest_solver_gap / run.zone), zones, run.seconds);
  report(name, "axial momentum - rim impulse; energy drift", "0; < 5e-3", run.momentum_error,
         format_number("%.1e", run.energy_drift), zones, run.seconds);
  report(name, "mean sweeps per step; cycles; contact work (J)", "-",
         static_cast<double>(run.sweeps) / static_cast<double>(std::max(run.cycles, 1L)),
         format_number("%.0f cycles; ", static_cast<double>(run.cycles)) + format_number("%.3g J", run.contact_work),
         zones, run.seconds);
}

}  // namespace

TEST_CASE("Contact striker into a plate without fracture: no interpenetration, momentum against the rim impulse, energy",
          "[contact][striker]") {
  const SimulationSetup setup = coarse_striker(contact::ReactionMethod::gauss_seidel);
  const ContactRun run = run_with_contact(setup);
  report_striker(run, contact::ReactionMethod::gauss_seidel, setup.mesh.zones.size());
  INFO("failure: " << run.failure << "; deepest penetration " << run.deepest_penetration << " m (zone " << run.zone
                   << " m); solver gap " << run.deepest_solver_gap << "; momentum error " << run.momentum_error
                   << "; drift " << run.energy_drift << "; contact work " << run.contact_work << " J; "
                   << run.seconds << " s");
  REQUIRE(run.failure.empty());
  CHECK(2 * run.contact_steps > run.cycles);  // the bullet pushes through the whole run
  // No interpenetration beyond 1e-3 of a zone (the acceptance bar), at any step, both ways (bullet nodes in the
  // plate, plate nodes in the bullet), measured geometrically (node inside a zone of the other body).
  CHECK(run.deepest_penetration < 1e-3 * run.zone);
  // The fixed rim is the only external force: axial momentum changes by its impulse, to round-off
  // (compatible RZ forces and equal and opposite contact reactions).
  CHECK(run.momentum_error < 1e-12);
  // Energy ledger closed within 0.5 % (the acceptance bar); contact work books what the reactions take.
  CHECK(run.energy_drift < 5e-3);
  CHECK(run.dissipation_excess <= 1e-12);
  CHECK(run.contact_work <= 0.0);
}

namespace {

// The lead zones with a corner bent into the zone (a dart: a negative corner sine, mesh/quality.hpp)
// at the end of the run.
int darts(const Simulation& sim, const Body& body) {
  const Mesh& mesh = sim.mesh();
  int folded = 0;
  for (Index z = body.zone_begin; z < body.zone_end; ++z) {
    if (mesh.zones.active[z] && min_corner_sine(mesh.corner_positions(z)) < 0.0) ++folded;
  }
  return folded;
}

// Runs `setup` with the physical hourglass form and the corner-collapse pressure (k = 1, threshold 1.5)
// and checks that no lead zone is folded at the end, that nothing passes deeper than 1e-3 of a zone,
// and the ledgers, as the impacts above.
void check_physical_with_collapse(SimulationSetup setup, const std::string& name) {
  setup.controls.hourglass.stiffness_form = HourglassStiffness::physical;
  setup.controls.hourglass.collapse_pressure = 1.0;
  int folded = -1;
  const ContactRun run = run_with_contact(setup, [&](const Simulation& sim) {
    if (sim.finished()) folded = darts(sim, sim.bodies()[0]);
  });
  report(name + ", physical hourglass form + corner-collapse pressure 1",
         "deepest penetration / zone (geometric, any pair, any step); lead zones folded at 30 us", "< 1e-3; 0",
         run.deepest_penetration / run.zone, format_number("%.0f folded", folded), setup.mesh.zones.size(), run.seconds);
  INFO("failure: " << run.failure << "; deepest penetration " << run.deepest_penetration / run.zone << " zone; "
                   << folded << " folded; " << run.cycles << " cycles");
  REQUIRE(run.failure.empty());
  CHECK(folded == 0);
  CHECK(run.deepest_penetration < 1e-3 * run.zone);
  CHECK(run.momentum_error < 1e-12);
  CHECK(run.energy_drift < 5e-3);
  CHECK(run.dissipation_excess <= 1e-12);
}

}  // namespace

TEST_CASE("Contact striker, physical hourglass stiffness with the corner-collapse pressure: no fold, no interpenetration",
          "[contact][striker][hourglass]") {
  // The physical hourglass form alone lets 21 of the lead's zones fold into darts by 30 us (7 with the
  // default coefficient form), and their neighbours then overlap them: plate nodes outside the lead
  // lie inside its folded zones, 0.48 of a zone deep by this test's geometric measure
  // (docs/validation.md, "The physical hourglass stiffness"). The corner-collapse pressure
  // (hourglass.collapse_pressure 1, threshold 1.5) resists a corner region compressed beyond 1.5
  // times its zone's density. Measured: no dart, deepest penetration 3.3e-4 of a zone.
  check_physical_with_collapse(coarse_striker(contact::ReactionMethod::gauss_seidel), "Contact striker (coarse)");
}

TEST_CASE("Contact striker into a plate without fracture, the paper's summation method",
          "[contact][striker][summation][!mayfail]") {
  // Known failure (docs/verification.md, Contact, C5): the summation method leaves penetration. It sums
  // the reactions of all candidates from one predicted state, each pass of a two-way pair weighted 1/2,
  // so a gap that only one pass sees (a node of one body against a segment of the other whose own nodes
  // are clear) is closed only half-way in a step; the rest is a pre-existing overlap next step, removed
  // by at most overlap_fraction of it and overlap_speed x dt per step. Measured at this zoning: 0.25 of
  // a zone (2.9e-2 left in the solver's own gap), against 2e-6 with Gauss-Seidel. Conservation holds.
  const SimulationSetup setup = coarse_striker(contact::ReactionMethod::summation);
  const ContactRun run = run_with_contact(setup);
  report_striker(run, contact::ReactionMethod::summation, setup.mesh.zones.size());
  INFO("failure: " << run.failure << "; deepest penetration " << run.deepest_penetration << " m (zone " << run.zone
                   << " m); solver gap " << run.deepest_solver_gap << "; momentum error " << run.momentum_error
                   << "; drift " << run.energy_drift << "; " << run.seconds << " s");
  REQUIRE(run.failure.empty());
  CHECK(run.deepest_penetration < 1e-3 * run.zone);
  CHECK(run.momentum_error < 1e-12);
  CHECK(run.energy_drift < 5e-3);
  CHECK(run.dissipation_excess <= 1e-12);
}

// ---- 4. three plates in contact --------------------------------------------------------------------

namespace {

// Uniaxial strain (slip walls above and below, 1 zone high, as E1): a flyer and three plates of
// Wilkins aluminium (elastic), each h = 2 mm thick, in contact, the flyer at v = 10 m/s. Exact (linear
// acoustics, equal impedances): a compressive pulse of length 2h and particle velocity v/2 runs through
// the plates; the flyer is left at rest when the release from its rear face reaches the interface
// (2h/c). The pulse reflects as tension from the last plate's rear face (3h from the impact face) and
// meets its own tail at the last interface (2h) at t = 4h/c, where contact cannot carry tension: the
// last plate separates with the whole pulse, velocity v (a momentum trap), and the flyer and the first
// two plates stay at rest, touching, with no force between them.
constexpr double trap_thickness = 0.002, trap_height = 2.5e-4, trap_speed = 10.0;

struct TrapRun {
  ContactRun run;
  double zone = 0.0, transit = 0.0;
  double separated = 0.0;     // last time the last interface's gap was below 1e-3 of a zone (s)
  double velocity[4] = {};    // flyer, plates 1-3 (mass-weighted mean, m/s)
  double final_gap = 0.0;     // last interface at the end (m)
  double widest_closed = 0.0; // widest gap of the first two interfaces at any step (m)
  long zones = 0;
};

TrapRun run_trap(int zones_through, double end_time) {
  const double h = trap_thickness;
  SimulationSetup setup;
  setup.geometry = GeometryKind::planar;
  setup.materials.push_back(elastic_aluminium());
  std::vector<generate::Patch> patches;
  for (int k = 0; k < 4; ++k) {
    patches.push_back(generate::rectangle(setup.mesh, generate::graded_axis((k - 1) * h, {{k * h, zones_through, 1.0}}),
                                          generate::graded_axis(0.0, {{trap_height, 1, 1.0}}), k));
    setup.bodies.push_back(body_from(k == 0 ? "flyer" : "plate" + std::to_string(k), 0, patches.back()));
    for (Index n : patches.back().sides.at("j_min")) setup.constraints.push_back({n, false, true});
    for (Index n : patches.back().sides.at("j_max")) setup.constraints.push_back({n, false, true});
  }
  for (Index n = patches[0].node_begin; n < patches[0].node_end; ++n) setup.mesh.nodes.u[n] = trap_speed;
  setup.contact.pairs = {{0, 1, 0.0}, {1, 2, 0.0}, {2, 3, 0.0}};
  setup.controls.end_time = end_time;

  TrapRun trap;
  trap.zone = h / zones_through;
  trap.transit = trap.zone / longitudinal_speed;
  trap.zones = setup.mesh.zones.size();
  // Gap of interface k (between body k and k + 1): body k+1's face minus body k's face (mean x).
  const auto face_x = [&](const Simulation& sim, int body, const char* side) {
    const std::vector<Index>& nodes = patches[static_cast<std::size_t>(body)].sides.at(side);
    double x = 0.0;
    for (Index n : nodes) x += sim.mesh().nodes.x[n];
    return x / static_cast<double>(nodes.size());
  };
  trap.run = run_with_contact(setup, [&](const Simulation& sim) {
    for (int k = 0; k < 2; ++k) trap.widest_closed = std::max(trap.widest_closed, face_x(sim, k + 1, "i_min") - face_x(sim, k, "i_max"));
    trap.final_gap = face_x(sim, 3, "i_min") - face_x(sim, 2, "i_max");
    if (trap.final_gap < 1e-3 * trap.zone) trap.separated = sim.time();
    if (sim.finished()) {
      for (int k = 0; k < 4; ++k) trap.velocity[k] = sim.summarise(sim.bodies()[static_cast<std::size_t>(k)]).velocity.x;
    }
  });
  return trap;
}

}  // namespace

TEST_CASE("Contact three plates struck by a flyer: the last plate takes the pulse and separates, the others stop",
          "[contact][plates]") {
  // Checked at 20, 40 and 80 zones per plate (0.1 to 0.025 mm; 80 to 320 zones in all, well under a
  // second): no body passes into another (geometric penetration of every pair, every step), the last
  // interface separates at 4h/c, the first two stay closed, and the velocities converge to the momentum
  // trap. They converge, not equal it: the pulse reaches the last interface smeared over a few zones
  // (three contacts and the viscosity round its tail), and the part of the tail still behind the
  // interface when it opens stays in plate 2. That part is a smear width over the pulse length 2h:
  // measured 4.6 %, 2.7 %, 1.6 % of v at 20, 40, 80 zones (and 1.0 % at 160), an observed order of
  // about 0.75; the test asserts that each doubling cuts the deficit by at least a quarter and that the
  // finest run is within 2 % of the exact velocities.
  const double h = trap_thickness, v = trap_speed, end_time = 2.5e-6;
  const double separation_exact = 4.0 * h / longitudinal_speed;  // 1.240 us
  double previous_deficit = 1.0;
  for (int zones_through : {20, 40, 80}) {
    const TrapRun t = run_trap(zones_through, end_time);
    const std::string name = "Contact three plates and a flyer (planar, " + std::to_string(zones_through) + " zones per plate)";
    const double deficit = 1.0 - t.velocity[3] / v;
    const double others = std::max({std::abs(t.velocity[0]), std::abs(t.velocity[1]), std::abs(t.velocity[2])});
    INFO(name << ": failure '" << t.run.failure << "'; separation " << t.separated << " s (exact " << separation_exact
              << ", zone transit " << t.transit << "); velocities " << t.velocity[0] << ", " << t.velocity[1] << ", "
              << t.velocity[2] << ", " << t.velocity[3] << " m/s; last gap " << t.final_gap
              << " m; widest gap of the others " << t.widest_closed << " m; deepest penetration "
              << t.run.deepest_penetration << " m");
    report(name, "last interface opens at (s)", format_number("%.4g", separation_exact), t.separated,
           format_number("%.2f zone transits", std::abs(t.separated - separation_exact) / t.transit), t.zones, t.run.seconds);
    report(name, "last plate velocity; flyer, plates 1-2 (largest |v|)", "10; 0", t.velocity[3],
           format_number("%.3f m/s", others), t.zones, t.run.seconds);
    report(name, "deepest penetration / zone; widest gap of the closed interfaces / zone", "< 1e-3; 0",
           t.run.deepest_penetration / t.zone, format_number("%.2e", t.widest_closed / t.zone), t.zones, t.run.seconds);
    REQUIRE(t.run.failure.empty());
    // No body passes into another by more than 1e-3 of a zone, at any step.
    CHECK(t.run.deepest_penetration < 1e-3 * t.zone);
    // The last interface separates at 4h/c within 3 zone transit times (E1's criterion for a smeared
    // release meeting at an interface); the gap then grows at about the last plate's speed.
    CHECK(std::abs(t.separated - separation_exact) <= 3.0 * t.transit);
    CHECK(t.final_gap > 0.5 * v * (end_time - separation_exact));
    // The first two interfaces open by less than a tenth of a zone: plate 2 creeps away from plate 1
    // only with the tail it keeps (deficit x v).
    CHECK(t.widest_closed < 0.1 * t.zone);
    // Convergence to the momentum trap, as described above.
    CHECK(deficit > 0.0);
    CHECK(deficit < 0.75 * previous_deficit);
    if (zones_through == 80) {
      CHECK(deficit < 0.02);
      CHECK(others < 0.02 * v);
    }
    previous_deficit = deficit;
    // No axial boundary acts (slip walls hold y only): momentum exact; energy closes.
    CHECK(t.run.momentum_error < 1e-12);
    CHECK(t.run.energy_drift < 1e-12);
    CHECK(t.run.dissipation_excess <= 1e-12);
  }
}

namespace {

// The paper's layered target (docs/validation.md: three 1 mm 6061-T6 plates in contact, rims
// fixed at r = 25 mm) struck by the lead bullet of examples/contact/striker_dishing.json at 355 m/s,
// fracture off, at the coarse zoning of the striker test: bullet 8 zones across its radius, each plate
// 3 zones through its 1 mm, 11 + 8 radially. Contact: the bullet against each plate, each plate against
// its neighbours.
std::string layered_scenario() {
  std::string plates;
  for (int k = 1; k <= 3; ++k) {
    plates += R"(, { "name": "plate)" + std::to_string(k) + R"(", "material": "al6061",
        "mesh": { "type": "rectangle", "z": { "from": )" + std::to_string(-0.001 * k) + R"(, "to": )" +
              std::to_string(-0.001 * (k - 1)) + R"(, "zones": 3 },
                  "r": { "from": 0.0, "segments": [ { "to": 0.00556, "zones": 11 }, { "to": 0.025, "zones": 8, "ratio": 1.1 } ] } },
        "boundary": { "r_max": "fixed" } })";
  }
  return R"({ "geometry": "axisymmetric", "end_time": 3e-5,
  "materials": {
    "lead": { "density": 11340.0, "eos": { "model": "linear", "bulk_modulus": 5e10 },
              "strength": { "model": "perfectly_plastic", "shear_modulus": 5.7e9, "yield_stress": 3e7 } },
    "al6061": { "density": 2700.0, "eos": { "model": "linear", "bulk_modulus": 7.3e10 },
                "strength": { "model": "perfectly_plastic", "shear_modulus": 2.46e10, "yield_stress": 2.8e8 } } },
  "bodies": [ { "name": "bullet", "material": "lead",
                "mesh": { "type": "nosed_cylinder", "radius": 0.00278, "length": 0.040878817633134536, "nose": "hemispherical",
                          "tip": 0.0001, "points": "-z", "radial_zones": 8, "shank_ratio": 1.04 },
                "initial": { "velocity": [-355.0, 0.0] } })" + plates + R"( ],
  "contact": { "pairs": [ { "bodies": ["bullet", "plate1"] }, { "bodies": ["bullet", "plate2"] }, { "bodies": ["bullet", "plate3"] },
                          { "bodies": ["plate1", "plate2"] }, { "bodies": ["plate2", "plate3"] } ] } })";
}

}  // namespace

TEST_CASE("Contact layered target struck by the bullet (RZ): no plate passes through another, the layers part",
          "[contact][plates][axisymmetric]") {
  // Checked: no pair passes into another (geometric, every step, < 1e-3 of a zone), momentum against
  // the rim impulse, the energy ledger. And the layers part: the gap between neighbouring plates (each
  // node of plate k+1's front face against plate k's rear face, interpolated at its radius) is followed
  // over the whole interface and the run. The impact's compressive wave crosses the 3 mm stack in
  // 0.5 us and reflects from the last plate's free rear face as tension, which contact cannot carry;
  // then the bullet bends the stack and the layers, pushed by contact only, take different curvatures
  // and part off the axis (the paper: "the rear layers bend strongly and separate"). Asserted: each
  // interface opens by more than a tenth of a plate zone somewhere (measured: up to 0.25 and 0.11 mm,
  // 0.7 and 0.3 of a zone, at r = 7.1 mm by 30 us, growing); the exact separation time of layers in
  // contact is the planar test above. The plates stay together on the axis, under the bullet.
  const scenario::Scenario scenario = scenario::parse_scenario(layered_scenario(), "layered target (test_contact.cpp)");
  SideLine rear[2], front[2];
  {
    const Simulation probe(scenario.setup);
    const Mesh& mesh = probe.mesh();
    for (int k = 0; k < 2; ++k) {
      const Body& upper = probe.bodies()[static_cast<std::size_t>(k + 1)];
      const Body& lower = probe.bodies()[static_cast<std::size_t>(k + 2)];
      const double face = -0.001 * (k + 1);
      std::vector<Index> r, f;
      for (Index n = upper.node_begin; n < upper.node_end; ++n) if (std::abs(mesh.nodes.x[n] - face) < 1e-12) r.push_back(n);
      for (Index n = lower.node_begin; n < lower.node_end; ++n) if (std::abs(mesh.nodes.x[n] - face) < 1e-12) f.push_back(n);
      rear[k] = side_line(mesh, r);
      front[k] = side_line(mesh, f);
    }
  }
  struct Opening { double widest = 0.0, at_time = 0.0, at_radius = 0.0, first = -1.0; };
  Opening opening[2];
  const double plate_zone = 0.001 / 3.0;
  const ContactRun run = run_with_contact(scenario.setup, [&](const Simulation& sim) {
    const Mesh& mesh = sim.mesh();
    for (int k = 0; k < 2; ++k) {
      for (Index n : front[k].nodes) {
        const double r = mesh.nodes.y[n];
        if (r > mesh.nodes.y[rear[k].nodes.back()]) continue;
        const double gap = rear[k].at(mesh, r, mesh.nodes.x) - mesh.nodes.x[n];
        Opening& o = opening[k];
        if (gap > o.widest) { o.widest = gap; o.at_time = sim.time(); o.at_radius = r; }
        if (gap > 1e-3 * plate_zone && o.first < 0.0) o.first = sim.time();
      }
    }
  });
  INFO("failure: " << run.failure << "; deepest penetration " << run.deepest_penetration << " m (zone " << run.zone
                   << " m); momentum error " << run.momentum_error << "; drift " << run.energy_drift);
  const std::string name = "Contact layered target and bullet (RZ, coarse)";
  const long zones = scenario.setup.mesh.zones.size();
  report(name, "deepest penetration / zone (any pair, any step)", "< 1e-3", run.deepest_penetration / run.zone,
         format_number("solver gap %.2e zone", -run.deepest_solver_gap / run.zone), zones, run.seconds);
  report(name, "axial momentum - rim impulse; energy drift", "0; < 5e-3", run.momentum_error,
         format_number("%.1e", run.energy_drift), zones, run.seconds);
  for (int k = 0; k < 2; ++k) {
    const std::string which = k == 0 ? "plates 1-2" : "plates 2-3";
    INFO(which << ": first opening " << opening[k].first << " s; widest " << opening[k].widest << " m at t "
               << opening[k].at_time << " r " << opening[k].at_radius);
    report(name, "gap " + which + ": first opening > 1e-3 zone (s); widest (m), at t, r", "-", opening[k].first,
           format_number("%.3g m, ", opening[k].widest) + format_number("%.3g s, ", opening[k].at_time) +
               format_number("r %.3g mm", 1e3 * opening[k].at_radius),
           zones, run.seconds);
    CHECK(opening[k].widest > 0.1 * plate_zone);
  }
  REQUIRE(run.failure.empty());
  CHECK(run.deepest_penetration < 1e-3 * run.zone);
  CHECK(run.momentum_error < 1e-12);
  CHECK(run.energy_drift < 5e-3);
  CHECK(run.dissipation_excess <= 1e-12);
}

TEST_CASE("Contact layered target, physical hourglass stiffness with the corner-collapse pressure: no fold, no interpenetration",
          "[contact][plates][axisymmetric][hourglass]") {
  // As the striker test above with hourglass.stiffness_form "physical" and collapse_pressure 1: with the
  // physical form alone plate nodes outside the lead lay 0.11 of a zone inside its folded zones
  // (docs/validation.md, "The physical hourglass stiffness"). Measured with the pressure: no lead zone
  // folded, deepest penetration 3.4e-4 of a zone.
  check_physical_with_collapse(scenario::parse_scenario(layered_scenario(), "layered target (test_contact.cpp)").setup,
                               "Contact layered target and bullet (RZ, coarse)");
}

