// The material library (include/krug/material/library.hpp): every constant against its cited source,
// written out again here independently of the library's table (a typo in either fails), the physical
// sanity of every set, and each set read through the scenario reader.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <variant>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/material/library.hpp"

namespace {

namespace library = krug::library;

struct Cited {
  const char* set;
  const char* key;  // block.key, or key for the material's own keys
  double value;
  const char* source;
};

// Johnson & Cook 1983 (JC83) Table 1; Johnson & Cook 1985 (JC85) Table 1; Steinberg 1996 (S96);
// Lesuer 2000 (L00); Lesuer, Kay & LeBlanc 2001 (L01); Kay 2003 (K03); Brar, Joshi & Harris 2009 (B09);
// ASM Handbook; Kaye & Laby (KL); Gulidov & Shabalin 1996 as the paper's scenarios always had it (GS96).
// Moduli derived from E and nu are given as E and nu here and derived below.
const Cited cited[] = {
    // 6061-T6
    {"al6061-t6", "density", 2703.0, "S96"},
    {"al6061-t6", "eos.bulk_sound_speed", 5240.0, "S96"},
    {"al6061-t6", "eos.hugoniot_slope", 1.40, "S96"},
    {"al6061-t6", "eos.gruneisen", 1.97, "S96"},
    {"al6061-t6", "strength.shear_modulus", 27.6e9, "S96"},
    {"al6061-t6", "strength.yield_stress", 324e6, "L01"},
    {"al6061-t6", "strength.hardening_coefficient", 114e6, "L01"},
    {"al6061-t6", "strength.hardening_exponent", 0.42, "L01"},
    {"al6061-t6", "strength.strain_rate_coefficient", 0.002, "L01"},
    {"al6061-t6", "strength.thermal_softening_exponent", 1.34, "L01"},
    {"al6061-t6", "strength.melt_temperature", 925.0, "L01"},
    {"al6061-t6", "strength.specific_heat", 896.0, "ASM"},
    {"al6061-t6", "damage.d1", -0.77, "L01"},
    {"al6061-t6", "damage.d2", 1.45, "L01"},
    {"al6061-t6", "damage.d3", -0.47, "L01"},
    {"al6061-t6", "damage.d4", 0.0, "L01"},
    {"al6061-t6", "damage.d5", 1.60, "L01"},
    // 2024-T3
    {"al2024-t3", "density", 2785.0, "S96"},
    {"al2024-t3", "eos.bulk_sound_speed", 5328.0, "S96"},
    {"al2024-t3", "eos.hugoniot_slope", 1.338, "S96"},
    {"al2024-t3", "eos.gruneisen", 2.00, "S96"},
    {"al2024-t3", "strength.shear_modulus", 28.6e9, "S96"},
    {"al2024-t3", "strength.yield_stress", 369e6, "L00"},
    {"al2024-t3", "strength.hardening_coefficient", 684e6, "L00"},
    {"al2024-t3", "strength.hardening_exponent", 0.73, "L00"},
    {"al2024-t3", "strength.strain_rate_coefficient", 0.0083, "L00"},
    {"al2024-t3", "strength.thermal_softening_exponent", 1.7, "L00"},
    {"al2024-t3", "strength.melt_temperature", 775.0, "JC83 2024-T351"},
    {"al2024-t3", "strength.specific_heat", 875.0, "JC83 2024-T351"},
    {"al2024-t3", "damage.d1", 0.13, "JC85 2024-T351"},
    {"al2024-t3", "damage.d2", 0.13, "JC85 2024-T351"},
    {"al2024-t3", "damage.d3", -1.5, "JC85 2024-T351"},
    {"al2024-t3", "damage.d4", 0.011, "JC85 2024-T351"},
    {"al2024-t3", "damage.d5", 0.0, "JC85 2024-T351"},
    // 7075-T6
    {"al7075-t6", "density", 2810.0, "ASM"},
    {"al7075-t6", "strength.shear_modulus", 26.9e9, "ASM"},
    {"al7075-t6", "strength.yield_stress", 546e6, "B09"},
    {"al7075-t6", "strength.hardening_coefficient", 674e6, "B09"},
    {"al7075-t6", "strength.hardening_exponent", 0.72, "B09"},
    {"al7075-t6", "strength.strain_rate_coefficient", 0.059, "B09"},
    {"al7075-t6", "strength.thermal_softening_exponent", 1.56, "B09"},
    {"al7075-t6", "strength.melt_temperature", 908.0, "ASM liquidus"},
    {"al7075-t6", "strength.specific_heat", 960.0, "ASM"},
    {"al7075-t6", "damage.d1", -0.068, "B09"},
    {"al7075-t6", "damage.d2", 0.451, "B09"},
    {"al7075-t6", "damage.d3", -0.952, "B09"},
    {"al7075-t6", "damage.d4", 0.036, "B09"},
    {"al7075-t6", "damage.d5", 0.697, "B09"},
    // lead
    {"lead", "density", 11350.0, "S96"},
    {"lead", "eos.bulk_sound_speed", 2006.0, "S96"},
    {"lead", "eos.hugoniot_slope", 1.429, "S96"},
    {"lead", "eos.gruneisen", 2.74, "S96"},
    {"lead", "strength.shear_modulus", 8.6e9, "S96"},
    {"lead", "strength.yield_stress", 8e6, "S96"},
    // OFHC copper
    {"ofhc-copper", "density", 8930.0, "S96"},
    {"ofhc-copper", "eos.bulk_sound_speed", 3940.0, "S96"},
    {"ofhc-copper", "eos.hugoniot_slope", 1.489, "S96"},
    {"ofhc-copper", "eos.gruneisen", 2.02, "S96"},
    {"ofhc-copper", "strength.shear_modulus", 47.7e9, "S96"},
    {"ofhc-copper", "strength.yield_stress", 90e6, "JC83"},
    {"ofhc-copper", "strength.hardening_coefficient", 292e6, "JC83"},
    {"ofhc-copper", "strength.hardening_exponent", 0.31, "JC83"},
    {"ofhc-copper", "strength.strain_rate_coefficient", 0.025, "JC83"},
    {"ofhc-copper", "strength.thermal_softening_exponent", 1.09, "JC83"},
    {"ofhc-copper", "strength.melt_temperature", 1356.0, "JC83"},
    {"ofhc-copper", "strength.specific_heat", 383.0, "JC83"},
    {"ofhc-copper", "damage.d1", 0.54, "JC85"},
    {"ofhc-copper", "damage.d2", 4.89, "JC85"},
    {"ofhc-copper", "damage.d3", -3.03, "JC85"},
    {"ofhc-copper", "damage.d4", 0.014, "JC85"},
    {"ofhc-copper", "damage.d5", 1.12, "JC85"},
    // 4340 steel, Rc 30
    {"steel-4340", "density", 7830.0, "JC83"},
    {"steel-4340", "strength.yield_stress", 792e6, "JC83"},
    {"steel-4340", "strength.hardening_coefficient", 510e6, "JC83"},
    {"steel-4340", "strength.hardening_exponent", 0.26, "JC83"},
    {"steel-4340", "strength.strain_rate_coefficient", 0.014, "JC83"},
    {"steel-4340", "strength.thermal_softening_exponent", 1.03, "JC83"},
    {"steel-4340", "strength.melt_temperature", 1793.0, "JC83"},
    {"steel-4340", "strength.specific_heat", 477.0, "JC83"},
    {"steel-4340", "damage.d1", 0.05, "JC85"},
    {"steel-4340", "damage.d2", 3.44, "JC85"},
    {"steel-4340", "damage.d3", -2.12, "JC85"},
    {"steel-4340", "damage.d4", 0.002, "JC85"},
    {"steel-4340", "damage.d5", 0.61, "JC85"},
    // Armco iron
    {"armco-iron", "density", 7890.0, "JC83"},
    {"armco-iron", "eos.bulk_modulus", 169.8e9, "KL"},
    {"armco-iron", "strength.shear_modulus", 81.6e9, "KL"},
    {"armco-iron", "strength.yield_stress", 175e6, "JC83"},
    {"armco-iron", "strength.hardening_coefficient", 380e6, "JC83"},
    {"armco-iron", "strength.hardening_exponent", 0.32, "JC83"},
    {"armco-iron", "strength.strain_rate_coefficient", 0.060, "JC83"},
    {"armco-iron", "strength.thermal_softening_exponent", 0.55, "JC83"},
    {"armco-iron", "strength.melt_temperature", 1811.0, "JC83"},
    {"armco-iron", "strength.specific_heat", 452.0, "JC83"},
    {"armco-iron", "damage.d1", -2.20, "JC85"},
    {"armco-iron", "damage.d2", 5.43, "JC85"},
    {"armco-iron", "damage.d3", -0.47, "JC85"},
    {"armco-iron", "damage.d4", 0.016, "JC85"},
    {"armco-iron", "damage.d5", 0.63, "JC85"},
    // tungsten alloy (.07 Ni .03 Fe)
    {"tungsten-alloy", "density", 17000.0, "JC83"},
    {"tungsten-alloy", "strength.yield_stress", 1506e6, "JC83"},
    {"tungsten-alloy", "strength.hardening_coefficient", 177e6, "JC83"},
    {"tungsten-alloy", "strength.hardening_exponent", 0.12, "JC83"},
    {"tungsten-alloy", "strength.strain_rate_coefficient", 0.016, "JC83"},
    {"tungsten-alloy", "strength.thermal_softening_exponent", 1.00, "JC83"},
    {"tungsten-alloy", "strength.melt_temperature", 1723.0, "JC83"},
    {"tungsten-alloy", "strength.specific_heat", 134.0, "JC83"},
    // Ti-6Al-4V
    {"ti-6al-4v", "density", 4419.0, "S96"},
    {"ti-6al-4v", "eos.bulk_sound_speed", 5130.0, "S96"},
    {"ti-6al-4v", "eos.hugoniot_slope", 1.028, "S96"},
    {"ti-6al-4v", "eos.gruneisen", 1.23, "S96"},
    {"ti-6al-4v", "strength.shear_modulus", 41.9e9, "S96"},
    {"ti-6al-4v", "strength.yield_stress", 1098e6, "L00"},
    {"ti-6al-4v", "strength.hardening_coefficient", 1092e6, "L00"},
    {"ti-6al-4v", "strength.hardening_exponent", 0.93, "L00"},
    {"ti-6al-4v", "strength.strain_rate_coefficient", 0.014, "L00"},
    {"ti-6al-4v", "strength.thermal_softening_exponent", 1.1, "L00"},
    {"ti-6al-4v", "strength.melt_temperature", 1878.0, "L00"},
    {"ti-6al-4v", "strength.specific_heat", 526.0, "ASM"},
    {"ti-6al-4v", "damage.d1", -0.09, "K03"},
    {"ti-6al-4v", "damage.d2", 0.25, "K03"},
    {"ti-6al-4v", "damage.d3", -0.5, "K03"},
    {"ti-6al-4v", "damage.d4", 0.014, "K03"},
    {"ti-6al-4v", "damage.d5", 3.87, "K03"},
    // RHA: 4340 at Rc 30 standing in (JC83, JC85); density ASM
    {"rha", "density", 7850.0, "ASM"},
    {"rha", "strength.yield_stress", 792e6, "JC83 4340"},
    {"rha", "strength.hardening_coefficient", 510e6, "JC83 4340"},
    {"rha", "strength.hardening_exponent", 0.26, "JC83 4340"},
    {"rha", "strength.strain_rate_coefficient", 0.014, "JC83 4340"},
    {"rha", "strength.thermal_softening_exponent", 1.03, "JC83 4340"},
    {"rha", "strength.melt_temperature", 1793.0, "JC83 4340"},
    {"rha", "strength.specific_heat", 477.0, "JC83 4340"},
    {"rha", "damage.d1", 0.05, "JC85 4340"},
    {"rha", "damage.d2", 3.44, "JC85 4340"},
    {"rha", "damage.d3", -2.12, "JC85 4340"},
    {"rha", "damage.d4", 0.002, "JC85 4340"},
    {"rha", "damage.d5", 0.61, "JC85 4340"},
    // The paper's sets: the numbers examples/paper/*.json always had (docs/validation.md)
    {"paper-al6061-t6", "density", 2700.0, "GS96"},
    {"paper-al6061-t6", "eos.bulk_modulus", 73e9, "GS96"},
    {"paper-al6061-t6", "strength.shear_modulus", 24.6e9, "GS96"},
    {"paper-al6061-t6", "strength.yield_stress", 0.28e9, "GS96"},
    {"paper-al6061-t6", "fracture.elongation", 0.4, "GS96"},
    {"paper-al6061-t6", "fracture.loosening", 0.03, "GS96"},
    {"paper-lead", "density", 11340.0, "GS96"},
    {"paper-lead", "eos.bulk_modulus", 50e9, "GS96"},
    {"paper-lead", "strength.shear_modulus", 5.7e9, "GS96"},
    {"paper-lead", "strength.yield_stress", 0.03e9, "GS96"},
};

// Moduli from Young's modulus and Poisson's ratio (ASM Handbook, or the stated estimate).
struct Elastic {
  const char* set;
  double young;
  double poisson;
  const char* source;
};
const Elastic elastic[] = {
    {"al7075-t6", 71.7e9, 0.33, "ASM vol. 2"},
    {"steel-4340", 205e9, 0.29, "ASM vol. 1"},
    {"rha", 205e9, 0.29, "ASM vol. 1 (4340)"},
    {"tungsten-alloy", 345e9, 0.29, "estimate for 90 % W alloys"},
};

std::string key_of(const library::Constant& c) {
  return c.block.empty() ? std::string(c.key) : fmt::format("{}.{}", c.block, c.key);
}

const library::Constant& constant(const library::MaterialSet& set, std::string_view block, std::string_view key) {
  const library::Constant* c = library::find_constant(set, block, key);
  INFO(set.name << ": " << block << "." << key);
  REQUIRE(c != nullptr);
  return *c;
}

double bulk_modulus(const library::MaterialSet& set) {
  const double rho = constant(set, "", "density").value;
  if (set.eos_model == "mie_gruneisen") {
    const double c0 = constant(set, "eos", "bulk_sound_speed").value;
    return rho * c0 * c0;
  }
  return constant(set, "eos", "bulk_modulus").value;
}

std::string scenario_with(const std::string& material) {
  return fmt::format(R"({{
  "geometry": "planar", "end_time": 1e-6,
  "materials": {{ "m": {} }},
  "bodies": [ {{ "name": "b", "material": "m",
                 "mesh": {{ "type": "rectangle", "x": {{ "from": 0, "to": 0.01, "zones": 2 }},
                                              "y": {{ "from": 0, "to": 0.01, "zones": 2 }} }} }} ]
}})", material);
}

}  // namespace

TEST_CASE("every library constant equals its cited value, and every cited value is in the library", "[library]") {
  std::set<std::string> checked;
  for (const Cited& c : cited) {
    const library::MaterialSet* set = library::find_material_set(c.set);
    INFO(c.set << " " << c.key << " (" << c.source << ")");
    REQUIRE(set != nullptr);
    const std::string key = c.key;
    const auto dot = key.find('.');
    const std::string block = dot == std::string::npos ? "" : key.substr(0, dot);
    const std::string name = dot == std::string::npos ? key : key.substr(dot + 1);
    CHECK(constant(*set, block, name).value == Approx(c.value).epsilon(1e-12));
    checked.insert(fmt::format("{}:{}", c.set, key));
  }
  for (const Elastic& e : elastic) {
    const library::MaterialSet* set = library::find_material_set(e.set);
    INFO(e.set << " from E and nu (" << e.source << ")");
    REQUIRE(set != nullptr);
    // K = E / (3 (1 - 2 nu)), G = E / (2 (1 + nu)); the library rounds to 0.1 GPa.
    CHECK(constant(*set, "eos", "bulk_modulus").value == Approx(e.young / (3.0 * (1.0 - 2.0 * e.poisson))).margin(0.06e9));
    CHECK(constant(*set, "strength", "shear_modulus").value == Approx(e.young / (2.0 * (1.0 + e.poisson))).margin(0.06e9));
    checked.insert(fmt::format("{}:eos.bulk_modulus", e.set));
    if (std::string(e.set) != "al7075-t6") checked.insert(fmt::format("{}:strength.shear_modulus", e.set));
  }
  // Nothing in the library escapes the tables above but the two conventions every Johnson–Cook set shares.
  for (const library::MaterialSet& set : library::material_sets) {
    for (const library::Constant& c : set.constants) {
      INFO(set.name << " " << key_of(c) << " = " << c.value);
      CHECK(!c.source.empty());
      if (c.key == "room_temperature") {
        CHECK(c.value == 293.0);
      } else if (c.key == "reference_strain_rate") {
        CHECK(c.value == 1.0);
      } else {
        CHECK(checked.count(fmt::format("{}:{}", set.name, key_of(c))) == 1);
      }
    }
  }
}

TEST_CASE("every library set is physical: sound speed, Poisson's ratio, yield below the shear modulus", "[library]") {
  std::set<std::string_view> names;
  for (const library::MaterialSet& set : library::material_sets) {
    INFO(set.name);
    CHECK(names.insert(set.name).second);  // one set per name
    CHECK(!set.source.empty());
    const double rho = constant(set, "", "density").value;
    const double bulk = bulk_modulus(set);
    const double shear = constant(set, "strength", "shear_modulus").value;
    const double yield = constant(set, "strength", "yield_stress").value;
    const double bulk_sound_speed = std::sqrt(bulk / rho);
    const double poisson = (3.0 * bulk - 2.0 * shear) / (2.0 * (3.0 * bulk + shear));
    INFO("c_bulk " << bulk_sound_speed << " m/s, nu " << poisson << ", Y/G " << yield / shear);
    CHECK(bulk_sound_speed > 1000.0);
    CHECK(bulk_sound_speed < 8000.0);
    CHECK(poisson > 0.0);
    CHECK(poisson < 0.5);
    CHECK(yield > 0.0);
    CHECK(yield < shear);
    // Metals: Poisson's ratio 0.25-0.45 (lead the highest).
    CHECK(poisson > 0.25);
    CHECK(poisson < 0.45);
    if (set.strength_model == "johnson_cook") {
      CHECK(constant(set, "strength", "melt_temperature").value > constant(set, "strength", "room_temperature").value);
      CHECK(constant(set, "strength", "specific_heat").value > 100.0);
    }
  }
  // The sets the library promises.
  for (const char* name : {"al6061-t6", "al2024-t3", "al7075-t6", "lead", "ofhc-copper", "steel-4340", "armco-iron",
                           "tungsten-alloy", "ti-6al-4v", "rha", "paper-al6061-t6", "paper-lead"}) {
    CHECK(names.count(name) == 1);
  }
}

TEST_CASE("every library set is read by the scenario reader, by name, into the models it names", "[library]") {
  for (const library::MaterialSet& set : library::material_sets) {
    INFO(set.name);
    krug::scenario::Scenario scenario;
    REQUIRE_NOTHROW(scenario = krug::scenario::parse_scenario(scenario_with(fmt::format("\"{}\"", set.name)), "library.json"));
    const krug::Material& m = scenario.scene.materials.front();
    CHECK(m.reference_density == constant(set, "", "density").value);
    CHECK(std::visit([](const auto& e) { return std::string(e.name); }, m.eos) == set.eos_model);
    CHECK(std::visit([](const auto& s) { return std::string(s.name); }, m.strength) == set.strength_model);
    CHECK(m.shear_modulus() == constant(set, "strength", "shear_modulus").value);
    const double yield = std::visit([](const auto& s) { return s.flow_stress(0.0); }, m.strength);
    CHECK(yield == constant(set, "strength", "yield_stress").value);
    CHECK(scenario.resolved_json.find(fmt::format("\"base\": \"{}\"", set.name)) != std::string::npos);
    if (const library::Constant* melt = library::find_constant(set, "strength", "melt_temperature")) {
      CHECK(std::get<krug::JohnsonCook>(m.strength).melt_temperature == melt->value);
    }
    // The damage constants are carried, not read: no "damage" key reaches the reader.
    CHECK(scenario.resolved_json.find("\"damage\"") == std::string::npos);
  }
}
