// The zones' physics state grouped by package (include/krug/mesh/zone_state.hpp): the groups'
// registries, and the zone state a setup may give a run.
#include <catch2/catch.hpp>

#include <set>
#include <string>
#include <string_view>

#include "krug/core/error.hpp"
#include "krug/krug.hpp"

using namespace krug;

namespace {

// A block of n x n zones of a solid without strength, at rest.
SimulationSetup block(int n) {
  SimulationSetup s;
  const auto axis = generate::graded_axis(0.0, {{1.0, n, 1.0}});
  const auto patch = generate::rectangle(s.mesh, axis, axis, 0);
  s.materials.push_back(Material{"solid", 2700.0, LinearBulk{7.0e10, 2700.0}, NoStrength{}});
  s.bodies.push_back({"block", 0, patch.node_begin, patch.node_end, patch.zone_begin, patch.zone_end});
  s.controls.end_time = 1.0;
  return s;
}

}  // namespace

TEST_CASE("zone state: every group's field once in the registries, resized with its fill value", "[mesh][zone_state]") {
  ZoneState state;
  state.resize(3);
  CHECK(state.size() == 3);
  std::set<std::string> names;
  int fields = 0;
  for_each_zone_state_field(state, [&](std::string_view name, const auto& field, std::size_t per, auto fill) {
    ++fields;
    names.emplace(name);
    INFO(name);
    CHECK(field.size() == 3 * per);
    for (const auto value : field) CHECK(value == fill);
  });
  CHECK(fields == 6 + 5 + 2 + 5);
  CHECK(names.size() == static_cast<std::size_t>(fields));
  // The checkpoint's length check names a field by its registry name: unique beside the mesh's too.
  Mesh mesh;
  for_each_zone_field(mesh.zones, [&](std::string_view name, auto&, std::size_t, auto) { names.emplace(name); });
  CHECK(names.size() == static_cast<std::size_t>(fields) + 14);
  CHECK(state.hydro.corner_force.size() == 24);
  CHECK(state.fracture.damage_time[2] == -1.0);
}

TEST_CASE("zone state: a run keeps the state its setup gives and refuses one of another size", "[solver][zone_state]") {
  SECTION("empty: every zone intact and unstressed, with its EOS state") {
    const Simulation sim(block(4));
    REQUIRE(sim.zone_state().size() == 16);
    for (Index z = 0; z < 16; ++z) {
      CHECK(sim.zone_state().fracture.damaged[z] == 0);
      CHECK(sim.zone_state().strength.deviator_xx[z] == 0.0);
      CHECK(sim.zone_state().hydro.sound_speed[z] > 0.0);
    }
  }
  SECTION("given: pre-damaged and pre-stressed zones start so") {
    SimulationSetup s = block(4);
    s.zone_state.resize(s.mesh.zones.size());
    s.zone_state.fracture.damaged[5] = 1;
    s.zone_state.strength.deviator_xy[6] = 1.0e6;
    const Simulation sim(s);
    CHECK(sim.zone_state().fracture.damaged[5] == 1);
    CHECK(sim.zone_state().strength.deviator_xy[6] == 1.0e6);
    CHECK(sim.zone_state().hydro.sound_speed[5] > 0.0);
  }
  SECTION("another size: refused, naming the field") {
    SimulationSetup s = block(4);
    s.zone_state.resize(s.mesh.zones.size());
    s.zone_state.hourglass.hourglass_y.resize(2);
    CHECK_THROWS_WITH(Simulation(s), Catch::Contains("hourglass_y"));
    s.zone_state.resize(3);
    CHECK_THROWS_AS(Simulation(s), InputError);
  }
  SECTION("a restored state of another size is refused") {
    Simulation sim(block(4));
    SimulationState state = sim.state();
    state.zone_state.resize(2);
    CHECK_THROWS_AS(sim.restore(state), InputError);
  }
}
