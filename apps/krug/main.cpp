// krug: the command-line driver. Parses arguments, loads a scenario, runs it through the library and
// reports progress; it holds no physics.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/io/run.hpp"
#include "krug/io/scenario.hpp"

namespace {

constexpr std::string_view usage = R"(usage:
  krug run SCENARIO.json [--out DIR] [--quiet | --verbose]
      Runs a scenario; writes DIR/summary.json, history.csv, final.vtu, run.pvd, snapshots/.
  krug validate SCENARIO.json
      Checks a scenario without running it.
  krug --help
)";

int fail_usage(const std::string& message) {
  std::fprintf(stderr, "krug: %s\n%s", message.c_str(), std::string(usage).c_str());
  return 2;
}

struct Arguments {
  std::string command;
  std::string scenario;
  std::string out;
  bool quiet = false;
  bool verbose = false;
};

int run(const Arguments& args) {
  const krug::io::Scenario scenario = krug::io::load_scenario(args.scenario);
  krug::io::RunOptions options;
  options.output_directory = args.out;
  const std::filesystem::path directory = args.out.empty() ? scenario.output.directory : args.out;
  double last_report = 0.0;
  const bool interactive = !args.quiet;
  options.on_cycle = [&](const krug::Simulation& s, double elapsed) {
    if (interactive && (elapsed - last_report >= 1.0 || (args.verbose && elapsed - last_report >= 0.1))) {
      last_report = elapsed;
      const double fraction = s.time() / s.controls().end_time;
      const double remaining = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
      std::fprintf(stderr, "\rkrug: t = %.4e s (%5.1f %%)  cycle %ld  dt = %.3e s  energy drift %.2e  %.0f s elapsed, ~%.0f s left   ",
                   s.time(), 100.0 * fraction, s.cycle(), s.last_time_step(),
                   s.ledger().relative_energy_drift(), elapsed, remaining);
      if (args.verbose) std::fputc('\n', stderr);
    }
    return true;
  };
  const krug::io::RunResult result = krug::io::run_scenario(scenario, options);
  if (interactive && last_report > 0.0) std::fputc('\n', stderr);
  if (result.status == krug::io::RunStatus::completed) {
    if (!args.quiet) {
      std::printf("krug: %s completed in %.2f s; results in %s (summary.json, history.csv, run.pvd)\n",
                  scenario.title.empty() ? args.scenario.c_str() : scenario.title.c_str(), result.wall_seconds,
                  directory.string().c_str());
    }
    return 0;
  }
  std::fprintf(stderr, "krug: run failed: %s\nkrug: the state at the failure is in %s (final.vtu, summary.json)\n",
               result.message.c_str(), directory.string().c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> words(argv + 1, argv + argc);
  if (words.empty() || words[0] == "--help" || words[0] == "-h") {
    std::fputs(std::string(usage).c_str(), words.empty() ? stderr : stdout);
    return words.empty() ? 2 : 0;
  }
  Arguments args;
  args.command = words[0];
  if (args.command != "run" && args.command != "validate") return fail_usage("unknown command \"" + args.command + "\"");
  for (std::size_t i = 1; i < words.size(); ++i) {
    const std::string& w = words[i];
    if (w == "--out") {
      if (i + 1 >= words.size()) return fail_usage("--out needs a directory");
      args.out = words[++i];
    } else if (w == "--quiet") {
      args.quiet = true;
    } else if (w == "--verbose") {
      args.verbose = true;
    } else if (!w.empty() && w[0] == '-') {
      return fail_usage("unknown option \"" + w + "\"");
    } else if (args.scenario.empty()) {
      args.scenario = w;
    } else {
      return fail_usage("more than one scenario given");
    }
  }
  if (args.scenario.empty()) return fail_usage("no scenario file given");
  try {
    if (args.command == "validate") {
      const krug::io::Scenario scenario = krug::io::load_scenario(args.scenario);
      std::printf("krug: %s is valid (%zu bodies, %d zones)\n", args.scenario.c_str(), scenario.setup.bodies.size(),
                  scenario.setup.mesh.zones.size());
      return 0;
    }
    return run(args);
  } catch (const krug::InputError& error) {
    std::fprintf(stderr, "krug: %s\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "krug: unexpected error: %s\n", error.what());
    return 3;
  }
}
