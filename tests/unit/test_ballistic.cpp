// Ballistic limit (krug/run/ballistic.hpp) on synthetic truths: the Lambert-Jonas fit recovers a
// known curve (exactly without noise; within its stated standard uncertainties with seeded Gaussian
// noise, and those uncertainties cover the truth about as often as a standard uncertainty should over
// many seeds), and the search converges on a synthetic target with a known ballistic limit, going
// around a failed and an unfinished run planted inside the bracket.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "krug/core/error.hpp"
#include "krug/run/ballistic.hpp"

using namespace krug::run;

namespace {

// Standard normal numbers from the raw output of std::mt19937_64 (which the standard fixes) by
// Box-Muller, so the noise is the same on every library.
struct Normal {
  std::mt19937_64 engine;
  explicit Normal(std::uint64_t seed) : engine(seed) {}
  double uniform() { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; }
  double operator()() {
    const double u1 = uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }
};

// Truth of the synthetic studies.
constexpr double true_a = 0.85, true_p = 2.4, true_v_bl = 300.0;

std::vector<double> speeds() {
  std::vector<double> v;
  for (int i = 0; i < 12; ++i) v.push_back(310.0 + 25.0 * i);  // 310 ... 585 m/s
  return v;
}

CurveFit fit_with_noise(std::uint64_t seed, double sigma) {
  Normal normal(seed);
  const std::vector<double> v_i = speeds();
  std::vector<double> v_r;
  for (double v : v_i) v_r.push_back(lambert_jonas(v, true_a, true_p, true_v_bl) + sigma * normal());
  CurveFitOptions start;
  start.v_bl = 0.95 * v_i.front();  // the search starts it at its bracket; here a blind start
  return fit_lambert_jonas(v_i, v_r, start);
}

}  // namespace

TEST_CASE("the Lambert-Jonas fit recovers an exact curve", "[ballistic]") {
  const CurveFit fit = fit_with_noise(1, 0.0);
  REQUIRE(fit.valid);
  CHECK(fit.a == Approx(true_a).epsilon(1e-6));
  CHECK(fit.p == Approx(true_p).epsilon(1e-5));
  CHECK(fit.v_bl == Approx(true_v_bl).epsilon(1e-6));
  CHECK(fit.rms < 1e-6);
  CHECK(lambert_jonas(true_v_bl - 1.0, true_a, true_p, true_v_bl) == 0.0);
}

TEST_CASE("with noise the fit recovers the truth within its stated uncertainties", "[ballistic]") {
  const double sigma = 3.0;  // m/s of residual velocity
  const CurveFit fit = fit_with_noise(20240611, sigma);
  REQUIRE(fit.valid);
  INFO("a " << fit.a << " +- " << fit.sigma_a << ", p " << fit.p << " +- " << fit.sigma_p << ", v_bl " << fit.v_bl
            << " +- " << fit.sigma_v_bl << ", rms " << fit.rms);
  REQUIRE(fit.sigma_a > 0.0);
  REQUIRE(fit.sigma_p > 0.0);
  REQUIRE(fit.sigma_v_bl > 0.0);
  // Three standard uncertainties: a one-seed check (the coverage test below checks the size of sigma).
  CHECK(std::abs(fit.a - true_a) < 3.0 * fit.sigma_a);
  CHECK(std::abs(fit.p - true_p) < 3.0 * fit.sigma_p);
  CHECK(std::abs(fit.v_bl - true_v_bl) < 3.0 * fit.sigma_v_bl);
  CHECK(fit.rms == Approx(sigma).epsilon(0.5));  // the residuals are the noise
  CHECK(fit.residuals.size() == 12);
}

TEST_CASE("the fit's standard uncertainties cover the truth about 68 % of the time", "[ballistic]") {
  // 400 seeds; a standard uncertainty covers 68.3 %; the binomial spread of the fraction is 2.3 %, so
  // 0.61-0.76 is three spreads. (Linearised uncertainties of a nonlinear fit: a check that they are
  // of the right size, neither a tenth nor ten times.)
  const int seeds = 400;
  int covered_a = 0, covered_p = 0, covered_v = 0, valid = 0;
  for (int s = 0; s < seeds; ++s) {
    const CurveFit fit = fit_with_noise(1000 + static_cast<std::uint64_t>(s), 3.0);
    if (!fit.valid) continue;
    ++valid;
    covered_a += std::abs(fit.a - true_a) < fit.sigma_a;
    covered_p += std::abs(fit.p - true_p) < fit.sigma_p;
    covered_v += std::abs(fit.v_bl - true_v_bl) < fit.sigma_v_bl;
  }
  INFO("valid " << valid << ", covered a " << covered_a << ", p " << covered_p << ", v_bl " << covered_v);
  CHECK(valid == seeds);
  CHECK(covered_a / double(valid) == Approx(0.683).margin(0.07));
  CHECK(covered_p / double(valid) == Approx(0.683).margin(0.07));
  CHECK(covered_v / double(valid) == Approx(0.683).margin(0.07));
}

TEST_CASE("with p and a fixed the fit finds v_bl alone (the Recht-Ipson form)", "[ballistic]") {
  std::vector<double> v_i = {320.0, 380.0, 450.0}, v_r;
  const double a = 2.6 / (2.6 + 0.3);
  for (double v : v_i) v_r.push_back(lambert_jonas(v, a, 2.0, 305.0));
  CurveFitOptions options;
  options.free_a = options.free_p = false;
  options.a = a;
  options.p = 2.0;
  options.v_bl = 290.0;
  const CurveFit fit = fit_lambert_jonas(v_i, v_r, options);
  REQUIRE(fit.valid);
  CHECK(fit.free_parameters == 1);
  CHECK(fit.v_bl == Approx(305.0).epsilon(1e-8));
  CHECK(fit.sigma_a == 0.0);
}

namespace {

// A synthetic target: perforated above v_true, with the Lambert-Jonas residual speed and a plug; the
// run at `fail_at` (the first speed asked inside `plant`) fails and the next one there is unfinished.
struct SyntheticTarget {
  double v_true = 312.34;
  double plant_low = 0.0, plant_high = 0.0;
  int planted = 0;
  std::vector<double> failed, unfinished;
  int calls = 0;
  std::size_t largest_batch = 0;
  std::vector<BallisticOutcome> operator()(const std::vector<double>& batch) {
    ++calls;
    largest_batch = std::max(largest_batch, batch.size());
    std::vector<BallisticOutcome> outcomes;
    for (double v : batch) {
      BallisticOutcome o;
      o.velocity = v;
      o.initial_mass = 2.6e-3;
      o.status = "completed";
      if (v > plant_low && v < plant_high && planted < 2) {
        o.result = planted == 0 ? ImpactResult::failed : ImpactResult::unfinished;
        (planted == 0 ? failed : unfinished).push_back(v);
        o.status = planted == 0 ? "failed" : "completed";
        ++planted;
      } else if (v > v_true) {
        o.result = ImpactResult::perforated;
        o.plug_mass = 0.3e-3;
        o.residual_velocity = lambert_jonas(v, 2.6 / 2.9, 2.0, v_true);
      } else {
        o.result = ImpactResult::stopped;
      }
      outcomes.push_back(o);
    }
    return outcomes;
  }
};

}  // namespace

TEST_CASE("the search converges on a synthetic target and goes around failed runs in the bracket", "[ballistic]") {
  for (int batch : {1, 2, 3, 4}) {
    INFO("batch " << batch);
    SyntheticTarget target;
    target.plant_low = 280.0;  // the first runs inside this window, which holds v_true, fail / do not finish
    target.plant_high = 340.0;
    BallisticOptions options;
    options.v_min = 150.0;
    options.v_max = 450.0;
    options.tolerance = 5.0;
    options.batch = batch;
    const BallisticStudy study = ballistic_search(options, std::ref(target));
    REQUIRE(study.bracketed);
    CHECK(study.converged);
    CHECK(study.bracket_high - study.bracket_low <= options.tolerance);
    CHECK(study.bracket_low < target.v_true);
    CHECK(study.bracket_high > target.v_true);
    CHECK(std::abs(study.v_bl - target.v_true) <= 0.5 * options.tolerance);
    CHECK(study.v50 == Approx(0.5 * (study.highest_stop + study.lowest_perforation)));
    CHECK(target.largest_batch <= static_cast<std::size_t>(std::max(2, batch)) + 3);  // the points above come at once
    // The planted runs are in the study, shown as such, never counted, and the notes name them.
    REQUIRE(target.failed.size() == 1);
    REQUIRE(target.unfinished.size() == 1);
    bool failed_shown = false, unfinished_shown = false;
    for (const BallisticOutcome& o : study.runs) {
      failed_shown = failed_shown || (o.velocity == target.failed[0] && o.result == ImpactResult::failed);
      unfinished_shown = unfinished_shown || (o.velocity == target.unfinished[0] && o.result == ImpactResult::unfinished);
    }
    CHECK(failed_shown);
    CHECK(unfinished_shown);
    std::string notes;
    for (const std::string& n : study.notes) notes += n + "\n";
    INFO(notes);
    if (target.failed[0] > study.bracket_low && target.failed[0] < study.bracket_high) {
      CHECK_THAT(notes, Catch::Contains("failed"));
    }
    // Points above and the fits: exact data, so the fits find v_true.
    int above = 0;
    for (const BallisticOutcome& o : study.runs) above += o.result == ImpactResult::perforated && o.velocity > study.bracket_high;
    CHECK(above >= options.points_above);
    REQUIRE(study.fit.valid);
    CHECK(study.fit.v_bl == Approx(target.v_true).epsilon(1e-5));
    CHECK(study.fit.p == Approx(2.0).epsilon(1e-4));
    REQUIRE(study.recht_ipson.valid);
    CHECK(study.recht_ipson.a == Approx(2.6 / 2.9));
    CHECK(study.recht_ipson.v_bl == Approx(target.v_true).epsilon(1e-8));
  }
}

TEST_CASE("a failed run planted where the bisection lands is reported inside the bracket", "[ballistic]") {
  // With one worker the first bisection point of [150, 450] is 300; every run in (299, 301) fails.
  SyntheticTarget target;
  target.v_true = 301.5;
  target.plant_low = 299.0;
  target.plant_high = 301.0;
  BallisticOptions options;
  options.v_min = 150.0;
  options.v_max = 450.0;
  options.tolerance = 10.0;
  const BallisticStudy study = ballistic_search(options, std::ref(target));
  REQUIRE(target.failed == std::vector<double>{300.0});
  REQUIRE(study.converged);
  CHECK(study.bracket_low < target.v_true);
  CHECK(study.bracket_high > target.v_true);
  bool named = false;
  for (const std::string& n : study.notes) named = named || (n.find("300.00 m/s") != std::string::npos && n.find("failed") != std::string::npos);
  CHECK(named);
}

TEST_CASE("a range without a ballistic limit says so; bad ranges are refused", "[ballistic]") {
  SyntheticTarget target;
  BallisticOptions options;
  options.v_min = 100.0;
  options.v_max = 250.0;  // all below v_true
  BallisticStudy study = ballistic_search(options, std::ref(target));
  CHECK_FALSE(study.bracketed);
  REQUIRE_FALSE(study.notes.empty());
  CHECK_THAT(study.notes[0], Catch::Contains("no run perforated"));
  options.v_min = 350.0;
  options.v_max = 500.0;  // all above
  study = ballistic_search(options, std::ref(target));
  CHECK_FALSE(study.bracketed);
  CHECK_THAT(study.notes[0], Catch::Contains("no run stopped"));
  options.v_min = 300.0;
  options.v_max = 300.0;
  CHECK_THROWS_AS(ballistic_search(options, std::ref(target)), krug::InputError);
  options.v_max = 400.0;
  options.tolerance = 0.0;
  CHECK_THROWS_AS(ballistic_search(options, std::ref(target)), krug::InputError);
}

TEST_CASE("a run's outcome from its summary", "[ballistic]") {
  const std::string perforated = R"({"status": "completed", "stopped_by": "stop rule", "cycles": 100, "wall_seconds": 1.5,
    "penetration": {"final": true, "perforated": true, "residual_velocity": 200.0, "residual_mass": 0.002,
    "initial_mass": 0.0026, "eroded_mass": 0.0001, "target_energy_absorbed": 30.0,
    "plug": {"body": "plate", "mass": 0.0002, "velocity": 210.0}, "whole": {"velocity": 190.0}}})";
  BallisticOutcome o = outcome_from_summary(perforated, 355.0);
  CHECK(o.result == ImpactResult::perforated);
  CHECK(o.residual_velocity == 200.0);
  CHECK(o.whole_velocity == 190.0);
  CHECK(o.plug_mass == 0.0002);
  CHECK(o.cycles == 100);
  const std::string unfinished = R"({"status": "completed", "stopped_by": "end_time",
    "penetration": {"final": false, "perforated": false, "plug": null}})";
  o = outcome_from_summary(unfinished, 200.0);
  CHECK(o.result == ImpactResult::unfinished);
  CHECK_THAT(o.message, Catch::Contains("end_time"));
  o = outcome_from_summary(R"({"status": "failed", "message": "tangled zone", "penetration": {"final": false}})", 200.0);
  CHECK(o.result == ImpactResult::failed);
  CHECK(o.message == "tangled zone");
  CHECK(outcome_from_summary("", 1.0).result == ImpactResult::failed);
  CHECK(outcome_from_summary(R"({"status": "completed"})", 1.0).result == ImpactResult::failed);
}

TEST_CASE("ballistic variants scale the projectile's velocity vector and refuse expressions", "[ballistic]") {
  const std::string scenario = R"({"title": "t", "end_time": 1e-4, "bodies": [{"name": "plate"},
    {"name": "bullet", "initial": {"velocity": [-300, 400]}}], "penetration": {"projectile": "bullet"}})";
  const BallisticProjectile p = ballistic_projectile(scenario, "test");
  CHECK(p.body == 1);
  CHECK(p.speed == Approx(500.0));
  const std::string variant = ballistic_variant(scenario, p, 250.0, true, "test");
  CHECK_THAT(variant, Catch::Contains("-150.0") && Catch::Contains("200.0") && Catch::Contains("0.0002") &&
                          Catch::Contains("ballistic run at 250.00 m/s"));
  CHECK(ballistic_run_name(352.5) == "v0352.50");
  auto error_of = [](const std::string& text) {
    try {
      (void)ballistic_projectile(text, "test");
    } catch (const krug::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_of(R"({"bodies": [{"name": "b"}]})"), Catch::Contains("penetration"));
  CHECK_THAT(error_of(R"({"bodies": [{"name": "b"}], "penetration": {"projectile": "x"}})"), Catch::Contains("not a body"));
  CHECK_THAT(error_of(R"({"bodies": [{"name": "b", "initial": {"velocity": ["-300*z", 0]}}], "penetration": {"projectile": "b"}})"),
             Catch::Contains("expression"));
  CHECK_THAT(error_of(R"({"bodies": [{"name": "b", "initial": {"velocity": [0, 0]}}], "penetration": {"projectile": "b"}})"),
             Catch::Contains("zero"));
  CHECK_THAT(error_of(R"({"bodies": [{"name": "b"}], "penetration": {"projectile": "b"}})"), Catch::Contains("missing"));
}
