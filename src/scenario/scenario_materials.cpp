// Reading a scenario's materials: library sets, models from their parameter lists, failure laws,
// erosion and the plausibility checks of a solid's data (scenario_materials.hpp).
#include "scenario_materials.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>

#include <fmt/format.h>

#include "json_reader.hpp"
#include "krug/core/error.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/material/library.hpp"

namespace krug::scenario::detail {

namespace {

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

}  // namespace


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

namespace {



const std::vector<std::string>& unusual_checks() {
  static const std::vector<std::string> checks = {"density", "sound_speed", "shear_modulus", "yield_stress",
                                                  "fracture_strain", "velocity", "angle"};
  return checks;
}

}  // namespace


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

namespace {


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

}  // namespace


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

}  // namespace krug::scenario::detail
