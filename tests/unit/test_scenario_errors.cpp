// The scenario reader: a malformed scenario is an InputError that names the JSON path, what was
// found and what was expected; unknown keys suggest the nearest valid key; unknown names list the
// valid ones. Through the library API (krug::scenario::parse_scenario).
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/run/run.hpp"
#include "krug/scenario/scenario.hpp"

using krug::InputError;
using krug::scenario::parse_scenario;

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
  CHECK(scenario.resolved_json.find("\"cfl_fluid\": 0.6") != std::string::npos);
  CHECK(scenario.setup.controls.cfl_fluid == 0.6);
  // A scenario that names `cfl` alone means every body; `cfl_fluid` then overrides it for the fluids.
  const auto one = parse_scenario(replaced(valid_scenario(), "\"bodies\"", "\"controls\": { \"cfl\": 0.4 }, \"bodies\""), "t.json");
  CHECK(one.setup.controls.cfl == 0.4);
  CHECK(one.setup.controls.cfl_fluid == 0.4);
  const auto both = parse_scenario(
      replaced(valid_scenario(), "\"bodies\"", "\"controls\": { \"cfl\": 0.4, \"cfl_fluid\": 0.7 }, \"bodies\""), "t.json");
  CHECK(both.setup.controls.cfl == 0.4);
  CHECK(both.setup.controls.cfl_fluid == 0.7);
  CHECK(scenario.resolved_json.find("\"quadratic\"") != std::string::npos);
  // The resolved document is itself a valid scenario giving the same mesh.
  const auto again = parse_scenario(scenario.resolved_json, "resolved.json");
  CHECK(again.setup.mesh.zones.size() == 16);
  // The physical hourglass stiffness has no coefficient: its resolved document leaves `stiffness` out, so
  // that it reads back (a restart reads it); a scenario that gives `stiffness` alone keeps the coefficient form.
  const auto physical = parse_scenario(
      replaced(valid_scenario(), "\"bodies\"", "\"controls\": { \"hourglass\": { \"stiffness_form\": \"physical\" } }, \"bodies\""),
      "p.json");
  CHECK(physical.setup.controls.hourglass.stiffness_form == krug::HourglassStiffness::physical);
  CHECK(physical.resolved_json.find("\"stiffness\":") == std::string::npos);
  const auto physical_again = parse_scenario(physical.resolved_json, "resolved.json");
  CHECK(physical_again.setup.controls.hourglass.stiffness_form == krug::HourglassStiffness::physical);
  const auto coefficient = parse_scenario(
      replaced(valid_scenario(), "\"bodies\"", "\"controls\": { \"hourglass\": { \"stiffness\": 0.1 } }, \"bodies\""), "c.json");
  CHECK(coefficient.setup.controls.hourglass.stiffness_form == krug::HourglassStiffness::coefficient);
  CHECK(coefficient.setup.controls.hourglass.stiffness == 0.1);
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
  SECTION("subzonal pressures at shocks only with the tensor viscosity, whose switch marks them") {
    const auto e = error_of(replaced(base, "\"end_time\": 0.1,",
                                     "\"end_time\": 0.1, \"controls\": {\"hourglass\": {\"subzonal_at_shocks\": true}},"));
    CHECK(e.find("controls.hourglass.subzonal_at_shocks") != std::string::npos);
    CHECK(e.find("tensor") != std::string::npos);
  }
  SECTION("no stiffness coefficient with the physical hourglass stiffness, which has none") {
    const auto e = error_of(replaced(base, "\"end_time\": 0.1,",
                                     "\"end_time\": 0.1, \"controls\": {\"hourglass\": {\"stiffness_form\": \"physical\", "
                                     "\"stiffness\": 0.1}},"));
    CHECK(e.find("controls.hourglass.stiffness") != std::string::npos);
    CHECK(e.find("physical") != std::string::npos);
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

// Physical sanity (issue: "non-positive density or moduli, Poisson ratio out of range, overlapping
// bodies, meshes too large for memory, an end time that would need more than a stated cycle budget").
namespace {

std::string two_blocks(double second_from) {
  return fmt::format(R"({{
    "geometry": "planar",
    "end_time": 1e-6,
    "materials": {{ "al": {{ "density": 2700, "eos": {{ "model": "linear", "bulk_modulus": 7.3e10 }},
                             "strength": {{ "model": "elastic", "shear_modulus": 2.6e10 }} }} }},
    "bodies": [ {{ "name": "left", "material": "al",
                   "mesh": {{ "type": "rectangle", "x": {{ "from": 0, "to": 0.01, "zones": 4 }},
                                                  "y": {{ "from": 0, "to": 0.01, "zones": 4 }} }} }},
                {{ "name": "right", "material": "al",
                   "mesh": {{ "type": "rectangle", "x": {{ "from": {}, "to": 0.02, "zones": 4 }},
                                                  "y": {{ "from": 0, "to": 0.01, "zones": 4 }} }} }} ]
  }})", second_from);
}

}  // namespace

TEST_CASE("physically impossible scenarios are refused with the values that make them so", "[scenario]") {
  SECTION("bodies that touch are accepted, bodies that overlap are not") {
    CHECK(error_of(two_blocks(0.01)) == "(no error)");
    // The right block starts 1 mm inside the left one (zones 2.5 mm): its nodes at x = 0.009 lie
    // 1 mm deep in the left block's last column of zones.
    const std::string e = error_of(two_blocks(0.009));
    CHECK_THAT(e, Catch::Contains("bodies[0] (\"left\") overlaps bodies[1] (\"right\")"));
    CHECK_THAT(e, Catch::Contains("0.001 m inside"));
  }
  SECTION("bodies whose nodes coincide overlap too") {
    // Two identical strips one zone thick (4 x 1 zones): every node of each lies on a boundary edge of
    // the other, none strictly inside a zone (the node test passes them), but every zone centre lies
    // inside the other strip's zone; the deepest reported: zone 1's centre (3.75, 5) mm, 5 mm from the
    // strip's faces y = 0 and y = 10 mm (its sides x = 2.5 and 5 mm are interior edges).
    std::string same = replaced(two_blocks(0.0), "\"to\": 0.02", "\"to\": 0.01");
    for (int body = 0; body < 2; ++body) {
      same = replaced(same, "\"y\": { \"from\": 0, \"to\": 0.01, \"zones\": 4 }", "\"y\": { \"from\": 0, \"to\": 0.01, \"zones\": 1 }");
    }
    const std::string e = error_of(same);
    CHECK_THAT(e, Catch::Contains("bodies[0] (\"left\") overlaps bodies[1] (\"right\")"));
    CHECK_THAT(e, Catch::Contains("the centre (0.00375, 0.005) of its zone 1 lies 0.005 m inside zone 1"));
  }
  SECTION("a shear modulus in the wrong units gives a negative Poisson ratio") {
    // K = 73 GPa with mu = 260 GPa (a slipped exponent): nu = (219 - 520) / (2 (219 + 260)) = -0.314.
    const std::string e = error_of(replaced(two_blocks(0.01), "2.6e10", "2.6e11"));
    CHECK_THAT(e, Catch::Contains("materials.al.strength.shear_modulus"));
    CHECK_THAT(e, Catch::Contains("-0.314"));
  }
  SECTION("non-positive density or modulus") {
    CHECK_THAT(error_of(replaced(two_blocks(0.01), "\"density\": 2700", "\"density\": 0")),
               Catch::Contains("materials.al.density"));
    CHECK_THAT(error_of(replaced(two_blocks(0.01), "7.3e10", "-7.3e10")),
               Catch::Contains("materials.al.eos.bulk_modulus"));
  }
  SECTION("a mesh too large for the machine is refused before it is built") {
    const std::string e = error_of(replaced(two_blocks(0.01), "\"zones\": 4 },\n                                                  \"y\": { \"from\": 0, \"to\": 0.01, \"zones\": 4 } } },\n                { \"name\": \"right\"",
                                            "\"zones\": 100000 },\n                                                  \"y\": { \"from\": 0, \"to\": 0.01, \"zones\": 100000 } } },\n                { \"name\": \"right\""));
    CHECK_THAT(e, Catch::Contains("bodies[0].mesh"));
    CHECK_THAT(e, Catch::Contains("more than"));
  }
}

TEST_CASE("held velocities that drive two bodies of a contact pair into each other are refused", "[scenario]") {
  // The two blocks touch along x = 0.01. Contact cannot move a held node, so a held face driven into
  // a fixed one would pass through it (measured before this check: the left block's face went 8 um
  // into the right one in 2 us at 4.18 m/s, and the run ended "completed" with its ledgers closed).
  auto with = [](const std::string& left_boundary, const std::string& right_boundary, bool pair) {
    std::string text = replaced(two_blocks(0.01), "\"zones\": 4 } } },\n                { \"name\": \"right\"",
                                "\"zones\": 4 } }, \"boundary\": " + left_boundary + " },\n                { \"name\": \"right\"");
    text = replaced(text, "\"zones\": 4 } } } ]", "\"zones\": 4 } }, \"boundary\": " + right_boundary + " } ]");
    if (pair) text = replaced(text, "\"bodies\": [", "\"contact\": { \"pairs\": [ { \"bodies\": [\"left\", \"right\"] } ] }, \"bodies\": [");
    return error_of(text);
  };
  const std::string pushing = R"({ "x_max": { "type": "velocity", "velocity": [4.18, null] } })";
  const std::string fixed = R"({ "x_min": "fixed" })";
  const std::string e = with(pushing, fixed, true);
  CHECK_THAT(e, Catch::Contains("contact.pairs[0]"));
  CHECK_THAT(e, Catch::Contains("bodies[0].boundary.x_max (velocity) holds v_x = 4.18 m/s"));
  CHECK_THAT(e, Catch::Contains("bodies[1].boundary.x_min (fixed) holds v_x = 0 m/s"));
  // Not contradictions: the faces separate, move together, are held in the other component only, or
  // are not in a contact pair.
  CHECK(with(R"({ "x_max": { "type": "velocity", "velocity": [-4.18, null] } })", fixed, true) == "(no error)");
  CHECK(with(pushing, R"({ "x_min": { "type": "velocity", "velocity": [4.18, null] } })", true) == "(no error)");
  CHECK(with(pushing, R"({ "x_min": { "type": "velocity", "velocity": [null, 0.0] } })", true) == "(no error)");
  CHECK(with(pushing, fixed, false) == "(no error)");
  // Sliding, not closing: the left block's bottom held at v_y = -1 and the right block's bottom on a
  // slip wall; at their shared corner node the two hold v_y at different values, but the bodies do
  // not face each other along y there.
  CHECK(with(R"({ "y_min": { "type": "velocity", "velocity": [null, -1.0] } })", R"({ "y_min": "slip" })", true) ==
        "(no error)");
}

TEST_CASE("an end time beyond the cycle budget is refused before the run", "[scenario]") {
  // Two 2.5 mm aluminium zones: c = sqrt((K + 4/3 mu) / rho) = 6.2 km/s, stable step about
  // 0.5 x 2.5e-3 / 6.2e3 = 2e-7 s. An end time of 1 s (a slip from 1e-6 s) needs about 5e6 cycles.
  std::string text = replaced(two_blocks(0.01), "\"end_time\": 1e-6", "\"end_time\": 1");
  text = replaced(text, "\"bodies\"", "\"controls\": { \"max_cycles\": 1000000 }, \"bodies\"");
  const auto scenario = parse_scenario(text, "test.json");
  std::string e = "(no error)";
  try {
    krug::run::validate_scenario(scenario);
  } catch (const InputError& error) {
    e = error.what();
  }
  CHECK_THAT(e, Catch::Contains("end_time"));
  CHECK_THAT(e, Catch::Contains("controls.max_cycles = 1000000"));
  CHECK_THAT(e, Catch::Contains("(set by zone "));
  // Within budget: accepted.
  CHECK_NOTHROW(krug::run::validate_scenario(parse_scenario(two_blocks(0.01), "test.json")));
}

TEST_CASE("documents that would crash or hang a reader are refused with the place named", "[scenario][robustness]") {
  SECTION("nesting deeper than the limit (a recursive reader's stack overflow)") {
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    const std::string e = error_of(replaced(valid_scenario(), "\"end_time\": 0.1", "\"end_time\": " + deep));
    CHECK_THAT(e, Catch::StartsWith("test.json: end_time[0][0]"));
    CHECK_THAT(e, Catch::Contains("nested more than 64 deep"));
    // A few levels are fine for the shape check (then refused by the reader for the type).
    CHECK_THAT(error_of(replaced(valid_scenario(), "\"end_time\": 0.1", "\"end_time\": [[[0.1]]]")),
               Catch::StartsWith("end_time: expected a number"));
  }
  SECTION("a key given twice: the second would silently win") {
    const std::string e = error_of(replaced(valid_scenario(), "\"end_time\": 0.1", "\"end_time\": 0.1, \"end_time\": -1"));
    CHECK(e == "test.json: end_time: the key \"end_time\" appears twice in one object; give each key once");
    const std::string nested = error_of(replaced(valid_scenario(), "\"zones\": 4 },", "\"zones\": 4, \"zones\": 5 },"));
    CHECK_THAT(nested, Catch::StartsWith("test.json: bodies[0].mesh.x.zones: the key \"zones\" appears twice"));
  }
  SECTION("output intervals that would write without end") {
    const std::string e = error_of(replaced(valid_scenario(), "\"end_time\": 0.1", "\"end_time\": 0.1, \"output\": { \"snapshot_interval\": 1e-320 }"));
    CHECK_THAT(e, Catch::StartsWith("output.snapshot_interval: expected an interval of at least end_time / 100000"));
    CHECK_THAT(error_of(replaced(valid_scenario(), "\"end_time\": 0.1", "\"end_time\": 0.1, \"output\": { \"history_interval\": 1e-12 }")),
               Catch::StartsWith("output.history_interval:"));
    CHECK_THAT(error_of(replaced(valid_scenario(), "\"end_time\": 0.1", "\"end_time\": 0.1, \"output\": { \"checkpoint_interval\": 1e-9 }")),
               Catch::StartsWith("output.checkpoint_interval:"));
    // Within the limit: accepted.
    CHECK(error_of(replaced(valid_scenario(), "\"end_time\": 0.1", "\"end_time\": 0.1, \"output\": { \"snapshot_interval\": 2e-6 }")) == "(no error)");
  }
  SECTION("coordinates beyond reason (a unit slip, or 1e300)") {
    const std::string e = error_of(replaced(valid_scenario(), "\"to\": 1, \"zones\": 4 },", "\"to\": 1e300, \"zones\": 4 },"));
    CHECK_THAT(e, Catch::StartsWith("bodies[0].mesh: a node at ("));
    CHECK_THAT(e, Catch::Contains("beyond 10000 m"));
  }
}

TEST_CASE("a scenario path that is not a regular file is refused, not waited on", "[scenario][robustness]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / fmt::format("krug_fifo_{}", ::getpid());
  std::filesystem::create_directories(dir);
  const std::filesystem::path fifo = dir / "scenario.json";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::string e = "(no error)";
  try {
    (void)krug::scenario::load_scenario(fifo);
  } catch (const InputError& error) {
    e = error.what();
  }
  CHECK_THAT(e, Catch::Contains("is not a regular file"));
  try {
    (void)krug::scenario::load_scenario(dir);
  } catch (const InputError& error) {
    e = error.what();
  }
  CHECK_THAT(e, Catch::Contains("is not a regular file"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("wrong input that used to pass: angles, expressions, the other geometry's axes", "[scenario][robustness]") {
  const std::string rectangle = "\"mesh\": { \"type\": \"rectangle\", \"x\": { \"from\": 0, \"to\": 1, \"zones\": 4 },\n"
                                "                                                 \"y\": { \"from\": 0, \"to\": 1, \"zones\": 4 } }";
  auto sector = [&](const std::string& angles) {
    return replaced(valid_scenario(), rectangle,
                    "\"mesh\": { \"type\": \"sector\", \"radius\": { \"from\": 0.1, \"to\": 1, \"zones\": 4 }, \"angle\": " +
                        angles + " }");
  };
  SECTION("a sector of more than a full turn, or angles in radians beyond the turn") {
    CHECK(error_of(replaced(sector("{ \"from\": 0, \"to\": 90, \"zones\": 4 }"), "\"boundary\": { \"x_min\": \"slip\" }",
                            "\"boundary\": {}")) == "(no error)");
    CHECK_THAT(error_of(sector("{ \"from\": 0, \"to\": 720, \"zones\": 4 }")),
               Catch::StartsWith("bodies[0].mesh.angle: the angles run from 0 to 720 degrees"));
    CHECK_THAT(error_of(sector("{ \"from\": -400, \"to\": 0, \"zones\": 4 }")), Catch::Contains("within [-360, 360]"));
    CHECK_THAT(error_of(sector("{ \"from\": 0, \"to\": 3.14159, \"zones\": 4 }")),
               Catch::Contains("3.14159 looks like an angle in radians"));
  }
  SECTION("expressions: only one formula, no assignment, bounded nesting") {
    auto density = [&](const std::string& expression) {
      return error_of(replaced(valid_scenario(), "\"specific_internal_energy\": 2.5",
                               "\"specific_internal_energy\": 2.5, \"density\": \"" + expression + "\""));
    };
    CHECK(density("(x <= 0.5) ? 1 : 0.125") == "(no error)");
    CHECK(density("1 + (x == 0.25) + (y != 1) + (x >= 2)") == "(no error)");
    CHECK_THAT(density("x = 3"), Catch::Contains("assigns a value"));
    CHECK_THAT(density("x += 3"), Catch::Contains("assigns a value"));
    CHECK_THAT(density("1, 2"), Catch::Contains("gives a list of values"));
    CHECK_THAT(density(std::string(40, '(') + "1" + std::string(40, ')')), Catch::Contains("more than 32 deep"));
    CHECK_THAT(density(std::string(1000, '(') + "1" + std::string(1000, ')')), Catch::Contains("more than 1000"));
    CHECK_THAT(density("x = 3"), Catch::StartsWith("bodies[0].initial.density: expression \"x = 3\""));
  }
  SECTION("a rectangle written with the other geometry's axis names names the key written") {
    const std::string e = error_of(replaced(valid_scenario(), "\"x\": { \"from\": 0, \"to\": 1, \"zones\": 4 }",
                                            "\"z\": { \"from\": 0, \"to\": 1, \"zones\": 4 }"));
    CHECK(e == "bodies[0].mesh.z: a planar rectangle names its axes \"x\" and \"y\"; found \"z\" (an axis of "
               "axisymmetric geometry)");
  }
}

TEST_CASE("unit slips that stay consistent are caught by plausibility checks, and allowed by name", "[scenario][robustness]") {
  // two_blocks(0.01): elastic aluminium, rho 2700 kg/m^3, K 7.3e10 Pa, mu 2.6e10 Pa (its definition above).
  const std::string base = two_blocks(0.01);
  SECTION("density in g/cm^3") {
    const std::string e = error_of(replaced(base, "\"density\": 2700", "\"density\": 2.7"));
    CHECK_THAT(e, Catch::StartsWith("materials.al.density: 2.7 kg/m^3 is outside"));
    CHECK_THAT(e, Catch::Contains("add \"density\" to the top-level \"allow_unusual\" list"));
    // Allowed by name (the sound speed is then out of range too, and is allowed as well).
    CHECK(error_of(replaced(replaced(base, "\"density\": 2700", "\"density\": 2.7"), "\"end_time\"",
                            "\"allow_unusual\": [\"density\", \"sound_speed\"], \"end_time\"")) == "(no error)");
  }
  SECTION("both moduli in GPa: the sound speed") {
    const std::string e = error_of(replaced(replaced(base, "7.3e10", "73"), "2.6e10", "26"));
    CHECK_THAT(e, Catch::Contains("longitudinal sound speed"));
    CHECK_THAT(e, Catch::Contains("\"sound_speed\""));
  }
  SECTION("the shear modulus alone in GPa") {
    CHECK_THAT(error_of(replaced(base, "2.6e10", "26")), Catch::Contains("less than 1e-5 of the bulk modulus"));
  }
  SECTION("a yield stress in Pa for MPa") {
    const std::string plastic = replaced(base, "{ \"model\": \"elastic\", \"shear_modulus\": 2.6e10 }",
                                         "{ \"model\": \"perfectly_plastic\", \"shear_modulus\": 2.6e10, \"yield_stress\": 3e8 }");
    CHECK(error_of(plastic) == "(no error)");
    CHECK_THAT(error_of(replaced(plastic, "3e8", "300")), Catch::Contains("of the shear modulus; solids lie between 1e-6 and 0.2"));
  }
  SECTION("a speed in km/s for m/s") {
    const std::string moving = "{ \"name\": \"left\", \"material\": \"al\", \"initial\": { \"velocity\": [800000, 0] },";
    const std::string e = error_of(replaced(base, "{ \"name\": \"left\", \"material\": \"al\",", moving));
    CHECK_THAT(e, Catch::StartsWith("bodies[0]: body \"left\" starts at 8e+05 m/s"));
    CHECK_THAT(e, Catch::Contains("faster than 1e5 m/s"));
  }
  SECTION("every equation of state with a bulk modulus is checked, not a list of two") {
    // The same unit slip, the density in g/cm^3, under each model that answers a bulk modulus
    // (reference_bulk_modulus in eos.hpp): Mie-Gruneisen copper (E3 constants) with the elastic strength,
    // and water as a stiffened gas (Saurel & Abgrall 1999), which has no strength model to make it a
    // solid otherwise and was not checked before the models answered.
    const std::string copper = replaced(base, "{ \"model\": \"linear\", \"bulk_modulus\": 7.3e10 }",
                                        "{ \"model\": \"mie_gruneisen\", \"bulk_sound_speed\": 3940, "
                                        "\"hugoniot_slope\": 1.49, \"gruneisen\": 2.0 }");
    CHECK(error_of(replaced(copper, "\"density\": 2700", "\"density\": 8930")) == "(no error)");
    // Mie-Gruneisen's K = rho0 c0^2 takes the slipped density too: 8.93 x 3940^2 = 1.386e8 Pa against the
    // shear modulus 2.6e10 Pa gives a Poisson ratio of -0.976, the first check to fail.
    CHECK_THAT(error_of(replaced(copper, "\"density\": 2700", "\"density\": 8.93")),
               Catch::Contains("the bulk modulus 1.386e+08 Pa of the eos, a Poisson ratio in [0, 0.5); this one gives -0.976"));
    const std::string water =
        replaced(replaced(replaced(base, "{ \"model\": \"linear\", \"bulk_modulus\": 7.3e10 }",
                                   "{ \"model\": \"stiffened_gas\", \"gamma\": 4.4, \"stiffness_pressure\": 6e8 }"),
                          ",\n                             \"strength\": { \"model\": \"elastic\", \"shear_modulus\": 2.6e10 }", ""),
                 "\"density\": 2700", "\"density\": 1000");
    CHECK(error_of(water) == "(no error)");
    CHECK_THAT(error_of(replaced(water, "\"density\": 1000", "\"density\": 1")),
               Catch::StartsWith("materials.al.density: 1 kg/m^3 is outside"));
    // A stiffened gas with p_inf = 0 is the ideal gas: not checked.
    CHECK(error_of(replaced(replaced(water, "\"density\": 1000", "\"density\": 1"), "6e8", "0")) == "(no error)");
  }
  SECTION("an unknown check name") {
    CHECK_THAT(error_of(replaced(base, "\"end_time\"", "\"allow_unusual\": [\"everything\"], \"end_time\"")),
               Catch::StartsWith("allow_unusual: expected an array of check names"));
  }
}

// Boundary loads and velocities in time (docs/scenario-format.md, "Boundary conditions"): a bad
// value names its JSON path.
TEST_CASE("boundary loads and functions of time: bad input names the JSON path", "[scenario][boundary]") {
  const std::string base = valid_scenario();
  auto on_x_max = [&](const std::string& condition) {
    return replaced(base, "\"boundary\": { \"x_min\": \"slip\" }", "\"boundary\": { \"x_min\": \"slip\", \"x_max\": " + condition + " }");
  };
  SECTION("valid: a constant pressure, a pressure and traction in time, a velocity ramp") {
    CHECK(error_of(on_x_max("{ \"type\": \"pressure\", \"pressure\": 1e5 }")) == "(no error)");
    CHECK(error_of(on_x_max("{ \"type\": \"traction\", \"traction\": \"1e4 * t\", \"pressure\": \"1e5 * min(t / 0.01, 1)\" }")) ==
          "(no error)");
    CHECK(error_of(on_x_max("{ \"type\": \"velocity\", \"velocity\": [\"-100 * min(t / 1e-6, 1)\", null] }")) == "(no error)");
  }
  SECTION("an unparseable p(t)") {
    const auto e = error_of(on_x_max("{ \"type\": \"pressure\", \"pressure\": \"1e5 * (t\" }"));
    CHECK_THAT(e, Catch::Contains("bodies[0].boundary.x_max.pressure"));
    CHECK_THAT(e, Catch::Contains("cannot evaluate expression"));
  }
  SECTION("a p(t) that is not finite during the run") {
    const auto e = error_of(on_x_max("{ \"type\": \"pressure\", \"pressure\": \"1e5 / (t - 0.05)\" }"));
    CHECK_THAT(e, Catch::Contains("bodies[0].boundary.x_max.pressure"));
    CHECK_THAT(e, Catch::Contains("t = 0.05"));
    CHECK_THAT(e, Catch::Contains("finite"));
  }
  SECTION("a non-finite traction and a velocity of position instead of time") {
    CHECK_THAT(error_of(on_x_max("{ \"type\": \"traction\", \"traction\": \"sqrt(t - 0.1)\" }")),
               Catch::Contains("bodies[0].boundary.x_max.traction"));
    const auto e = error_of(on_x_max("{ \"type\": \"velocity\", \"velocity\": [\"x * t\", null] }"));
    CHECK_THAT(e, Catch::Contains("bodies[0].boundary.x_max.velocity[0]"));
    CHECK_THAT(e, Catch::Contains("variables: t, pi"));
  }
  SECTION("a pressure without its value, or as a bare name") {
    CHECK_THAT(error_of(on_x_max("{ \"type\": \"pressure\" }")), Catch::Contains("bodies[0].boundary.x_max.pressure"));
    const auto e = error_of(on_x_max("\"pressure\""));
    CHECK_THAT(e, Catch::Contains("bodies[0].boundary.x_max"));
    CHECK_THAT(e, Catch::Contains("slip"));
  }
  SECTION("a pressure on the axis, where the radial velocity is held") {
    std::string rz = replaced(base, "\"geometry\": \"planar\"", "\"geometry\": \"axisymmetric\"");
    rz = replaced(rz, "\"x\": { \"from\": 0, \"to\": 1, \"zones\": 4 }", "\"z\": { \"from\": 0, \"to\": 1, \"zones\": 4 }");
    rz = replaced(rz, "\"y\": { \"from\": 0, \"to\": 1, \"zones\": 4 }", "\"r\": { \"from\": 0, \"to\": 1, \"zones\": 4 }");
    rz = replaced(rz, "\"boundary\": { \"x_min\": \"slip\" }", "\"boundary\": { \"r_min\": { \"type\": \"pressure\", \"pressure\": 1e5 } }");
    const auto e = error_of(rz);
    CHECK_THAT(e, Catch::Contains("bodies[0].boundary.r_min"));
    CHECK_THAT(e, Catch::Contains("lies on the axis"));
  }
  SECTION("a pressure on a side that a condition also holds (a scene built in C++)") {
    krug::scenario::Scenario scenario = parse_scenario(base, "test.json");
    krug::setup::SideBoundary load{"x_min", krug::setup::SideCondition::pressure, {}};
    load.pressure = [](double) { return 1e5; };
    scenario.scene.bodies[0].boundary.push_back(load);
    std::string e = "(no error)";
    try {
      (void)krug::setup::build_simulation(scenario.scene);
    } catch (const InputError& error) {
      e = error.what();
    }
    CHECK_THAT(e, Catch::Contains("bodies[0].boundary.x_min"));
    CHECK_THAT(e, Catch::Contains("held by a slip condition and also given a pressure load"));
    // Whichever comes first in the list.
    auto& sides = scenario.scene.bodies[0].boundary;
    std::rotate(sides.begin(), sides.end() - 1, sides.end());
    REQUIRE(sides.front().condition == krug::setup::SideCondition::pressure);
    e = "(no error)";
    try {
      (void)krug::setup::build_simulation(scenario.scene);
    } catch (const InputError& error) {
      e = error.what();
    }
    CHECK_THAT(e, Catch::Contains("held by a slip condition and also given a pressure load"));
  }
}

TEST_CASE("gauge errors name the JSON path", "[scenario][gauges]") {
  const std::string base = valid_scenario();
  const auto with_gauges = [&](const std::string& gauges) {
    return replaced(base, "\"end_time\": 0.1,", "\"end_time\": 0.1, \"gauges\": " + gauges + ",");
  };
  SECTION("a valid block parses") {
    const auto scenario = parse_scenario(
        with_gauges(R"({"interval": 0.01, "tracers": [{"name": "a", "position": [0.5, 0.5]}],
                        "surfaces": [{"name": "s", "body": "box", "position": [1.0, 0.5]}], "forces": true})"),
        "test.json");
    CHECK(scenario.gauges.tracers.size() == 1);
    CHECK(scenario.gauges.surfaces.size() == 1);
    CHECK(scenario.gauges.forces);
  }
  SECTION("a tracer outside every body") {
    const auto e = error_of(with_gauges(R"({"interval": 0.01, "tracers": [{"name": "a", "position": [2.0, 0.5]}]})"));
    CHECK(e.find("gauges.tracers[0].position") != std::string::npos);
    CHECK(e.find("no zone") != std::string::npos);
  }
  SECTION("an unknown quantity") {
    const auto e = error_of(with_gauges(
        R"({"interval": 0.01, "tracers": [{"name": "a", "position": [0.5, 0.5], "quantities": ["presure"]}]})"));
    CHECK(e.find("gauges.tracers[0].quantities[0]") != std::string::npos);
    CHECK(e.find("did you mean \"pressure\"") != std::string::npos);
  }
  SECTION("a temperature where no material has one") {
    const auto e = error_of(with_gauges(
        R"({"interval": 0.01, "tracers": [{"name": "a", "position": [0.5, 0.5], "quantities": ["temperature"]}]})"));
    CHECK(e.find("gauges.tracers[0].quantities[0]") != std::string::npos);
    CHECK(e.find("johnson_cook") != std::string::npos);
  }
  SECTION("a non-positive interval") {
    for (const char* interval : {"0", "-1e-3"}) {
      const auto e = error_of(with_gauges(fmt::format(R"({{"interval": {}, "forces": true}})", interval)));
      CHECK(e.find("gauges.interval") != std::string::npos);
    }
  }
  SECTION("a surface gauge on an unknown body, a zero direction, a repeated name, no gauge at all") {
    CHECK(error_of(with_gauges(R"({"interval": 0.01, "surfaces": [{"name": "s", "body": "bx", "position": [1, 0]}]})"))
              .find("gauges.surfaces[0].body") != std::string::npos);
    CHECK(error_of(with_gauges(
                       R"({"interval": 0.01, "surfaces": [{"name": "s", "body": "box", "position": [1, 0], "direction": [0, 0]}]})"))
              .find("gauges.surfaces[0].direction") != std::string::npos);
    CHECK(error_of(with_gauges(R"({"interval": 0.01, "tracers": [{"name": "a", "position": [0.5, 0.5]},
                                                                  {"name": "a", "position": [0.2, 0.5]}]})"))
              .find("gauges.tracers[1].name") != std::string::npos);
    CHECK(error_of(with_gauges(R"({"interval": 0.01})")).find("gauges") != std::string::npos);
    CHECK(error_of(with_gauges(R"({"interval": 0.01, "force": true})")).find("did you mean \"forces\"") != std::string::npos);
  }
}
