// The hydro kernels alone (include/krug/hydro/zone_forces.hpp, zone_update.hpp), called directly on
// one zone built in code, without a scenario or a Simulation: the work of the pressure corner forces
// against the exact p dV of a uniform compression, the deviator under a rigid rotation, and the sum
// of a zone's corner forces (docs/theory.md §2 steps 1 and 5).
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <limits>

#include "krug/hydro/zone_forces.hpp"
#include "krug/hydro/zone_update.hpp"
#include "krug/material/eos.hpp"
#include "krug/material/strength.hpp"

using namespace krug;

namespace {

// A mesh of one zone and the zone's state (intact, unstressed), as the kernels take them.
struct OneZone : Mesh {
  ZoneState state;
};

// A mesh of one zone with corners x (counter-clockwise), at rest, of density rho and specific
// energy e; its mass is rho times its area (planar) or r-weighted volume (RZ).
OneZone one_zone(const quad::Corners& x, GeometryKind geometry, double rho, double e) {
  OneZone mesh;
  mesh.nodes.resize(4);
  mesh.zones.resize(1);
  mesh.state.resize(1);
  for (Index p = 0; p < 4; ++p) {
    mesh.nodes.x[p] = x[p].x;
    mesh.nodes.y[p] = x[p].y;
    mesh.nodes.body[p] = 0;
  }
  ZoneFields& zones = mesh.zones;
  zones.corners[0] = {0, 1, 2, 3};
  zones.body[0] = 0;
  zones.area[0] = quad::area(x);
  zones.volume[0] = geometry == GeometryKind::axisymmetric ? quad::axisymmetric_volume(x) : zones.area[0];
  zones.density[0] = rho;
  zones.mass[0] = rho * zones.volume[0];
  zones.specific_energy[0] = e;
  return mesh;
}

quad::Corners positions(const Mesh& mesh) { return mesh.corner_positions(0); }

double volume_of(const quad::Corners& x, GeometryKind geometry) {
  return geometry == GeometryKind::axisymmetric ? quad::axisymmetric_volume(x) : quad::area(x);
}

// Sets every node's velocity u^{n-1/2} = u^{n+1/2} = velocity(p), so that the mid velocity ubar of the
// energy update is that velocity.
template <class Velocity>
void set_velocities(Mesh& mesh, Velocity velocity) {
  for (Index p = 0; p < 4; ++p) {
    const Vec2 u = velocity(p);
    mesh.nodes.u[p] = mesh.nodes.u_old[p] = u.x;
    mesh.nodes.v[p] = mesh.nodes.v_old[p] = u.y;
  }
}

void move_nodes(Mesh& mesh, double dt) {
  for (Index p = 0; p < 4; ++p) {
    mesh.nodes.x[p] += dt * mesh.nodes.u[p];
    mesh.nodes.y[p] += dt * mesh.nodes.v[p];
  }
}

// sum_p f_p . u_p of the stored corner forces: the rate of work of the zone's forces on its nodes.
double corner_power(const OneZone& mesh) {
  double power = 0.0;
  for (int p = 0; p < 4; ++p) {
    power += mesh.state.hydro.corner_force[2 * static_cast<std::size_t>(p)] * mesh.nodes.u[p] +
             mesh.state.hydro.corner_force[2 * static_cast<std::size_t>(p) + 1] * mesh.nodes.v[p];
  }
  return power;
}

// Hydro parameters with no viscosity and no hourglass control: the corner forces are the stress's alone.
ZoneForceParams stress_only() {
  ZoneForceParams params;
  params.viscosity.model = ViscosityModel::off;
  params.hourglass.viscous = 0.0;
  params.hourglass.stiffness = 0.0;
  return params;
}

template <GeometryKind G, ViscosityModel V>
void compute_forces_with(OneZone& mesh, const ZoneForceParams& params) {
  ZoneState& z = mesh.state;
  compute_corner_forces<G, V>(mesh, z.hydro, z.strength, z.hourglass, z.fracture, 0, 1, params);
}

template <GeometryKind G>
void compute_forces(OneZone& mesh, const ZoneForceParams& params) {
  switch (params.viscosity.model) {
    case ViscosityModel::edge: compute_forces_with<G, ViscosityModel::edge>(mesh, params); break;
    case ViscosityModel::scalar: compute_forces_with<G, ViscosityModel::scalar>(mesh, params); break;
    case ViscosityModel::tensor: compute_forces_with<G, ViscosityModel::tensor>(mesh, params); break;
    case ViscosityModel::off: compute_forces_with<G, ViscosityModel::off>(mesh, params); break;
    case ViscosityModel::automatic: FAIL("the kernels take a resolved model (zone_force_params)"); break;
  }
}

void compute_forces(OneZone& mesh, GeometryKind geometry, const ZoneForceParams& params) {
  if (geometry == GeometryKind::axisymmetric) {
    compute_forces<GeometryKind::axisymmetric>(mesh, params);
  } else {
    compute_forces<GeometryKind::planar>(mesh, params);
  }
}

// A distorted quadrilateral (no two sides parallel), off the axis.
const quad::Corners distorted{Vec2{0.20, 0.30}, Vec2{1.10, 0.25}, Vec2{1.00, 1.20}, Vec2{0.30, 1.00}};

}  // namespace

// (a) A uniform compression about a point c, u_p = -eps (x_p - c), is a homothety: every length scales
// by s(t) = 1 - eps (t - t^n), the area by s^2 and, with c on the axis, the r-weighted volume by s^3.
// The stress corner force of a pressure is f_p = p dA/dx_p (planar) or p dV/dx_p (RZ, control
// volume), so its rate of work sum_p f_p . u_p is p dV/dt at the geometry the forces were built on.
// Over a step dt = k / eps:
//   - forces on x^n (the scheme: F^n, then x^{n+1} = x^n + dt u): W = p dt dV/dt(t^n) = -d p V k, d = 2
//     (planar) or 3 (RZ), against the exact p dV = p V ((1 - k)^d - 1); the difference is the
//     higher-order terms of the binomial, p V k^2 (planar) and p V (3 k^2 - k^3) (RZ), a relative
//     k/2 and about k: the first-order error of holding the forces at t^n, not round-off;
//   - forces on the mid-step geometry: the midpoint rule is exact for a quadratic, so the planar work
//     is p dV to round-off; the cubic RZ volume leaves p V (2 h^3), h = k/2, from
//     (1 + h)^3 - (1 - h)^3 = 6 h + 2 h^3.
// The energy update m de = -dt sum_p f_p . ubar_p (update_zones) must turn W into -m de exactly.
// Tolerances: 1e-13 of p |dV| (the terms are sums of a few products, each with a relative round-off
// of a few 1e-16; k = 0.01 makes the higher-order terms 5e-3 and 3e-2 of p dV, far above it).
TEST_CASE("hydro kernels: the pressure work of a uniform compression is p dV", "[hydro][kernel]") {
  const double rho = 1.2, gamma = 1.4, pressure = 2.5e5;
  const double e = pressure / ((gamma - 1.0) * rho);
  const double eps = 1.0e3;  // 1/s
  const double k = 0.01;
  const double dt = k / eps;
  const ZoneForceParams params = stress_only();
  ZoneUpdateParams update;
  update.time_step_mid = dt;
  update.time_step_next = dt;

  auto check_step = [&](GeometryKind geometry, Vec2 centre, double dimension) {
    OneZone mesh = one_zone(distorted, geometry, rho, e);
    mesh.state.hydro.pressure[0] = pressure;
    set_velocities(mesh, [&](Index p) { return -eps * (positions(mesh)[p] - centre); });
    const double volume = volume_of(positions(mesh), geometry);
    compute_forces(mesh, geometry, params);
    const double work = dt * corner_power(mesh);
    move_nodes(mesh, dt);
    const double exact = pressure * (volume_of(positions(mesh), geometry) - volume);
    // The binomial's higher-order terms: V ((1 - k)^d - 1) + d V k.
    const double remainder = dimension == 2 ? pressure * volume * k * k : pressure * volume * (3 * k * k - k * k * k);
    CHECK(work == Approx(exact - remainder).epsilon(0.0).margin(1e-13 * std::abs(exact)));
    CHECK(std::abs(work - exact) > 1e-3 * std::abs(exact));  // the remainder is there, and not round-off

    const double energy_before = mesh.zones.mass[0] * mesh.zones.specific_energy[0];
    const ZoneUpdateResult result = geometry == GeometryKind::axisymmetric
        ? update_zones<GeometryKind::axisymmetric>(mesh, mesh.state.hydro, mesh.state.strength, mesh.state.fracture, 0,
                                                   1, IdealGas{gamma}, NoStrength{}, update)
        : update_zones<GeometryKind::planar>(mesh, mesh.state.hydro, mesh.state.strength, mesh.state.fracture, 0, 1,
                                             IdealGas{gamma}, NoStrength{}, update);
    REQUIRE(result.failed_zone < 0);
    const double heating = mesh.zones.mass[0] * mesh.zones.specific_energy[0] - energy_before;
    CHECK(heating == Approx(-work).epsilon(0.0).margin(1e-13 * std::abs(work)));
    CHECK(mesh.zones.volume[0] == Approx(volume_of(positions(mesh), geometry)).epsilon(1e-15));
  };

  SECTION("planar, forces at t^n, through update_zones") { check_step(GeometryKind::planar, Vec2{0.6, 0.7}, 2); }
  SECTION("axisymmetric control volume, forces at t^n, through update_zones") {
    check_step(GeometryKind::axisymmetric, Vec2{0.6, 0.0}, 3);  // the centre on the axis: V ~ s^3
  }

  SECTION("forces on the mid-step geometry") {
    for (const GeometryKind geometry : {GeometryKind::planar, GeometryKind::axisymmetric}) {
      const Vec2 centre{0.6, 0.0};
      OneZone mesh = one_zone(distorted, geometry, rho, e);  // the mid-step geometry x^{n+1/2}
      mesh.state.hydro.pressure[0] = pressure;
      set_velocities(mesh, [&](Index p) { return -eps * (positions(mesh)[p] - centre); });
      const double volume = volume_of(positions(mesh), geometry);
      compute_forces(mesh, geometry, params);
      const double work = dt * corner_power(mesh);
      move_nodes(mesh, -0.5 * dt);
      const double start = volume_of(positions(mesh), geometry);
      move_nodes(mesh, dt);
      const double exact = pressure * (volume_of(positions(mesh), geometry) - start);
      const double h = 0.5 * k;
      const double remainder = geometry == GeometryKind::axisymmetric ? 2.0 * pressure * volume * h * h * h : 0.0;
      INFO((geometry == GeometryKind::axisymmetric ? "axisymmetric" : "planar"));
      CHECK(work == Approx(exact + remainder).epsilon(0.0).margin(1e-13 * std::abs(exact)));
    }
  }
}

// (b) A rigid rotation by theta about a point, taken in one step: x^{n+1} = c + R (x^n - c) and
// u = (x^{n+1} - x^n) / dt. On the mid-step geometry u = (2/dt) (R - I)(R + I)^{-1} (x - c), and
// (R - I)(R + I)^{-1} = tan(theta/2) J (J the quarter turn): the velocity gradient is a pure spin,
// omega = (2/dt) tan(theta/2), with no strain rate. update_zones must then rotate the deviator by
// omega dt = 2 tan(theta/2) (the exact rotation, strength.hpp) and change nothing else: J2 = s:s/2 and
// the trace (0) kept, the out-of-plane component untouched, no plastic strain, the density kept.
// Tolerances: the strain rate is zero up to the round-off of the velocity gradient, |L| 1e-16, which
// the Hooke increment multiplies by 2 mu dt: 2 mu x 2 tan(theta/2) x 1e-16 ~ 3e-6 Pa for mu = 80 GPa;
// against |s| = 2.1e8 Pa that is 1.5e-14, and 1e-12 of |s| leaves a margin of about 70.
TEST_CASE("hydro kernels: a rigid rotation keeps the deviator's invariants", "[hydro][kernel]") {
  const double theta = 0.2;  // rad, in one step
  const double dt = 1.0e-7;  // s
  const Vec2 centre{0.5, 0.4};
  const PerfectlyPlastic strength{80.0e9, 1.0e9};  // Pa; J2 below yield: an elastic step
  const LinearBulk eos{140.0e9, 7850.0};
  const Deviator stress{1.1e8, 2.3e7, -7.7e7, -1.33e8};  // trace-free, general
  const double s_norm = std::sqrt(double_contraction(stress, stress));
  REQUIRE(equivalent_stress(stress) < strength.yield_stress);

  OneZone mesh = one_zone(distorted, GeometryKind::planar, 7850.0, 0.0);
  mesh.state.strength.deviator_xx[0] = stress.xx;
  mesh.state.strength.deviator_yy[0] = stress.yy;
  mesh.state.strength.deviator_xy[0] = stress.xy;
  mesh.state.strength.deviator_zz[0] = stress.zz;
  const double c = std::cos(theta), s = std::sin(theta);
  const quad::Corners start = positions(mesh);
  set_velocities(mesh, [&](Index p) {
    const Vec2 d = start[p] - centre;
    const Vec2 rotated{c * d.x - s * d.y, s * d.x + c * d.y};
    return (1.0 / dt) * (rotated - d);
  });
  move_nodes(mesh, dt);  // x^{n+1}; the zone's corner forces are zero, so the energy does not change

  ZoneUpdateParams update;
  update.time_step_mid = dt;
  update.time_step_next = dt;
  update.shear_modulus = strength.shear_modulus;
  const ZoneUpdateResult result = update_zones<GeometryKind::planar>(
      mesh, mesh.state.hydro, mesh.state.strength, mesh.state.fracture, 0, 1, eos, strength, update);
  REQUIRE(result.failed_zone < 0);

  const Deviator after{mesh.state.strength.deviator_xx[0], mesh.state.strength.deviator_yy[0], mesh.state.strength.deviator_xy[0],
                       mesh.state.strength.deviator_zz[0]};
  const double tolerance = 1e-12 * s_norm;
  CHECK(0.5 * double_contraction(after, after) ==
        Approx(0.5 * double_contraction(stress, stress)).epsilon(0.0).margin(tolerance * s_norm));
  CHECK(std::abs(trace(after)) < tolerance);
  CHECK(after.zz == Approx(stress.zz).epsilon(0.0).margin(tolerance));
  // Rotated, by omega dt = 2 tan(theta/2) (0.2007 rad, not theta: the mid-step spin times dt).
  const Deviator expected = rotate_deviator(stress, 2.0 * std::tan(0.5 * theta));
  CHECK(after.xx == Approx(expected.xx).epsilon(0.0).margin(tolerance));
  CHECK(after.yy == Approx(expected.yy).epsilon(0.0).margin(tolerance));
  CHECK(after.xy == Approx(expected.xy).epsilon(0.0).margin(tolerance));
  CHECK(std::abs(after.xy - stress.xy) > 1e-2 * s_norm);  // it did turn
  CHECK(mesh.state.strength.plastic_strain[0] == 0.0);
  CHECK(mesh.zones.density[0] == Approx(7850.0).epsilon(1e-14));  // a rotation keeps the area
}

// (c) The corner forces of a zone, with every part on (stress with a deviator, edge viscosity on
// compressing edges, viscous and stiffness hourglass), on a distorted zone with an arbitrary velocity
// field:
//   planar: sum_p f_p = 0 (sum_p dA/dx_p = 0; each viscous damper acts in equal and opposite pairs;
//           the hourglass shape vector sums to zero, quad.hpp);
//   RZ control volume: sum_p f_p,z = 0, the zone's axial momentum (docs/theory.md §2 step 1), but the
//           radial forces sum to -sigma_tt A: the hoop stress's pull on the meridional section, since
//           sum_p dV/dr_p = A (moving the zone by dr changes V = integral of r dA by A dr) and the in-plane
//           operators (dA/dx_p, or the r-weighted B_p of a body with strength) sum to zero.
// Tolerance: 1e-13 of the largest corner force (the sums cancel terms of that size).
TEST_CASE("hydro kernels: the corner forces of a zone sum to zero (RZ: axially, and radially to the hoop stress)",
          "[hydro][kernel]") {
  const double pressure = 3.0e8;
  const Deviator stress{1.1e8, 2.3e7, -7.7e7, -1.33e8};
  const std::array<Vec2, 4> velocity{Vec2{40.0, -15.0}, Vec2{-55.0, 10.0}, Vec2{-20.0, -35.0}, Vec2{30.0, 60.0}};

  ZoneForceParams params;  // defaults: edge viscosity with limiter, viscous and stiffness hourglass
  params.shock_slope = 0.75;
  params.shear_modulus = 26.0e9;
  params.previous_time_step = 1.0e-8;

  auto build = [&](bool with_deviator) {
    OneZone mesh = one_zone(distorted, GeometryKind::planar, 2700.0, 0.0);
    mesh.state.hydro.pressure[0] = pressure;
    mesh.state.hydro.sound_speed[0] = 5000.0;
    if (with_deviator) {
      mesh.state.strength.deviator_xx[0] = stress.xx;
      mesh.state.strength.deviator_yy[0] = stress.yy;
      mesh.state.strength.deviator_xy[0] = stress.xy;
      mesh.state.strength.deviator_zz[0] = stress.zz;
    }
    set_velocities(mesh, [&](Index p) { return velocity[static_cast<std::size_t>(p)]; });
    return mesh;
  };
  auto total = [](const OneZone& mesh) {
    Vec2 sum{};
    double largest = 0.0;
    for (std::size_t p = 0; p < 4; ++p) {
      const Vec2 f{mesh.state.hydro.corner_force[2 * p], mesh.state.hydro.corner_force[2 * p + 1]};
      sum += f;
      largest = std::max(largest, norm(f));
    }
    return std::pair{sum, largest};
  };

  SECTION("planar") {
    OneZone mesh = build(true);
    compute_forces<GeometryKind::planar>(mesh, params);
    const auto [sum, largest] = total(mesh);
    CHECK(mesh.state.hydro.viscous_speed[0] > 0.0);  // the viscosity acted
    CHECK((mesh.state.hourglass.hourglass_x[0] != 0.0 && mesh.state.hourglass.hourglass_y[0] != 0.0));  // and the hourglass springs
    CHECK(std::abs(sum.x) < 1e-13 * largest);
    CHECK(std::abs(sum.y) < 1e-13 * largest);
  }

  SECTION("axisymmetric control volume") {
    for (const bool with_deviator : {false, true}) {
      INFO((with_deviator ? "with a deviator (r-weighted operator B_p)" : "a gas (dA/dx_p)"));
      ZoneForceParams form = params;
      if (!with_deviator) form.shear_modulus = 0.0;
      OneZone mesh = build(with_deviator);
      compute_forces<GeometryKind::axisymmetric>(mesh, form);
      const auto [sum, largest] = total(mesh);
      CHECK(mesh.state.hydro.viscous_speed[0] > 0.0);
      CHECK(std::abs(sum.x) < 1e-13 * largest);
      const double hoop = (with_deviator ? stress.zz : 0.0) - pressure;  // sigma_tt
      const double area = quad::area(distorted);
      CHECK(sum.y == Approx(-hoop * area).epsilon(0.0).margin(1e-13 * largest));
      CHECK(std::abs(sum.y) > 0.1 * largest);  // the radial sum is not zero
    }
  }
}

// The stiffness hourglass state of a zone driven in its hourglass mode grows by k mu dt (|b|^2/A) q a
// step; with hourglass.plastic_limit k_p it stops at k_p Y0 |b| (docs/theory.md §2 step 1) and stays
// there, and without the bound it passes it. A square of side h: b_p = dA/dx_p = (+-h/2, +-h/2), so
// |b|^2 = 4 h^2 / 2 and |b| = h sqrt(2), computed here from the corners, not by the kernel.
TEST_CASE("hydro kernels: the hourglass stiffness state stops at the plastic bound", "[hydro][kernel][hourglass]") {
  const double h = 1.0e-3, flow_stress = 3.0e7, speed = 5.0;
  const quad::Corners square{Vec2{0.0, 0.0}, Vec2{h, 0.0}, Vec2{h, h}, Vec2{0.0, h}};
  const double b_norm = std::sqrt(2.0) * h;
  ZoneForceParams params = stress_only();
  params.hourglass.stiffness = 0.05;
  params.shear_modulus = 5.7e9;  // lead
  params.flow_stress = flow_stress;
  params.previous_time_step = 1.0e-7;  // 285 N/m a step (q = 5 m/s): the k_p = 1 bound in 149 steps
  for (const double limit : {1.0, 0.5, 0.0}) {
    INFO("plastic_limit " << limit);
    params.hourglass.plastic_limit = limit;
    OneZone mesh = one_zone(square, GeometryKind::planar, 11340.0, 0.0);
    set_velocities(mesh, [&](Index p) { return Vec2{p % 2 == 0 ? speed : -speed, 0.0}; });  // the hourglass mode
    const double bound = limit * flow_stress * b_norm;
    double largest = 0.0, previous = 0.0;
    bool grew = true;
    for (int step = 0; step < 400; ++step) {
      compute_forces<GeometryKind::planar>(mesh, params);
      const double size = std::hypot(mesh.state.hourglass.hourglass_x[0], mesh.state.hourglass.hourglass_y[0]);
      grew = grew && size >= previous;
      previous = size;
      largest = std::max(largest, size);
      if (limit > 0.0) REQUIRE(size <= bound * (1.0 + 1e-14));
    }
    CHECK(grew);  // the state never shrinks while the mode is driven one way
    if (limit > 0.0) {
      CHECK(largest == Approx(bound).epsilon(1e-14));  // reached, and held there
    } else {
      CHECK(largest > 2.0 * flow_stress * b_norm);  // unbounded: far past the k_p = 1 bound
    }
  }
}

// The physical hourglass stiffness (artificial_forces.hpp, zone_bending) in units of E'/3: a
// rectangle of half-sides a (along x) and b resists the mode's x part by b/a and its y part by a/b, the
// stiffness of its pure bending; rotated, the same tensor rotated; numbered from another corner (its two
// mid-lines exchanged), the same tensor.
TEST_CASE("hydro kernels: the physical hourglass stiffness is the rectangle's bending", "[hydro][kernel][hourglass]") {
  const double a = 2.0e-3, b = 0.5e-3;
  auto corners = [&](double angle, int first) {
    const std::array<Vec2, 4> local{Vec2{-a, -b}, Vec2{a, -b}, Vec2{a, b}, Vec2{-a, b}};
    const double c = std::cos(angle), s = std::sin(angle);
    quad::Corners x;
    for (int p = 0; p < 4; ++p) {
      const Vec2 l = local[static_cast<std::size_t>((p + first) % 4)];
      x[static_cast<std::size_t>(p)] = Vec2{1.0e-3 + c * l.x - s * l.y, 2.0e-3 + s * l.x + c * l.y};
    }
    return x;
  };
  const detail::Bending aligned = detail::zone_bending(corners(0.0, 0), 4.0 * a * b).stiffness;
  CHECK(aligned.xx == Approx(b / a).epsilon(1e-13));
  CHECK(aligned.yy == Approx(a / b).epsilon(1e-13));
  CHECK(std::abs(aligned.xy) < 1e-13);
  for (const double angle : {0.3, 1.1, 2.5}) {
    for (const int first : {0, 1, 2, 3}) {
      INFO("angle " << angle << ", numbered from corner " << first);
      const quad::Corners x = corners(angle, first);
      const detail::Bending k = detail::zone_bending(x, quad::area(x)).stiffness;
      const double c = std::cos(angle), s = std::sin(angle);
      CHECK(k.xx == Approx(c * c * b / a + s * s * a / b).epsilon(1e-12));
      CHECK(k.yy == Approx(s * s * b / a + c * c * a / b).epsilon(1e-12));
      CHECK(k.xy == Approx(c * s * (b / a - a / b)).epsilon(1e-12));
    }
  }
  // In the kernel: one step of the x-mode rate q on the aligned rectangle adds (E'/3)(b/a) dt q to the state.
  ZoneForceParams params = stress_only();
  params.hourglass.stiffness_form = HourglassStiffness::physical;
  params.shear_modulus = 26.0e9;
  params.bending_modulus = 75.0e9;
  params.flow_stress = std::numeric_limits<double>::infinity();
  params.previous_time_step = 1.0e-9;
  OneZone mesh = one_zone(corners(0.0, 0), GeometryKind::planar, 2700.0, 0.0);
  const double speed = 3.0;
  set_velocities(mesh, [&](Index p) { return Vec2{p % 2 == 0 ? speed : -speed, 0.0}; });
  compute_forces<GeometryKind::planar>(mesh, params);
  const double q = 2.0 * speed;  // sum_p gamma_p u_p, gamma = h / 2 on a rectangle
  CHECK(mesh.state.hourglass.hourglass_x[0] == Approx(75.0e9 / 3.0 * (b / a) * 1.0e-9 * q).epsilon(1e-12));
  CHECK(mesh.state.hourglass.hourglass_y[0] == 0.0);
  // Driven on, the state stops at k_p times the rectangle's fully plastic bending, Y' b along x and Y' a
  // along y (Y' = 2 Y0 / sqrt(3)), and stays there.
  params.flow_stress = 2.8e8;
  params.previous_time_step = 1.0e-8;  // the x-mode bound in about 430 steps, the y-mode one in about 110
  const double plastic = 2.0 / std::sqrt(3.0) * 2.8e8;
  for (const bool along_x : {true, false}) {
    for (const double limit : {1.0, 0.5}) {
      INFO((along_x ? "x" : "y") << " mode, plastic_limit " << limit);
      params.hourglass.plastic_limit = limit;
      OneZone driven = one_zone(corners(0.0, 0), GeometryKind::planar, 2700.0, 0.0);
      set_velocities(driven, [&](Index p) {
        const double v = p % 2 == 0 ? speed : -speed;
        return along_x ? Vec2{v, 0.0} : Vec2{0.0, v};
      });
      double largest = 0.0;
      for (int step = 0; step < 2000; ++step) {
        compute_forces<GeometryKind::planar>(driven, params);
        largest = std::max(largest, std::hypot(driven.state.hourglass.hourglass_x[0], driven.state.hourglass.hourglass_y[0]));
      }
      const double bound = limit * plastic * (along_x ? b : a);
      CHECK(largest == Approx(bound).epsilon(1e-12));
      CHECK(std::hypot(driven.state.hourglass.hourglass_x[0], driven.state.hourglass.hourglass_y[0]) ==
            Approx(bound).epsilon(1e-12));
    }
  }
}

// The tensor viscosity (Campbell & Shashkov 2001) alone on the distorted zone, compressed and sheared
// (one zone: no continuing edges, so the limiter is 0 and the viscosity fully on): its side forces are
// equal and opposite (the corner forces sum to zero, also in RZ), and it only dissipates: the work rate
// sum_p f_p . u_p is negative and equal to minus the booked viscous power, to round-off.
TEST_CASE("hydro kernels: the tensor viscosity conserves momentum and dissipates", "[hydro][kernel]") {
  const Vec2 centre = quad::centre(distorted);
  for (const GeometryKind geometry : {GeometryKind::planar, GeometryKind::axisymmetric}) {
    INFO((geometry == GeometryKind::planar ? "planar" : "axisymmetric control volume"));
    OneZone mesh = one_zone(distorted, geometry, 1.3, 0.0);
    mesh.state.hydro.sound_speed[0] = 0.7;
    set_velocities(mesh, [&](Index p) {
      const Vec2 d = distorted[static_cast<std::size_t>(p)] - centre;
      return Vec2{-1.5 * d.x + 0.4 * d.y, -0.8 * d.y - 0.3 * d.x};  // compression with shear and rotation
    });
    ZoneForceParams params = stress_only();
    params.viscosity.model = ViscosityModel::tensor;
    params.shock_slope = 1.6667 / 2.0;
    ZoneState& z = mesh.state;
    const ArtificialPower power =
        geometry == GeometryKind::planar
            ? compute_corner_forces<GeometryKind::planar, ViscosityModel::tensor>(mesh, z.hydro, z.strength, z.hourglass,
                                                                                  z.fracture, 0, 1, params)
            : compute_corner_forces<GeometryKind::axisymmetric, ViscosityModel::tensor>(
                  mesh, z.hydro, z.strength, z.hourglass, z.fracture, 0, 1, params);
    Vec2 sum{};
    double largest = 0.0;
    for (std::size_t p = 0; p < 4; ++p) {
      const Vec2 f{z.hydro.corner_force[2 * p], z.hydro.corner_force[2 * p + 1]};
      sum += f;
      largest = std::max(largest, norm(f));
    }
    CHECK(largest > 0.0);
    CHECK(z.hydro.viscous_speed[0] > 0.0);
    CHECK(std::abs(sum.x) < 1e-14 * largest);
    CHECK(std::abs(sum.y) < 1e-14 * largest);
    const double rate = corner_power(mesh);
    CHECK(rate < 0.0);
    CHECK(power.viscous == Approx(-rate).epsilon(1e-13));
  }
}

// The corner-collapse pressure (hourglass.collapse_pressure k, collapse_threshold theta;
// artificial_forces.hpp): on a unit square of density rho whose corner regions of the median mesh keep
// their initial masses rho / 4, a corner whose region's density rho_p exceeds theta rho pushes with
// dp = k c^2 (rho_p - theta rho) through dV(S_p)/dx_q. The expected forces here come from the region's
// area by central differences of the shoelace formula (exact to round-off: the area is quadratic in
// the positions), not from the kernel's corner-region algebra. No pressure, viscosity or hourglass
// control: the corner forces are the collapse pressure's alone.
TEST_CASE("hydro kernels: the corner-collapse pressure acts past its threshold only, against the fold",
          "[hydro][kernel][hourglass]") {
  const double rho0 = 1000.0, c = 1000.0, k = 1.0, theta = 1.5;
  const quad::Corners square{Vec2{0.0, 0.0}, Vec2{1.0, 0.0}, Vec2{1.0, 1.0}, Vec2{0.0, 1.0}};
  auto region_area = [](const quad::Corners& x, int p) {
    const Vec2 centre = 0.25 * (x[0] + x[1] + x[2] + x[3]);
    const Vec2 a = x[static_cast<std::size_t>(p)];
    const Vec2 b = 0.5 * (a + x[static_cast<std::size_t>((p + 1) % 4)]);
    const Vec2 d = 0.5 * (a + x[static_cast<std::size_t>((p + 3) % 4)]);
    const std::array<Vec2, 4> v{a, b, centre, d};
    double twice = 0.0;
    for (std::size_t i = 0; i < 4; ++i) twice += v[i].x * v[(i + 1) % 4].y - v[(i + 1) % 4].x * v[i].y;
    return 0.5 * twice;
  };
  // The zone with its corner 2 moved to `moved` (its mass unchanged: the density from the new area).
  auto build = [&](Vec2 moved) {
    quad::Corners x = square;
    x[2] = moved;
    OneZone mesh = one_zone(x, GeometryKind::planar, rho0 / quad::area(x), 0.0);
    for (std::size_t p = 0; p < 4; ++p) mesh.zones.subzone_mass[p] = 0.25 * rho0;
    mesh.state.hydro.sound_speed[0] = c;
    return mesh;
  };
  ZoneForceParams params = stress_only();
  params.hourglass.collapse_pressure = k;
  params.hourglass.collapse_threshold = theta;
  auto force = [](const OneZone& mesh, std::size_t p) {
    return Vec2{mesh.state.hydro.corner_force[2 * p], mesh.state.hydro.corner_force[2 * p + 1]};
  };

  SECTION("a corner pushed in, its region below theta times the zone's density: no force at all") {
    OneZone mesh = build({0.8, 0.8});
    const double ratio = 0.25 * rho0 / region_area(positions(mesh), 2) / mesh.zones.density[0];
    INFO("corner 2's density over the zone's " << ratio);
    REQUIRE(ratio > 1.0);   // the corner is compressed beyond the zone's mean
    REQUIRE(ratio < theta); // but inside the dead band
    compute_forces<GeometryKind::planar>(mesh, params);
    for (std::size_t p = 0; p < 4; ++p) CHECK((force(mesh, p).x == 0.0 && force(mesh, p).y == 0.0));
  }

  SECTION("a corner folded into its zone (a dart, the corner reflex): the region's pressure pushes it out") {
    OneZone mesh = build({0.45, 0.45});
    const quad::Corners x = positions(mesh);
    const double rho = mesh.zones.density[0];
    std::array<double, 4> dp{};
    for (int p = 0; p < 4; ++p) {
      const double rho_p = 0.25 * rho0 / region_area(x, p);
      dp[static_cast<std::size_t>(p)] = rho_p > theta * rho ? k * c * c * (rho_p - theta * rho) : 0.0;
    }
    INFO("dp " << dp[0] << " " << dp[1] << " " << dp[2] << " " << dp[3]);
    REQUIRE(dp[2] > 0.0);  // the folded corner is past the threshold
    compute_forces<GeometryKind::planar>(mesh, params);
    const double h = 1e-4;
    Vec2 sum{0.0, 0.0};
    for (int q = 0; q < 4; ++q) {
      Vec2 expected{0.0, 0.0};
      for (int p = 0; p < 4; ++p) {
        quad::Corners plus = x, minus = x;
        plus[static_cast<std::size_t>(q)].x += h;
        minus[static_cast<std::size_t>(q)].x -= h;
        expected.x += dp[static_cast<std::size_t>(p)] * (region_area(plus, p) - region_area(minus, p)) / (2.0 * h);
        plus = x;
        minus = x;
        plus[static_cast<std::size_t>(q)].y += h;
        minus[static_cast<std::size_t>(q)].y -= h;
        expected.y += dp[static_cast<std::size_t>(p)] * (region_area(plus, p) - region_area(minus, p)) / (2.0 * h);
      }
      const Vec2 f = force(mesh, static_cast<std::size_t>(q));
      INFO("node " << q << ": force (" << f.x << ", " << f.y << ") against (" << expected.x << ", " << expected.y << ")");
      CHECK(f.x == Approx(expected.x).epsilon(1e-9).margin(1e-9 * dp[2]));
      CHECK(f.y == Approx(expected.y).epsilon(1e-9).margin(1e-9 * dp[2]));
      sum += f;
    }
    // Momentum: the forces of a zone sum to zero. The folded corner is pushed back out, along (1, 1).
    CHECK(std::abs(sum.x) < 1e-12 * dp[2]);
    CHECK(std::abs(sum.y) < 1e-12 * dp[2]);
    CHECK(force(mesh, 2).x > 0.0);
    CHECK(force(mesh, 2).y > 0.0);
  }

  SECTION("off (the default): no force for the same dart") {
    OneZone mesh = build({0.45, 0.45});
    compute_forces<GeometryKind::planar>(mesh, stress_only());
    for (std::size_t p = 0; p < 4; ++p) CHECK((force(mesh, p).x == 0.0 && force(mesh, p).y == 0.0));
  }
}

// ViscosityModel::automatic, a run's default (Controls), resolves by the body's strength and the geometry
// (parameters.hpp, body_viscosity): the tensor viscosity with the corner-collapse pressure only for an
// axisymmetric body without strength; a named model applies to every body, and a collapse pressure given
// overrides the automatic one.
TEST_CASE("hydro parameters: each body's viscosity model and corner-collapse pressure", "[hydro][viscosity]") {
  constexpr GeometryKind rz = GeometryKind::axisymmetric, xy = GeometryKind::planar;
  ViscosityParams viscosity;
  HourglassParams hourglass;
  viscosity.model = ViscosityModel::automatic;
  for (const GeometryKind g : {rz, xy}) {
    CHECK(body_viscosity(viscosity, hourglass, true, g).model == ViscosityModel::edge);
    CHECK(body_viscosity(viscosity, hourglass, true, g).collapse_pressure == 0.0);
  }
  CHECK(body_viscosity(viscosity, hourglass, false, rz).model == ViscosityModel::tensor);
  CHECK(body_viscosity(viscosity, hourglass, false, rz).collapse_pressure == automatic_collapse_pressure);
  CHECK(body_viscosity(viscosity, hourglass, false, xy).model == ViscosityModel::edge);
  CHECK(body_viscosity(viscosity, hourglass, false, xy).collapse_pressure == 0.0);
  hourglass.collapse_pressure = 0.25;
  CHECK(body_viscosity(viscosity, hourglass, false, rz).collapse_pressure == 0.25);
  CHECK(body_viscosity(viscosity, hourglass, false, xy).collapse_pressure == 0.25);
  CHECK(body_viscosity(viscosity, hourglass, true, rz).collapse_pressure == 0.25);
  hourglass.collapse_pressure.reset();
  for (const ViscosityModel named : {ViscosityModel::edge, ViscosityModel::scalar, ViscosityModel::tensor, ViscosityModel::off}) {
    viscosity.model = named;
    for (const bool strength : {true, false}) {
      for (const GeometryKind g : {rz, xy}) {
        CHECK(body_viscosity(viscosity, hourglass, strength, g).model == named);
        CHECK(body_viscosity(viscosity, hourglass, strength, g).collapse_pressure == 0.0);
      }
    }
  }
}
