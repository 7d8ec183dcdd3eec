#include "ballistic_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <optional>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/output/text_file.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/output/ballistic_files.hpp"
#include "krug/run/ballistic.hpp"
#include "plots.hpp"
#include "sweep_runner.hpp"

namespace krug::app {

namespace {

double speed_in(const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v <= 0.0) {
    throw InputError(fmt::format("--velocity: {} \"{}\" is not a positive number (m/s)", what, text));
  }
  return v;
}

// Thrown by the evaluator to end the study at an interruption (ballistic_search lets it through).
struct Interrupted {};

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read", file.string()));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

int run_ballistic(const BallisticArguments& arguments, const Workers& workers, const std::atomic<bool>& interrupted,
                  const volatile std::sig_atomic_t& signal_number) {
  // The range.
  const auto comma = arguments.velocity.find(',');
  if (comma == std::string::npos) throw InputError("--velocity: expected MIN,MAX (m/s), e.g. --velocity 150,450");
  run::BallisticOptions options;
  options.v_min = speed_in(arguments.velocity.substr(0, comma), "MIN");
  options.v_max = speed_in(arguments.velocity.substr(comma + 1), "MAX");
  if (options.v_min >= options.v_max) {
    throw InputError(fmt::format("--velocity: MIN ({}) must be below MAX ({})", options.v_min, options.v_max));
  }
  options.tolerance = arguments.tolerance;
  options.points_above = arguments.points_above;
  options.batch = arguments.jobs > 0 ? arguments.jobs : std::max(1, workers.slots);

  // The scenario: a penetration scenario whose projectile has a velocity vector; the variants at both
  // ends are checked by the reader before anything runs.
  const std::filesystem::path scenario(arguments.scenario);
  const std::string text = read_file(scenario);
  (void)scenario::parse_scenario(text, scenario.string());
  const run::BallisticProjectile projectile = run::ballistic_projectile(text, scenario.string());
  for (double v : {options.v_min, options.v_max}) {
    try {
      (void)scenario::parse_scenario(run::ballistic_variant(text, projectile, v, arguments.scale_end_time, scenario.string(), arguments.end_time_factor),
                               scenario.string());
    } catch (const InputError& e) {
      throw InputError(fmt::format("the variant at {} m/s is not a valid scenario: {}", v, e.what()));
    }
  }
  const std::filesystem::path out = arguments.out.empty()
                                        ? std::filesystem::path("out") / (scenario.stem().string() + "-ballistic")
                                        : std::filesystem::path(arguments.out);
  std::error_code error;
  std::filesystem::create_directories(out / "runs", error);
  if (error) throw InputError(fmt::format("{}: cannot create: {}", (out / "runs").string(), error.message()));
  if (!arguments.quiet) {
    std::fprintf(stderr,
                 "krug: ballistic limit of %s (projectile %s, %.1f m/s as given) between %.1f and %.1f m/s, to %.1f m/s, "
                 "%d runs per round (%s), into %s\n",
                 scenario.string().c_str(), projectile.name.c_str(), projectile.speed, options.v_min, options.v_max,
                 options.tolerance, options.batch, workers.description.c_str(), out.string().c_str());
  }

  // One batch of speeds: each a krug run child in DIR/runs/v<speed>/, unless that folder already holds
  // a finished run of the same variant (an earlier, interrupted study into this folder).
  auto evaluate = [&](const std::vector<double>& speeds) {
    std::vector<RunJob> jobs;
    std::vector<std::size_t> speed_of;  // job index -> speed index
    std::vector<int> codes(speeds.size(), -1);
    std::vector<bool> kept(speeds.size(), false);
    std::vector<std::filesystem::path> directories;
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      const double v = speeds[i];
      const std::filesystem::path directory = out / "runs" / run::ballistic_run_name(v);
      directories.push_back(directory);
      const std::filesystem::path file = directory / "scenario.json";
      const std::string variant = run::ballistic_variant(text, projectile, v, arguments.scale_end_time, scenario.string(), arguments.end_time_factor);
      if (const std::optional<int> finished = finished_run(directory, scenario::parse_scenario(variant, file.string()).resolved_json)) {
        codes[i] = *finished;
        kept[i] = true;
        continue;
      }
      std::filesystem::remove_all(directory, error);
      std::filesystem::create_directories(directory, error);
      output::write_text_atomically(file, variant);
      std::vector<std::string> extra;
      if (!arguments.pictures) extra = {"--no-pictures", "--no-plots"};
      jobs.push_back({file, directory, extra});
      speed_of.push_back(i);
    }
    std::vector<run::BallisticOutcome> outcomes(speeds.size());
    const std::vector<int> run_codes = workers.run(jobs, {});
    for (std::size_t k = 0; k < run_codes.size(); ++k) codes[speed_of[k]] = run_codes[k];
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      const std::filesystem::path summary = directories[i] / "summary.json";
      if (std::filesystem::exists(summary)) {
        outcomes[i] = run::outcome_from_summary(read_file(summary), speeds[i]);
      } else {
        outcomes[i].velocity = speeds[i];
        outcomes[i].result = run::ImpactResult::failed;
        outcomes[i].status = "not run";
        outcomes[i].message = codes[i] < 0 ? "not started (interrupted)"
                                           : fmt::format("no summary.json (exit code {}; see log.txt)", codes[i]);
      }
      if (codes[i] >= 128 && outcomes[i].message.empty()) outcomes[i].message = "interrupted";
      outcomes[i].directory = std::filesystem::relative(directories[i], out, error).string();
      if (!arguments.quiet) {
        const run::BallisticOutcome& o = outcomes[i];
        std::string detail;
        if (o.result == run::ImpactResult::perforated) detail = fmt::format(": residual velocity {:.1f} m/s", o.residual_velocity);
        if (o.result == run::ImpactResult::failed || o.result == run::ImpactResult::unfinished) detail = ": " + o.message;
        std::fprintf(stderr, "krug: %8.2f m/s %s%s (%.1f s%s)\n", speeds[i], run::to_string(o.result), detail.c_str(),
                     o.wall_seconds, kept[i] ? ", kept from an earlier study" : "");
      }
    }
    if (interrupted.load()) throw Interrupted();
    return outcomes;
  };
  run::BallisticStudy latest;
  auto on_round = [&](const run::BallisticStudy& study) {
    latest = study;
    output::write_ballistic_results(out, study, scenario.string());  // the tables so far, round by round
  };
  run::BallisticStudy study;
  try {
    study = run::ballistic_search(options, evaluate, on_round);
  } catch (const Interrupted&) {
    latest.notes.push_back("interrupted: the study is incomplete");
    output::write_ballistic_results(out, latest, scenario.string());
    std::fprintf(stderr, "krug: interrupted after %zu runs; the tables so far are in %s\n", latest.runs.size(),
                 out.string().c_str());
    return 128 + (signal_number > 0 ? static_cast<int>(signal_number) : 2);
  }
  output::write_ballistic_results(out, study, scenario.string());
  const std::string note = make_ballistic_plot(out);
  if (!note.empty() && !arguments.quiet) std::fprintf(stderr, "krug: %s\n", note.c_str());
  for (const std::string& line : run::ballistic_summary_lines(study)) std::printf("krug: %s\n", line.c_str());
  std::printf("krug: results in %s (ballistic.csv, ballistic.json%s, runs/)\n", out.string().c_str(),
              note.empty() ? ", ballistic.png" : "");
  return study.converged ? 0 : 1;
}

}  // namespace krug::app
