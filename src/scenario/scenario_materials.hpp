#pragma once
// Reading a scenario's materials (private to the io library): library sets by name with key-by-key
// overrides (expand_material), one material's EOS, strength and failure law read from the parameter
// lists their headers describe (read_material), erosion limits, and the plausibility checks of a
// solid's data with the scenario's "allow_unusual" exceptions. Used by scenario.cpp's parse_scenario;
// every error names the JSON path.
#include <set>
#include <string>

#include "json_reader.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/material/material.hpp"

namespace krug::scenario::detail {

// The plausibility checks a physicist would make of a solid's data and of a scenario's speeds and
// angles; each catches a unit slip (GPa for Pa, g/cm^3 for kg/m^3, percent, radians, km/s) that would
// otherwise run and fail later for an unrelated reason. A deliberate exception is named in the
// top-level "allow_unusual" list.
struct Allowances {
  std::set<std::string> allowed;
  bool allows(const std::string& check) const { return allowed.count(check) > 0; }
};

// The hint appended to a plausibility error: how to allow the check deliberately.
std::string allow_hint(const std::string& check);
// The top-level "allow_unusual" list (written back resolved).
Allowances read_allowances(JsonObject& top);
// An erosion block {"altitude_ratio", "plastic_strain"}; keys not given keep the values of `base`.
fracture::ErosionLimits read_erosion(JsonObject spec, fracture::ErosionLimits base);
// The material given at `path` (materials.NAME) as the reader reads it: a library set by name, or one
// with "base" and overrides, expanded; anything else returned as it is.
Json expand_material(const Json& given, const std::string& path);
// One material block: density, EOS, strength, and its failure law and erosion limits.
Material read_material(const std::string& name, JsonObject spec, fracture::FailureLaw& failure,
                       fracture::ErosionLimits& erosion, const Allowances& allow);

}  // namespace krug::scenario::detail
