// Scenario JSON -> SimulationSetup. The only place (with outputs) that knows the file format.
#include "krug/io/scenario.hpp"

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
#include "scenario_run.hpp"
#include "krug/core/error.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/material/library.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/nosed_cylinder.hpp"

namespace krug::io {

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

// The constant of key `key` of a strength model (its parameter list), if the model has one.
std::optional<double> strength_constant(const Strength& strength, std::string_view key) {
  return std::visit(
      [&](const auto& model) -> std::optional<double> {
        for (const auto& p : parameters(std::type_identity<std::decay_t<decltype(model)>>{})) {
          if (p.key == key) return model.*(p.member);
        }
        return std::nullopt;
      },
      strength);
}

// One model of a variant (Eos, Strength, fracture::FailureLaw) from its block: "model" names it (the
// alternatives' `name`s, in the variant's order; `fallback`: the model when the key is absent), and its
// parameters are read as its header describes them (krug/core/parameters.hpp). A model's
// `reference_density` is the material's. An optional parameter that stands for a strength constant
// (`strength_key`) takes the material's `strength` value when it is not given; an optional parameter
// whose value when absent is infinite (a limit that is off) is not written into the resolved scenario
// (JSON has no infinity).
template <class Model>
Model read_model_parameters(JsonObject& spec, double reference_density, const Strength* strength = nullptr) {
  Model model{};
  for (const ModelParameter<Model>& p : parameters(std::type_identity<Model>{})) {
    const Range range{p.minimum, p.maximum, p.minimum_exclusive};
    double fallback = p.fallback;
    if (!p.strength_key.empty() && strength != nullptr) {
      if (const auto value = strength_constant(*strength, p.strength_key)) fallback = *value;
    }
    if (p.required) {
      model.*(p.member) = spec.number(p.key, range);
    } else if (!std::isfinite(fallback) && !spec.has(p.key)) {
      spec.optional_raw(p.key);  // named among the valid keys
      model.*(p.member) = fallback;
    } else {
      model.*(p.member) = spec.number(p.key, fallback, range);
    }
  }
  if constexpr (requires { model.reference_density; }) model.reference_density = reference_density;
  return model;
}

template <class Variant>
Variant read_model(JsonObject& spec, std::optional<std::string_view> fallback, double reference_density,
                   const Strength* strength = nullptr, bool echo_fallback = true) {
  const std::vector<std::string> names = alternative_names<Variant>();
  std::string chosen;
  if (fallback && !echo_fallback && !spec.has("model")) {
    spec.optional_raw("model");  // named among the valid keys; the default is not written out
    chosen = std::string(*fallback);
  } else {
    chosen = fallback ? spec.choice("model", names, *fallback) : spec.choice("model", names);
  }
  return make_alternative<Variant>(chosen, [&]<class Model>(std::type_identity<Model>) {
    return read_model_parameters<Model>(spec, reference_density, strength);
  });
}

// An erosion block {"altitude_ratio", "plastic_strain"}; keys not given keep the values of `base`.
fracture::ErosionLimits read_erosion(JsonObject spec, fracture::ErosionLimits base) {
  base.altitude_ratio = spec.number("altitude_ratio", base.altitude_ratio, Range::between(0.0, 1.0));
  if (spec.has("plastic_strain")) {
    base.plastic_strain = spec.number("plastic_strain", Range::positive());
  } else {
    spec.optional_raw("plastic_strain");  // named among the valid keys
  }
  spec.finish();
  return base;
}

// The plausibility checks a physicist would make of a solid's data and of a scenario's speeds and
// angles; each catches a unit slip (GPa for Pa, g/cm^3 for kg/m^3, percent, radians, km/s) that would
// otherwise run and fail later for an unrelated reason. A deliberate exception is named in the
// top-level "allow_unusual" list.
struct Allowances {
  std::set<std::string> allowed;
  bool allows(const std::string& check) const { return allowed.count(check) > 0; }
};

const std::vector<std::string>& unusual_checks() {
  static const std::vector<std::string> checks = {"density", "sound_speed", "shear_modulus", "yield_stress",
                                                  "fracture_strain", "velocity", "angle"};
  return checks;
}

std::string allow_hint(const std::string& check) {
  return fmt::format("; if this is deliberate, add \"{}\" to the top-level \"allow_unusual\" list", check);
}

Allowances read_allowances(JsonObject& top) {
  Allowances a;
  const Json* list = top.optional_raw("allow_unusual");
  if (!list) {
    top.resolve("allow_unusual", Json::array());
    return a;
  }
  const std::string expected = fmt::format("an array of check names ({})", fmt::join(unusual_checks(), ", "));
  if (!list->is_array()) top.fail("allow_unusual", expected);
  for (const Json& item : *list) {
    if (!item.is_string() || std::find(unusual_checks().begin(), unusual_checks().end(), item.get<std::string>()) ==
                                 unusual_checks().end()) {
      top.fail("allow_unusual", expected);
    }
    a.allowed.insert(item.get<std::string>());
  }
  top.resolve("allow_unusual", *list);
  return a;
}

// The library's names, quoted, for messages.
std::string library_names() {
  std::string list;
  for (const library::MaterialSet& set : library::material_sets) {
    list += fmt::format("{}\"{}\"", list.empty() ? "" : ", ", set.name);
  }
  return list;
}

// A library set as the material block the reader reads: density, eos, strength and, where the set has
// them, fracture criteria. The damage constants (block "damage") enter only a fracture block that asks
// for the Johnson-Cook law (expand_material).
Json library_material(const library::MaterialSet& set) {
  Json m = Json::object();
  m["eos"] = Json{{"model", std::string(set.eos_model)}};
  m["strength"] = Json{{"model", std::string(set.strength_model)}};
  for (const library::Constant& c : set.constants) {
    if (c.block == "damage") continue;
    if (c.block.empty()) {
      m[std::string(c.key)] = c.value;
    } else {
      m[std::string(c.block)][std::string(c.key)] = c.value;
    }
  }
  return m;
}

// The material given at `path` (materials.NAME) as the reader reads it. A string names a library set; an
// object with "base" names one and overrides it: a block given with another "model" replaces the set's
// block, any other block is merged into it key by key, and any other key replaces the set's. The set's
// name stays as "base" (information). Anything else is returned as it is.
Json expand_material(const Json& given, const std::string& path) {
  const Json* base = nullptr;
  std::string where = path;
  if (given.is_string()) {
    base = &given;
  } else if (given.is_object() && given.contains("base")) {
    base = &given["base"];
    where = path + ".base";
    if (!base->is_string()) {
      throw InputError(fmt::format("{}: expected the name of a library material (a string; krug materials lists "
                                   "them), found {}", where, describe_value(*base)));
    }
  } else {
    if (!given.is_object()) {
      throw InputError(fmt::format("{}: expected a material (an object) or the name of a library material, found {}",
                                   path, describe_value(given)));
    }
    return given;
  }
  const std::string name = base->get<std::string>();
  const library::MaterialSet* set = library::find_material_set(name);
  if (!set) {
    std::vector<std::string> names;
    for (const library::MaterialSet& s : library::material_sets) names.emplace_back(s.name);
    auto guess = nearest(name, names);
    for (std::size_t i = 0; !guess && !name.empty() && i < names.size(); ++i) {
      if (names[i].find(name) != std::string::npos) guess = names[i];  // "copper": "ofhc-copper"
    }
    throw InputError(fmt::format("{}: unknown library material \"{}\"; the library has {}{}", where, name,
                                 library_names(), guess ? fmt::format(" (did you mean \"{}\"?)", *guess) : ""));
  }
  Json expanded = library_material(*set);
  if (given.is_object()) {
    for (const auto& [key, value] : given.items()) {
      if (key == "base") continue;
      Json& into = expanded[key];
      const bool other_model = value.is_object() && value.contains("model") &&
                               !(into.is_object() && into.contains("model") && into["model"] == value["model"]);
      if (value.is_object() && into.is_object() && !other_model) {
        for (const auto& [k, v] : value.items()) into[k] = v;
      } else {
        into = value;
      }
    }
  }
  // "fracture": {"model": "johnson_cook"} takes the set's published D1..D5 for the constants it does
  // not give itself; a set without them leaves the reader to ask for them.
  const auto fracture = expanded.find("fracture");
  if (fracture != expanded.end() && fracture->is_object() && fracture->contains("model") &&
      (*fracture)["model"] == std::string(fracture::JohnsonCookDamage::name)) {
    for (const library::Constant& c : set->constants) {
      if (c.block == "damage" && !fracture->contains(std::string(c.key))) (*fracture)[std::string(c.key)] = c.value;
    }
  }
  expanded["base"] = name;
  return expanded;
}

Material read_material(const std::string& name, JsonObject spec, fracture::FailureLaw& failure,
                       fracture::ErosionLimits& erosion, const Allowances& allow) {
  Material m;
  m.name = name;
  if (spec.has("base")) {
    spec.text("base");  // the library set it came from, kept as information
  } else {
    spec.optional_raw("base");  // named among the valid keys
  }
  m.reference_density = spec.number("density", Range::positive());
  JsonObject eos = spec.object("eos");
  m.eos = read_model<Eos>(eos, std::nullopt, m.reference_density);
  eos.finish();
  JsonObject strength = spec.object_or_empty("strength");
  m.strength = read_model<Strength>(strength, std::variant_alternative_t<0, Strength>::name, m.reference_density);
  // Physical sanity: the Poisson ratio implied by the bulk and shear moduli, nu = (3K - 2 mu) / (2 (3K + mu)),
  // lies in (-1, 1/2) for any positive moduli; a negative one almost always means a unit slip (GPa vs Pa)
  // in one of them, so it is refused here with both values.
  const double shear_modulus = m.shear_modulus();
  const double bulk_modulus = reference_bulk_modulus(m.eos);  // each model's answer; 0 for a gas
  if (shear_modulus > 0.0 && bulk_modulus > 0.0) {
    const double poisson = (3.0 * bulk_modulus - 2.0 * shear_modulus) / (2.0 * (3.0 * bulk_modulus + shear_modulus));
    if (poisson < 0.0) {
      strength.fail("shear_modulus", fmt::format("a shear modulus giving, with the bulk modulus {:.4g} Pa of the eos, a "
                                                 "Poisson ratio in [0, 0.5); this one gives {:.3f} (a unit slip?)",
                                                 bulk_modulus, poisson));
    }
  }
  // A solid or a liquid (an eos with a bulk modulus at its reference state, or a strength model): the
  // ranges of real solids, from foams and polymers to tungsten (gases are often non-dimensional, and are
  // not checked).
  const bool solid = bulk_modulus > 0.0 || shear_modulus > 0.0;
  if (solid && !allow.allows("density") && !(m.reference_density >= 100.0 && m.reference_density <= 25'000.0)) {
    throw InputError(fmt::format("{}: {:g} kg/m^3 is outside the 100 to 25 000 kg/m^3 of solids (g/cm^3 for kg/m^3?){}",
                                 spec.path_of("density"), m.reference_density, allow_hint("density")));
  }
  if (solid && bulk_modulus > 0.0 && !allow.allows("sound_speed")) {
    const double c = std::sqrt((bulk_modulus + 4.0 / 3.0 * shear_modulus) / m.reference_density);
    if (!(c >= 100.0 && c <= 20'000.0)) {
      throw InputError(fmt::format("{}: the longitudinal sound speed sqrt((K + 4/3 mu) / rho) = {:.4g} m/s is outside "
                                   "the 100 to 20 000 m/s of solids (moduli in GPa for Pa?){}",
                                   eos.path(), c, allow_hint("sound_speed")));
    }
  }
  if (shear_modulus > 0.0 && std::isfinite(shear_modulus) && bulk_modulus > 0.0 && !allow.allows("shear_modulus") &&
      shear_modulus < 1e-5 * bulk_modulus) {
    throw InputError(fmt::format("{}: {:.4g} Pa is less than 1e-5 of the bulk modulus {:.4g} Pa (GPa for Pa?){}",
                                 strength.path_of("shear_modulus"), shear_modulus, bulk_modulus, allow_hint("shear_modulus")));
  }
  const double yield = std::visit([](const auto& model) { return model.flow_stress(0.0); }, m.strength);
  if (shear_modulus > 0.0 && std::isfinite(yield) && yield > 0.0 && !allow.allows("yield_stress") &&
      !(yield >= 1e-6 * shear_modulus && yield <= 0.2 * shear_modulus)) {
    throw InputError(fmt::format("{}: an initial yield stress of {:.4g} Pa is {:.3g} of the shear modulus; solids lie "
                                 "between 1e-6 and 0.2 (Pa for MPa?){}",
                                 strength.path(), yield, yield / shear_modulus, allow_hint("yield_stress")));
  }
  strength.finish();
  if (auto f = spec.optional_object("fracture")) {
    // A failure law (krug/fracture/failure_law.hpp): criteria (1) of the paper unless "model" names another.
    failure = read_model<fracture::FailureLaw>(*f, std::variant_alternative_t<0, fracture::FailureLaw>::name,
                                               m.reference_density, &m.strength, false);
    if (const auto* limits = std::get_if<fracture::FractureLimits>(&failure)) {
      // Criteria (1): each enabled only when its limit is given.
      if (!allow.allows("fracture_strain")) {
        for (const auto& [key, value] :
             {std::pair{"elongation", limits->elongation}, std::pair{"shear_strain", limits->shear_strain}}) {
          if (value != fracture::disabled && value > 10.0) {
            throw InputError(fmt::format("{}: a strain of {:g} is more than 10 (1000 %); strains are fractions, not "
                                         "percent{}",
                                         f->path_of(key), value, allow_hint("fracture_strain")));
          }
        }
      }
      f->finish();
      if (!limits->any()) {
        f->fail_here("expected at least one limit: elongation, tensile_stress, compressive_stress, shear_strain or internal_energy");
      }
    } else {
      f->finish();
    }
  }
  if (auto e = spec.optional_object("erosion")) erosion = read_erosion(std::move(*e), erosion);
  spec.finish();
  return m;
}

Controls read_controls(JsonObject controls, double end_time, long& max_zones) {
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
    const std::string model = v->choice("model", {"edge", "scalar", "off"}, "edge");
    c.viscosity.model = model == "edge" ? ViscosityModel::edge : model == "scalar" ? ViscosityModel::scalar
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
    c.hourglass.stiffness = h->number("stiffness", c.hourglass.stiffness, Range::between(0.0, 1.0));
    c.hourglass.subzonal_pressure =
        h->number("subzonal_pressure", c.hourglass.subzonal_pressure, Range::between(0.0, 2.0));
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

  scene.controls = read_controls(top.object_or_empty("controls"), end_time, scene.max_zones);
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

}  // namespace krug::io
