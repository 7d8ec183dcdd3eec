// The scenario reader: a malformed scenario is an InputError that names the JSON path, what was
// found and what was expected; unknown keys suggest the nearest valid key; unknown names list the
// valid ones. Through the library API (krug::io::parse_scenario).
#include <catch2/catch.hpp>

#include <string>

#include "krug/core/error.hpp"
#include "krug/io/scenario.hpp"

using krug::InputError;
using krug::io::parse_scenario;

namespace {

std::string valid_scenario() {
  return R"({
    "geometry": "planar",
    "end_time": 0.1,
    "materials": { "gas": { "density": 1.0, "eos": { "model": "ideal_gas", "gamma": 1.4 } } },
    "bodies": [ { "name": "box", "material": "gas",
                  "mesh": { "type": "rectangle", "x": { "from": 0, "to": 1, "zones": 4 },
                                                 "y": { "from": 0, "to": 1, "zones": 4 } },
                  "initial": { "specific_internal_energy": 2.5 },
                  "boundary": { "x_min": "slip" } } ]
  })";
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_scenario(text, "test.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("a valid scenario parses and resolves its defaults", "[scenario]") {
  const auto scenario = parse_scenario(valid_scenario(), "test.json");
  CHECK(scenario.setup.mesh.zones.size() == 16);
  CHECK(scenario.setup.bodies.at(0).name == "box");
  // The resolved document carries defaults that were not in the file.
  CHECK(scenario.resolved_json.find("\"cfl\": 0.5") != std::string::npos);
  CHECK(scenario.resolved_json.find("\"quadratic\"") != std::string::npos);
  // The resolved document is itself a valid scenario giving the same mesh.
  const auto again = parse_scenario(scenario.resolved_json, "resolved.json");
  CHECK(again.setup.mesh.zones.size() == 16);
}

TEST_CASE("scenario errors name the JSON path and what was expected", "[scenario]") {
  const std::string base = valid_scenario();
  SECTION("unknown key with a suggestion") {
    const auto e = error_of(replaced(base, "\"end_time\"", "\"end_tme\""));
    CHECK(e.find("end_tme") != std::string::npos);
    CHECK(e.find("did you mean \"end_time\"") != std::string::npos);
  }
  SECTION("wrong type") {
    const auto e = error_of(replaced(base, "\"gamma\": 1.4", "\"gamma\": \"1.4\""));
    CHECK(e.find("materials.gas.eos.gamma") != std::string::npos);
    CHECK(e.find("found a string") != std::string::npos);
  }
  SECTION("value out of range") {
    const auto e = error_of(replaced(base, "\"density\": 1.0", "\"density\": -1.0"));
    CHECK(e.find("materials.gas.density") != std::string::npos);
    CHECK(e.find("> 0") != std::string::npos);
  }
  SECTION("unknown model lists the valid ones") {
    const auto e = error_of(replaced(base, "\"ideal_gas\"", "\"ideal_gs\""));
    CHECK(e.find("materials.gas.eos.model") != std::string::npos);
    CHECK(e.find("\"linear\"") != std::string::npos);
    CHECK(e.find("did you mean \"ideal_gas\"") != std::string::npos);
  }
  SECTION("unknown material") {
    const auto e = error_of(replaced(base, "\"material\": \"gas\"", "\"material\": \"gass\""));
    CHECK(e.find("bodies[0].material") != std::string::npos);
    CHECK(e.find("did you mean \"gas\"") != std::string::npos);
  }
  SECTION("missing key") {
    const auto e = error_of(replaced(base, "\"end_time\": 0.1,", ""));
    CHECK(e.find("end_time: missing") != std::string::npos);
  }
  SECTION("unknown boundary side") {
    const auto e = error_of(replaced(base, "\"x_min\": \"slip\"", "\"left\": \"slip\""));
    CHECK(e.find("bodies[0].boundary.left") != std::string::npos);
    CHECK(e.find("x_min") != std::string::npos);
  }
  SECTION("bad expression") {
    const auto e = error_of(replaced(base, "\"specific_internal_energy\": 2.5", "\"specific_internal_energy\": \"2.5*(x\""));
    CHECK(e.find("bodies[0].initial.specific_internal_energy") != std::string::npos);
  }
  SECTION("expression not finite somewhere") {
    const auto e = error_of(replaced(base, "\"specific_internal_energy\": 2.5", "\"specific_internal_energy\": \"1/(x-0.125)\""));
    CHECK(e.find("expected a finite number") != std::string::npos);
  }
  SECTION("not JSON at all") {
    const auto e = error_of(base.substr(0, base.size() / 2));
    CHECK(e.find("not valid JSON") != std::string::npos);
  }
  SECTION("slip on a side that is not along an axis") {
    const auto e = error_of(replaced(base, "\"type\": \"rectangle\",", "\"type\": \"rectangle\", \"map\": [\"x + 0.1*y*y\", \"y\"],"));
    CHECK(e.find("not a straight line along an axis") != std::string::npos);
  }
}
