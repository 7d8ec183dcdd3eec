// The material library as a scenario meets it: a library set named by a string, a set with overrides
// (merged key by key; another model replaces the block), the errors for an unknown name, a "base" that
// is not a string and an unknown override key (each naming the JSON path), what scenario.resolved.json
// keeps, and `krug materials [NAME]`.
#include <catch2/catch.hpp>

#include <string>

#include <fmt/format.h>

#include "test_support.hpp"
#include "krug/core/error.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/output/sweep_files.hpp"
#include "krug/scenario/edit.hpp"
#include "krug/material/library.hpp"

namespace fs = std::filesystem;
using krug::test::Json;
using krug::test::run_krug;

namespace {

std::string scenario_with(const std::string& material) {
  return fmt::format(R"({{
  "geometry": "planar", "end_time": 1e-6,
  "materials": {{ "plate": {} }},
  "bodies": [ {{ "name": "b", "material": "plate",
                 "mesh": {{ "type": "rectangle", "x": {{ "from": 0, "to": 0.01, "zones": 2 }},
                                              "y": {{ "from": 0, "to": 0.01, "zones": 2 }} }} }} ]
}})", material);
}

Json resolved_material(const std::string& material) {
  const krug::scenario::Scenario s = krug::scenario::parse_scenario(scenario_with(material), "materials.json");
  return Json::parse(s.resolved_json)["materials"]["plate"];
}

std::string error_of(const std::string& material) {
  try {
    (void)krug::scenario::parse_scenario(scenario_with(material), "materials.json");
  } catch (const krug::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a material named by a string resolves to the library set, with its name kept as base", "[app][materials]") {
  const Json m = resolved_material("\"al6061-t6\"");
  CHECK(m["base"] == "al6061-t6");
  // Steinberg 1996 (6061-T6) and Lesuer et al. 2001 (Johnson-Cook), as in docs/materials.md.
  CHECK(m["density"] == 2703.0);
  CHECK(m["eos"]["model"] == "mie_gruneisen");
  CHECK(m["eos"]["bulk_sound_speed"] == 5240.0);
  CHECK(m["eos"]["hugoniot_slope"] == 1.40);
  CHECK(m["eos"]["gruneisen"] == 1.97);
  CHECK(m["strength"]["model"] == "johnson_cook");
  CHECK(m["strength"]["shear_modulus"] == 27.6e9);
  CHECK(m["strength"]["yield_stress"] == 324e6);
  CHECK(m["strength"]["hardening_coefficient"] == 114e6);
  CHECK(m["strength"]["melt_temperature"] == 925.0);
  CHECK(!m.contains("fracture"));
  // The paper's set carries its fracture criterion.
  const Json paper = resolved_material("\"paper-al6061-t6\"");
  CHECK(paper["fracture"]["elongation"] == 0.4);
  CHECK(paper["fracture"]["loosening"] == 0.03);
  CHECK(paper["eos"] == Json({{"model", "linear"}, {"bulk_modulus", 7.3e10}}));
}

TEST_CASE("a set with overrides: keys merge into a block, another model replaces it", "[app][materials]") {
  // Merge: one strength key changed, the others kept; a top-level key and a new block added.
  const Json merged = resolved_material(
      R"({"base": "al6061-t6", "density": 2710.0, "strength": {"yield_stress": 3.0e8}, "fracture": {"elongation": 0.3}})");
  CHECK(merged["base"] == "al6061-t6");
  CHECK(merged["density"] == 2710.0);
  CHECK(merged["strength"]["model"] == "johnson_cook");
  CHECK(merged["strength"]["yield_stress"] == 3.0e8);
  CHECK(merged["strength"]["hardening_coefficient"] == 114e6);
  CHECK(merged["strength"]["hardening_exponent"] == 0.42);
  CHECK(merged["fracture"]["elongation"] == 0.3);
  CHECK(merged["eos"]["bulk_sound_speed"] == 5240.0);
  // The same model named again still merges.
  const Json same = resolved_material(R"({"base": "al6061-t6", "strength": {"model": "johnson_cook", "yield_stress": 3.0e8}})");
  CHECK(same["strength"]["hardening_coefficient"] == 114e6);
  // Another model replaces the block: nothing of Johnson-Cook is left.
  const Json replaced = resolved_material(
      R"({"base": "al6061-t6", "strength": {"model": "perfectly_plastic", "shear_modulus": 2.6e10, "yield_stress": 2.9e8}})");
  CHECK(replaced["strength"] ==
        Json({{"model", "perfectly_plastic"}, {"shear_modulus", 2.6e10}, {"yield_stress", 2.9e8}}));
  const Json linear = resolved_material(R"({"base": "ofhc-copper", "eos": {"model": "linear", "bulk_modulus": 1.4e11}})");
  CHECK(linear["eos"] == Json({{"model", "linear"}, {"bulk_modulus", 1.4e11}}));
  CHECK(linear["density"] == 8930.0);
  // The resolved scenario reads back to itself (a restart reads it).
  const krug::scenario::Scenario first = krug::scenario::parse_scenario(
      scenario_with(R"({"base": "lead", "erosion": {"altitude_ratio": 0.1}})"), "first.json");
  const krug::scenario::Scenario again = krug::scenario::parse_scenario(first.resolved_json, "resolved.json");
  CHECK(again.resolved_json == first.resolved_json);
}

TEST_CASE("an unknown library name, a base that is not a name and a bad override are refused with the JSON path",
          "[app][materials]") {
  const std::string unknown = error_of("\"al6061\"");
  CHECK(unknown.find("materials.plate: unknown library material \"al6061\"") != std::string::npos);
  CHECK(unknown.find("\"al6061-t6\", \"al2024-t3\"") != std::string::npos);  // the known names are listed
  CHECK(unknown.find("paper-lead") != std::string::npos);
  CHECK(unknown.find("did you mean \"al6061-t6\"") != std::string::npos);
  const std::string in_base = error_of(R"({"base": "copper"})");
  CHECK(in_base.find("did you mean \"ofhc-copper\"") != std::string::npos);
  CHECK(in_base.find("materials.plate.base: unknown library material \"copper\"") != std::string::npos);
  const std::string not_a_name = error_of(R"({"base": 7})");
  CHECK(not_a_name.find("materials.plate.base: expected the name of a library material") != std::string::npos);
  const std::string bad_key = error_of(R"({"base": "al6061-t6", "strength": {"yield_stres": 3.0e8}})");
  CHECK(bad_key.find("materials.plate.strength.yield_stres: unknown key") != std::string::npos);
  const std::string bad_value = error_of(R"({"base": "al6061-t6", "strength": {"yield_stress": -1}})");
  CHECK(bad_value.find("materials.plate.strength.yield_stress") != std::string::npos);
  const std::string neither = error_of("[1, 2]");
  CHECK(neither.find("materials.plate: expected a material (an object) or the name of a library material") !=
        std::string::npos);
}

TEST_CASE("krug materials lists the library; krug materials NAME prints every constant with its source",
          "[app][materials][cli]") {
  if (!krug::test::have_app()) return;
  const fs::path dir = krug::test::scratch("materials_cli");
  const auto list = run_krug({"materials"}, dir / "list.log");
  CHECK(list.exit_code == 0);
  for (const krug::library::MaterialSet& set : krug::library::material_sets) {
    CHECK(list.output.find(std::string(set.name)) != std::string::npos);
    CHECK(list.output.find(std::string(set.source)) != std::string::npos);
  }
  const auto one = run_krug({"materials", "steel-4340"}, dir / "one.log");
  CHECK(one.exit_code == 0);
  CHECK(one.output.find("strength.yield_stress") != std::string::npos);
  CHECK(one.output.find("JC83 (4340 steel, Rc 30), A") != std::string::npos);
  CHECK(one.output.find("damage.d2") != std::string::npos);
  CHECK(one.output.find("no failure law reads them yet") != std::string::npos);
  const auto unknown = run_krug({"materials", "unobtainium"}, dir / "unknown.log");
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.output.find("unknown material \"unobtainium\"") != std::string::npos);
  CHECK(unknown.output.find("ofhc-copper") != std::string::npos);
}

TEST_CASE("the schema's library names are the library's", "[app][materials][schema]") {
  const Json schema = krug::test::read_json(fs::path(KRUG_EXAMPLES_DIR).parent_path() / "docs" / "scenario.schema.json");
  Json names = Json::array();
  for (const krug::library::MaterialSet& set : krug::library::material_sets) names.push_back(std::string(set.name));
  CHECK(schema["$defs"]["material_name"]["enum"] == names);
}

TEST_CASE("a sweep into a material named by a string overrides the library set", "[app][materials][sweep]") {
  const fs::path scenario = fs::path(KRUG_EXAMPLES_DIR) / "paper" / "coarse" / "monolithic_3mm_2.6g_z5.json";
  REQUIRE(krug::test::read_json(scenario)["materials"]["al6061"] == "paper-al6061-t6");
  const auto variants = krug::output::prepare_sweep(
      scenario, {krug::scenario::parse_sweep_set("materials.al6061.strength.yield_stress=2.5e8,3.0e8")},
      krug::test::scratch("sweep_library"));
  REQUIRE(variants.size() == 2);
  const Json written = krug::test::read_json(variants[1].scenario)["materials"]["al6061"];
  CHECK(written == Json({{"base", "paper-al6061-t6"}, {"strength", {{"yield_stress", 3.0e8}}}}));
  const Json resolved =
      Json::parse(krug::scenario::parse_scenario(krug::test::read_text(variants[1].scenario), "v.json").resolved_json);
  CHECK(resolved["materials"]["al6061"]["strength"]["yield_stress"] == 3.0e8);
  CHECK(resolved["materials"]["al6061"]["strength"]["shear_modulus"] == 2.46e10);  // the set's, kept
}
