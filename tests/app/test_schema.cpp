// docs/scenario.schema.json against the reader (src/scenario/scenario.cpp), which stay one source of
// truth by these checks:
//  1. every example (examples/**/*.json) and every test scenario (tests/app/data/*.json) is valid
//     against the schema, and so is the resolved scenario the reader makes of it;
//  2. at every object path of every resolved scenario, the keys the reader fills in are properties
//     of the schema there, and the keys the reader accepts there (listed by its unknown-key error
//     when an unknown key is planted) are exactly the schema's properties;
//  3. every object schema (each oneOf branch: equations of state, strength models, mesh types...)
//     is met by some scenario, so check 2 reaches all of them;
//  4. every number with a bound in the schema is rejected by both the schema and the reader just
//     outside the bound, and accepted by both on it (inclusive) or just inside (exclusive); a wrong
//     type (a string, a boolean) is rejected by both;
//  5. summary.json of completed, failed and fracturing runs follows docs/summary.schema.json (the
//     fixed contract of docs/outputs.md).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>

#include "krug/core/error.hpp"
#include "krug/output/run_files.hpp"
#include "krug/scenario/scenario.hpp"
#include "schema_validator.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using krug::test::Json;
using krug::test::SchemaValidator;

namespace {

const SchemaValidator& schema() {
  static const SchemaValidator validator(krug::test::read_json(KRUG_SCHEMA_FILE));
  return validator;
}

// "bodies[0].mesh.x" -> "/bodies/0/mesh/x"
Json::json_pointer pointer(const std::string& path) {
  std::string p;
  std::string word;
  auto flush = [&] {
    if (!word.empty()) p += "/" + word;
    word.clear();
  };
  for (char c : path) {
    if (c == '.' || c == '[' || c == ']') {
      flush();
    } else {
      word += c;
    }
  }
  flush();
  return Json::json_pointer(p);
}

// Axis and side names of the other geometry are not keys of this scenario.
bool belongs_to_geometry(const std::string& key, const std::string& geometry) {
  static const std::set<std::string> planar = {"x", "y", "x_min", "x_max", "y_min", "y_max"};
  static const std::set<std::string> axisymmetric = {"z", "r", "z_min", "z_max", "r_min", "r_max"};
  if (geometry == "planar") return !axisymmetric.count(key);
  return !planar.count(key);
}

std::string error_of(const std::string& text) {
  try {
    (void)krug::scenario::parse_scenario(text, "mutated.json");
  } catch (const krug::InputError& e) {
    return e.what();
  }
  return "";
}

void collect_object_schemas(const Json& s, std::set<const Json*>& out) {
  if (!s.is_object()) return;
  if (s.contains("properties")) {
    out.insert(&s);
    for (const auto& [key, sub] : s["properties"].items()) collect_object_schemas(sub, out);
  }
  if (s.contains("items")) collect_object_schemas(s["items"], out);
  if (s.contains("additionalProperties")) collect_object_schemas(s["additionalProperties"], out);
  for (const char* word : {"oneOf", "anyOf"}) {
    if (s.contains(word)) {
      for (const Json& branch : s[word]) collect_object_schemas(branch, out);
    }
  }
  if (s.contains("$defs")) {
    for (const auto& [key, sub] : s["$defs"].items()) collect_object_schemas(sub, out);
  }
}

std::string describe(const std::set<std::string>& keys) {
  std::string text;
  for (const auto& k : keys) text += (text.empty() ? "" : ", ") + k;
  return text;
}

}  // namespace

TEST_CASE("every example and test scenario is valid against the schema, resolved or not", "[schema]") {
  const auto files = krug::test::scenario_files();
  REQUIRE(files.size() >= 3);
  for (const auto& file : files) {
    INFO(file.string());
    const std::string text = krug::test::read_text(file);
    const auto errors = schema().validate(Json::parse(text));
    CHECK(errors == std::vector<std::string>{});
    krug::scenario::Scenario scenario;
    REQUIRE_NOTHROW(scenario = krug::scenario::parse_scenario(text, file.string()));
    const auto resolved_errors = schema().validate(Json::parse(scenario.resolved_json));
    CHECK(resolved_errors == std::vector<std::string>{});
  }
}

TEST_CASE("the keys the reader accepts are exactly the schema's properties, at every path", "[schema]") {
  std::set<const Json*> visited;
  long objects = 0;
  for (const auto& file : krug::test::scenario_files()) {
    const Json resolved = Json::parse(krug::scenario::parse_scenario(krug::test::read_text(file), file.string()).resolved_json);
    const std::string geometry = resolved.at("geometry").get<std::string>();
    schema().walk(resolved, [&](const std::string& path, const Json& object, const Json& object_schema, bool is_map) {
      if (is_map) return;  // materials: any name
      INFO(file.filename().string() << " at \"" << path << "\"");
      visited.insert(&object_schema);
      ++objects;
      std::set<std::string> schema_keys;
      for (const auto& [key, _] : object_schema["properties"].items()) {
        if (belongs_to_geometry(key, geometry)) schema_keys.insert(key);
      }
      // What the reader filled in is described by the schema.
      for (const auto& [key, _] : object.items()) {
        INFO("resolved key " << key);
        CHECK(schema_keys.count(key) == 1);
      }
      // What the reader accepts here: plant an unknown key and read the list in its error.
      Json mutated = resolved;
      mutated[pointer(path)]["zz_not_a_key"] = 1;
      const std::string error = error_of(mutated.dump());
      const std::string where = (path.empty() ? "" : path + ".") + "zz_not_a_key: unknown key";
      REQUIRE(error.find(where) != std::string::npos);
      const std::string marker = "valid keys here: ";
      const auto at = error.find(marker);
      REQUIRE(at != std::string::npos);
      std::set<std::string> accepted;
      std::string list = error.substr(at + marker.size());
      for (std::size_t start = 0; start <= list.size();) {
        const auto comma = list.find(", ", start);
        const std::string key = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (!key.empty()) accepted.insert(key);
        if (comma == std::string::npos) break;
        start = comma + 2;
      }
      // Known differences, each a suggestion list rather than an accepted key:
      // - an axis given as {from, to, zones, ratio} also names "segments", its other form;
      if (object.contains("from") && object.contains("to")) accepted.erase("segments");
      // - a sector starting at radius 0 has no inner side.
      if (path.size() > 9 && path.substr(path.size() - 9) == ".boundary" &&
          mutated[pointer(path.substr(0, path.size() - 9))]["mesh"].value("type", "") == "sector" &&
          mutated[pointer(path.substr(0, path.size() - 9))]["mesh"]["radius"].value("from", 1.0) == 0.0) {
        schema_keys.erase("inner");
      }
      INFO("reader accepts: " << describe(accepted) << "\nschema has:     " << describe(schema_keys));
      CHECK(accepted == schema_keys);
    });
  }
  CHECK(objects > 100);
  // Every object schema was met by some scenario.
  std::set<const Json*> all;
  collect_object_schemas(schema().root(), all);
  std::vector<std::string> missed;
  for (const Json* s : all) {
    if (!visited.count(s)) missed.push_back(s->dump().substr(0, 160));
  }
  INFO("object schemas no scenario uses (add one to tests/app/data/):");
  for (const auto& m : missed) INFO(m);
  CHECK(missed.empty());
}

TEST_CASE("numbers just outside the schema's bounds are rejected by both, on them accepted by both", "[schema]") {
  long checked = 0;
  // Each property of each object schema once, in the smallest scenario that has it (parsing is the cost).
  auto files = krug::test::scenario_files();
  std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return fs::file_size(a) < fs::file_size(b); });
  std::set<std::pair<const Json*, std::string>> done;
  for (const auto& file : files) {
    const Json resolved = Json::parse(krug::scenario::parse_scenario(krug::test::read_text(file), file.string()).resolved_json);
    schema().walk(resolved, [&](const std::string& path, const Json& object, const Json& object_schema, bool is_map) {
      if (is_map) return;
      for (const auto& [key, value] : object.items()) {
        if (!value.is_number() || !object_schema["properties"].contains(key)) continue;
        if (!done.insert({&object_schema, key}).second) continue;
        const Json& s = schema().deref(object_schema["properties"][key]);
        if (!s.contains("type")) continue;  // enums, anyOf
        const bool integer = s["type"] == "integer";
        const std::string at = (path.empty() ? "" : path + ".") + key;
        auto with = [&](const Json& v) {
          Json mutated = resolved;
          mutated[pointer(at)] = v;
          return mutated;
        };
        auto rejected = [&](const Json& v) {
          INFO(file.filename().string() << ": " << at << " = " << v.dump());
          const Json mutated = with(v);
          CHECK_FALSE(schema().valid(mutated));
          CHECK_THROWS_AS(krug::scenario::parse_scenario(mutated.dump(), "mutated.json"), krug::InputError);
          ++checked;
        };
        // On the bound the reader may still refuse for another reason (a nose longer than its
        // cylinder, a degenerate zone), but never with a range error at this path.
        auto accepted = [&](const Json& v) {
          INFO(file.filename().string() << ": " << at << " = " << v.dump());
          const Json mutated = with(v);
          CHECK(schema().valid(mutated));
          const std::string error = error_of(mutated.dump());
          INFO(error);
          CHECK(error.find(at + ": expected") == std::string::npos);
          ++checked;
        };
        constexpr double inf = std::numeric_limits<double>::infinity();
        // Large zone counts are valid but would build a large mesh: only their rejection is checked.
        const bool costly = integer && key.find("zones") != std::string::npos;
        if (s.contains("minimum")) {
          const double m = s["minimum"].get<double>();
          rejected(integer ? Json(m - 1) : Json(std::nextafter(m, -inf)));
          if (!costly) accepted(integer ? Json(static_cast<long>(m)) : Json(m));
        }
        if (s.contains("exclusiveMinimum")) {
          const double m = s["exclusiveMinimum"].get<double>();
          rejected(Json(m));
          if (!costly) accepted(Json(m == 0.0 ? 1e-300 : std::nextafter(m, inf)));
        }
        if (s.contains("maximum")) {
          const double m = s["maximum"].get<double>();
          rejected(integer ? Json(m + 1) : Json(std::nextafter(m, inf)));
          if (!costly) accepted(integer ? Json(static_cast<long>(m)) : Json(m));
        }
        rejected(Json("1.0"));
        rejected(Json(true));
        if (integer) rejected(Json(value.get<double>() + 0.5));
      }
    });
  }
  CHECK(checked > 200);
}

TEST_CASE("summary.json of completed, failed and fracturing runs follows docs/summary.schema.json", "[schema]") {
  const SchemaValidator contract(krug::test::read_json(fs::path(KRUG_SCHEMA_FILE).parent_path() / "summary.schema.json"));
  struct Case {
    fs::path file;
    std::function<void(Json&)> edit;
    std::string status;
  };
  const fs::path e1 = fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json";
  const std::vector<Case> cases = {
      {e1, [](Json&) {}, "completed"},
      // A time-step floor above the stable step (1.9e-8 s): a numerical failure at the first cycle.
      {e1, [](Json& d) { d["controls"]["time_step_floor"] = 1e-6; }, "failed"},
      {fs::path(KRUG_APP_TEST_DATA_DIR) / "fracture_plate.json", [](Json&) {}, "completed"},
      {fs::path(KRUG_EXAMPLES_DIR) / "verification" / "taylor_bar.json", [](Json& d) { d["end_time"] = 2e-6; }, "completed"},
      // A penetration block (its summary block), stopped by the stop rule once the flyer has stopped.
      {e1, [](Json& d) { d["penetration"] = {{"projectile", "flyer"}}; d["stop"] = {{"no_contact_time", 5e-7}}; }, "completed"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    INFO(cases[i].file.filename().string() << " case " << i);
    Json document = krug::test::read_json(cases[i].file);
    cases[i].edit(document);
    const fs::path dir = krug::test::scratch("summary_contract_" + std::to_string(i));
    krug::output::RunOptions options;
    options.output_directory = dir;
    (void)krug::output::run_scenario(krug::scenario::parse_scenario(document.dump(), cases[i].file.string()), options);
    const Json summary = krug::test::read_json(dir / "summary.json");
    CHECK(summary["status"] == cases[i].status);
    CHECK(summary.contains("penetration") == document.contains("penetration"));
    const auto errors = contract.validate(summary);
    CHECK(errors == std::vector<std::string>{});
  }
}
