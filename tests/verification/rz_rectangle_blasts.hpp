#pragma once
// The spherical blasts on a rectangular RZ mesh that does not follow the flow (docs/verification.md,
// F7): the Sedov and the Noh problems on [0, L]^2 quarters, judged on rays through the origin. Shared
// by the default-resolution tests (test_sedov.cpp, test_noh.cpp) and the finer meshes of the
// convergence label (convergence_hard_cases.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "noh_measures.hpp"
#include "verification_support.hpp"

namespace krug::verification::rz_rectangle {

inline constexpr double rays[] = {0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0};  // degrees from the z axis

// The example `file` (a rectangle of 50 x 50 zones) at n x n zones.
inline scenario::Scenario load(const std::string& file, int n) {
  const std::filesystem::path path = example_path(file);
  std::string text = read_text(path);
  const std::string from = "\"zones\": 50", to = "\"zones\": " + std::to_string(n);
  int replaced = 0;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()), ++replaced) {
    text.replace(at, from.size(), to);
  }
  REQUIRE(replaced == 2);
  return scenario::parse_scenario(text, path.string());
}

// The controls of docs/verification.md F7's last measurement: the tensor viscosity with subzonal
// pressures 2 acting at shocks only (hourglass.subzonal_at_shocks), otherwise the scenario's.
inline void use_tensor_with_subzonal_at_shocks(scenario::Scenario& scenario) {
  scenario.setup.controls.viscosity.model = ViscosityModel::tensor;
  scenario.setup.controls.hourglass.subzonal_pressure = 2.0;
  scenario.setup.controls.hourglass.subzonal_at_shocks = true;
}

// The cycles the Noh rectangle takes to its end time at n x n zones with Wilkins' scalar q (F7's
// workaround, which completes it at 50 x 50): the budget check_noh allows 3 x of. 0 if that run stops.
inline long noh_scalar_q_cycles(int n) {
  scenario::Scenario scalar_q = load("noh_spherical_rectangle.json", n);
  scalar_q.setup.controls.viscosity.model = ViscosityModel::scalar;
  const Run reference = run_to_end(scalar_q);
  return reference.completed() ? reference.simulation.cycle() : 0;
}

inline Vec2 zone_centre(const Mesh& mesh, Index z) {
  Vec2 c{};
  for (Index n : mesh.zones.corners[z]) c += 0.25 * mesh.nodes.position(n);
  return c;
}

// Zones whose centre lies within 2.5 degrees of the ray (4 degrees on the axis and the z = 0 plane,
// which have zones on one side only).
inline bool on_ray(Vec2 centre, double degrees) {
  const double half_width = (degrees <= 0.0 || degrees >= 90.0) ? 4.0 : 2.5;
  return std::abs(std::atan2(centre.y, centre.x) * 180.0 / std::numbers::pi - degrees) <= half_width;
}

// Sedov: the radius of the densest zone on the ray.
inline double sedov_shock_on_ray(const Simulation& sim, double degrees) {
  const Mesh& mesh = sim.mesh();
  double best_density = -1.0, radius = 0.0;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    if (!mesh.zones.active[z]) continue;
    const Vec2 c = zone_centre(mesh, z);
    if (on_ray(c, degrees) && mesh.zones.density[z] > best_density) {
      best_density = mesh.zones.density[z];
      radius = norm(c);
    }
  }
  return radius;
}

// Noh: the largest radius of a zone on the ray whose density exceeds 40 (between the pre-shock 16 and
// the post-shock 64 of the spherical Noh at t = 0.6).
inline double noh_shock_on_ray(const Simulation& sim, double degrees) {
  const Mesh& mesh = sim.mesh();
  double radius = 0.0;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    const Vec2 c = zone_centre(mesh, z);
    if (on_ray(c, degrees) && mesh.zones.density[z] > 40.0) radius = std::max(radius, norm(c));
  }
  return radius;
}

// The Sedov rectangle (sedov_spherical_rectangle.json, [0, 1.2]^2 at n x n zones) run to t = 1: the
// shock within 2 zones of r = 1 on every ray (the axis ray only when `judge_axis`), energy to 1e-12.
inline void check_sedov(const scenario::Scenario& scenario, int n, const std::string& label, bool judge_axis) {
  const double zone = 1.2 / n;
  const Run run = run_to_end(scenario);
  INFO(label << ": " << run.failure);
  REQUIRE(run.completed());
  CHECK(run.simulation.ledger().relative_energy_drift() < 1e-12);
  report(label, "cycles to t = 1", "", static_cast<double>(run.simulation.cycle()), "", run.simulation.mesh().zones.size(),
         run.seconds);
  for (const double ray : rays) {
    const double shock = sedov_shock_on_ray(run.simulation, ray);
    INFO("ray " << ray << " degrees: shock at " << shock);
    report(label, format_number("shock r on the %.0f degree ray", ray), "1.000", shock,
           format_number("%+.1f zones", (shock - 1.0) / zone), run.simulation.mesh().zones.size(), run.seconds);
    if (judge_axis || ray > 0.0) CHECK(std::abs(shock - 1.0) < 2.0 * zone);
  }
}

// The Noh rectangle (noh_spherical_rectangle.json, [0, 1]^2 at n x n zones) run to t = 0.6, judged
// against the criteria of docs/verification.md F7: at most 3 x the cycles of `scalar_q_cycles` (the
// scalar-q run on the same mesh); shock (density crossing 40) within 2 zones of 0.2 on every ray,
// spread over the rays <= 2 zones; plateau on r in [0.1, r_s - 2h], rays 10-80 degrees: mean within
// 10 % of 64, worst zone within 20 %; energy to 1e-12.
inline void check_noh(const scenario::Scenario& scenario, int n, long scalar_q_cycles, const std::string& label) {
  using noh::plateau_from;
  using noh::shock_radius;
  const Run run = run_to_end(scenario);
  INFO(label << ": " << run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  const double h = 1.0 / n;
  CHECK(sim.cycle() <= 3 * scalar_q_cycles);
  CHECK(sim.ledger().relative_energy_drift() < 1e-12);
  report(label, "cycles (3 x scalar q at most)", std::to_string(3 * scalar_q_cycles), static_cast<double>(sim.cycle()), "",
         sim.mesh().zones.size(), run.seconds);
  double lowest = 1.0, highest = 0.0;
  for (const double ray : rays) {
    const double shock = noh_shock_on_ray(sim, ray);
    INFO("ray " << ray << ": shock at " << shock);
    CHECK(std::abs(shock - shock_radius) <= 2.0 * h);
    lowest = std::min(lowest, shock);
    highest = std::max(highest, shock);
    report(label, format_number("shock r on the %.0f degree ray", ray), "0.2000", shock,
           format_number("%+.1f zones", (shock - shock_radius) / h), sim.mesh().zones.size(), run.seconds);
  }
  CHECK(highest - lowest <= 2.0 * h);
  double sum = 0.0, worst = 0.0;
  int count = 0;
  for (Index z = 0; z < sim.mesh().zones.size(); ++z) {
    const Vec2 c = zone_centre(sim.mesh(), z);
    const double angle = std::atan2(c.y, c.x) * 180.0 / std::numbers::pi, r = norm(c);
    if (angle < 10.0 || angle > 80.0 || r < plateau_from || r > shock_radius - 2.0 * h) continue;
    sum += sim.mesh().zones.density[z];
    worst = std::max(worst, std::abs(sim.mesh().zones.density[z] / 64.0 - 1.0));
    ++count;
  }
  REQUIRE(count > 0);
  const double mean = sum / count;
  INFO("plateau: " << count << " zones, mean " << mean << ", worst " << worst);
  CHECK(std::abs(mean / 64.0 - 1.0) < 0.10);
  CHECK(worst < 0.20);
  report(label, "plateau rho (mean; worst zone)", "64", mean, format_number("worst %.1f %%", 100.0 * worst),
         sim.mesh().zones.size(), run.seconds);
}

}  // namespace krug::verification::rz_rectangle
