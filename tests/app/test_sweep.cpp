// Parameter sweeps: the --set syntax and the variants (library API, krug::scenario), then `krug sweep` on
// E1 (examples/verification/slab_impact.json, 60 zones) as 2 x 2 variants in 2 processes. E1 has an
// exact answer for each variant: equal impedances, so the 5 mm flyer stops and the 10 mm target
// leaves with half the flyer's speed (momentum m_f v = m_t v_t with m_t = 2 m_f), whatever the
// density.
#include <catch2/catch.hpp>

#include <map>

#include "krug/core/error.hpp"
#include "krug/output/sweep_files.hpp"
#include "krug/scenario/edit.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using krug::scenario::parse_sweep_set;

TEST_CASE("sweep values (--set) split at top-level commas and keep JSON values whole", "[app][sweep]") {
  const auto p = parse_sweep_set(R"(materials.steel.eos=1,2.5,[3,4],"a,b",{"k":[1,2]},steel)");
  CHECK(p.path == "materials.steel.eos");
  CHECK(p.values == std::vector<std::string>{"1", "2.5", "[3,4]", "\"a,b\"", R"({"k":[1,2]})", "steel"});
  CHECK(parse_sweep_set("bodies[0].initial.velocity[0]=350").values.size() == 1);
  for (const char* bad : {"no_equals", "=1,2", "a=", "a=1,,2", "a[x]=1", "a[0=1", "a..b=1"}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_sweep_set(bad), krug::InputError);
  }
}

TEST_CASE("variants are the cartesian product, checked by the reader before anything runs", "[app][sweep]") {
  const fs::path scenario = fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json";
  const fs::path dir = krug::test::scratch("sweep_prepare");
  const auto variants = krug::output::prepare_sweep(
      scenario, {parse_sweep_set("bodies[0].initial.velocity[0]=10,20,30"), parse_sweep_set("controls.cfl=0.3,0.5")}, dir);
  REQUIRE(variants.size() == 6);
  CHECK(variants[0].name == "000_velocity0=10_cfl=0.3");
  CHECK(variants[1].name == "001_velocity0=10_cfl=0.5");  // the last parameter varies fastest
  CHECK(variants[5].name == "005_velocity0=30_cfl=0.5");
  const auto written = krug::test::read_json(variants[3].scenario);
  CHECK(written["bodies"][0]["initial"]["velocity"][0] == 20);
  CHECK(written["controls"]["cfl"] == 0.5);  // "controls" was not in the file: created
  // The title names the variant after the base title, so that its pictures and logs say which it is.
  CHECK(written["title"] == krug::test::read_json(scenario)["title"].get<std::string>() +
                                " - sweep variant 003: bodies[0].initial.velocity[0]=20, controls.cfl=0.5");

  auto error_of = [&](const std::string& set) {
    try {
      (void)krug::output::prepare_sweep(scenario, {parse_sweep_set(set)}, krug::test::scratch("sweep_bad"));
    } catch (const krug::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK_THAT(error_of("bodies[5].name=a"), Catch::Contains("has 2 items"));
  CHECK_THAT(error_of("title.x=1"), Catch::Contains("is not an object"));
  CHECK_THAT(error_of("materials.aluminium.density=2700,-1"), Catch::Contains("variant 001_density=-1"));
  CHECK_THAT(error_of("materials.aluminium.density=-1"), Catch::Contains("materials.aluminium.density"));
  CHECK_THAT(error_of("bodies[0].materal=aluminium"), Catch::Contains("did you mean \"material\""));
}

TEST_CASE("krug sweep runs the variants in parallel and tabulates them", "[app][sweep]") {
  if (!krug::test::have_app()) return;
  const fs::path dir = krug::test::scratch("sweep_e1");
  const auto result = krug::test::run_krug(
      {"sweep", (fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json").string(), "--set",
       "bodies[0].initial.velocity[0]=10,20", "--set", "materials.aluminium.density=2785,3000", "--set",
       "output.pictures.enabled=false", "--set", "output.plots=false", "--jobs", "2", "--out", dir.string()},
      dir / "sweep.log");
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  const auto rows = krug::test::read_csv_table(dir / "sweep.csv");
  REQUIRE(rows.size() == 4);
  const std::vector<std::pair<double, double>> expected = {{10, 2785}, {10, 3000}, {20, 2785}, {20, 3000}};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    INFO(row.at("variant"));
    CHECK(std::stod(row.at("bodies[0].initial.velocity[0]")) == expected[i].first);
    CHECK(std::stod(row.at("materials.aluminium.density")) == expected[i].second);
    CHECK(row.at("status") == "completed");
    CHECK(row.at("stopped_by") == "end_time");
    CHECK(std::stod(row.at("time")) == Approx(4e-6).epsilon(1e-12));
    CHECK(std::stoi(row.at("cycles")) > 100);
    CHECK(std::stod(row.at("mass_error")) < 1e-14);
    // Exact: target at v/2, flyer at rest; the discrete contact leaves 0.05 % (verification.md E1).
    const double v = expected[i].first;
    CHECK(std::stod(row.at("target_vx")) == Approx(v / 2).epsilon(2e-3));
    CHECK(std::abs(std::stod(row.at("flyer_vx"))) < 1e-3 * v);
    CHECK(std::stod(row.at("flyer_mass")) == Approx(expected[i].second * 0.005 * 2.5e-4).epsilon(1e-12));
    CHECK(row.at("target_zones") == "40");
    CHECK(fs::exists(dir / row.at("variant") / "summary.json"));
    CHECK(fs::exists(dir / row.at("variant") / "log.txt"));
  }
}

TEST_CASE("a sweep with a failing variant exits 1 and says so in the table", "[app][sweep]") {
  if (!krug::test::have_app()) return;
  const fs::path dir = krug::test::scratch("sweep_failing");
  const auto result = krug::test::run_krug(
      {"sweep", (fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json").string(), "--set",
       "controls.time_step_floor=1e-6,0", "--set", "output={\"plots\": false, \"pictures\": {\"enabled\": false}}",
       "--jobs", "2", "--out", dir.string(), "--quiet"},
      dir / "sweep.log");
  INFO(result.output);
  CHECK(result.exit_code == 1);
  const auto rows = krug::test::read_csv_table(dir / "sweep.csv");
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].at("status") == "failed");
  // A floor above the stable step (1.9e-8 s) stops the run at its first cycle with a diagnostic.
  CHECK(rows[0].at("stopped_by") == "failure");
  CHECK_THAT(rows[0].at("message"), Catch::Contains("floor"));
  CHECK(rows[1].at("status") == "completed");
  CHECK(rows[1].at("output") == R"({"plots":false,"pictures":{"enabled":false}})");  // as given
}

TEST_CASE("a sweep of a penetration scenario tabulates the penetration block", "[app][sweep][penetration]") {
  if (!krug::test::have_app()) return;
  // E1 with the flyer named as the projectile: it stops inside the target (docs/outputs.md, Penetration).
  krug::test::Json document = krug::test::read_json(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json");
  document["penetration"] = {{"projectile", "flyer"}};
  document["stop"] = {{"no_contact_time", 5e-7}};
  document["output"] = {{"plots", false}, {"pictures", {{"enabled", false}}}};
  const fs::path dir = krug::test::scratch("sweep_penetration");
  krug::test::write_text(dir / "slab_penetration.json", document.dump(2));
  const auto result = krug::test::run_krug(
      {"sweep", (dir / "slab_penetration.json").string(), "--set", "bodies[0].initial.velocity[0]=10,20", "--jobs", "2",
       "--out", (dir / "out").string()},
      dir / "sweep.log");
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  const auto rows = krug::test::read_csv_table(dir / "out" / "sweep.csv");
  REQUIRE(rows.size() == 2);
  for (const auto& row : rows) {
    INFO(row.at("variant"));
    CHECK(row.at("stopped_by") == "stop rule");
    CHECK(row.at("penetration_perforated") == "false");
    CHECK(row.at("penetration_final") == "true");
    CHECK(row.at("penetration_perforation_time").empty());
    CHECK(row.at("penetration_plug_mass").empty());
    CHECK(std::abs(std::stod(row.at("penetration_residual_velocity"))) < 0.5);
    CHECK(std::stod(row.at("penetration_target_energy_absorbed")) > 0.0);
  }
}

TEST_CASE("edit_scenario applies edits by JSON path in memory and keeps the key order", "[app][sweep]") {
  const std::string text = R"({"title": "t", "bodies": [{"name": "a", "initial": {"velocity": [1, 2]}}], "controls": {}})";
  const std::string edited = krug::scenario::edit_scenario(
      text, {{"bodies[0].initial.velocity[0]", "350"}, {"controls.fracture.altitude_ratio", "0.2"}, {"title", "new"}},
      "test");
  const auto document = nlohmann::ordered_json::parse(edited);
  CHECK(document["bodies"][0]["initial"]["velocity"] == nlohmann::ordered_json::parse("[350, 2]"));
  CHECK(document["controls"]["fracture"]["altitude_ratio"] == 0.2);  // a missing object is created
  CHECK(document["title"] == "new");                                 // not JSON: taken as a string
  CHECK(document.begin().key() == "title");                          // the order of the text
  CHECK(edited.back() == '\n');
  auto error_of = [&](const std::string& path) {
    try {
      (void)krug::scenario::edit_scenario(text, {{path, "1"}}, "test");
    } catch (const krug::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_of("bodies[3].name"), Catch::Contains("bodies[3].name") && Catch::Contains("has 1 items"));
  CHECK_THAT(error_of("title.x"), Catch::Contains("is not an object"));
  CHECK_THAT(error_of("bodies.x"), Catch::Contains("is not an object"));
  CHECK_THAT(error_of("a..b"), Catch::Contains("an empty key"));
  CHECK_THROWS_AS(krug::scenario::edit_scenario("{not json", {}, "test"), krug::InputError);
}

TEST_CASE("a sweep into a folder with finished variants runs only the others (resume)", "[app][sweep]") {
  if (!krug::test::have_app()) return;
  const fs::path dir = krug::test::scratch("sweep_resume");
  const std::vector<std::string> arguments = {
      "sweep", (fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json").string(), "--set",
      "bodies[0].initial.velocity[0]=10,20,30", "--set", "output={\"plots\": false, \"pictures\": {\"enabled\": false}}",
      "--jobs", "2", "--out", dir.string()};
  auto without_timing = [](std::vector<std::map<std::string, std::string>> rows) {
    for (auto& row : rows) row.erase("wall_seconds");
    return rows;
  };
  const auto first = krug::test::run_krug(arguments, dir / "first.log");
  INFO(first.output);
  REQUIRE(first.exit_code == 0);
  const auto table = without_timing(krug::test::read_csv_table(dir / "sweep.csv"));
  REQUIRE(table.size() == 3);
  const fs::path kept = dir / table[1].at("variant");
  const auto kept_time = fs::last_write_time(kept / "summary.json");
  // Half-done: one variant's summary gone, another's cut in half (a run killed while writing it), and
  // nothing must look finished to a scenario that differs.
  fs::remove(dir / table[0].at("variant") / "summary.json");
  const fs::path cut = dir / table[2].at("variant") / "summary.json";
  const std::string text = krug::test::read_text(cut);
  krug::test::write_text(cut, text.substr(0, text.size() / 2));
  const auto second = krug::test::run_krug(arguments, dir / "second.log");
  INFO(second.output);
  REQUIRE(second.exit_code == 0);
  CHECK_THAT(second.output, Catch::Contains("1 of them finished in an earlier sweep into this folder (kept); 2 to run"));
  CHECK(fs::last_write_time(kept / "summary.json") == kept_time);
  CHECK(without_timing(krug::test::read_csv_table(dir / "sweep.csv")) == table);
  // A folder whose run was of another scenario is run again.
  krug::test::write_text(kept / "scenario.resolved.json", "{}\n");
  const auto third = krug::test::run_krug(arguments, dir / "third.log");
  INFO(third.output);
  CHECK_THAT(third.output, Catch::Contains("2 of them finished in an earlier sweep into this folder (kept); 1 to run"));
  CHECK(without_timing(krug::test::read_csv_table(dir / "sweep.csv")) == table);
}
