// The axisymmetric deviatoric force on the axis row and the outer row (docs/verification.md, "The axis
// row's deviatoric force"). The RZ control-volume force on a corner is -[(sigma_2D - sigma_tt I) B_p +
// sigma_tt c_p] with B_p = integral of grad N_p r dA, the quadrature of the nodal masses
// integral N_p r dA; its adjoint gives the strain rate. Two checks:
//   * static: under a stress linear in z the assembled axial force on every node equals dsigma/dz times
//     the node's mass per unit density, on every row of a graded radial mesh, the axis and the outer
//     row included (the mean-radius rule (V/A) b_p gave 1.500 x on the axis row, 0.955 x on the outer);
//   * in motion: a piston into a rod between a slip lateral wall (RZ, 800 x 4 zones) is uniaxial strain,
//     so every radial row must equal the planar strip (800 x 1, slip walls), elastic and elastic-plastic.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "krug/mesh/quad.hpp"
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

TEST_CASE("RZ deviatoric force under a stress linear in z is mass-consistent on every row", "[axisymmetric][axis_row]") {
  // A column of rectangles: z uniform (h = 1), r graded (0, 0.3, 0.8, 1.6, 3.0: axis row to outer row).
  const std::vector<double> r{0.0, 0.3, 0.8, 1.6, 3.0};
  const double slope = 2.5;  // d sigma_zz / dz
  for (std::size_t j = 0; j + 1 < r.size(); ++j) {
    // Interior node at z = 3 on the row's lower and upper radius: sum over the zones around it.
    for (int side = 0; side < 2; ++side) {
      const double node_r = r[j + static_cast<std::size_t>(side)];
      double force = 0.0, mass = 0.0;
      for (int k = 2; k < 4; ++k) {  // zones [2, 3] and [3, 4] along z
        for (std::size_t jj = (j > 0 ? j - 1 : 0); jj <= std::min(j + 1, r.size() - 2); ++jj) {
          const quad::Corners x{Vec2{double(k), r[jj]}, Vec2{double(k + 1), r[jj]}, Vec2{double(k + 1), r[jj + 1]},
                                Vec2{double(k), r[jj + 1]}};
          const std::array<Vec2, 4> in_plane = quad::axisymmetric_gradient_integrals(x);
          const std::array<double, 4> volumes = quad::axisymmetric_corner_volumes(x);
          const double sigma = slope * (k + 0.5);  // the zone's mean stress sigma_zz (s_zz only: no pressure)
          for (int p = 0; p < 4; ++p) {
            if (x[p].x != 3.0 || x[p].y != node_r) continue;
            force += -sigma * in_plane[p].x;  // -(sigma_2D - sigma_tt I) B_p, axial, sigma_tt = 0
            mass += volumes[p];
          }
        }
      }
      INFO("row " << j << ", node at r = " << node_r << ": force " << force << ", slope x mass " << slope * mass);
      CHECK(force == Approx(slope * mass).epsilon(1e-12));
    }
  }
}

namespace {

struct Profile {
  std::vector<std::vector<double>> rows;  // axial stress sigma_zz = s_zz - p per zone, by radial row
  double radial_speed = 0.0;              // largest |u_r| of any node
};

Profile uniaxial_run(bool axisymmetric, double piston_speed, bool plastic) {
  nlohmann::json strength = {{"model", plastic ? "perfectly_plastic" : "elastic"}, {"shear_modulus", 2.46e10}};
  if (plastic) strength["yield_stress"] = 2.8e8;
  const char* a = axisymmetric ? "z" : "x";
  const char* b = axisymmetric ? "r" : "y";
  nlohmann::json boundary = {{std::string(a) + "_min", {{"type", "velocity"}, {"velocity", {piston_speed, nullptr}}}},
                             {std::string(b) + "_max", "slip"}};
  if (!axisymmetric) boundary[std::string(b) + "_min"] = "slip";
  const nlohmann::json document = {
      {"geometry", axisymmetric ? "axisymmetric" : "planar"},
      {"end_time", 11e-6},
      {"materials", {{"al", {{"density", 2700.0}, {"eos", {{"model", "linear"}, {"bulk_modulus", 7.3e10}}}, {"strength", strength}}}}},
      {"bodies",
       {{{"name", "rod"},
         {"material", "al"},
         {"mesh", {{"type", "rectangle"}, {a, {{"from", 0.0}, {"to", 0.08}, {"zones", 800}}},
                   {b, {{"from", 0.0}, {"to", 0.0004}, {"zones", axisymmetric ? 4 : 1}}}}},
         {"boundary", boundary}}}}};
  Run run(scenario::parse_scenario(document.dump(), "uniaxial rod").setup);
  advance(run);
  INFO(run.failure);
  REQUIRE(run.completed());
  const Mesh& mesh = run.simulation.mesh();
  const ZoneState& zone_state = run.simulation.zone_state();
  Profile profile;
  const int rows = axisymmetric ? 4 : 1;
  profile.rows.assign(static_cast<std::size_t>(rows), {});
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    profile.rows[static_cast<std::size_t>(z / 800)].push_back(zone_state.strength.deviator_xx[z] - zone_state.hydro.pressure[z]);
  }
  for (Index n = 0; n < mesh.nodes.size(); ++n) profile.radial_speed = std::max(profile.radial_speed, std::abs(mesh.nodes.v[n]));
  return profile;
}

}  // namespace

// Measured: elastic 50 m/s, every row within 6.2e-8 of the strip's peak stress, |u_r| 1.6e-9 of the piston
// speed; elastic-plastic 400 m/s, within 1.8e-5, |u_r| 2.1e-9 (with the mean-radius rule: 0.20 m/s of
// radial velocity at 50 m/s and the axis row 19-30 % off in the foot of the front).
TEST_CASE("A piston into an RZ rod with a slip wall is the planar strip, row by row", "[axisymmetric][axis_row]") {
  for (const auto& [speed, plastic] : {std::pair{50.0, false}, std::pair{400.0, true}}) {
    INFO((plastic ? "elastic-plastic, " : "elastic, ") << speed << " m/s");
    const Profile rod = uniaxial_run(true, speed, plastic);
    const Profile strip = uniaxial_run(false, speed, plastic);
    double scale = 0.0;
    for (double s : strip.rows[0]) scale = std::max(scale, std::abs(s));
    REQUIRE(scale > 0.0);
    for (std::size_t row = 0; row < rod.rows.size(); ++row) {
      double worst = 0.0;
      for (std::size_t k = 0; k < strip.rows[0].size(); ++k) worst = std::max(worst, std::abs(rod.rows[row][k] - strip.rows[0][k]));
      INFO("row " << row << ": worst difference " << worst / scale << " of the peak stress " << scale);
      CHECK(worst <= 1e-4 * scale);
      report(plastic ? "RZ rod vs planar strip, elastic-plastic 400 m/s" : "RZ rod vs planar strip, elastic 50 m/s",
             format_number("row %.0f: worst |sigma_zz - strip| / peak", static_cast<double>(row)), "0",
             worst / scale, "<= 1e-4", 3200, 0.0);
    }
    INFO("radial speed " << rod.radial_speed);
    CHECK(rod.radial_speed < 1e-6 * speed);
  }
}

// The closed form of quad::axisymmetric_gradient_integrals against an independent 2 x 2 Gauss quadrature
// of grad N_p r det J (exact for bilinear quads), on distorted quads on and off the axis.
TEST_CASE("r-weighted shape-function gradients: closed form equals Gauss quadrature", "[axisymmetric][axis_row]") {
  const std::vector<quad::Corners> quads{
      {Vec2{0.1, 0.0}, Vec2{1.1, 0.0}, Vec2{1.3, 1.4}, Vec2{0.0, 1.1}},
      {Vec2{2.0, 0.5}, Vec2{2.7, 0.6}, Vec2{2.9, 1.9}, Vec2{1.8, 1.2}},
      {Vec2{0.0, 0.0}, Vec2{1.0, 0.0}, Vec2{1.0, 1.0}, Vec2{0.0, 1.0}}};
  for (const quad::Corners& c : quads) {
    constexpr double g = 0.57735026918962576;
    const std::array<double, 4> xs{-1.0, 1.0, 1.0, -1.0}, es{-1.0, -1.0, 1.0, 1.0};
    std::array<Vec2, 4> gauss{};
    for (double xi : {-g, g}) {
      for (double eta : {-g, g}) {
        Vec2 dxi{}, deta{};
        double r = 0.0;
        std::array<double, 4> nxi, neta;
        for (int p = 0; p < 4; ++p) {
          r += 0.25 * (1 + xs[p] * xi) * (1 + es[p] * eta) * c[p].y;
          nxi[p] = 0.25 * xs[p] * (1 + es[p] * eta);
          neta[p] = 0.25 * es[p] * (1 + xs[p] * xi);
          dxi += nxi[p] * c[p];
          deta += neta[p] * c[p];
        }
        for (int p = 0; p < 4; ++p) gauss[p] += r * Vec2{deta.y * nxi[p] - dxi.y * neta[p], dxi.x * neta[p] - deta.x * nxi[p]};
      }
    }
    const std::array<Vec2, 4> closed = quad::axisymmetric_gradient_integrals(c);
    Vec2 sum{};
    for (int p = 0; p < 4; ++p) {
      CHECK(closed[p].x == Approx(gauss[p].x).margin(1e-14));
      CHECK(closed[p].y == Approx(gauss[p].y).margin(1e-14));
      sum += closed[p];
    }
    CHECK(std::abs(sum.x) < 1e-14);
    CHECK(std::abs(sum.y) < 1e-14);
  }
}
