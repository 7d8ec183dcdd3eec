// The setup module builds a run from a scene written in C++ types (setup/scene.hpp), with no JSON:
// the same scene written as a scenario file gives the same setup bit for bit, and what only a built
// mesh can show (overlapping bodies, a curved symmetry side, a non-positive density, an unknown side,
// too many zones) is an InputError naming the body.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "krug/core/error.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/setup/scene.hpp"
#include "krug/solver/simulation.hpp"

using namespace krug;

namespace {

// Two gas blocks side by side, the left one moving right into the right one, written as a file.
const char* two_blocks_json = R"({
  "geometry": "planar",
  "end_time": 1e-3,
  "materials": { "gas": { "density": 1.0, "eos": { "model": "ideal_gas", "gamma": 1.4 } } },
  "bodies": [
    { "name": "left", "material": "gas",
      "mesh": { "type": "rectangle", "x": { "from": -1, "to": 0, "zones": 6, "ratio": 1.1 },
                                     "y": { "from": 0, "to": 0.5, "zones": 3 } },
      "initial": { "velocity": ["2 + 0.1 * y", 0], "specific_internal_energy": "1 + x * x" },
      "boundary": { "y_min": "symmetry", "y_max": { "type": "velocity", "velocity": [null, 0] } } },
    { "name": "right", "material": "gas",
      "mesh": { "type": "rectangle", "x": { "from": 0, "to": 1, "zones": 5 },
                                     "y": { "from": 0, "to": 0.5, "zones": 3 } },
      "initial": { "density": "1 + x", "specific_internal_energy": 2.5,
                   "energy_deposit": { "energy": 0.3, "point": [0.5, 0.25] } },
      "boundary": { "x_max": "fixed", "y_min": "symmetry" } } ]
})";

// The same two blocks in C++ types. Materials, contact and controls come from the file (their
// readers are tested elsewhere); the bodies are written here.
setup::SceneDescription two_blocks_scene(const setup::SceneDescription& from_file) {
  setup::SceneDescription scene;
  scene.geometry = GeometryKind::planar;
  scene.materials = from_file.materials;
  scene.fracture = from_file.fracture;
  scene.contact = from_file.contact;
  scene.controls = from_file.controls;

  setup::BodyDescription left;
  left.name = "left";
  left.mesh.shape = setup::RectangleMesh{generate::graded_axis(-1.0, {{0.0, 6, 1.1}}),
                                         generate::graded_axis(0.0, {{0.5, 3, 1.0}})};
  left.initial.velocity = std::array<setup::PointFunction, 2>{[](double, double y) { return 2 + 0.1 * y; },
                                                              [](double, double) { return 0.0; }};
  left.initial.specific_internal_energy = [](double x, double) { return 1 + x * x; };
  left.boundary = {{"y_max", setup::SideCondition::velocity, {std::nullopt, 0.0}},
                   {"y_min", setup::SideCondition::symmetry, {}}};
  scene.bodies.push_back(left);

  setup::BodyDescription right;
  right.name = "right";
  right.mesh.shape = setup::RectangleMesh{generate::graded_axis(0.0, {{1.0, 5, 1.0}}),
                                          generate::graded_axis(0.0, {{0.5, 3, 1.0}})};
  right.initial.density = [](double x, double) { return 1 + x; };
  right.initial.specific_internal_energy = [](double, double) { return 2.5; };
  right.initial.energy_deposit = setup::EnergyDeposit{0.3, Vec2{0.5, 0.25}};
  right.boundary = {{"x_max", setup::SideCondition::fixed, {}}, {"y_min", setup::SideCondition::symmetry, {}}};
  scene.bodies.push_back(right);
  return scene;
}

// Every node and zone field of the two meshes, byte for byte.
bool same_mesh(Mesh a, Mesh b) {
  std::vector<std::string> left, right;
  auto bytes_of = [](std::vector<std::string>& out) {
    return [&out](const char*, auto& field, int, auto) {
      out.emplace_back(reinterpret_cast<const char*>(field.data()), field.size() * sizeof(field[0]));
    };
  };
  for_each_node_field(a.nodes, bytes_of(left));
  for_each_zone_field(a.zones, bytes_of(left));
  for_each_node_field(b.nodes, bytes_of(right));
  for_each_zone_field(b.zones, bytes_of(right));
  return left == right;
}

std::string error_of(const setup::SceneDescription& scene) {
  try {
    (void)setup::build_simulation(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("a scene written in C++ builds the setup its scenario file builds, bit for bit", "[setup]") {
  const scenario::Scenario scenario = scenario::parse_scenario(two_blocks_json, "two_blocks.json");
  const SimulationSetup from_file = scenario.setup;
  const SimulationSetup from_code = setup::build_simulation(two_blocks_scene(scenario.scene));

  REQUIRE(from_code.mesh.zones.size() == 33);
  CHECK(same_mesh(from_file.mesh, from_code.mesh));
  REQUIRE(from_code.bodies.size() == 2);
  for (std::size_t b = 0; b < 2; ++b) {
    CHECK(from_code.bodies[b].node_begin == from_file.bodies[b].node_begin);
    CHECK(from_code.bodies[b].zone_end == from_file.bodies[b].zone_end);
  }
  REQUIRE(from_code.constraints.size() == from_file.constraints.size());
  for (std::size_t i = 0; i < from_code.constraints.size(); ++i) {
    CHECK(from_code.constraints[i].node == from_file.constraints[i].node);
    CHECK(from_code.constraints[i].fix_x == from_file.constraints[i].fix_x);
    CHECK(from_code.constraints[i].fix_y == from_file.constraints[i].fix_y);
  }
  // Hand values: the left body's top right node moves at 2 + 0.1 x 0.5 along x and is held at 0 along
  // y; the deposit raised the specific energy above 2.5 in the zones round one interior node of the
  // right body (at most four).
  const Body& left = from_code.bodies[0];
  const Index top_right = left.node_end - 1;
  CHECK(from_code.mesh.nodes.x[top_right] == 0.0);
  CHECK(from_code.mesh.nodes.y[top_right] == 0.5);
  CHECK(from_code.mesh.nodes.u[top_right] == 2 + 0.1 * 0.5);
  CHECK(from_code.mesh.nodes.v[top_right] == 0.0);
  const Body& right = from_code.bodies[1];
  int raised = 0;
  for (Index z = right.zone_begin; z < right.zone_end; ++z) raised += from_code.mesh.zones.specific_energy[z] > 2.5;
  CHECK(raised >= 1);
  CHECK(raised <= 4);

  // The two run the same: 40 cycles, same state.
  Simulation a(from_file), b(from_code);
  for (int i = 0; i < 40; ++i) {
    a.step();
    b.step();
  }
  CHECK(a.time() == b.time());
  CHECK(same_mesh(a.state().mesh, b.state().mesh));
}

TEST_CASE("setup errors name the body: overlap, side, density, zones, material", "[setup]") {
  const scenario::Scenario scenario = scenario::parse_scenario(two_blocks_json, "two_blocks.json");
  const setup::SceneDescription good = two_blocks_scene(scenario.scene);
  CHECK(error_of(good) == "(no error)");

  SECTION("bodies that overlap name both bodies and the depth") {
    setup::SceneDescription scene = good;
    scene.bodies[1].mesh.shape = setup::RectangleMesh{generate::graded_axis(-0.1, {{1.0, 5, 1.0}}),
                                                      generate::graded_axis(0.0, {{0.5, 3, 1.0}})};
    const std::string e = error_of(scene);
    CHECK(e.find("bodies[0] (\"left\") overlaps bodies[1] (\"right\")") != std::string::npos);
    CHECK(e.find("inside zone") != std::string::npos);
  }
  SECTION("a body's where names it in the message") {
    setup::SceneDescription scene = good;
    scene.bodies[1].where = "the plate";
    scene.bodies[1].initial.density = [](double x, double) { return 0.55 - x; };  // negative beyond x = 0.55
    CHECK(error_of(scene).rfind("the plate.initial.density: gives -", 0) == 0);
  }
  SECTION("an unknown side lists the body's sides") {
    setup::SceneDescription scene = good;
    scene.bodies[0].boundary.push_back({"z_min", setup::SideCondition::fixed, {}});
    const std::string e = error_of(scene);
    CHECK(e.rfind("bodies[0].boundary.z_min:", 0) == 0);
    CHECK(e.find("x_max, x_min, y_max, y_min") != std::string::npos);
  }
  SECTION("symmetry on a curved side is refused") {
    setup::SceneDescription scene = good;
    scene.bodies[0].mesh.map = [](Vec2 p) { return Vec2{p.x, p.y + 0.1 * p.x * p.x}; };  // y_min bends
    scene.bodies[0].mesh.shape = setup::RectangleMesh{generate::graded_axis(-1.0, {{-0.2, 6, 1.0}}),
                                                      generate::graded_axis(0.0, {{0.5, 3, 1.0}})};
    CHECK(error_of(scene).find("is not a straight line along an axis") != std::string::npos);
  }
  SECTION("too many zones are refused before any is made") {
    setup::SceneDescription scene = good;
    scene.bodies[0].mesh.shape = setup::RectangleMesh{generate::graded_axis(-1.0, {{0.0, 100000, 1.0}}),
                                                      generate::graded_axis(0.0, {{0.5, 1000, 1.0}})};
    CHECK(error_of(scene).rfind("bodies[0].mesh: 100000000 zones (100000000 in the scene with the bodies before it, about 50 GB", 0) == 0);
    scene.max_zones = 30;  // a lower limit: the first body (18 zones) fits, the second (15) does not
    scene.bodies[0] = good.bodies[0];
    CHECK(error_of(scene).rfind("bodies[1].mesh: 15 zones (33 in the scene with the bodies before it", 0) == 0);
  }
  SECTION("the area-weighted RZ form is refused for a body with strength, accepted for gases") {
    setup::SceneDescription scene = good;
    scene.geometry = GeometryKind::axisymmetric;
    scene.controls.axisymmetric_form = AxisymmetricForm::area_weighted;
    for (auto& body : scene.bodies) body.boundary.clear();  // planar side names
    CHECK(error_of(scene) == "(no error)");  // both blocks are gas
    scene.materials.push_back(scene.materials[0]);
    scene.materials.back().name = "steel";
    scene.materials.back().strength = Elastic{8.0e10};
    scene.bodies[1].material = 1;
    const std::string e = error_of(scene);
    CHECK(e.rfind("controls.axisymmetric_form: \"area_weighted\" is for gases only, and body \"right\"", 0) == 0);
    CHECK(e.find("material \"steel\" with strength") != std::string::npos);
    scene.controls.axisymmetric_form = AxisymmetricForm::control_volume;
    CHECK(error_of(scene) == "(no error)");
  }
  SECTION("a material index outside the scene's materials") {
    setup::SceneDescription scene = good;
    scene.bodies[1].material = 3;
    CHECK(error_of(scene).rfind("bodies[1]: material index 3", 0) == 0);
  }
}

namespace {

// A scenario of one gas body in RZ with this mesh block.
std::string one_body(const std::string& mesh) {
  return R"({ "geometry": "axisymmetric", "end_time": 1e-3,
    "materials": { "gas": { "density": 1.0, "eos": { "model": "ideal_gas", "gamma": 1.4 } } },
    "bodies": [ { "name": "body", "material": "gas", "mesh": )" + mesh + R"( } ] })";
}

// A sample mesh block of every kind the registry holds, with the sides the kind names (setup::side_names).
struct KindSample {
  std::string block;
  std::vector<std::string> sides;
};
const std::map<std::string, KindSample, std::less<>> kind_samples = {
    {"rectangle", {R"({ "type": "rectangle", "z": { "from": 0, "to": 1, "zones": 2 }, "r": { "from": 0, "to": 1, "zones": 2 } })",
                   {"r_max", "r_min", "z_max", "z_min"}}},
    {"sector", {R"({ "type": "sector", "radius": { "from": 0, "to": 1, "zones": 2 }, "angle": { "from": 0, "to": 90, "zones": 2 } })",
                {"end", "outer", "start"}}},
    {"nosed_cylinder", {R"({ "type": "nosed_cylinder", "radius": 0.005, "length": 0.02, "radial_zones": 4 })",
                        {"axis", "nose", "rear", "side"}}},
};

}  // namespace

// Mesh kinds are one registry, the variant setup::MeshShape (scene.hpp): the reader offers its names,
// in its order, and reads each kind into its own alternative, which build_simulation generates, with
// the position map that every kind accepts.
TEST_CASE("mesh kinds: the reader offers the registry's kinds, and each reads, builds and names its sides",
          "[setup][mesh]") {
  std::vector<std::string> names;
  std::string listed;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (names.emplace_back(std::variant_alternative_t<I, setup::MeshShape>::name), ...);
  }(std::make_index_sequence<std::variant_size_v<setup::MeshShape>>{});
  for (const std::string& name : names) listed += (listed.empty() ? "\"" : ", \"") + name + "\"";
  CHECK(listed == R"("rectangle", "sector", "nosed_cylinder")");

  // An unknown kind: the message lists the registry's names.
  try {
    (void)scenario::parse_scenario(one_body(R"({ "type": "hexagon" })"), "test.json");
    FAIL("an unknown mesh type was accepted");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()) == "bodies[0].mesh.type: unknown name \"hexagon\"; expected one of " + listed);
  }

  for (std::size_t index = 0; index < names.size(); ++index) {
    INFO("mesh kind " << names[index]);
    const auto sample = kind_samples.find(names[index]);
    REQUIRE(sample != kind_samples.end());  // a new kind needs its sample here
    const scenario::Scenario scenario = scenario::parse_scenario(one_body(sample->second.block), "test.json");
    const setup::MeshDescription& mesh = scenario.scene.bodies.at(0).mesh;
    CHECK(mesh.shape.index() == index);  // read into its own alternative
    CHECK(scenario.setup.mesh.zones.size() > 0);  // and generated
    std::vector<std::string> sides;
    for (const auto& [user, generator] : setup::side_names(mesh, GeometryKind::axisymmetric)) sides.push_back(user);
    CHECK(sides == sample->second.sides);

    // The key every kind shares: "map" moves every generated node (here by 0.01 m along z).
    std::string mapped = sample->second.block;
    mapped.insert(1, R"( "map": ["z + 0.01", "r"],)");
    const scenario::Scenario moved = scenario::parse_scenario(one_body(mapped), "test.json");
    const NodeFields& before = scenario.setup.mesh.nodes;
    const NodeFields& after = moved.setup.mesh.nodes;
    REQUIRE(after.size() == before.size());
    for (Index n = 0; n < before.size(); ++n) {
      CHECK(after.x[n] == before.x[n] + 0.01);
      CHECK(after.y[n] == before.y[n]);
    }
  }
}
