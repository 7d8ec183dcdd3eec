// Scenario JSON -> SimulationSetup. The only place (with outputs) that knows the file format.
#include "krug/scenario/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <type_traits>
#include <utility>
#include <variant>

#include <fmt/format.h>

#include "expression.hpp"
#include "json_reader.hpp"
#include "scenario_bodies.hpp"
#include "scenario_materials.hpp"
#include "scenario_run.hpp"
#include "krug/core/error.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/material/library.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/nosed_cylinder.hpp"

namespace krug::scenario {

namespace {

using detail::AxisNames;
using detail::axis_names;
using detail::read_boundary;
using detail::read_initial;
using detail::body_index;
using detail::read_mesh;
using detail::read_output;
using detail::read_penetration;
using detail::read_stop_rule;
using detail::read_gauges;
using detail::check_gauges;
using detail::Allowances;
using detail::allow_hint;
using detail::expand_material;
using detail::read_allowances;
using detail::read_erosion;
using detail::read_material;

Controls read_controls(JsonObject controls, double end_time, GeometryKind geometry, long& max_zones) {
  Controls c;
  c.end_time = end_time;
  JsonObject* spec = &controls;
  // One number sets both (a scenario that names `cfl` alone means every body); `cfl_fluid` then
  // overrides it for bodies without strength.
  const bool cfl_given = spec->has("cfl");
  c.cfl = spec->number("cfl", c.cfl, Range{0.0, 1.0, true});
  c.cfl_fluid = spec->number("cfl_fluid", cfl_given ? c.cfl : c.cfl_fluid, Range{0.0, 1.0, true});
  c.initial_time_step = spec->number("initial_time_step", 0.0, Range::non_negative());
  c.max_time_step = spec->number("max_time_step", end_time, Range::positive());
  c.time_step_growth = spec->number("time_step_growth", c.time_step_growth, Range{1.0, 10.0, false});
  c.max_volume_change = spec->number("max_volume_change", c.max_volume_change, Range{0.0, 1.0, true});
  c.time_step_floor = spec->number("time_step_floor", 0.0, Range::non_negative());
  c.max_cycles = spec->integer("max_cycles", c.max_cycles, 1, 2'000'000'000);
  max_zones = spec->integer("max_zones", setup::max_zones, 1, 2'000'000'000);
  c.threads = static_cast<int>(spec->integer("threads", c.threads, 1, 256));
  {
    JsonObject viscosity = spec->object_or_empty("viscosity");
    JsonObject* v = &viscosity;
    const std::string model = v->choice("model", {"edge", "scalar", "tensor", "off", "auto"}, "auto");
    c.viscosity.model = model == "edge"     ? ViscosityModel::edge
                        : model == "scalar" ? ViscosityModel::scalar
                        : model == "tensor" ? ViscosityModel::tensor
                        : model == "auto"   ? ViscosityModel::automatic
                                            : ViscosityModel::off;
    c.viscosity.quadratic = v->number("quadratic", c.viscosity.quadratic, Range::non_negative());
    c.viscosity.linear = v->number("linear", c.viscosity.linear, Range::non_negative());
    c.viscosity.limiter = v->flag("limiter", c.viscosity.limiter);
    c.viscosity.heat_conduction = v->number("heat_conduction", c.viscosity.heat_conduction, Range::between(0.0, 4.0));
    v->finish();
  }
  {
    JsonObject hourglass = spec->object_or_empty("hourglass");
    JsonObject* h = &hourglass;
    c.hourglass.viscous = h->number("viscous", c.hourglass.viscous, Range::between(0.0, 1.0));
    // A scenario that gives a stiffness coefficient asks for the form that has one, unless it names a form.
    const bool physical_by_default = c.hourglass.stiffness_form == HourglassStiffness::physical && !h->has("stiffness");
    const std::string form =
        h->choice("stiffness_form", {"coefficient", "physical"}, physical_by_default ? "physical" : "coefficient");
    c.hourglass.stiffness_form = form == "physical" ? HourglassStiffness::physical : HourglassStiffness::coefficient;
    if (c.hourglass.stiffness_form == HourglassStiffness::physical && h->has("stiffness")) {
      h->fail("stiffness", "no stiffness coefficient with stiffness_form \"physical\" (the zone's own bending stiffness); "
                           "set stiffness_form \"coefficient\" to size it by a coefficient");
    }
    if (c.hourglass.stiffness_form == HourglassStiffness::coefficient) {
      c.hourglass.stiffness = h->number("stiffness", c.hourglass.stiffness, Range::between(0.0, 1.0));
    }
    c.hourglass.plastic_limit = h->number("plastic_limit", c.hourglass.plastic_limit, Range::between(0.0, 10.0));
    c.hourglass.subzonal_pressure =
        h->number("subzonal_pressure", c.hourglass.subzonal_pressure, Range::between(0.0, 2.0));
    c.hourglass.subzonal_at_shocks = h->flag("subzonal_at_shocks", c.hourglass.subzonal_at_shocks);
    // The subzonal pressures act in bodies without strength: the flag needs the model those take to be
    // the tensor viscosity.
    const bool tensor_in_gases =
        body_viscosity(c.viscosity, c.hourglass, false, geometry).model == ViscosityModel::tensor;
    if (c.hourglass.subzonal_at_shocks && !tensor_in_gases) {
      h->fail("subzonal_at_shocks", "false unless viscosity.model is \"tensor\", or \"auto\" in axisymmetric geometry (the "
                                    "tensor viscosity's switch marks the shocks)");
    }
    c.hourglass.collapse_pressure = h->optional_number("collapse_pressure", Range::between(0.0, 10.0));
    c.hourglass.collapse_threshold =
        h->number("collapse_threshold", c.hourglass.collapse_threshold, Range::between(1.0, 10.0));
    h->finish();
  }
  {
    JsonObject fracture = spec->object_or_empty("fracture");
    FractureControls& f = c.fracture;
    f.altitude_ratio = fracture.number("altitude_ratio", f.altitude_ratio, Range{0.0, 1.0, true});
    f.interior_altitude_ratio = fracture.number("interior_altitude_ratio", f.interior_altitude_ratio, Range{0.0, 1.0, true});
    f.particles_per_zone = static_cast<int>(fracture.integer("particles_per_zone", f.particles_per_zone, 1, 4));
    if (f.particles_per_zone != 1 && f.particles_per_zone != 4) fracture.fail("particles_per_zone", "1 or 4");
    f.time_step_floor_ratio = fracture.number("time_step_floor_ratio", f.time_step_floor_ratio, Range{0.0, 1.0, true});
    f.particle_travel = fracture.number("particle_travel", f.particle_travel, Range{0.0, 1.0, true});
    fracture.finish();
  }
  const std::string form = spec->choice("axisymmetric_form", {"control_volume", "area_weighted"}, "control_volume");
  c.axisymmetric_form = form == "area_weighted" ? AxisymmetricForm::area_weighted : AxisymmetricForm::control_volume;
  spec->finish();
  return c;
}

contact::ContactSetup read_contact(JsonObject spec, const std::vector<Body>& bodies, GeometryKind geometry,
                                   const std::vector<bool>& fracturing) {
  contact::ContactSetup setup;
  const bool any_fracture = std::find(fracturing.begin(), fracturing.end(), true) != fracturing.end();
  if (any_fracture && !spec.has("pairs")) {
    // With fracture on, contact defaults to all pairs and each fracturing body's self-contact (a plug
    // against its own plate is a self-contact); particles meet everything (docs/theory.md §2 step 7).
    Json resolved_pairs = Json::array();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      for (std::size_t j = i; j < bodies.size(); ++j) {
        if (i == j && !fracturing[i]) continue;
        setup.pairs.push_back({static_cast<Index>(i), static_cast<Index>(j), 0.0});
        resolved_pairs.push_back({{"bodies", {bodies[i].name, bodies[j].name}}, {"friction", 0.0}});
      }
    }
    spec.optional_raw("pairs");
    spec.resolve("pairs", resolved_pairs);
  } else if (const Json* pairs = spec.optional_raw("pairs")) {
    if (!pairs->is_array()) spec.fail("pairs", "an array of {bodies: [first, second], friction}");
    Json resolved_pairs = Json::array();
    for (std::size_t i = 0; i < pairs->size(); ++i) {
      Json resolved = Json::object();
      JsonObject pair((*pairs)[i], fmt::format("{}.pairs[{}]", spec.path(), i), &resolved);
      const Json& names = pair.raw("bodies");
      if (!names.is_array() || names.size() != 2) pair.fail("bodies", "two body names [first, second] (the same name twice: self-contact)");
      pair.resolve("bodies", names);
      contact::BodyPair p;
      p.first = body_index(pair, "bodies", names[0], bodies, pair.path_of("bodies") + "[0]");
      p.second = body_index(pair, "bodies", names[1], bodies, pair.path_of("bodies") + "[1]");
      p.friction = pair.number("friction", 0.0, Range::between(0.0, 10.0));
      pair.finish();
      setup.pairs.push_back(p);
      resolved_pairs.push_back(resolved);
    }
    spec.resolve("pairs", resolved_pairs);
  } else {
    spec.resolve("pairs", Json::array());
  }
  if (const Json* walls = spec.optional_raw("walls")) {
    if (!walls->is_array()) spec.fail("walls", "an array of {point, normal, friction, bodies}");
    Json resolved_walls = Json::array();
    for (std::size_t i = 0; i < walls->size(); ++i) {
      Json resolved = Json::object();
      JsonObject wall((*walls)[i], fmt::format("{}.walls[{}]", spec.path(), i), &resolved);
      contact::RigidWall w;
      auto vector = [&](std::string_view key) {
        const Json& v = wall.raw(key);
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
          wall.fail(key, fmt::format("an array [{}, {}] of two numbers", axis_name(geometry, 0), axis_name(geometry, 1)));
        }
        wall.resolve(key, v);
        return Vec2{v[0].get<double>(), v[1].get<double>()};
      };
      w.point = vector("point");
      const Vec2 normal = vector("normal");
      if (!(norm(normal) > 0.0)) wall.fail("normal", "a non-zero vector pointing into the allowed side");
      w.normal = (1.0 / norm(normal)) * normal;
      w.friction = wall.number("friction", 0.0, Range::between(0.0, 10.0));
      if (const Json* names = wall.optional_raw("bodies")) {
        if (!names->is_array()) wall.fail("bodies", "an array of body names");
        for (std::size_t k = 0; k < names->size(); ++k) {
          w.bodies.push_back(body_index(wall, "bodies", (*names)[k], bodies, fmt::format("{}[{}]", wall.path_of("bodies"), k)));
        }
        wall.resolve("bodies", *names);
      }
      wall.finish();
      setup.walls.push_back(w);
      resolved_walls.push_back(resolved);
    }
    spec.resolve("walls", resolved_walls);
  } else {
    spec.resolve("walls", Json::array());
  }
  const std::string method = spec.choice("method", {"gauss_seidel", "summation"}, "gauss_seidel");
  setup.controls.method = method == "summation" ? contact::ReactionMethod::summation : contact::ReactionMethod::gauss_seidel;
  setup.controls.max_sweeps = static_cast<int>(spec.integer("max_sweeps", setup.controls.max_sweeps, 1, 10000));
  setup.controls.solve_stalled = spec.flag("solve_stalled", setup.controls.solve_stalled);
  setup.controls.gap_tolerance = spec.number("gap_tolerance", setup.controls.gap_tolerance, Range::positive());
  setup.controls.overlap_fraction = spec.number("overlap_fraction", setup.controls.overlap_fraction, Range{0.0, 1.0, true});
  setup.controls.overlap_speed = spec.number("overlap_speed", setup.controls.overlap_speed, Range::non_negative());
  spec.finish();
  return setup;
}

}  // namespace

const std::vector<std::string>& picture_fields() {
  static const std::vector<std::string> fields = {"density", "pressure", "specific_internal_energy",
                                                  "equivalent_plastic_strain", "damaged", "sound_speed",
                                                  "speed", "body"};
  return fields;
}

Scenario parse_scenario(const std::string& json_text, const std::string& origin, const ReadLimits& read_limits) {
  const Json document = parse_document<Json>(json_text, origin);
  Scenario scenario;
  Json resolved = Json::object();
  JsonObject top(document, "", &resolved);
  if (const Json* schema = top.optional_raw("$schema")) {
    // Lets an editor find docs/scenario.schema.json; not copied to the resolved scenario.
    if (!schema->is_string()) top.fail("$schema", "a string (the schema's address, ignored)");
  }
  scenario.title = top.text("title", "");
  top.text("description", "");
  const Allowances allow = read_allowances(top);
  const std::string geometry_name = top.choice("geometry", {"planar", "axisymmetric"});
  const GeometryKind geometry = geometry_name == "planar" ? GeometryKind::planar : GeometryKind::axisymmetric;
  setup::SceneDescription& scene = scenario.scene;
  scene.geometry = geometry;
  const double end_time = top.number("end_time", Range::positive());

  // Materials: an object name -> definition, or the name of a library set, or a set with overrides.
  std::map<std::string, Index> material_index;
  std::vector<fracture::ErosionLimits> material_erosion;  // per material; a body's own block overrides it
  std::vector<Json> expanded_materials;  // read in place of the given ones; outlive their readers
  {
    JsonObject materials = top.object("materials");
    expanded_materials.reserve(materials.keys().size());
    for (const std::string& name : materials.keys()) {
      material_index[name] = static_cast<Index>(scene.materials.size());
      fracture::FailureLaw limits;
      fracture::ErosionLimits erosion;
      expanded_materials.push_back(expand_material(materials.raw(name), materials.path_of(name)));
      scene.materials.push_back(
          read_material(name, materials.object_from(name, expanded_materials.back()), limits, erosion, allow));
      scene.fracture.push_back(limits);
      material_erosion.push_back(erosion);
    }
    if (scene.materials.empty()) materials.fail_here("expected at least one material");
    materials.finish();
  }

  // Bodies: an array, each with its own nodes.
  const Json& bodies = top.raw("bodies");
  if (!bodies.is_array() || bodies.empty()) top.fail("bodies", "a non-empty array of bodies");
  Json resolved_bodies = Json::array();
  std::vector<Body> named_bodies;  // name, material and erosion of each body (the readers below name bodies)
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Json resolved_body = Json::object();
    JsonObject spec(bodies[i], fmt::format("bodies[{}]", i), &resolved_body);
    Body body;
    body.name = spec.text("name");
    if (body.name.empty()) spec.fail("name", "a non-empty name");
    for (const Body& other : named_bodies) {
      if (other.name == body.name) spec.fail("name", "a name no other body has");
    }
    const std::string material = spec.text("material");
    const auto m = material_index.find(material);
    if (m == material_index.end()) {
      std::vector<std::string> names;
      std::string list;
      for (const auto& [name, _] : material_index) { names.push_back(name); list += (list.empty() ? "\"" : ", \"") + name + "\""; }
      const auto guess = nearest(material, names);
      throw InputError(fmt::format("{}: unknown material \"{}\"; defined materials: {}{}", spec.path_of("material"),
                                   material, list, guess ? fmt::format(" (did you mean \"{}\"?)", *guess) : ""));
    }
    body.material = m->second;
    body.set_erosion(material_erosion[static_cast<std::size_t>(body.material)]);
    if (auto erosion = spec.optional_object("erosion")) body.set_erosion(read_erosion(std::move(*erosion), body.erosion()));
    setup::BodyDescription description;
    description.name = body.name;
    description.material = body.material;
    description.erosion = body.erosion();
    if (auto rezone = spec.optional_object("rezone")) {
      description.rezone.altitude_ratio = rezone->number("altitude_ratio", Range{0.0, 1.0, true});
      description.rezone.relaxation = rezone->number("relaxation", description.rezone.relaxation, Range{0.0, 1.0, true});
      rezone->finish();
    }
    description.where = spec.path();
    description.mesh = read_mesh(spec.object("mesh"), geometry, allow.allows("angle"));
    if (auto initial = spec.optional_object("initial")) description.initial = read_initial(*initial, geometry);
    if (auto boundary = spec.optional_object("boundary")) {
      description.boundary = read_boundary(*boundary, description.mesh, geometry);
    }
    spec.finish();
    scene.bodies.push_back(std::move(description));
    named_bodies.push_back(body);
    resolved_bodies.push_back(resolved_body);
  }
  top.resolve("bodies", resolved_bodies);
  std::vector<bool> fracturing;
  for (const Body& body : named_bodies) fracturing.push_back(fracture::enabled(scene.fracture[static_cast<std::size_t>(body.material)]));
  scene.contact = read_contact(top.object_or_empty("contact"), named_bodies, geometry, fracturing);

  scene.controls = read_controls(top.object_or_empty("controls"), end_time, geometry, scene.max_zones);
  if (read_limits.max_zones > 0) scene.max_zones = std::min(scene.max_zones, read_limits.max_zones);
  const bool solids = std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) {
    return !std::holds_alternative<std::variant_alternative_t<0, Strength>>(m.strength);
  });
  scenario.output = read_output(top.object_or_empty("output"), end_time, geometry, solids);
  if (auto penetration = top.optional_object("penetration")) {
    scenario.penetration = read_penetration(*penetration, named_bodies);
  }
  if (scenario.penetration) {  // a penetration run always has a stop rule: by default, clear of the targets
    scenario.stop = read_stop_rule(top.object_or_empty("stop"), named_bodies, scenario.penetration);
  } else if (auto stop = top.optional_object("stop")) {
    scenario.stop = read_stop_rule(*stop, named_bodies, scenario.penetration);
  }
  if (auto gauges = top.optional_object("gauges")) {
    scenario.gauges = read_gauges(*gauges, named_bodies, geometry);
  }
  top.finish();
  scenario.resolved_json = resolved.dump(2);
  scenario.setup = setup::build_simulation(scenario.scene);
  check_gauges(scenario.gauges, scenario.setup);
  if (!allow.allows("velocity")) {
    // Speeds of impact problems reach tens of km/s (meteoroids); 1e5 m/s is a slip (km/s for m/s).
    const Mesh& mesh = scenario.setup.mesh;
    for (const Body& body : scenario.setup.bodies) {
      for (Index n = body.node_begin; n < body.node_end; ++n) {
        const double speed = std::hypot(mesh.nodes.u[n], mesh.nodes.v[n]);
        if (speed > 1e5) {
          throw InputError(fmt::format("{}: body \"{}\" starts at {:.4g} m/s at ({:.4g}, {:.4g}), faster than 1e5 m/s "
                                       "(km/s for m/s?){}",
                                       scenario.scene.bodies[static_cast<std::size_t>(&body - scenario.setup.bodies.data())].where,
                                       body.name, speed, mesh.nodes.x[n], mesh.nodes.y[n], allow_hint("velocity")));
        }
      }
    }
  }
  return scenario;
}

Scenario load_scenario(const std::filesystem::path& file) {
  Scenario scenario = parse_scenario(read_text_file(file, "scenario file"), file.string());
  scenario.source = file;
  if (scenario.output.directory.empty()) scenario.output.directory = "out/" + file.stem().string();
  return scenario;
}

}  // namespace krug::scenario
