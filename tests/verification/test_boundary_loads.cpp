// B1-B3 of docs/verification.md ("Boundary loads and velocities in time"): boundary loads and a velocity given as a function of time, against
// d'Alembert's solution for plane waves in uniaxial strain (J. D. Achenbach, Wave Propagation in
// Elastic Solids, North-Holland 1973, ch. 2): in a linear elastic half-space at rest, a face driven at
// v(t) launches u(x, t) = v(t - x / c_L), sigma_xx = -rho c_L u, with c_L = sqrt((K + 4G/3) / rho);
// a pressure step P launches sigma_xx = -P, u = P / (rho c_L) behind a front at c_L t.
//
//   pressure_step.json               planar strip, slip walls, 10 MPa on x_min
//   pressure_step_axisymmetric.json  RZ cylinder, slip on r_max (still uniaxial strain), 10 MPa on z_min
//   ramp_piston.json                 planar strip, x_min driven at 1 m/s min(t / 2 us, 1)
//   (inline)                         B4 a spherical cavity under a pressure step, B5 a traction step in plane shear
//
// The solid is linear only to first order (p = K (rho/rho0 - 1), a hypoelastic deviator): at the
// strains here (u / c_L < 1e-4) its departure from the linear answer is of that relative order.
#include <catch2/catch.hpp>

#include <cmath>

#include "test_solid_measures.hpp"

using namespace krug;
using namespace krug::verification;
using namespace krug::verification::solid;

namespace {

// The solid of the three examples.
constexpr double density = 2700.0, bulk_modulus = 7.0e10, shear_modulus = 2.6e10;
const double wave_speed = std::sqrt((bulk_modulus + 4.0 * shear_modulus / 3.0) / density);  // c_L = 6226.19 m/s
constexpr double strip_length = 0.1;
constexpr int strip_zones = 500;
constexpr double dx = strip_length / strip_zones;

// The ledgers with the load or the driven face: energy to round-off, mass exact, axial momentum
// changed by exactly the boundary impulse.
void check_ledgers(const Simulation& sim) {
  const Ledger& ledger = sim.ledger();
  INFO("energy drift " << ledger.relative_energy_drift() << ", W_boundary " << ledger.energy.boundary << " J, impulse "
                       << ledger.axial_boundary_impulse);
  CHECK(ledger.energy.boundary > 0.0);  // the load does work on the body
  CHECK(ledger.relative_energy_drift() < 1e-12);
  CHECK(ledger.relative_mass_error() == 0.0);
  CHECK(std::abs(ledger.axial_momentum - ledger.initial_axial_momentum - ledger.axial_boundary_impulse) <
        1e-12 * std::abs(ledger.axial_boundary_impulse));
}

// A pressure step: the plateau behind the front and the front's position.
void check_pressure_step(const std::string& file, const std::string& problem) {
  const scenario::Scenario scenario = load_example(file);
  Run run(scenario.setup);
  advance(run);
  INFO(run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const double pressure = 1.0e7;
  const double velocity = pressure / (density * wave_speed);  // 0.59486 m/s
  const std::vector<StripZone> strip = strip_profile(sim, sim.bodies()[0]);
  // Velocities are at t^{n+1/2} = t - dt/2 (the stored half step), stresses at t.
  const double t_velocity = sim.time() - 0.5 * sim.last_time_step();
  const double front = velocity_front(strip, 0.5 * velocity);
  INFO(problem << ": front " << front << " m, exact " << wave_speed * t_velocity << " m");
  // A captured jump is centred on its mid-level: within 2 zones of c_L t (the E3 criterion; measured
  // -0.23 zones planar and RZ).
  CHECK(std::abs(front - wave_speed * t_velocity) < 2.0 * dx);

  // The plateau from 10 zones behind the face to 20 zones behind the front (clear of the jump's
  // smeared structure and of its ringing's first periods). Within 1e-3: the model's departure from
  // linearity is O(u / c_L) = 1e-4 (measured +1.3e-4 in sigma_xx, +1.1e-4 in u, planar and RZ).
  const UniaxialState reference{density, 0.0, 0.0, -pressure, velocity, wave_speed};
  const StripPlateau plateau = strip_plateau(strip, 10 * dx, front - 20 * dx, reference);
  REQUIRE(plateau.zones > 200);
  INFO(problem << " plateau (" << plateau.zones << " zones): sigma_xx " << plateau.mean.stress_xx << " Pa, u "
               << plateau.mean.velocity << " m/s; largest velocity deviation " << plateau.largest_velocity_deviation);
  CHECK(plateau.mean.stress_xx == Approx(-pressure).epsilon(1e-3));
  CHECK(plateau.mean.velocity == Approx(velocity).epsilon(1e-3));
  report(problem, "plateau sigma_xx (Pa)", "-1e7", plateau.mean.stress_xx,
         format_number("%+.1e", plateau.mean.stress_xx / -pressure - 1.0), sim.mesh().zones.size(), run.seconds);
  report(problem, "plateau u (m/s)", "0.59486", plateau.mean.velocity,
         format_number("%+.1e", plateau.mean.velocity / velocity - 1.0), sim.mesh().zones.size(), run.seconds);
  report(problem, "front at 10 us (m)", format_number("%.5f", wave_speed * t_velocity), front,
         format_number("%+.2f zones", (front - wave_speed * t_velocity) / dx), sim.mesh().zones.size(), run.seconds);
  check_ledgers(sim);
}

}  // namespace

TEST_CASE("B1 pressure step on an elastic half-space, planar: plateau, front, ledgers", "[B1][boundary]") {
  check_pressure_step("pressure_step.json", "B1 pressure step, planar");
}

TEST_CASE("B2 pressure step on the end of an elastic cylinder, RZ: plateau, front, ledgers", "[B2][boundary]") {
  check_pressure_step("pressure_step_axisymmetric.json", "B2 pressure step, RZ");
  // Uniaxial strain in RZ: every row carries the same wave (no radial motion of the slip-walled cylinder).
  const scenario::Scenario scenario = load_example("pressure_step_axisymmetric.json");
  Run run(scenario.setup);
  advance(run);
  REQUIRE(run.completed());
  const NodeFields& nodes = run.simulation.mesh().nodes;
  double largest_radial = 0.0, largest_axial = 0.0;
  for (Index p = 0; p < nodes.size(); ++p) {
    largest_radial = std::max(largest_radial, std::abs(nodes.v[p]));
    largest_axial = std::max(largest_axial, std::abs(nodes.u[p]));
  }
  INFO("largest |u_r| " << largest_radial << " m/s, largest |u_z| " << largest_axial << " m/s");
  CHECK(largest_radial < 1e-6 * largest_axial);  // measured 1.3e-8 (round-off of the r-weighted forces)
}

TEST_CASE("B3 piston driven by a velocity ramp v(t): the ramp translated at c_L, sigma = -rho c_L v, ledgers",
          "[B3][boundary]") {
  const scenario::Scenario scenario = load_example("ramp_piston.json");
  constexpr double speed = 1.0, rise = 2.0e-6;
  auto piston = [&](double t) { return speed * std::clamp(t / rise, 0.0, 1.0); };
  Run run(scenario.setup);
  // The stress of the zone at the face during the ramp: its centre (dx/2) sees v(t - dx / (2 c_L)).
  double face_stress = 0.0, face_exact = 0.0;
  advance(run, [&](const Simulation& sim) {
    if (face_exact == 0.0 && sim.time() >= 0.5 * rise) {
      const StripZone first = strip_profile(sim, sim.bodies()[0]).front();
      face_stress = first.stress_xx();
      face_exact = -density * wave_speed * piston(sim.time() - first.position / wave_speed);
    }
  });
  INFO(run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const std::vector<StripZone> strip = strip_profile(sim, sim.bodies()[0]);
  const double t_velocity = sim.time() - 0.5 * sim.last_time_step();

  // The face: the driven nodes move at v(t^{n+1/2}) exactly, and the face's zone carries -rho c_L v.
  const NodeFields& nodes = sim.mesh().nodes;
  int driven = 0;
  for (Index p = 0; p < nodes.size(); ++p) {
    if (nodes.x0[p] != 0.0) continue;
    ++driven;
    CHECK(nodes.u[p] == speed);
  }
  CHECK(driven == 2);
  INFO("face zone sigma_xx at t = 1 us: " << face_stress << " Pa, exact " << face_exact << " Pa");
  CHECK(face_stress == Approx(face_exact).epsilon(1e-3));  // measured +2.6e-5

  // The ramp's position: its mid-level crossing at c_L (t - rise / 2).
  const double middle = velocity_front(strip, 0.5 * speed);
  const double middle_exact = wave_speed * (t_velocity - 0.5 * rise);
  INFO("ramp middle " << middle << " m, exact " << middle_exact << " m");
  CHECK(std::abs(middle - middle_exact) < 0.5 * dx);  // measured +0.02 zones

  // The shape: every zone against v(t - x / c_L), and the stress plateau behind the ramp.
  double largest = 0.0, l1 = 0.0, exact_l1 = 0.0;
  for (const StripZone& z : strip) {
    const double exact = piston(t_velocity - z.position / wave_speed);
    largest = std::max(largest, std::abs(z.velocity - exact));
    l1 += std::abs(z.velocity - exact);
    exact_l1 += std::abs(exact);
  }
  INFO("largest |u - v(t - x/c_L)| " << largest << " m/s; L1 error / L1 norm " << l1 / exact_l1);
  // The kinks at the ramp's foot and top are rounded over a few zones (largest error there, measured
  // 1.4e-2 of v); elsewhere the ramp is carried exactly (L1 measured 5.8e-4).
  CHECK(largest < 0.02 * speed);
  CHECK(l1 / exact_l1 < 2e-3);
  const UniaxialState reference{density, 0.0, 0.0, -density * wave_speed * speed, speed, wave_speed};
  const double top = wave_speed * (t_velocity - rise);  // the ramp's top
  const StripPlateau plateau = strip_plateau(strip, 10 * dx, top - 10 * dx, reference);
  REQUIRE(plateau.zones > 200);
  INFO("plateau (" << plateau.zones << " zones): sigma_xx " << plateau.mean.stress_xx << " Pa (exact "
                   << reference.stress_xx << "), u " << plateau.mean.velocity);
  CHECK(plateau.mean.stress_xx == Approx(reference.stress_xx).epsilon(1e-3));  // measured +6.1e-5
  CHECK(plateau.mean.velocity == Approx(speed).epsilon(1e-3));
  report("B3 ramp piston", "plateau sigma_xx (Pa)", "-1.68107e7", plateau.mean.stress_xx,
         format_number("%+.1e", plateau.mean.stress_xx / reference.stress_xx - 1.0), strip_zones, run.seconds);
  report("B3 ramp piston", "ramp middle at 10 us (m)", format_number("%.5f", middle_exact), middle,
         format_number("%+.2f zones", (middle - middle_exact) / dx), strip_zones, run.seconds);
  report("B3 ramp piston", "largest |u - v(t - x/c_L)| (m/s)", "0", largest, format_number("%.1e of v", largest / speed),
         strip_zones, run.seconds);
  check_ledgers(sim);
}

// B4: a spherical cavity of radius a in an elastic solid, a pressure step p0 on its wall (the RZ
// meridian quarter: the axis holds u_r, z = 0 is a symmetry plane, the outer radius is beyond the
// front). The classical solution (Blake 1952; Achenbach 1973, Wave Propagation in Elastic Solids,
// the pressurised spherical cavity), derived here from the potential phi = f(tau) / R, tau = t - (R - a) / c_L:
// sigma_RR = rho f'' / R - 4 mu u / R with u = phi_R, and sigma_RR(a) = -p0 gives
//   f'' + 2 alpha f' + omega0^2 f = -p0 a / rho,  alpha = 2 c_S^2 / (c_L a),  omega0 = 2 c_S / a,
// at rest before tau = 0: f = f_s [1 - e^{-alpha tau} (cos w tau + (alpha / w) sin w tau)],
// f_s = -p0 a^3 / (4 mu), w = sqrt(omega0^2 - alpha^2); the radial velocity is
//   v(R, t) = -f''(tau) / (c_L R) - f'(tau) / R^2   (0 ahead of the front, tau < 0),
// a jump of p0 a / (rho c_L R) at the front that rings down to the static expansion.
TEST_CASE("B4 spherical cavity under a pressure step: the radial velocity against the closed form", "[B4][boundary]") {
  constexpr double a = 0.01, outer = 0.06, p0 = 1.0e7, end_time = 6.0e-6;
  constexpr int radial_zones = 250;  // and 30 zones over the quarter
  const std::string text = R"({
    "title": "B4: spherical cavity under a pressure step", "geometry": "axisymmetric", "end_time": 6.0e-6,
    "materials": { "elastic": { "density": 2700.0, "eos": { "model": "linear", "bulk_modulus": 7.0e10 },
                                "strength": { "model": "elastic", "shear_modulus": 2.6e10 } } },
    "bodies": [ { "name": "solid", "material": "elastic",
                  "mesh": { "type": "sector", "radius": { "from": 0.01, "to": 0.06, "zones": 250 },
                            "angle": { "from": 0.0, "to": 90.0, "zones": 30 } },
                  "boundary": { "inner": { "type": "pressure", "pressure": 1.0e7 }, "end": "symmetry" } } ]
  })";
  const scenario::Scenario scenario = scenario::parse_scenario(text, "b4.json");
  Run run(scenario.setup);
  advance(run);
  INFO(run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  REQUIRE(sim.time() == Approx(end_time));

  const double shear_speed = std::sqrt(shear_modulus / density);
  const double alpha = 2.0 * shear_speed * shear_speed / (wave_speed * a), omega0 = 2.0 * shear_speed / a;
  const double w = std::sqrt(omega0 * omega0 - alpha * alpha);
  const double f_static = -p0 * a * a * a / (4.0 * shear_modulus);
  auto exact = [&](double radius, double t) {
    const double tau = t - (radius - a) / wave_speed;
    if (tau <= 0.0) return 0.0;
    const double decay = std::exp(-alpha * tau);
    const double f1 = f_static * omega0 * omega0 / w * decay * std::sin(w * tau);
    const double f2 = f_static * omega0 * omega0 / w * decay * (w * std::cos(w * tau) - alpha * std::sin(w * tau));
    return -f2 / (wave_speed * radius) - f1 / (radius * radius);
  };
  const double t_velocity = sim.time() - 0.5 * sim.last_time_step();
  const double front = a + wave_speed * t_velocity;
  const double dr = (outer - a) / radial_zones;
  // Every node behind the front (clear of its smeared jump by 15 zones) and off the wall by 2 zones:
  // its radial velocity against v at its initial radius (the displacements are below 1e-6 m).
  const NodeFields& nodes = sim.mesh().nodes;
  double error = 0.0, norm_exact = 0.0, largest = 0.0, peak = 0.0;
  int count = 0;
  for (Index p = 0; p < nodes.size(); ++p) {
    const Vec2 x0{nodes.x0[p], nodes.y0[p]};
    const double radius = norm(x0);
    if (radius < a + 2.0 * dr || radius > front - 15.0 * dr) continue;
    const double radial = dot(nodes.velocity(p), (1.0 / radius) * x0);
    const double reference = exact(radius, t_velocity);
    error += std::abs(radial - reference);
    norm_exact += std::abs(reference);
    largest = std::max(largest, std::abs(radial - reference));
    peak = std::max(peak, std::abs(reference));
    ++count;
  }
  REQUIRE(count > 1000);
  INFO(count << " nodes: L1 error / L1 norm " << error / norm_exact << ", largest error " << largest
             << " m/s, largest exact velocity " << peak << " m/s; the jump at the front " << p0 * a / (density * wave_speed * front)
             << " m/s");
  // Measured: L1 4.5e-3, largest 3.7e-2 of the peak (250 x 30 zones).
  CHECK(error / norm_exact < 1e-2);
  CHECK(largest < 0.05 * peak);
  report("B4 spherical cavity", "L1 error of u_R behind the front / L1 norm", "0", error / norm_exact,
         format_number("%.1e", error / norm_exact), sim.mesh().zones.size(), run.seconds);
  report("B4 spherical cavity", "largest error of u_R behind the front (m/s)", "0", largest,
         format_number("%.1e of the peak", largest / peak), sim.mesh().zones.size(), run.seconds);
  check_ledgers(sim);
}

// B5: a traction step on the face of a half-space in plane shear: the strip of B1 with its long sides
// holding u_x = 0 (they supply the sigma_xy of a plane shear wave there; sigma_yy = 0 in it) and a
// traction tau on x_min. Exact (Achenbach 1973, ch. 2, the transverse wave): v_y = f(t - x / c_S),
// sigma_xy = -rho c_S v_y; the face's traction gives sigma_xy = tau behind the front at c_S t. The
// traction points along the side traversed counter-clockwise about the body: -y on x_min, so tau =
// -10 MPa pulls the face towards +y and v_y = -tau / (rho c_S) = 1.1935 m/s.
TEST_CASE("B5 traction step on a half-space in plane shear: the shear plateau and front", "[B5][boundary]") {
  const std::string text = R"({
    "title": "B5: traction step, plane shear", "geometry": "planar", "end_time": 1.0e-5,
    "materials": { "elastic": { "density": 2700.0, "eos": { "model": "linear", "bulk_modulus": 7.0e10 },
                                "strength": { "model": "elastic", "shear_modulus": 2.6e10 } } },
    "bodies": [ { "name": "strip", "material": "elastic",
                  "mesh": { "type": "rectangle", "x": { "from": 0.0, "to": 0.1, "zones": 500 },
                            "y": { "from": 0.0, "to": 0.0002, "zones": 1 } },
                  "boundary": { "x_min": { "type": "traction", "traction": -1.0e7 },
                                "y_min": { "type": "velocity", "velocity": [0.0, null] },
                                "y_max": { "type": "velocity", "velocity": [0.0, null] } } } ]
  })";
  const scenario::Scenario scenario = scenario::parse_scenario(text, "b5.json");
  Run run(scenario.setup);
  advance(run);
  INFO(run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const double traction = -1.0e7;
  const double shear_speed = std::sqrt(shear_modulus / density);
  const double velocity = -traction / (density * shear_speed);
  const double t_velocity = sim.time() - 0.5 * sim.last_time_step();
  // Per zone: centre x, mean v_y of its corners, sigma_xy.
  struct Sample {
    double x, v, shear;
  };
  std::vector<Sample> strip;
  const Mesh& mesh = sim.mesh();
  const ZoneState& zone_state = sim.zone_state();
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    const ZoneCorners& c = mesh.zones.corners[z];
    double x = 0.0, v = 0.0;
    for (const Index n : c) {
      x += 0.25 * mesh.nodes.x[n];
      v += 0.25 * mesh.nodes.v[n];
    }
    strip.push_back({x, v, zone_state.strength.deviator_xy[z]});
  }
  std::sort(strip.begin(), strip.end(), [](const Sample& a, const Sample& b) { return a.x < b.x; });
  double front = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = strip.size() - 1; k > 0; --k) {
    const double a = strip[k - 1].v - 0.5 * velocity, b = strip[k].v - 0.5 * velocity;
    if ((a >= 0.0) != (b >= 0.0)) {
      front = strip[k - 1].x + a / (a - b) * (strip[k].x - strip[k - 1].x);
      break;
    }
  }
  INFO("shear front " << front << " m, exact " << shear_speed * t_velocity << " m");
  // Within 2 zones (measured -1.04: the shear front is captured without viscosity, which acts on
  // compression only, and its ringing leads the mid-level crossing back).
  CHECK(std::abs(front - shear_speed * t_velocity) < 2.0 * dx);
  double mean_v = 0.0, mean_shear = 0.0;
  int count = 0;
  for (const Sample& s : strip) {
    if (s.x < 10 * dx || s.x > front - 20 * dx) continue;
    mean_v += s.v;
    mean_shear += s.shear;
    ++count;
  }
  REQUIRE(count > 100);
  mean_v /= count;
  mean_shear /= count;
  INFO("plateau (" << count << " zones): v_y " << mean_v << " m/s (exact " << velocity << "), sigma_xy " << mean_shear
                   << " Pa (exact " << traction << ")");
  // Within 1e-3, as B1 (measured -1.4e-4 in v_y, -3.8e-4 in sigma_xy).
  CHECK(mean_v == Approx(velocity).epsilon(1e-3));
  CHECK(mean_shear == Approx(traction).epsilon(1e-3));
  report("B5 traction step", "plateau sigma_xy (Pa)", "-1e7", mean_shear, format_number("%+.1e", mean_shear / traction - 1.0),
         sim.mesh().zones.size(), run.seconds);
  report("B5 traction step", "plateau v_y (m/s)", format_number("%.5f", velocity), mean_v,
         format_number("%+.1e", mean_v / velocity - 1.0), sim.mesh().zones.size(), run.seconds);
  report("B5 traction step", "front at 10 us (m)", format_number("%.5f", shear_speed * t_velocity), front,
         format_number("%+.2f zones", (front - shear_speed * t_velocity) / dx), sim.mesh().zones.size(), run.seconds);
  // The ledgers: the traction's work, and the held sides' (which do none: u_x = 0 there).
  const Ledger& ledger = sim.ledger();
  INFO("energy drift " << ledger.relative_energy_drift() << ", W_boundary " << ledger.energy.boundary);
  CHECK(ledger.energy.boundary > 0.0);
  CHECK(ledger.relative_energy_drift() < 1e-12);
}

// The boundary package keeps no state over a run: a run with a load and one with a velocity in time
// restart from Simulation::state() exactly (the same bits as the run that did not stop).
TEST_CASE("runs with a pressure load or a velocity in time restart exactly", "[boundary]") {
  for (const char* file : {"pressure_step.json", "ramp_piston.json"}) {
    INFO(file);
    const scenario::Scenario scenario = load_example(file);
    Simulation straight(scenario.setup);
    for (int k = 0; k < 150; ++k) straight.step();
    const SimulationState halfway = straight.state();
    for (int k = 0; k < 150; ++k) straight.step();
    Simulation restarted(scenario.setup);
    restarted.restore(halfway);
    for (int k = 0; k < 150; ++k) restarted.step();
    CHECK(restarted.mesh().nodes.u == straight.mesh().nodes.u);
    CHECK(restarted.mesh().nodes.x == straight.mesh().nodes.x);
    CHECK(restarted.ledger().energy.boundary == straight.ledger().energy.boundary);
    CHECK(restarted.ledger().axial_boundary_impulse == straight.ledger().axial_boundary_impulse);
  }
}
