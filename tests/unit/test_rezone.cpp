// Rezoning (include/krug/solver/rezone.hpp): the relaxation of interior nodes and the conservative
// remap of the zones they touch.
#include <catch2/catch.hpp>

#include <cmath>

#include "krug/core/error.hpp"
#include "krug/krug.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/solver/rezone.hpp"

using namespace krug;

namespace {

// A block of 8 x 6 zones on geometrically graded axes (so that no interior node sits at the mean of its
// neighbours and every one of them moves), moving uniformly, with a uniform stress and plastic strain.
struct UniformBlock {
  SimulationState state;
  Body body;
  Material material;
  GeometryKind geometry;
  Vec2 velocity;
};

UniformBlock uniform_block(GeometryKind geometry) {
  SimulationSetup s;
  s.geometry = geometry;
  const auto patch = generate::rectangle(s.mesh, generate::graded_axis(0.0, {{2.0e-3, 8, 1.3}}),
                                         generate::graded_axis(0.0, {{1.0e-3, 6, 0.7}}), 0);
  s.materials.push_back(Material{"copper", 8930.0, LinearBulk{1.3e11, 8930.0}, LinearHardening{4.33e10, 4.0e8, 1.0e8}});
  s.bodies.push_back({"block", 0, patch.node_begin, patch.node_end, patch.zone_begin, patch.zone_end});
  s.controls.end_time = 1.0;
  // In RZ the axis row holds its radial component; the block moves along the axis there.
  const Vec2 velocity = geometry == GeometryKind::axisymmetric ? Vec2{-300.0, 0.0} : Vec2{-300.0, 120.0};
  for (Index n = patch.node_begin; n < patch.node_end; ++n) {
    s.mesh.nodes.u[n] = velocity.x;
    s.mesh.nodes.v[n] = velocity.y;
  }
  const Simulation sim(s);
  UniformBlock b{sim.state(), sim.bodies().front(), sim.materials().front(), geometry, velocity};
  StrengthZoneFields& strength = b.state.zone_state.strength;
  for (Index z = 0; z < b.state.mesh.zones.size(); ++z) {
    strength.deviator_xx[z] = 1.5e8;
    strength.deviator_yy[z] = -0.5e8;
    strength.deviator_xy[z] = 0.7e8;
    strength.deviator_zz[z] = -1.0e8;
    strength.plastic_strain[z] = 0.25;
    b.state.mesh.zones.specific_energy[z] = 1.0e4;
  }
  b.body.rezone_ratio = 2.0;  // every zone counts as distorted: every interior node moves
  b.body.rezone_relaxation = 0.5;
  return b;
}

// rezone_body on the block's whole state, with the block's relaxation.
RezoneResult rezone(UniformBlock& b) {
  RezoneParams params;
  params.relaxation = b.body.rezone_relaxation;
  RezoneScratch scratch;
  return rezone_body(b.state.mesh, b.state.zone_state, b.body, b.material, b.geometry, node_corners(b.state.mesh), params,
                     scratch);
}

}  // namespace

TEST_CASE("rezone: a uniform state moving uniformly stays exactly uniform, and the books close",
          "[rezone][conservation]") {
  for (const GeometryKind geometry : {GeometryKind::planar, GeometryKind::axisymmetric}) {
    INFO((geometry == GeometryKind::planar ? "planar" : "axisymmetric"));
    UniformBlock b = uniform_block(geometry);
    Mesh& mesh = b.state.mesh;
    const double rho = b.material.reference_density;
    double mass_before = 0.0;
    for (Index z = 0; z < mesh.zones.size(); ++z) mass_before += mesh.zones.mass[z];
    const RezoneResult result = rezone(b);
    // 5 x 7 interior nodes on the 9 x 7 node grid (the RZ axis row and every side stay).
    CHECK(result.moved_nodes == 35);
    CHECK(result.remapped_zones == 48);
    // The moved nodes really left their places: the graded spacing is not the neighbours' mean.
    double largest_move = 0.0;
    for (Index n = 0; n < mesh.nodes.size(); ++n) {
      largest_move = std::max(largest_move, norm(mesh.nodes.position(n) - Vec2{mesh.nodes.x0[n], mesh.nodes.y0[n]}));
    }
    CHECK(largest_move > 1.0e-5);

    // Uniform stays uniform (to round-off): density, energy, stress, plastic strain, velocity.
    double mass_after = 0.0;
    for (Index z = 0; z < mesh.zones.size(); ++z) {
      const quad::Corners x = mesh.corner_positions(z);
      const double volume = geometry == GeometryKind::axisymmetric ? quad::axisymmetric_volume(x) : quad::area(x);
      CHECK(mesh.zones.volume[z] == Approx(volume).epsilon(1e-14));
      CHECK(mesh.zones.density[z] == Approx(rho).epsilon(1e-12));
      CHECK(mesh.zones.mass[z] == Approx(rho * volume).epsilon(1e-12));
      CHECK(mesh.zones.specific_energy[z] == Approx(1.0e4).epsilon(1e-10));
      const StrengthZoneFields& s = b.state.zone_state.strength;
      CHECK(s.deviator_xx[z] == Approx(1.5e8).epsilon(1e-12));
      CHECK(s.deviator_xy[z] == Approx(0.7e8).epsilon(1e-12));
      CHECK(s.deviator_zz[z] == Approx(-1.0e8).epsilon(1e-12));
      CHECK(s.plastic_strain[z] == Approx(0.25).epsilon(1e-12));
      mass_after += mesh.zones.mass[z];
      double corners_total = 0.0, subzones_total = 0.0;
      for (int p = 0; p < 4; ++p) {
        corners_total += mesh.zones.corner_mass[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p)];
        subzones_total += mesh.zones.subzone_mass[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p)];
      }
      CHECK(corners_total == Approx(mesh.zones.mass[z]).epsilon(1e-13));
      CHECK(subzones_total == Approx(mesh.zones.mass[z]).epsilon(1e-13));
    }
    CHECK(mass_after == Approx(mass_before).epsilon(1e-14));
    // Every node's mass is the sum of its corner masses, and the velocity is the uniform one.
    std::vector<double> node_mass(static_cast<std::size_t>(mesh.nodes.size()), 0.0);
    for (Index z = 0; z < mesh.zones.size(); ++z) {
      for (int p = 0; p < 4; ++p) {
        node_mass[static_cast<std::size_t>(mesh.zones.corners[z][p])] +=
            mesh.zones.corner_mass[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p)];
      }
    }
    for (Index n = 0; n < mesh.nodes.size(); ++n) {
      CHECK(mesh.nodes.mass[n] == Approx(node_mass[static_cast<std::size_t>(n)]).epsilon(1e-13));
      CHECK(mesh.nodes.u[n] == Approx(b.velocity.x).epsilon(1e-12));
      CHECK(mesh.nodes.v[n] == Approx(b.velocity.y).margin(1e-12 * std::abs(b.velocity.x)));
    }
    // Nothing to turn into heat: the kinetic energy is unchanged to round-off.
    CHECK(std::abs(result.kinetic_to_internal) < 1e-12 * 0.5 * mass_before * dot(b.velocity, b.velocity));
  }
}

TEST_CASE("rezone: a shear flow's momentum is kept exactly, its kinetic energy change goes to heat",
          "[rezone][conservation]") {
  for (const GeometryKind geometry : {GeometryKind::planar, GeometryKind::axisymmetric}) {
    INFO((geometry == GeometryKind::planar ? "planar" : "axisymmetric"));
    UniformBlock b = uniform_block(geometry);
    Mesh& mesh = b.state.mesh;
    // A velocity field with curvature: the moved nodes' interpolated velocities are not exact, the
    // uniform correction restores the momentum, the kinetic energy's change is booked.
    for (Index n = 0; n < mesh.nodes.size(); ++n) {
      const double y = mesh.nodes.y[n] / 1.0e-3;
      mesh.nodes.u[n] = -300.0 + 200.0 * y * y;
    }
    const auto momentum_and_energy = [&] {
      Vec2 momentum{};
      double energy = 0.0;
      for (Index n = 0; n < mesh.nodes.size(); ++n) {
        momentum += mesh.nodes.mass[n] * mesh.nodes.velocity(n);
        energy += 0.5 * mesh.nodes.mass[n] * dot(mesh.nodes.velocity(n), mesh.nodes.velocity(n));
      }
      for (Index z = 0; z < mesh.zones.size(); ++z) energy += mesh.zones.mass[z] * mesh.zones.specific_energy[z];
      return std::pair{momentum, energy};
    };
    const auto [momentum_before, energy_before] = momentum_and_energy();
    const RezoneResult result = rezone(b);
    REQUIRE(result.moved_nodes == 35);
    const auto [momentum_after, energy_after] = momentum_and_energy();
    CHECK(momentum_after.x == Approx(momentum_before.x).epsilon(1e-14));
    CHECK(energy_after == Approx(energy_before).epsilon(1e-14));
    CHECK(result.kinetic_to_internal != 0.0);
  }
}

TEST_CASE("rezone: read from a body's block, refused on a body with a failure law", "[rezone][scenario]") {
  const std::string base = R"({
    "geometry": "axisymmetric", "end_time": 1e-6,
    "materials": { "copper": { "density": 8930.0, "eos": { "model": "linear", "bulk_modulus": 1.3e11 },
                               "strength": { "model": "linear_hardening", "shear_modulus": 4.33e10,
                                             "yield_stress": 4.0e8, "hardening_modulus": 1.0e8 } FAILURE } },
    "bodies": [ { "name": "bar", "material": "copper", REZONE
                  "mesh": { "type": "rectangle", "z": { "from": 0.0, "to": 0.01, "zones": 10 },
                            "r": { "from": 0.0, "to": 0.002, "zones": 2 } } } ] })";
  const auto scenario_text = [&](const std::string& rezone, const std::string& failure) {
    std::string text = base;
    text.replace(text.find("REZONE"), 6, rezone);
    text.replace(text.find("FAILURE"), 7, failure);
    return text;
  };
  const scenario::Scenario plain = scenario::parse_scenario(scenario_text("", ""), "plain");
  CHECK(plain.setup.bodies.front().rezone_ratio == 0.0);
  const scenario::Scenario rezoned =
      scenario::parse_scenario(scenario_text(R"("rezone": { "altitude_ratio": 0.4, "relaxation": 0.1 },)", ""), "rezoned");
  CHECK(rezoned.setup.bodies.front().rezone_ratio == 0.4);
  CHECK(rezoned.setup.bodies.front().rezone_relaxation == 0.1);
  CHECK_THROWS_WITH(scenario::parse_scenario(scenario_text(R"("rezone": { "altitude_ratio": 1.5 },)", ""), "bad"),
                    Catch::Contains("bodies[0].rezone.altitude_ratio"));
  CHECK_THROWS_WITH(scenario::parse_scenario(scenario_text(R"("rezone": { "ratio": 0.5 },)", ""), "unknown"),
                    Catch::Contains("bodies[0].rezone"));
  CHECK_THROWS_WITH(
      scenario::parse_scenario(scenario_text(R"("rezone": { "altitude_ratio": 0.5 },)",
                                             R"(, "fracture": { "elongation": 0.4, "loosening": 0.03 })"),
                               "failure"),
      Catch::Contains("bodies[0].rezone") && Catch::Contains("failure law"));
}
