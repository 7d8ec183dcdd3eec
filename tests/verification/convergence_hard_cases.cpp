// The hard cases of docs/verification.md F7 on the finer meshes, with the two opt-in controls that
// cure them (controls.hourglass.subzonal_pressure 0.5 and controls.viscosity.heat_conduction 2,
// control-volume form, edge viscosity): the spherical Noh on the RZ rectangle at 100 x 100, the
// spherical Sedov on RZ rectangles of 100 x 100 and 200 x 200 zones, and the spherical Noh on polar
// meshes refined beyond the verification mesh (200 x 60 and 200 x 80), each judged by the criteria of
// its default-resolution test (test_noh.cpp, test_sedov.cpp). KRUG_CONVERGENCE_SCALE scales the meshes
// (CI runs 0.25), never below the default meshes (50 x 50; the polar 100 x 30 and 100 x 40). The polar
// Noh at 200 x 60 and the rectangles are also run with default controls, which pass them.
// Full scale takes a few minutes, most of it the two polar meshes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "noh_measures.hpp"
#include "rz_rectangle_blasts.hpp"
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

namespace {

int scaled(int zones, int smallest) {
  return std::max(smallest, static_cast<int>(std::lround(zones * convergence_scale())));
}

void cure(scenario::Scenario& scenario) {
  scenario.setup.controls.viscosity.model = ViscosityModel::edge;  // the default gives an RZ gas the tensor viscosity
  scenario.setup.controls.hourglass.subzonal_pressure = 0.5;
  scenario.setup.controls.viscosity.heat_conduction = 2.0;
}

std::string mesh_name(int a, int b) { return std::to_string(a) + " x " + std::to_string(b); }

// The RZ rectangles of 100 x 100 and 200 x 200 at the study's scale (at least 50 x 50), each once:
// the reduced scale can give the same mesh twice.
template <class Run>
void for_each_finer_rectangle(Run&& run) {
  int previous = 0;
  for (const int full : {100, 200}) {
    const int n = scaled(full, 50);
    if (n == previous) continue;
    previous = n;
    run(n);
  }
}

}  // namespace

// Measured at 100 x 100: 2 511 cycles, shock -0.3 to 0 zones, plateau -2.0 % mean, 3.3 % worst.
TEST_CASE("Hard cases, finer: Noh spherical on the RZ rectangle at 100 x 100 with the two controls",
          "[convergence][subzonal][noh]") {
  const int n = scaled(100, 50);
  // The cycle budget: 3 x the scalar-q run on the same mesh. At 100 x 100 that run stops (at cycle
  // 1 171, CFL 0.5: F7's workaround fails there too), so the budget is then the 50 x 50 scalar-q
  // run's cycles scaled with the zone size (n / 50), as a time step proportional to the zone gives.
  long scalar_q_cycles = 0;
  for (const int mesh : n == 50 ? std::vector<int>{50} : std::vector<int>{n, 50}) {
    scenario::Scenario scalar_q = rz_rectangle::load("noh_spherical_rectangle.json", mesh);
    scalar_q.setup.controls.viscosity.model = ViscosityModel::scalar;
    const Run reference = run_to_end(scalar_q);
    report("Noh, spherical (RZ rectangle " + mesh_name(mesh, mesh) + ", scalar q)", "cycles to t = 0.6", "",
           static_cast<double>(reference.simulation.cycle()), reference.completed() ? "completed" : "stops",
           reference.simulation.mesh().zones.size(), reference.seconds);
    if (reference.completed()) {
      scalar_q_cycles = reference.simulation.cycle() * n / mesh;
      break;
    }
  }
  REQUIRE(scalar_q_cycles > 0);
  scenario::Scenario scenario = rz_rectangle::load("noh_spherical_rectangle.json", n);
  cure(scenario);
  rz_rectangle::check_noh(scenario, n, scalar_q_cycles,
                          "Noh, spherical (RZ rectangle " + mesh_name(n, n) + ", subzonal 0.5 + heat 2)");
}

// Measured: 100 x 100 in 865 cycles, 200 x 200 in 2 013, the shock within 1.4 zones on every ray. With default controls these stop at t = 0.045 and 0.0079 (F7).
TEST_CASE("Hard cases, finer: Sedov spherical on RZ rectangles of 100 x 100 and 200 x 200 with the two controls",
          "[convergence][subzonal][sedov]") {
  for_each_finer_rectangle([](int n) {
    scenario::Scenario scenario = rz_rectangle::load("sedov_spherical_rectangle.json", n);
    cure(scenario);
    rz_rectangle::check_sedov(scenario, n, "Sedov, spherical (RZ rectangle " + mesh_name(n, n) + ", subzonal 0.5 + heat 2)",
                              true);
  });
}

// The verification mesh is 100 x 40 (test_noh.cpp); with default controls 200 x 60 stops at t = 0.168
// (zone 23, cycle 19 742) and 200 x 80 at t = 0.099 (F7). Measured with the two controls: 45 s and
// 84 s, shock within 0.43 zones on every row, plateau -1.6 %, worst zone 1.7 %.
TEST_CASE("Hard cases, finer: Noh spherical on RZ polar meshes of 200 x 60 and 200 x 80 with the two controls",
          "[convergence][subzonal][noh]") {
  for (const auto& [full_radial, full_angular] : {std::pair{200, 60}, std::pair{200, 80}}) {
    const int radial = scaled(full_radial, 100), angular = scaled(full_angular, full_angular / 2);
    scenario::Scenario scenario = load_example("noh_spherical.json", {zones(40, angular), zones(100, radial)});  // angular first: a radial count of 40x cannot collide
    cure(scenario);
    const std::string label = "Noh, spherical (RZ polar " + mesh_name(radial, angular) + ", subzonal 0.5 + heat 2)";
    noh::check_noh(run_to_end(scenario), {label.c_str(), 3, Coordinate::radius});
  }
}

// Default controls (the tensor viscosity with the corner-collapse pressure in these gases; docs/verification.md
// F7) on the finer rectangles, cycle budget as above. Measured: the Noh at 100 x 100 in 889 cycles and at
// 200 x 200 in 4 676 (shock within 0.1 to 0.4 zones on every ray, plateau -3.8 % and -2.0 %, worst zone
// 5.6 % and 3.1 %); the Sedov in 1 047 and 2 263 cycles, within 0.4 zones on every ray.
TEST_CASE("Hard cases, finer: Noh and Sedov spherical on RZ rectangles with default controls",
          "[convergence][noh][sedov]") {
  const long scalar_q_cycles = rz_rectangle::noh_scalar_q_cycles(50);
  REQUIRE(scalar_q_cycles > 0);
  for_each_finer_rectangle([&](int n) {
    rz_rectangle::check_noh(rz_rectangle::load("noh_spherical_rectangle.json", n), n, scalar_q_cycles * n / 50,
                            "Noh, spherical (RZ rectangle " + mesh_name(n, n) + ", default controls)");
    rz_rectangle::check_sedov(rz_rectangle::load("sedov_spherical_rectangle.json", n), n,
                              "Sedov, spherical (RZ rectangle " + mesh_name(n, n) + ", default controls)", true);
  });
}

// Default controls (the tensor viscosity with the corner-collapse pressure in this gas; docs/verification.md
// F7) on the polar mesh refined to 200 x 60, where the edge viscosity stops at t = 0.168. Measured at full
// scale: 113 202 cycles, shock 0.2014 in every angular bin, plateau mean -2.8 %, worst zone 3.7 %, energy
// 7e-16. At 200 x 80 the default run does not finish (a known failure, F7): the centre's triangles next to
// the axis are pressed onto it and the damping bound of their zones' step falls below 1e-7 s by t = 0.013.
TEST_CASE("Hard cases, finer: Noh spherical on the RZ polar mesh of 200 x 60 with default controls",
          "[convergence][noh]") {
  const int radial = scaled(200, 100), angular = scaled(60, 30);
  scenario::Scenario scenario = load_example("noh_spherical.json", {zones(40, angular), zones(100, radial)});
  const std::string label = "Noh, spherical (RZ polar " + mesh_name(radial, angular) + ", default controls)";
  noh::check_noh(run_to_end(scenario), {label.c_str(), 3, Coordinate::radius});
}

// The tensor viscosity (controls.viscosity.model = "tensor", otherwise default controls) on the finer
// rectangles: the Noh at 100 x 100 (cycle budget as above) and the Sedov at 100 x 100 and 200 x 200.
// The Noh at 100 x 100 stopped at t = 0.488 (zone 405, cycle 928) until the tensor viscosity's step was
// bounded by its damping at the nodes (docs/theory.md §2); measured since: 2 307 cycles (budget 2 898),
// shock within 0.3 zones on every ray, plateau -3.9 % mean, 5.5 % worst zone (docs/verification.md F7).
TEST_CASE("Hard cases, finer: Noh spherical on the RZ rectangle with the tensor viscosity",
          "[convergence][tensor][noh]") {
  const int n = scaled(100, 50);
  const long scalar_q_cycles = rz_rectangle::noh_scalar_q_cycles(50);
  REQUIRE(scalar_q_cycles > 0);
  scenario::Scenario noh = rz_rectangle::load("noh_spherical_rectangle.json", n);
  noh.setup.controls.viscosity.model = ViscosityModel::tensor;
  rz_rectangle::check_noh(noh, n, scalar_q_cycles * n / 50,
                          "Noh, spherical (RZ rectangle " + mesh_name(n, n) + ", tensor q)");
}

// The same with the gas rezoned (`rezone`, altitude ratio 0.5; docs/verification.md F7): measured at
// 100 x 100 in 1 117 cycles (budget 2 898), shock -0.1 to +0.4 zones on every ray, plateau -1.7 % mean,
// 3.9 % worst zone. At 200 x 200 it takes 8 291 cycles against its budget of 5 796 (3 373 of them set by
// the tensor viscosity's damping bound and 3 987 by the growth limit after its cuts; 3 773 before the
// bound replaced the factor max(1, L_c / h)), so only the 100 x 100 mesh is checked here (F7's table).
TEST_CASE("Hard cases, finer: Noh spherical on RZ rectangles with the tensor viscosity and rezoning",
          "[convergence][tensor][rezone][noh]") {
  const long scalar_q_cycles = rz_rectangle::noh_scalar_q_cycles(50);
  REQUIRE(scalar_q_cycles > 0);
  const int n = scaled(100, 50);
  scenario::Scenario noh = rz_rectangle::load("noh_spherical_rectangle.json", n);
  noh.setup.controls.viscosity.model = ViscosityModel::tensor;
  noh.setup.bodies.front().rezone_ratio = 0.5;
  rz_rectangle::check_noh(noh, n, scalar_q_cycles * n / 50,
                          "Noh, spherical (RZ rectangle " + mesh_name(n, n) + ", tensor q, rezoned)");
}

TEST_CASE("Hard cases, finer: Sedov spherical on RZ rectangles with the tensor viscosity",
          "[convergence][tensor][sedov]") {
  for_each_finer_rectangle([](int m) {
    scenario::Scenario sedov = rz_rectangle::load("sedov_spherical_rectangle.json", m);
    sedov.setup.controls.viscosity.model = ViscosityModel::tensor;
    rz_rectangle::check_sedov(sedov, m, "Sedov, spherical (RZ rectangle " + mesh_name(m, m) + ", tensor q)", true);
  });
}

// The tensor viscosity with subzonal pressures at shocks only (hourglass.subzonal_pressure 2,
// subzonal_at_shocks; test_tensor_viscosity.cpp) on the finer rectangles, otherwise default controls.
// Measured (with the damping bound, docs/verification.md F7): the Noh at 100 x 100 in 752 cycles (shock
// within 0.3 zones on every ray, plateau -3.7 %, worst zone 5.5 %) and at 200 x 200 in 1 466 (within
// 0.4 zones, -1.8 %, 3.0 %); the Sedov in 964 and 2 606 cycles, within 0.4 zones on every ray.
TEST_CASE("Hard cases, finer: Noh and Sedov spherical on RZ rectangles, tensor viscosity with subzonal pressures at shocks",
          "[convergence][tensor][subzonal][noh][sedov]") {
  const long scalar_q_cycles = rz_rectangle::noh_scalar_q_cycles(50);
  REQUIRE(scalar_q_cycles > 0);
  for_each_finer_rectangle([&](int n) {
    scenario::Scenario noh = rz_rectangle::load("noh_spherical_rectangle.json", n);
    rz_rectangle::use_tensor_with_subzonal_at_shocks(noh);
    rz_rectangle::check_noh(noh, n, scalar_q_cycles * n / 50,
                            "Noh, spherical (RZ rectangle " + mesh_name(n, n) + ", tensor q, subzonal 2 at shocks)");
    scenario::Scenario sedov = rz_rectangle::load("sedov_spherical_rectangle.json", n);
    rz_rectangle::use_tensor_with_subzonal_at_shocks(sedov);
    rz_rectangle::check_sedov(sedov, n, "Sedov, spherical (RZ rectangle " + mesh_name(n, n) + ", tensor q, subzonal 2 at shocks)", true);
  });
}
