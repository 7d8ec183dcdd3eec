// The output field `stress_triaxiality` (src/solver/output_fields.cpp) on a state whose triaxiality is
// known: a rod pulled in uniaxial tension (RZ, free lateral surface, from the
// homogeneous stretching field, as E9's rod) has eta = -p / sigma_vm = 1/3 once it flows (the mean stress
// is sigma_zz / 3, the von Mises stress sigma_zz); pushed, -1/3. The values come through the registry,
// as the VTU writer takes them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <variant>
#include <vector>

#include "krug/krug.hpp"
#include "krug/solver/output_fields.hpp"
#include "verification_support.hpp"

using namespace krug;

namespace {

std::vector<double> field_values(const Simulation& sim, std::string_view name) {
  std::vector<Index> items(static_cast<std::size_t>(sim.mesh().zones.size()));
  std::iota(items.begin(), items.end(), Index{0});
  for (const OutputField& f : output_fields()) {
    if (f.location == OutputLocation::zone && f.name == name) return std::get<std::vector<double>>(f.fill(sim, items));
  }
  FAIL("no zone output field " << name);
  return {};
}

// Wilkins aluminium hardening as E9's rod, Y = 300 MPa + 2 GPa eps_p (without hardening the rod rings
// about 1/3 by 0.01 after yield); the far end at `speed` (m/s), 10 mm, 2 mm radius.
Simulation rod(double speed) {
  setup::SceneDescription scene;
  scene.geometry = GeometryKind::axisymmetric;
  scene.materials.push_back(Material{"aluminium", 2785.0, LinearBulk{7.906e10, 2785.0}, LinearHardening{2.76e10, 3.0e8, 2.0e9}});
  setup::BodyDescription bar;
  bar.name = "rod";
  bar.mesh.shape = setup::RectangleMesh{generate::graded_axis(0.0, {{0.01, 10, 1.0}}), generate::graded_axis(0.0, {{0.002, 4, 1.0}})};
  bar.initial.velocity = std::array<setup::PointFunction, 2>{[speed](double x, double) { return speed * x / 0.01; },
                                                             [](double, double) { return 0.0; }};
  bar.boundary = {{"z_min", setup::SideCondition::symmetry, {}}, {"z_max", setup::SideCondition::velocity, {speed, std::nullopt}}};
  scene.bodies.push_back(bar);
  scene.controls.end_time = 1.0;
  return Simulation(setup::build_simulation(scene));
}

}  // namespace

TEST_CASE("output field stress_triaxiality: 1/3 in uniaxial tension, -1/3 in compression (RZ rod)",
          "[verification][outputs]") {
  for (const double speed : {10.0, -10.0}) {
    Simulation sim = rod(speed);
    const std::vector<double>& plastic_strain = sim.zone_state().strength.plastic_strain;
    const Index count = sim.mesh().zones.size();
    while (*std::min_element(plastic_strain.begin(), plastic_strain.end()) < 0.02) sim.step();
    const std::vector<double> eta = field_values(sim, "stress_triaxiality");
    REQUIRE(eta.size() == static_cast<std::size_t>(count));
    const double expected = speed > 0.0 ? 1.0 / 3.0 : -1.0 / 3.0;
    double worst = 0.0;
    for (const double e : eta) worst = std::max(worst, std::abs(e - expected));
    verification::report("output field stress_triaxiality, RZ rod", speed > 0.0 ? "tension, eps_p >= 0.02" : "compression, eps_p >= 0.02",
                         speed > 0.0 ? "1/3" : "-1/3", eta.front(), verification::format_number("worst zone off by %.2e", worst),
                         count, 0.0);
    CHECK(worst < 0.01);
  }
}
