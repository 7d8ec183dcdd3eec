// The stop rule (scenario key "stop", include/krug/run/stop_rule.hpp): first on velocity histories
// made up here, then on E1 (examples/verification/slab_impact.json), where the exact answer is
// known: the 5 mm flyer at 10 m/s hits a 10 mm target of the same material, and the two separate at
// 2 h_f / c_L = 1.550 us with the flyer at rest (equal impedances). With no_contact_time 0.5 us the
// run must end at about 1.55 + 0.5 us, long before its end time of 4 us.
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>

#include "krug/output/run_files.hpp"
#include "krug/run/stop_rule.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using krug::Vec2;
using krug::run::StopMonitor;
using krug::scenario::StopRule;
using krug::test::Json;

namespace {

StopRule rule(double window, double fraction) {
  StopRule r;
  r.body = "projectile";
  r.no_contact_time = window;
  r.velocity_change = fraction;
  return r;
}

// Feeds v(t) at steps of dt until the monitor says stop; returns that time (or -1).
template <class Velocity>
double stop_time(StopMonitor& monitor, Velocity v, double dt, double end) {
  for (double t = 0.0; t <= end; t += dt) {
    if (monitor.observe(t, v(t))) return t;
  }
  return -1.0;
}

}  // namespace

TEST_CASE("the stop rule on made-up velocity histories", "[app][stop]") {
  SECTION("a body in free flight never arms, so the run is not cut short before the impact") {
    StopMonitor monitor(rule(1.0, 0.01));
    CHECK(stop_time(monitor, [](double) { return Vec2{300.0, 0.0}; }, 0.01, 10.0) < 0.0);
    CHECK_FALSE(monitor.state().armed);
  }
  SECTION("after a hit (300 -> 200 m/s over [2, 3]) it stops one window after the velocity settles") {
    StopMonitor monitor(rule(1.0, 0.01));
    auto v = [](double t) { return Vec2{t < 2.0 ? 300.0 : t < 3.0 ? 300.0 - 100.0 * (t - 2.0) : 200.0, 0.0}; };
    const double t = stop_time(monitor, v, 0.01, 10.0);
    // Armed when |dV| first exceeds 3 m/s (t = 2.03..2.04); the window of 1 must hold within 3 m/s of
    // the current 200 m/s: 300 - 100 (t' - 2) <= 203 for every t' in [t - 1, t], so t - 1 >= 2.97.
    CHECK(t == Approx(3.97).margin(0.011));
  }
  SECTION("small ringing below the tolerance does not prevent the stop; a second hit delays it") {
    StopMonitor monitor(rule(0.5, 0.02));
    auto v = [](double t) {
      const double base = t < 1.0 ? 100.0 : t < 1.3 ? 50.0 : 20.0;  // hits at t = 1 and t = 1.3
      return Vec2{base + 0.5 * std::sin(40.0 * t), 0.0};           // ringing of +-0.5 m/s < 2 m/s
    };
    const double t = stop_time(monitor, v, 0.001, 10.0);
    CHECK(t == Approx(1.8).margin(0.002));  // one window after the second hit
  }
  SECTION("the second component counts too") {
    StopMonitor monitor(rule(1.0, 0.01));
    auto v = [](double t) { return Vec2{100.0, t < 1.0 ? 0.0 : t < 2.0 ? 10.0 * (t - 1.0) : 10.0}; };
    CHECK(stop_time(monitor, v, 0.01, 10.0) == Approx(2.9).margin(0.011));
  }
  SECTION("a body not yet clear of the rule's plane holds the stop; once clear it stops at once") {
    StopMonitor monitor(rule(1.0, 0.01));
    auto v = [](double t) { return Vec2{t < 2.0 ? 300.0 : t < 3.0 ? 300.0 - 100.0 * (t - 2.0) : 200.0, 0.0}; };
    double stopped = -1.0;
    for (double t = 0.0; t <= 10.0 && stopped < 0.0; t += 0.01) {
      if (monitor.observe(t, v(t), t >= 6.0)) stopped = t;  // clear of the plane from t = 6 on
    }
    CHECK(stopped == Approx(6.0).margin(0.011));  // the velocity window has held since 3.97
  }
  SECTION("a body that starts at rest uses the largest speed it reaches as its scale") {
    StopMonitor monitor(rule(1.0, 0.01));
    auto v = [](double t) { return Vec2{t < 1.0 ? 0.0 : t < 2.0 ? 50.0 * (t - 1.0) : 50.0, 0.0}; };
    CHECK(stop_time(monitor, v, 0.01, 10.0) == Approx(2.99).margin(0.011));
  }
}

TEST_CASE("a projectile run ends by the stop rule once the flyer is free (E1)", "[app][stop]") {
  Json document = krug::test::read_json(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json");
  document["stop"] = {{"body", "flyer"}, {"no_contact_time", 5e-7}};
  const auto scenario = krug::scenario::parse_scenario(document.dump(), "slab_stop.json");
  const fs::path dir = krug::test::scratch("stop_rule_e1");
  krug::output::RunOptions options;
  options.output_directory = dir;
  const auto result = krug::output::run_scenario(scenario, options);
  CHECK(result.status == krug::run::RunStatus::completed);
  CHECK(result.stopped_by == "stop rule");
  const Json summary = krug::test::read_json(dir / "summary.json");
  CHECK(summary["status"] == "completed");
  CHECK(summary["stopped_by"] == "stop rule");
  // Separation at 1.550 us (exact), then a window of 0.5 us; the discrete separation is a few cycles
  // (of about 2 ns) late and the flyer's velocity settles within 1 % a little after it.
  CHECK(summary["time"].get<double>() > 2.0e-6);
  CHECK(summary["time"].get<double>() < 2.3e-6);
  CHECK(std::abs(summary["bodies"]["flyer"]["velocity"][0].get<double>()) < 0.1);  // 1 % of 10 m/s

  SECTION("restarted inside the window, it stops at the same cycle") {
    const fs::path stopped = krug::test::scratch("stop_rule_e1_restart");
    std::atomic<bool> interrupt{false};
    krug::output::RunOptions first;
    first.output_directory = stopped;
    first.interrupt = &interrupt;
    first.on_cycle = [&](const krug::Simulation& s, double) {
      if (s.time() >= 1.8e-6) interrupt = true;
      return true;
    };
    REQUIRE(krug::output::run_scenario(scenario, first).message == "interrupted");
    krug::output::RunOptions second;
    second.output_directory = stopped;
    CHECK(krug::output::restart_scenario(stopped / "checkpoint.bin", second).stopped_by == "stop rule");
    CHECK(krug::test::summary_without_timing(stopped / "summary.json") == krug::test::summary_without_timing(dir / "summary.json"));
  }
}

// The loop writes no file: it tells its observer (krug/run/observer.hpp) after every cycle, when a
// checkpoint is due and at the end. An observer that only counts sees the run RunRecorder would write.
class CountingObserver final : public krug::run::RunObserver {
 public:
  void cycle(const krug::Simulation&) override { ++cycles; }
  std::filesystem::path checkpoint(const krug::Simulation& simulation, krug::run::RunProgress& progress) override {
    ++checkpoints;
    kept = progress;
    checkpoint_time = simulation.time();
    return "kept in memory";
  }
  void finish(const krug::Simulation&, const krug::run::RunResult& result) override {
    ++finishes;
    stopped_by = result.stopped_by;
  }
  long cycles = 0;
  int checkpoints = 0, finishes = 0;
  double checkpoint_time = 0.0;
  krug::run::RunProgress kept;
  std::string stopped_by;
};

TEST_CASE("the run loop reaches its outputs only through its observer (E1)", "[app][stop]") {
  Json document = krug::test::read_json(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json");
  document["stop"] = {{"body", "flyer"}, {"no_contact_time", 5e-7}};
  const auto scenario = krug::scenario::parse_scenario(document.dump(), "slab_observed.json");
  REQUIRE_FALSE(fs::exists(scenario.output.directory));

  krug::Simulation simulation(scenario.setup);
  CountingObserver observer;
  const auto result = krug::run::run_simulation(scenario, simulation, observer, {});
  CHECK(result.stopped_by == "stop rule");
  CHECK(observer.cycles == simulation.cycle());
  CHECK(observer.checkpoints == 0);
  CHECK(observer.finishes == 1);
  CHECK(observer.stopped_by == "stop rule");
  CHECK_FALSE(fs::exists(scenario.output.directory));  // nothing written

  SECTION("an interruption is a checkpoint the observer keeps, with the loop's part of the progress") {
    krug::Simulation interrupted(scenario.setup);
    CountingObserver first;
    std::atomic<bool> interrupt{false};
    krug::run::RunOptions options;
    options.interrupt = &interrupt;
    options.on_cycle = [&](const krug::Simulation& s, double) {
      if (s.time() >= 1.8e-6) interrupt = true;
      return true;
    };
    const auto stopped = krug::run::run_simulation(scenario, interrupted, first, options);
    CHECK(stopped.stopped_by == "interrupted");
    CHECK(stopped.checkpoint == "kept in memory");
    REQUIRE(first.checkpoints == 1);
    CHECK(first.checkpoint_time == interrupted.time());
    CHECK(first.kept.has_stop_state);
    CHECK(first.kept.stop.armed);  // the flyer was hit before 1.8 us

    // Continued from the kept progress (the state as it was), it stops where the whole run did.
    CountingObserver second;
    const auto resumed = krug::run::resume_simulation(scenario, interrupted, first.kept, second, {});
    CHECK(resumed.stopped_by == "stop rule");
    CHECK(interrupted.cycle() == simulation.cycle());
    CHECK(interrupted.time() == simulation.time());
    CHECK(first.cycles + second.cycles == observer.cycles);
  }
}

TEST_CASE("the stop rule's clear_of plane: the run waits until the whole body has passed it (E1)", "[app][stop]") {
  // The flyer occupies x in [-5, 0] mm and moves towards +x; after the separation it is at rest.
  Json document = krug::test::read_json(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json");
  const auto run = [&](double plane, const std::string& name) {
    document["stop"] = {{"body", "flyer"}, {"no_contact_time", 5e-7}, {"clear_of", plane}};
    const auto scenario = krug::scenario::parse_scenario(document.dump(), name + ".json");
    krug::output::RunOptions options;
    options.output_directory = krug::test::scratch(name);
    return krug::output::run_scenario(scenario, options);
  };
  // A plane behind the flyer: clear from the start, so the rule stops the run as without the plane.
  const auto behind = run(-6e-3, "stop_rule_clear_behind");
  CHECK(behind.stopped_by == "stop rule");
  // The target's face: the flyer never passes it, so the run goes on to its end time.
  const auto face = run(0.0, "stop_rule_clear_face");
  CHECK(face.status == krug::run::RunStatus::completed);
  CHECK(face.stopped_by == "end_time");
}

TEST_CASE("without a stop rule, summary.json says the run ran to its end time", "[app][stop]") {
  const auto scenario = krug::scenario::load_scenario(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json");
  const fs::path dir = krug::test::scratch("stop_rule_none");
  krug::output::RunOptions options;
  options.output_directory = dir;
  CHECK(krug::output::run_scenario(scenario, options).stopped_by == "end_time");
  CHECK(krug::test::read_json(dir / "summary.json")["stopped_by"] == "end_time");
}
