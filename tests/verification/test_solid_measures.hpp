#pragma once
// Measures of the solid-mechanics verification problems (verification.md E3-E7), shared by the
// default-resolution tests (test_solid_*.cpp) and the convergence studies (convergence_solid.cpp):
// exact uniaxial-strain states, fronts and plateaux along a strip, yield-surface checks, and the
// Taylor bar's length and impact-face radius.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "krug/material/strength.hpp"
#include "verification_support.hpp"

namespace krug::verification::solid {

// ---- uniaxial strain ---------------------------------------------------------------------------

// One state behind a wave in uniaxial strain (x the strain direction), relative to the material at
// rest ahead of the waves: density, pressure, axial deviator, axial Cauchy stress, particle velocity
// and the front's speed (lab frame: relative to the material at rest ahead of both waves).
struct UniaxialState {
  double density, pressure, deviator_xx, stress_xx, velocity, front_speed;
};

// E3 (verification.md table): copper, Mie-Grueneisen c0 3940 m/s, s 1.49, Gamma0 2, mu 45 GPa,
// Y 90 MPa, piston 20 m/s. The exact solution of the model: the elastic precursor carries the
// material to the yield density rho0 exp(Y / (2 mu)) (hypoelastic uniaxial strain gives
// s_xx = -(4/3) mu ln(rho/rho0), which reaches -2Y/3 there); both waves satisfy the Rankine-Hugoniot
// jump conditions with the Mie-Grueneisen energy; the plastic wave brings the material to the piston
// speed. Re-derived independently (bisection on the plastic jump) to the table's digits.
namespace piston {
inline constexpr double reference_density = 8930.0, shear_modulus = 4.5e10, yield_stress = 9.0e7;
inline constexpr double piston_speed = 20.0;
inline constexpr UniaxialState elastic{8938.934, 1.3903e8, -6.0e7, -1.9903e8, 4.7198, 4722.18};
inline constexpr UniaxialState plastic{8973.453, 6.8159e8, -6.0e7, -7.4159e8, 20.0, 3976.96};
}  // namespace piston

// E4 (verification.md): Wilkins aluminium, Mie-Grueneisen c0 5328 m/s, s 1.338, Gamma0 2,
// mu 27.6 GPa, Y 300 MPa, flyer 800 m/s onto the same material: interface 400 m/s. The precursor's
// density rho0 exp(Y/(2 mu)) = 2800.18 and pressure 0.43588 GPa follow from the same derivation
// (sigma_xx = s_xx - p with s_xx = -2Y/3); values in the target's frame.
namespace flyer {
inline constexpr double reference_density = 2785.0, shear_modulus = 2.76e10, yield_stress = 3.0e8;
inline constexpr double interface_speed = 400.0;
inline constexpr UniaxialState elastic{2800.18, 4.3588e8, -2.0e8, -6.3588e8, 35.18, 6490.4};
inline constexpr UniaxialState plastic{2985.63, 6.4359e9, -2.0e8, -6.6359e9, 400.0, 5908.5};
}  // namespace flyer

// One zone of a strip one zone across (x along the strip).
struct StripZone {
  Index zone = 0;
  double position = 0.0;  // centre x
  double density = 0.0, pressure = 0.0, deviator_xx = 0.0, velocity = 0.0, plastic_strain = 0.0;
  double stress_xx() const { return deviator_xx - pressure; }
};

inline std::vector<StripZone> strip_profile(const Simulation& sim, const Body& body) {
  std::vector<StripZone> strip;
  const ZoneState& zone_state = sim.zone_state();
  for (const ZoneSample& s : row_profile(sim, body, 0, Coordinate::first_axis)) {
    strip.push_back({s.zone, s.position, s.density, s.pressure, zone_state.strength.deviator_xx[s.zone], s.velocity,
                     zone_state.strength.plastic_strain[s.zone]});
  }
  return strip;
}

// Where the zone velocity first crosses `level`, scanning from the far end (largest x) of the strip
// towards the driven end; linear interpolation between zone centres. NaN if it never does.
inline double velocity_front(const std::vector<StripZone>& strip, double level) {
  for (std::size_t k = strip.size() - 1; k > 0; --k) {
    const double a = strip[k - 1].velocity - level, b = strip[k].velocity - level;
    if ((a >= 0.0) != (b >= 0.0)) return strip[k - 1].position + a / (a - b) * (strip[k].position - strip[k - 1].position);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// Means and largest relative deviations of the state over the zones whose centre lies in [from, to].
struct StripPlateau {
  int zones = 0;
  UniaxialState mean{0, 0, 0, 0, 0, 0};
  double largest_velocity_deviation = 0.0;  // max |u / u_ref - 1|
};

inline StripPlateau strip_plateau(const std::vector<StripZone>& strip, double from, double to,
                                  const UniaxialState& reference, double velocity_offset = 0.0) {
  StripPlateau p;
  for (const StripZone& z : strip) {
    if (z.position < from || z.position > to) continue;
    ++p.zones;
    p.mean.density += z.density;
    p.mean.pressure += z.pressure;
    p.mean.deviator_xx += z.deviator_xx;
    p.mean.stress_xx += z.stress_xx();
    p.mean.velocity += z.velocity + velocity_offset;
    p.largest_velocity_deviation =
        std::max(p.largest_velocity_deviation, std::abs((z.velocity + velocity_offset) / reference.velocity - 1.0));
  }
  if (p.zones > 0) {
    p.mean.density /= p.zones;
    p.mean.pressure /= p.zones;
    p.mean.deviator_xx /= p.zones;
    p.mean.stress_xx /= p.zones;
    p.mean.velocity /= p.zones;
  }
  return p;
}

// ---- the yield surface -------------------------------------------------------------------------

inline Deviator zone_deviator(const StrengthZoneFields& strength, Index z) {
  return {strength.deviator_xx[z], strength.deviator_yy[z], strength.deviator_xy[z], strength.deviator_zz[z]};
}

// von Mises equivalent stress sqrt(3/2 s:s) of a zone (Pa).
inline double zone_equivalent_stress(const StrengthZoneFields& strength, Index z) {
  return equivalent_stress(zone_deviator(strength, z));
}

// Tracks, over a run, which zones yielded in the last step (their plastic strain grew).
struct YieldTracker {
  std::vector<double> previous, current;
  void observe(const Simulation& sim) {
    previous.swap(current);
    current.assign(sim.zone_state().strength.plastic_strain.begin(), sim.zone_state().strength.plastic_strain.end());
  }
  bool yielded_last_step(Index z) const {
    return previous.size() == current.size() && current[z] > previous[z];
  }
};

// ---- E5: the beryllium plate's bending mode ----------------------------------------------------

// The plate's initial velocity field is the beam's first free-free mode W. Its modal displacement
// q(t) = sum_p M_p W_p (y_p(t) - y_p(0)) (W_p the initial v_y of node p) starts at 0, rises, and
// crosses zero every half period; the projection filters out the higher modes and the waves that the
// beam-theory field (not the exact 2D mode) also excites, which make the mid-plate velocity noisy.
struct PlateVibration {
  std::vector<double> crossings;  // times of the zero crossings of q after t = 0 (s)
  std::vector<double> peaks;      // max |q| over each half period (kg m^2/s)
  long zones = 0;
  double seconds = 0.0;
  double energy_drift = 0.0;      // ledger relative drift at the end
  double symmetry_error = 0.0;    // max over mirror node pairs of |u(x) + u(-x)|, |v(x) - v(-x)| / max |v|
  double peak_internal = 0.0;     // largest internal energy over the run (J per m)
  double hourglass_work = 0.0;    // the ledger's hourglass work at the end (J per m)
  double largest_hourglass_work = 0.0;  // its largest magnitude over the run
  std::string failure;
  // Mean period over the crossings (each interval is a half period).
  double period() const {
    if (crossings.size() < 2) return std::numeric_limits<double>::quiet_NaN();
    return 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  }
};

// beryllium_plate.json at nx x ny zones with the initial velocity scaled by `amplitude`; `physical`:
// the physical hourglass stiffness in place of the scenario's coefficient 0.05.
inline PlateVibration run_plate(int nx, int ny, double amplitude, double end_time = 9.0e-5, bool physical = false) {
  char factor[64];
  std::snprintf(factor, sizeof factor, "\"%.17g * 4.3369e-5", amplitude);
  const scenario::Scenario scenario = load_example(
      "beryllium_plate.json",
      {{"\"x\": { \"from\": -0.03, \"to\": 0.03, \"zones\": 60 }",
        "\"x\": { \"from\": -0.03, \"to\": 0.03, \"zones\": " + std::to_string(nx) + " }"},
       {"\"y\": { \"from\": -0.005, \"to\": 0.005, \"zones\": 10 }",
        "\"y\": { \"from\": -0.005, \"to\": 0.005, \"zones\": " + std::to_string(ny) + " }"},
       {"\"1.0 * 4.3369e-5", factor},
       {"\"end_time\": 9.0e-5", "\"end_time\": " + std::to_string(end_time)},
       {"\"stiffness\": 0.05", physical ? "\"stiffness_form\": \"physical\"" : "\"stiffness\": 0.05"}});
  Run run(scenario.setup);
  const NodeFields& nodes = run.simulation.mesh().nodes;
  const std::vector<double> shape(nodes.v.begin(), nodes.v.end()), start(nodes.y.begin(), nodes.y.end());
  auto modal = [&]() {
    double q = 0.0;
    for (Index p = 0; p < nodes.size(); ++p) q += nodes.mass[p] * shape[p] * (nodes.y[p] - start[p]);
    return q;
  };
  PlateVibration result;
  double previous_q = 0.0, previous_t = 0.0, peak = 0.0;
  advance(run, [&](const Simulation& sim) {
    const double q = modal(), t = sim.time();
    if (sim.cycle() > 1 && (q > 0.0) != (previous_q > 0.0)) {
      result.crossings.push_back(previous_t + (t - previous_t) * previous_q / (previous_q - q));
      result.peaks.push_back(peak);
      peak = 0.0;
    }
    peak = std::max(peak, std::abs(q));
    result.peak_internal = std::max(result.peak_internal, sim.ledger().energy.internal);
    result.largest_hourglass_work = std::max(result.largest_hourglass_work, std::abs(sim.ledger().energy.hourglass));
    previous_q = q;
    previous_t = t;
  });
  result.zones = static_cast<long>(nx) * ny;
  result.seconds = run.seconds;
  result.failure = run.failure;
  result.energy_drift = run.simulation.ledger().relative_energy_drift();
  result.hourglass_work = run.simulation.ledger().energy.hourglass;
  // Mirror symmetry about x = 0: node (i, j) and (nx - i, j), stored row by row.
  double worst = 0.0, largest = 0.0;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const Index a = j * (nx + 1) + i, b = j * (nx + 1) + (nx - i);
      worst = std::max({worst, std::abs(nodes.u[a] + nodes.u[b]), std::abs(nodes.v[a] - nodes.v[b])});
      largest = std::max(largest, std::hypot(nodes.u[a], nodes.v[a]));
    }
  }
  result.symmetry_error = worst / largest;
  return result;
}

// ---- Taylor bar ------------------------------------------------------------------------------------

// Length (largest z of any node: the rear face) and impact-face radius (largest r of the nodes that
// started on the impact face z = 0), the two measures of verification.md E6.
struct TaylorMeasures {
  double length = 0.0, face_radius = 0.0;
};

inline std::vector<Index> impact_face_nodes(const Mesh& mesh, const Body& body) {
  std::vector<Index> face;
  for (Index p = body.node_begin; p < body.node_end; ++p) {
    if (mesh.nodes.x[p] == 0.0) face.push_back(p);
  }
  return face;
}

inline TaylorMeasures taylor_measures(const Mesh& mesh, const Body& body, const std::vector<Index>& face) {
  TaylorMeasures m;
  for (Index p = body.node_begin; p < body.node_end; ++p) m.length = std::max(m.length, mesh.nodes.x[p]);
  for (Index p : face) m.face_radius = std::max(m.face_radius, mesh.nodes.y[p]);
  return m;
}

// Runs a Taylor bar (the scene's first body, its impact face at z = 0) to its end time; requires it to
// get there and returns the bar's measures at the end.
inline TaylorMeasures advance_taylor(Run& run) {
  const Body& bar = run.simulation.bodies().front();
  const std::vector<Index> face = impact_face_nodes(run.simulation.mesh(), bar);
  advance(run);
  INFO(run.failure);
  REQUIRE(run.completed());
  return taylor_measures(run.simulation.mesh(), bar, face);
}

struct TaylorLevel {
  int axial = 0, radial = 0;
  TaylorMeasures measures;
  double seconds = 0.0;
  long cycles = 0;
};

// The uniform family of taylor_bar.json's domain: 7.5 k x k zones (aspect 1.35, as 60 x 8). `adjust`
// may change the scenario's controls before the run.
inline TaylorLevel taylor_level(int radial, const std::function<void(scenario::Scenario&)>& adjust = {}) {
  const int axial = radial * 15 / 2;
  // Replace the graded default mesh by a uniform one of the same bar (the mesh is the only change).
  const std::string text = read_text(example_path("taylor_bar.json"));
  const std::size_t begin = text.find("\"mesh\"");
  const std::size_t end = text.find("\"initial\"");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  const std::string uniform = R"("mesh": { "type": "rectangle", "z": { "from": 0.0, "to": 0.0324, "zones": )" +
                              std::to_string(axial) + R"( }, "r": { "from": 0.0, "to": 0.0032, "zones": )" +
                              std::to_string(radial) + " } },\n      ";
  scenario::Scenario scenario = load_example("taylor_bar.json", {{text.substr(begin, end - begin), uniform}});
  if (adjust) adjust(scenario);
  Run run(scenario.setup);
  const Body& bar = run.simulation.bodies().front();
  const std::vector<Index> face = impact_face_nodes(run.simulation.mesh(), bar);
  advance(run);
  INFO("Taylor bar at " << axial << " x " << radial << " zones: " << run.failure);
  REQUIRE(run.completed());
  return {axial, radial, taylor_measures(run.simulation.mesh(), bar, face), run.seconds, run.simulation.cycle()};
}

// Richardson extrapolation from three levels refined by a constant ratio: the observed order
// p = log((f1 - f2)/(f2 - f3)) / log(ratio) and the limit f3 + (f3 - f2)/(ratio^p - 1). NaN order if
// the differences do not shrink monotonically (no asymptotic range).
struct Richardson {
  double order = std::numeric_limits<double>::quiet_NaN();
  double limit = std::numeric_limits<double>::quiet_NaN();
};

inline Richardson richardson(double coarse, double medium, double fine, double ratio = 2.0) {
  Richardson r;
  const double d1 = coarse - medium, d2 = medium - fine;
  if (d1 == 0.0 || d2 == 0.0 || (d1 > 0.0) != (d2 > 0.0) || std::abs(d2) >= std::abs(d1)) return r;
  r.order = std::log(d1 / d2) / std::log(ratio);
  r.limit = fine + (fine - medium) / (std::pow(ratio, r.order) - 1.0);
  return r;
}

}  // namespace krug::verification::solid
