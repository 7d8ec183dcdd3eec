// A piston driven into water at rest, stiffened-gas equation of state (gamma 4.4, p_inf 6e8 Pa,
// Saurel & Abgrall 1999). In the variable pi = p + p_inf the stiffened gas is an ideal gas, so the
// shock the piston drives follows the ideal-gas jump conditions with c0^2 = gamma (p0 + p_inf)/rho0:
//   D = a + sqrt(a^2 + c0^2),  a = (gamma + 1) u_p / 4,   rho1 = rho0 D / (D - u_p),   p1 = p0 + rho0 D u_p
// (the strong-shock relation of any gamma-law material; Zel'dovich & Raizer, "Physics of Shock
// Waves", ch. I). Water at rest at p0 = 0 needs e0 = gamma p_inf / ((gamma - 1) rho0).
// The scenario: examples/verification/water_piston.json.
#include <catch2/catch.hpp>

#include <cmath>

#include "krug/scenario/scenario.hpp"
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

namespace {

constexpr double gamma_water = 4.4, p_inf = 6e8, rho0 = 1000.0, piston = 100.0;
constexpr double length = 0.2;  // m
constexpr int strip_zones = 400;  // dx = 0.5 mm

}  // namespace

TEST_CASE("stiffened gas: a piston in water drives the shock of the ideal-gas jump conditions in p + p_inf",
          "[eos][stiffened_gas]") {
  // The initial energy in the scenario is gamma p_inf / ((gamma - 1) rho0): p0 = 0.
  REQUIRE(std::abs(776470.5882352941 - gamma_water * p_inf / ((gamma_water - 1.0) * rho0)) < 1e-6);
  const scenario::Scenario scenario = load_example("water_piston.json");  // examples/verification/
  Run run = run_to_end(scenario);
  INFO(run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const double t = sim.time();
  const double c0 = std::sqrt(gamma_water * p_inf / rho0);  // 1 624.8 m/s
  const double a = 0.25 * (gamma_water + 1.0) * piston;
  const double shock_speed = a + std::sqrt(a * a + c0 * c0);  // 1 765.4 m/s
  const double p1 = rho0 * shock_speed * piston;               // 1.765e8 Pa
  const double rho1 = rho0 * shock_speed / (shock_speed - piston);

  // The shock: where the zone-mean velocity crosses half the piston's speed; a captured jump is centred
  // there. Within 2 zones of D t (the criterion of the other piston and shock-tube problems).
  const Mesh& mesh = sim.mesh();
  const ZoneState& zone_state = sim.zone_state();
  const Body& body = sim.bodies().front();
  double front = 0.0;
  std::vector<double> centre, pressure, density, velocity;
  for (Index z = body.zone_begin; z < body.zone_end; ++z) {
    const ZoneCorners& n = mesh.zones.corners[z];
    double x = 0.0, u = 0.0;
    for (Index p : n) {
      x += 0.25 * mesh.nodes.x[p];
      u += 0.25 * mesh.nodes.u[p];
    }
    centre.push_back(x);
    velocity.push_back(u);
    pressure.push_back(zone_state.hydro.pressure[z]);
    density.push_back(mesh.zones.density[z]);
  }
  for (std::size_t i = 1; i < centre.size(); ++i) {
    if (velocity[i - 1] >= 0.5 * piston && velocity[i] < 0.5 * piston) {
      front = centre[i - 1] + (centre[i] - centre[i - 1]) * (velocity[i - 1] - 0.5 * piston) / (velocity[i - 1] - velocity[i]);
    }
  }
  const double dx = length / strip_zones;
  const double exact_front = shock_speed * t;  // the shock starts at x = 0 at t = 0
  INFO("front " << front << " m, exact " << exact_front << " m (" << (front - exact_front) / dx << " zones)");
  CHECK(std::abs(front - exact_front) < 2.0 * dx);

  // The plateau between the piston and the shock, away from both by 10 zones: mean pressure and
  // density within 1 % of the jump conditions, velocity within 1 %; ahead of the shock, at rest at p = 0.
  double p_sum = 0.0, rho_sum = 0.0, u_sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < centre.size(); ++i) {
    if (centre[i] > piston * t + 10 * dx && centre[i] < exact_front - 10 * dx) {
      p_sum += pressure[i];
      rho_sum += density[i];
      u_sum += velocity[i];
      ++count;
    }
  }
  REQUIRE(count > 50);
  INFO("plateau p " << p_sum / count << " Pa (exact " << p1 << "), rho " << rho_sum / count << " (exact " << rho1
                    << "), u " << u_sum / count);
  CHECK(std::abs(p_sum / count / p1 - 1.0) < 0.01);
  CHECK(std::abs((rho_sum / count - rho0) / (rho1 - rho0) - 1.0) < 0.01);
  CHECK(std::abs(u_sum / count / piston - 1.0) < 0.01);
  CHECK(std::abs(pressure.back()) < 1e-6 * p1);
  CHECK(std::abs(density.back() / rho0 - 1.0) < 1e-9);  // round-off in p0 = 0 only

  // The ledger closes: the piston's work equals the gain of kinetic and internal energy.
  CHECK(sim.ledger().relative_energy_drift() < 1e-12);
}
