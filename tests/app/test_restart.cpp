// Checkpoints and restart, through the library API (krug::output::run_scenario / restart_scenario).
// A restarted run must be the run that was never stopped: summary.json equal apart from
// wall_seconds, and history.csv and run.pvd equal byte for byte. The scenario is E1
// (examples/verification/slab_impact.json: two elastic slabs in contact that separate at 1.55 us),
// so contact is active when the run is stopped at 1.2 us; and a small fracture scenario
// (tests/app/data/fracture_plate.json), so particles, damage and fracture counters pass through a
// checkpoint too.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>

#include "krug/core/error.hpp"
#include "krug/output/checkpoint.hpp"
#include "krug/output/run_files.hpp"
#include "krug/scenario/scenario.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using krug::output::RunOptions;
using krug::run::RunStatus;
using krug::test::Json;
using krug::test::read_text;
using krug::test::summary_without_timing;

namespace {

krug::scenario::Scenario scenario_with(const fs::path& file, const std::function<void(Json&)>& edit) {
  Json document = krug::test::read_json(file);
  edit(document);
  return krug::scenario::parse_scenario(document.dump(), file.string());
}

RunOptions to(const fs::path& directory) {
  RunOptions options;
  options.output_directory = directory;
  return options;
}

// Runs `scenario` into `directory`, interrupting it (as SIGINT would) once the time passes `at`.
krug::run::RunResult interrupted_run(const krug::scenario::Scenario& scenario, const fs::path& directory, double at) {
  std::atomic<bool> interrupt{false};
  RunOptions options = to(directory);
  options.interrupt = &interrupt;
  options.on_cycle = [&](const krug::Simulation& s, double) {
    if (s.time() >= at) interrupt = true;
    return true;
  };
  return krug::output::run_scenario(scenario, options);
}

void check_same_run(const fs::path& reference, const fs::path& restarted) {
  CHECK(summary_without_timing(restarted / "summary.json") == summary_without_timing(reference / "summary.json"));
  CHECK(read_text(restarted / "history.csv") == read_text(reference / "history.csv"));
  CHECK(read_text(restarted / "run.pvd") == read_text(reference / "run.pvd"));
  CHECK(read_text(restarted / "final.vtu") == read_text(reference / "final.vtu"));
}

}  // namespace

TEST_CASE("an interrupted run writes a checkpoint and, restarted, ends as if never stopped", "[app][restart]") {
  const fs::path file = fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json";
  const auto scenario = krug::scenario::load_scenario(file);
  const fs::path reference = krug::test::scratch("restart_reference");
  const fs::path stopped = krug::test::scratch("restart_interrupted");
  REQUIRE(krug::output::run_scenario(scenario, to(reference)).status == RunStatus::completed);

  const auto first = interrupted_run(scenario, stopped, 1.2e-6);
  CHECK(first.status == RunStatus::failed);
  CHECK(first.message == "interrupted");
  CHECK(first.stopped_by == "interrupted");
  REQUIRE(fs::exists(stopped / "checkpoint.bin"));
  const Json interrupted = krug::test::read_json(stopped / "summary.json");
  CHECK(interrupted["status"] == "failed");
  CHECK(interrupted["message"] == "interrupted");
  CHECK(interrupted["time"].get<double>() < 1.3e-6);
  // The slabs are in contact at 1.2 us (separation at 1.55 us): the contact state matters.
  CHECK(interrupted["bodies"]["target"]["velocity"][0].get<double>() > 1.0);

  const auto second = krug::output::restart_scenario(stopped / "checkpoint.bin", to(stopped));
  CHECK(second.status == RunStatus::completed);
  CHECK(second.warnings.empty());
  check_same_run(reference, stopped);
}

TEST_CASE("a periodic checkpoint restarts into another directory with the whole history", "[app][restart]") {
  const fs::path file = fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json";
  const auto plain = krug::scenario::load_scenario(file);
  const auto with_checkpoints = scenario_with(file, [](Json& d) { d["output"]["checkpoint_interval"] = 1.5e-6; });
  const fs::path reference = krug::test::scratch("checkpoint_reference");
  const fs::path periodic = krug::test::scratch("checkpoint_periodic");
  const fs::path elsewhere = krug::test::scratch("checkpoint_elsewhere");
  REQUIRE(krug::output::run_scenario(plain, to(reference)).status == RunStatus::completed);
  const auto run = krug::output::run_scenario(with_checkpoints, to(periodic));
  REQUIRE(run.status == RunStatus::completed);
  // Taking checkpoints does not change the run.
  CHECK(summary_without_timing(periodic / "summary.json") == summary_without_timing(reference / "summary.json"));
  // The last checkpoint is the one at 3 us (taken at the first cycle end at or after it).
  const krug::output::Checkpoint checkpoint = krug::output::read_checkpoint(periodic / "checkpoint.bin");
  CHECK(checkpoint.state.time >= 3.0e-6);
  CHECK(checkpoint.state.time < 3.1e-6);
  CHECK(checkpoint.progress.next_checkpoint_time == Approx(4.5e-6).margin(1e-15));

  const auto restarted = krug::output::restart_scenario(periodic / "checkpoint.bin", to(elsewhere));
  CHECK(restarted.status == RunStatus::completed);
  check_same_run(reference, elsewhere);
  // The earlier snapshots were brought along.
  CHECK(fs::exists(elsewhere / "snapshots" / "state_00000.vtu"));
}

TEST_CASE("particles and fracture counters survive a checkpoint", "[app][restart]") {
  const fs::path file = fs::path(KRUG_APP_TEST_DATA_DIR) / "fracture_plate.json";
  const auto scenario = krug::scenario::load_scenario(file);
  const fs::path reference = krug::test::scratch("fracture_reference");
  const fs::path stopped = krug::test::scratch("fracture_interrupted");
  REQUIRE(krug::output::run_scenario(scenario, to(reference)).status == RunStatus::completed);
  const Json whole = krug::test::read_json(reference / "summary.json");
  REQUIRE(whole["particles"]["count"].get<long>() > 0);
  // Stop when the first particles exist, so they are in the checkpoint.
  std::atomic<bool> interrupt{false};
  RunOptions options = to(stopped);
  options.interrupt = &interrupt;
  options.on_cycle = [&](const krug::Simulation& s, double) {
    if (s.particles().size() > 0) interrupt = true;
    return true;
  };
  REQUIRE(krug::output::run_scenario(scenario, options).message == "interrupted");
  REQUIRE(krug::output::read_checkpoint(stopped / "checkpoint.bin").state.particles.size() > 0);
  CHECK(krug::output::restart_scenario(stopped / "checkpoint.bin", to(stopped)).status == RunStatus::completed);
  check_same_run(reference, stopped);
}

TEST_CASE("a rezoned run restarts as if never stopped", "[app][restart][rezone]") {
  // The rezoned 454 m/s Taylor bar (examples/verification/taylor_bar_454_rezone.json), run to 50 us and
  // stopped at 40 us, after its remap has moved nodes: the rezone keeps no state beyond the mesh's.
  const fs::path file = fs::path(KRUG_EXAMPLES_DIR) / "verification" / "taylor_bar_454_rezone.json";
  const auto scenario = scenario_with(file, [](Json& d) { d["end_time"] = 5e-5; });
  const fs::path reference = krug::test::scratch("rezone_reference");
  const fs::path stopped = krug::test::scratch("rezone_interrupted");
  REQUIRE(krug::output::run_scenario(scenario, to(reference)).status == RunStatus::completed);
  REQUIRE(krug::test::read_json(reference / "summary.json")["ledger"]["energy"]["rezone"].get<double>() > 0.0);
  REQUIRE(interrupted_run(scenario, stopped, 4e-5).message == "interrupted");
  CHECK(krug::output::restart_scenario(stopped / "checkpoint.bin", to(stopped)).status == RunStatus::completed);
  check_same_run(reference, stopped);
}

TEST_CASE("Johnson-Cook damage survives a checkpoint taken while it accumulates", "[app][restart]") {
  // tests/app/data/johnson_cook_plate.json: the plate's zones carry D (zone field `damage`) and the
  // plastic strain already counted in it; a restart from a checkpoint taken when some zone has
  // 0 < D < 1 must end with the same bits (final.vtu includes the field `damage`).
  const fs::path file = fs::path(KRUG_APP_TEST_DATA_DIR) / "johnson_cook_plate.json";
  const auto scenario = krug::scenario::load_scenario(file);
  const fs::path reference = krug::test::scratch("johnson_cook_reference");
  const fs::path stopped = krug::test::scratch("johnson_cook_interrupted");
  REQUIRE(krug::output::run_scenario(scenario, to(reference)).status == RunStatus::completed);
  std::atomic<bool> interrupt{false};
  RunOptions options = to(stopped);
  options.interrupt = &interrupt;
  options.on_cycle = [&](const krug::Simulation& s, double) {
    const auto& damage = s.zone_state().fracture.damage;
    if (std::any_of(damage.begin(), damage.end(), [](double d) { return d > 0.0 && d < 1.0; })) interrupt = true;
    return true;
  };
  REQUIRE(krug::output::run_scenario(scenario, options).message == "interrupted");
  const auto checkpoint = krug::output::read_checkpoint(stopped / "checkpoint.bin");
  const auto& damage = checkpoint.state.zone_state.fracture.damage;
  CHECK(std::any_of(damage.begin(), damage.end(), [](double d) { return d > 0.0 && d < 1.0; }));
  CHECK(krug::output::restart_scenario(stopped / "checkpoint.bin", to(stopped)).status == RunStatus::completed);
  check_same_run(reference, stopped);
}

TEST_CASE("damaged or foreign checkpoints are refused with an InputError", "[app][restart]") {
  const fs::path file = fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json";
  const auto scenario = krug::scenario::load_scenario(file);
  const fs::path dir = krug::test::scratch("checkpoint_damaged");
  REQUIRE(interrupted_run(scenario, dir, 1.0e-6).message == "interrupted");
  const std::string bytes = read_text(dir / "checkpoint.bin");
  auto refused = [&](const std::string& damaged, const std::string& expected) {
    krug::test::write_text(dir / "damaged.bin", damaged);
    try {
      (void)krug::output::read_checkpoint(dir / "damaged.bin");
      FAIL("accepted a damaged checkpoint");
    } catch (const krug::InputError& e) {
      CHECK_THAT(e.what(), Catch::Contains(expected));
    }
  };
  refused(bytes.substr(0, bytes.size() / 2), "truncated");
  refused(bytes.substr(0, 4), "too short");
  std::string flipped = bytes;
  flipped[bytes.size() / 3] = static_cast<char>(flipped[bytes.size() / 3] ^ 0x10);
  refused(flipped, "checksum");
  std::string other_version = bytes;
  other_version[8] = static_cast<char>(krug::output::checkpoint_version + 1);  // a version this krug does not read
  refused(other_version, "checksum");  // the version is covered by the checksum too
  refused("not a checkpoint at all, but long enough to have a trailer", "KRUGCKPT");
  CHECK_THROWS_AS(krug::output::read_checkpoint(dir / "missing.bin"), krug::InputError);

  // A checkpoint of another mesh.
  const auto other = krug::scenario::load_scenario(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "sod.json");
  CHECK_THROWS_AS(krug::output::restart_scenario(other, dir / "checkpoint.bin", to(krug::test::scratch("checkpoint_foreign"))),
                  krug::InputError);
  // An edited scenario of the same mesh continues, with a warning (here: a later end time).
  const auto longer = scenario_with(file, [](Json& d) { d["end_time"] = 5e-6; });
  const fs::path extended_dir = krug::test::scratch("checkpoint_extended");
  const auto extended = krug::output::restart_scenario(longer, dir / "checkpoint.bin", to(extended_dir));
  CHECK(extended.status == RunStatus::completed);
  CHECK(extended.warnings.size() == 1);
  CHECK(krug::test::read_json(extended_dir / "summary.json")["time"].get<double>() == Approx(5e-6).epsilon(1e-12));
}

// Gauges through a checkpoint: gauges.csv of a run interrupted while the slabs are in contact and
// restarted (into the same directory, and from a periodic checkpoint into another one) is the file of
// the run that never stopped, byte for byte: the rows written after the checkpoint are cut, and the
// force gauges' impulses carried by the checkpoint go on.
TEST_CASE("gauges.csv survives a checkpoint and a restart byte for byte", "[app][restart][gauges]") {
  const fs::path file = fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json";
  const auto add_gauges = [](Json& d) {
    d["gauges"] = Json::parse(R"({"interval": 1e-7,
      "tracers": [ { "name": "mid", "position": [0.005, 1e-4] } ],
      "surfaces": [ { "name": "rear", "body": "target", "position": [0.01, 0.0] } ],
      "forces": true })");
  };
  const auto scenario = scenario_with(file, add_gauges);
  const auto periodic = scenario_with(file, [&](Json& d) {
    add_gauges(d);
    d["output"]["checkpoint_interval"] = 1.5e-6;
  });
  const fs::path reference = krug::test::scratch("gauges_reference");
  const fs::path stopped = krug::test::scratch("gauges_interrupted");
  const fs::path checkpoints = krug::test::scratch("gauges_periodic");
  const fs::path elsewhere = krug::test::scratch("gauges_elsewhere");
  REQUIRE(krug::output::run_scenario(scenario, to(reference)).status == RunStatus::completed);
  const std::string expected = read_text(reference / "gauges.csv");
  // Header, the first state, 40 rows at 1e-7 s over 4 us, the last state.
  CHECK(expected.rfind("time,cycle,mid_x,mid_y,mid_vx,mid_vy,mid_pressure,", 0) == 0);
  CHECK(std::count(expected.begin(), expected.end(), '\n') >= 42);
  CHECK(expected.find("pair_flyer_target_Fx,pair_flyer_target_Fy,pair_flyer_target_Ix") != std::string::npos);
  CHECK(expected.find("held_target_y_min_Fx") != std::string::npos);
  CHECK(expected.find("held_target_y_max_Fx") != std::string::npos);

  interrupted_run(scenario, stopped, 1.2e-6);
  REQUIRE(fs::exists(stopped / "checkpoint.bin"));
  REQUIRE(krug::output::restart_scenario(stopped / "checkpoint.bin", to(stopped)).status == RunStatus::completed);
  CHECK(read_text(stopped / "gauges.csv") == expected);

  REQUIRE(krug::output::run_scenario(periodic, to(checkpoints)).status == RunStatus::completed);
  CHECK(read_text(checkpoints / "gauges.csv") == expected);
  REQUIRE(krug::output::restart_scenario(checkpoints / "checkpoint.bin", to(elsewhere)).status == RunStatus::completed);
  CHECK(read_text(elsewhere / "gauges.csv") == expected);
}
