// `krug ballistic` end to end on a small planar case (tests/app/data/ballistic_plate.json: a steel rod
// against a 1 mm aluminium plate, a fraction of a second per run): the outputs exist and agree with
// one another (every perforation faster than every stop, the limit inside its bracket, the bracket
// within the tolerance, each row's run directory with its resolved scenario), and bad input is refused.
#include <catch2/catch.hpp>

#include <map>

#include "test_support.hpp"

namespace fs = std::filesystem;
using krug::test::Json;

namespace {


const fs::path scenario = fs::path(KRUG_APP_TEST_DATA_DIR) / "ballistic_plate.json";

}  // namespace

TEST_CASE("krug ballistic brackets the limit of a small plate and writes consistent outputs", "[app][ballistic]") {
  if (!krug::test::have_app()) SUCCEED("no krug app built");
  if (!krug::test::have_app()) return;
  const fs::path dir = krug::test::scratch("ballistic_plate");
  const auto result = krug::test::run_krug({"ballistic", scenario.string(), "--velocity", "60,400", "--tolerance", "10",
                                            "--jobs", "2", "--out", (dir / "out").string()},
                                           dir / "ballistic.log");
  INFO(result.output);
  REQUIRE(result.exit_code == 0);
  CHECK_THAT(result.output, Catch::Contains("ballistic limit V_bl") && Catch::Contains("V50"));
  const Json study = krug::test::read_json(dir / "out" / "ballistic.json");
  const auto rows = krug::test::read_csv_table(dir / "out" / "ballistic.csv");
  REQUIRE(study["bracketed"] == true);
  REQUIRE(study["converged"] == true);
  const double low = study["bracket"][0], high = study["bracket"][1];
  CHECK(high - low <= 10.0);
  CHECK(study["v_bl"].get<double>() > low);
  CHECK(study["v_bl"].get<double>() < high);
  CHECK(study["v50"].get<double>() == Approx(0.5 * (study["highest_stop"].get<double>() + study["lowest_perforation"].get<double>())));
  REQUIRE(rows.size() == study["runs"].get<std::size_t>());
  double fastest_stop = 0.0, slowest_perforation = 1e9;
  int perforated_above = 0;
  for (const auto& row : rows) {
    INFO(row.at("velocity") << " " << row.at("result"));
    const double v = std::stod(row.at("velocity"));
    CHECK(v >= 60.0);
    CHECK(v <= 400.0);
    if (row.at("result") == "stopped") fastest_stop = std::max(fastest_stop, v);
    if (row.at("result") == "perforated") {
      slowest_perforation = std::min(slowest_perforation, v);
      perforated_above += v > high;
      CHECK(row.at("perforated") == "true");
      CHECK(row.at("final") == "true");
      CHECK(std::stod(row.at("residual_velocity")) < v);  // the plate slowed it
    }
    if (row.at("result") == "unfinished" || row.at("result") == "failed") CHECK(row.at("perforated").empty());
    // Every run can be re-run alone: its scenario and the resolved one are there.
    CHECK(fs::exists(dir / "out" / row.at("directory") / "scenario.json"));
    CHECK(fs::exists(dir / "out" / row.at("directory") / "scenario.resolved.json"));
  }
  CHECK(fastest_stop < slowest_perforation);  // every perforation faster than every stop
  CHECK(fastest_stop == low);
  CHECK(slowest_perforation == high);
  CHECK(perforated_above >= 3);
  // The fit and the reference are there, with uncertainties and residuals.
  CHECK(study["lambert_jonas"]["valid"] == true);
  CHECK(study["lambert_jonas"]["sigma_v_bl"].get<double>() > 0.0);
  CHECK(study["lambert_jonas"]["residuals"].size() == study["counts"]["perforated"].get<std::size_t>());
  CHECK(study["recht_ipson"]["valid"] == true);
  CHECK(study["recht_ipson"]["p"] == 2.0);
  // The variant keeps the direction and scales the speed.
  const Json variant = krug::test::read_json(dir / "out" / rows.front().at("directory") / "scenario.json");
  CHECK(variant["bodies"][0]["initial"]["velocity"][0].get<double>() == Approx(std::stod(rows.front().at("velocity"))));
  CHECK(variant["bodies"][0]["initial"]["velocity"][1].get<double>() == 0.0);
}

TEST_CASE("krug ballistic refuses bad input with a message and exit code 2", "[app][ballistic]") {
  if (!krug::test::have_app()) return;
  const fs::path dir = krug::test::scratch("ballistic_bad");
  auto run = [&](std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), "ballistic");
    return krug::test::run_krug(arguments, dir / "bad.log");
  };
  const fs::path no_penetration = fs::path(KRUG_APP_TEST_DATA_DIR) / "fracture_plate.json";
  auto r = run({no_penetration.string(), "--velocity", "100,200", "--out", (dir / "a").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("penetration"));
  r = run({scenario.string(), "--velocity", "300,200", "--out", (dir / "b").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("must be below"));
  r = run({scenario.string(), "--velocity", "abc,200", "--out", (dir / "c").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("not a positive number"));
  r = run({scenario.string(), "--velocity", "100", "--out", (dir / "d").string()});
  CHECK(r.exit_code == 2);
  r = run({scenario.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("--velocity"));
  r = run({scenario.string(), "--velocity", "100,200", "--tolerance", "-1"});
  CHECK(r.exit_code == 2);
  // An expression for the projectile's velocity cannot be scaled.
  Json document = krug::test::read_json(scenario);
  document["bodies"][0]["initial"]["velocity"] = {"400 + 0*x", 0.0};
  krug::test::write_text(dir / "expression.json", document.dump(2));
  r = run({(dir / "expression.json").string(), "--velocity", "100,200", "--out", (dir / "e").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("expression"));
}
