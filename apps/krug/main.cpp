// krug: the command-line driver. Parses arguments, loads a scenario, runs it through the library and
// reports progress; draws pictures (Cairo) and has the history plotted (Python); runs sweeps as child
// processes. It holds no physics.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/material/library.hpp"
#include "krug/output/run_files.hpp"
#include "krug/scenario/scenario.hpp"
#include "pictures.hpp"
#include "plots.hpp"
#include "ballistic_runner.hpp"
#include "mpi_workers.hpp"
#include "sweep_runner.hpp"

namespace {

constexpr std::string_view usage = R"(usage:
  krug run SCENARIO.json [--out DIR] [--threads N] [--quiet | --verbose] [--no-pictures] [--no-plots]
      Runs a scenario; writes DIR/summary.json, history.csv, final.vtu, run.pvd, snapshots/,
      pictures/ (PNG, with Cairo) and plots/ (PNG, with Python and matplotlib). --threads sets
      controls.threads (the Lagrangian step's zone and node loops; results are the same bits).
  krug run --restart DIR/checkpoint.bin [--out DIR] [--threads N] [--quiet | --verbose] [--no-pictures] [--no-plots]
      Continues a run from a checkpoint (output.checkpoint_interval, or written on Ctrl-C/SIGTERM),
      with the scenario.resolved.json next to it; outputs go to DIR (default: the checkpoint's).
  krug validate SCENARIO.json [--quiet]
      Checks a scenario without running it, and describes the set-up the run would start from.
  krug sweep SCENARIO.json --set PATH=V1,V2,... [--set ...] [--jobs N] [--out DIR] [--mpi] [--quiet]
      Runs every combination of the values (PATH like materials.steel.density or
      bodies[0].initial.velocity[0]) in parallel processes into DIR/<variant>/ and writes
      DIR/sweep.csv (default DIR: out/<scenario>-sweep). Variants that an earlier sweep into DIR
      finished (a whole summary.json of the same scenario) are kept, not run again.
  krug materials [NAME]
      Lists the material library (name, density, equation of state, strength, source); with a NAME,
      every constant of that set with its source. A scenario names a set as "materials": {"plate":
      "al6061-t6"} or {"plate": {"base": "al6061-t6", ...overrides...}} (docs/materials.md).
  krug ballistic SCENARIO.json --velocity MIN,MAX [--tolerance DV] [--points-above N] [--jobs N]
                 [--out DIR] [--pictures] [--keep-end-time] [--end-time-factor F] [--mpi] [--quiet]
      Ballistic limit of a scenario with a "penetration" block: the projectile's initial velocity is
      scaled (direction kept); a bracket of MIN and MAX is narrowed by N-section (N = --jobs runs at a
      time) until no wider than DV (default 10 m/s), then --points-above (default 3) perforating runs
      above it feed a Lambert-Jonas fit. Each speed runs as krug run in DIR/runs/v<speed>/; writes
      DIR/ballistic.csv, ballistic.json, ballistic.png (default DIR: out/<scenario>-ballistic).
      Below the scenario's speed the end time is stretched by the speed ratio unless --keep-end-time;
      --end-time-factor F multiplies every run's end time (near the limit a projectile clears slowly).
      Speeds an earlier study into DIR finished are kept, not run again.
  mpirun -np N krug sweep|ballistic ...
      (a krug built with MPI) The runs go to the N ranks, one at a time each, rank 0 included; DIR
      must be on a file system every rank sees. Ballistic rounds have N runs unless --jobs says
      otherwise; a sweep ignores --jobs. --mpi uses MPI even when not started by mpirun.
  krug --help | --version

Exit codes: 0 completed, 1 run failed, 2 bad input or usage, 3 unexpected error,
128 + signal when interrupted (130 for Ctrl-C; a checkpoint is written first).
)";

// The whole word as a number from 1 to `most`; 0 when it is missing, not a number or out of range.
int count_in(const std::string* word, long most) {
  if (!word) return 0;
  char* end = nullptr;
  const long n = std::strtol(word->c_str(), &end, 10);
  return *end == '\0' && n >= 1 && n <= most ? static_cast<int>(n) : 0;
}

// `krug materials [NAME]`: the library, or one set with every constant and its source.
int list_materials(const std::vector<std::string>& names) {
  namespace library = krug::library;
  if (names.size() > 1) {
    std::fprintf(stderr, "krug: materials takes at most one NAME\n");
    return 2;
  }
  if (names.empty()) {
    std::printf("%-16s %8s  %-14s %-18s %s\n", "name", "kg/m^3", "eos", "strength", "source");
    for (const library::MaterialSet& set : library::material_sets) {
      const library::Constant* density = library::find_constant(set, "", "density");
      std::printf("%-16.*s %8.0f  %-14.*s %-18.*s %.*s\n", static_cast<int>(set.name.size()), set.name.data(),
                  density ? density->value : 0.0, static_cast<int>(set.eos_model.size()), set.eos_model.data(),
                  static_cast<int>(set.strength_model.size()), set.strength_model.data(),
                  static_cast<int>(set.source.size()), set.source.data());
    }
    std::printf("krug materials NAME prints one set with every constant and its source (docs/materials.md).\n");
    return 0;
  }
  const library::MaterialSet* set = library::find_material_set(names.front());
  if (!set) {
    std::string list;
    for (const library::MaterialSet& s : library::material_sets) list += fmt::format("{}{}", list.empty() ? "" : ", ", s.name);
    std::fprintf(stderr, "krug: unknown material \"%s\"; the library has: %s\n", names.front().c_str(), list.c_str());
    return 2;
  }
  std::printf("%s: %s\n", std::string(set->name).c_str(), std::string(set->title).c_str());
  std::printf("source: %s\n", std::string(set->source).c_str());
  std::printf("notes: %s\n", std::string(set->notes).c_str());
  std::printf("eos.model = %s, strength.model = %s\n", std::string(set->eos_model).c_str(),
              std::string(set->strength_model).c_str());
  for (const library::Constant& c : set->constants) {
    const std::string key = c.block.empty() ? std::string(c.key) : fmt::format("{}.{}", c.block, c.key);
    std::printf("  %-38s %-12.6g %-9s %s\n", key.c_str(), c.value, std::string(c.unit).c_str(),
                std::string(c.source).c_str());
  }
  if (library::find_constant(*set, "damage", "d1")) {
    std::printf("The damage constants (Johnson-Cook D1..D5) are those the Johnson-Cook failure law takes: \"fracture\": {\"model\": \"johnson_cook\"} in a material based on this set.\n");
  }
  return 0;
}

int fail_usage(const std::string& message) {
  std::fprintf(stderr, "krug: %s\n%s", message.c_str(), std::string(usage).c_str());
  return 2;
}

// Ctrl-C and SIGTERM ask the run to stop at the end of the cycle (it writes a checkpoint); a second
// one stops at once.
std::atomic<bool> interrupted{false};
volatile std::sig_atomic_t signal_number = 0;

extern "C" void on_signal(int s) {
  if (interrupted.load()) _exit(128 + s);
  signal_number = s;
  interrupted.store(true);
}

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a waiting sweep wakes up
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

struct Arguments {
  std::string command;
  std::string scenario;
  std::string restart;
  std::string out;
  bool quiet = false;
  bool verbose = false;
  bool pictures = true;
  bool plots = true;
  std::vector<std::string> sets;
  int jobs = 0;
  std::string velocity;           // ballistic: MIN,MAX
  double tolerance = 10.0;        // ballistic, m/s
  int points_above = 3;           // ballistic
  bool keep_end_time = false;     // ballistic
  double end_time_factor = 1.0;   // ballistic
  bool run_pictures = false;      // ballistic: the runs' pictures and plots
  bool mpi = false;               // sweep, ballistic: on MPI ranks even when not started by a launcher
  int threads = 0;  // 0: the scenario's controls.threads
};

int run(const Arguments& args) {
  const bool restarting = !args.restart.empty();
  const std::filesystem::path checkpoint(args.restart);
  krug::scenario::Scenario scenario =
      restarting ? krug::scenario::load_scenario(checkpoint.parent_path() / "scenario.resolved.json")
                 : krug::scenario::load_scenario(args.scenario);
  if (args.threads > 0) scenario.setup.controls.threads = args.threads;  // the results do not depend on it
  const std::filesystem::path directory =
      !args.out.empty() ? std::filesystem::path(args.out)
      : restarting     ? (checkpoint.parent_path().empty() ? std::filesystem::path(".") : checkpoint.parent_path())
                       : std::filesystem::path(scenario.output.directory);
  const std::string title = !scenario.title.empty() ? scenario.title
                            : restarting            ? checkpoint.parent_path().filename().string()
                                                    : std::filesystem::path(args.scenario).stem().string();
  krug::output::RunOptions options;
  options.output_directory = directory;
  options.interrupt = &interrupted;

  const bool want_pictures = args.pictures && scenario.output.pictures.enabled;
  if (want_pictures && krug::app::pictures_available()) {
    // With every_snapshot and no window of its own, the first picture fixes the view for the run.
    auto settings = std::make_shared<krug::scenario::PictureSettings>(scenario.output.pictures);
    options.picture = [settings, title](const krug::Simulation& s, const std::filesystem::path& dir,
                                        const std::string& name) {
      if (settings->every_snapshot && !settings->window) settings->window = krug::app::default_fixed_window(s);
      (void)krug::app::write_picture(s, *settings, title, dir, name);
    };
  } else if (want_pictures && !args.quiet) {
    std::fprintf(stderr, "krug: no pictures: this krug was built without Cairo (libcairo2-dev)\n");
  }

  double last_report = 0.0;
  const bool interactive = !args.quiet;
  bool progress_shown = false;  // a progress line (ended by \r) is on the terminal
  auto print_line = [&](const std::string& line) {
    std::fprintf(stderr, "%skrug: %s\n", progress_shown && !args.verbose ? "\n" : "", line.c_str());
    progress_shown = false;
  };
  if (interactive) {
    options.on_start = [&](const krug::Simulation& s) {
      for (const std::string& line : krug::run::start_up_lines(scenario, s)) print_line(line);
    };
    options.on_event = [&](const krug::run::RunEvent& event) {
      print_line(fmt::format("t = {:.4e} s, cycle {}: {}", event.time, event.cycle, event.what));
    };
  }
  options.on_cycle = [&](const krug::Simulation& s, double elapsed) {
    if (interactive && (elapsed - last_report >= 1.0 || (args.verbose && elapsed - last_report >= 0.1))) {
      last_report = elapsed;
      const double fraction = s.time() / s.controls().end_time;
      const double remaining = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
      // dt with what set it: a zone (by body and zone), or the growth and other limits.
      const std::string controller = s.time_step_limit() == krug::TimeStepLimit::zone
                                         ? krug::run::describe_zone(s, s.controlling_zone())
                                     : s.time_step_limit() == krug::TimeStepLimit::growth          ? "growth limit"
                                     : s.time_step_limit() == krug::TimeStepLimit::particle_travel ? "particle travel"
                                                                                                    : "step limit";
      if (scenario.stop) {
        // The stop rule ends the run when its answer is final: the end time is only a bound, and a
        // percentage or time left against it would mislead.
        std::fprintf(stderr, "\rkrug: t = %.4e s  cycle %ld  dt = %.3e s (%s)  energy drift %.2e  %.0f s elapsed, until the stop rule   ",
                     s.time(), s.cycle(), s.last_time_step(), controller.c_str(), s.ledger().relative_energy_drift(), elapsed);
      } else {
        std::fprintf(stderr, "\rkrug: t = %.4e s (%5.1f %%)  cycle %ld  dt = %.3e s (%s)  energy drift %.2e  %.0f s elapsed, ~%.0f s left   ",
                     s.time(), 100.0 * fraction, s.cycle(), s.last_time_step(), controller.c_str(),
                     s.ledger().relative_energy_drift(), elapsed, remaining);
      }
      progress_shown = true;
      if (args.verbose) std::fputc('\n', stderr);
    }
    return true;
  };
  install_signal_handlers();
  const krug::run::RunResult result = restarting ? krug::output::restart_scenario(scenario, checkpoint, options)
                                                   : krug::output::run_scenario(scenario, options);
  if (interactive && progress_shown && !args.verbose) std::fputc('\n', stderr);
  for (const std::string& warning : result.warnings) std::fprintf(stderr, "krug: warning: %s\n", warning.c_str());

  if (args.plots && scenario.output.plots) {
    const std::string note = krug::app::make_plots(directory);
    if (!note.empty() && !args.quiet) std::fprintf(stderr, "krug: %s\n", note.c_str());
  }

  if (result.stopped_by == "interrupted") {
    std::fprintf(stderr, "krug: interrupted; checkpoint %s\nkrug: continue with: krug run --restart %s\n",
                 result.checkpoint.string().c_str(), result.checkpoint.string().c_str());
    return 128 + (signal_number > 0 ? static_cast<int>(signal_number) : SIGINT);
  }
  if (result.status == krug::run::RunStatus::completed) {
    if (!args.quiet) {
      const std::string how = result.stopped_by == "stop rule" ? " (ended by the stop rule)" : "";
      std::printf("krug: %s completed%s in %.2f s; results in %s (summary.json, history.csv, run.pvd)\n", title.c_str(),
                  how.c_str(), result.wall_seconds, directory.string().c_str());
      for (const std::string& line : krug::output::penetration_lines(result)) std::printf("krug: %s\n", line.c_str());
    }
    return 0;
  }
  std::fprintf(stderr, "krug: run failed: %s\nkrug: the state at the failure is in %s (final.vtu, summary.json)\n",
               result.message.c_str(), directory.string().c_str());
  return 1;
}

// Who runs a study's runs: the MPI ranks, or child processes here (--jobs, default one per hardware thread).
krug::app::Workers workers(const Arguments& args, krug::app::MpiStudy* mpi) {
  if (mpi) return mpi->workers(interrupted, signal_number);
  const int jobs = args.jobs > 0 ? args.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return krug::app::local_workers(jobs, interrupted, signal_number);
}

}  // namespace

// The x86-64 level this binary was compiled for (CMake's KRUG_ARCH), and whether this processor runs it.
#if defined(__AVX512F__) && defined(__AVX512BW__) && defined(__AVX512VL__) && defined(__AVX512DQ__)
#define KRUG_INSTRUCTION_SET "x86-64-v4"
#elif defined(__AVX2__) && defined(__FMA__)
#define KRUG_INSTRUCTION_SET "x86-64-v3"
#endif
#ifdef KRUG_INSTRUCTION_SET
constexpr const char* instruction_set = KRUG_INSTRUCTION_SET;
#else
constexpr const char* instruction_set = nullptr;
#endif

// Checked feature by feature (the level names are known to __builtin_cpu_supports only from GCC 12).
bool processor_runs_instruction_set() {
#if defined(KRUG_INSTRUCTION_SET) && defined(__x86_64__) && defined(__GNUC__)
  __builtin_cpu_init();
  bool runs = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
#if defined(__AVX512F__)
  runs = runs && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512cd");
#endif
  return runs;
#else
  return true;
#endif
}

int main(int argc, char** argv) {
  if (!processor_runs_instruction_set()) {
    std::fprintf(stderr,
                 "krug: this build uses %s instructions, which this processor does not have; rebuild with "
                 "cmake -DKRUG_ARCH=portable\n",
                 instruction_set);
    return 3;
  }
  std::vector<std::string> words(argv + 1, argv + argc);
  if (words.empty() || words[0] == "--help" || words[0] == "-h") {
    std::fputs(std::string(usage).c_str(), words.empty() ? stderr : stdout);
    return words.empty() ? 2 : 0;
  }
  if (words[0] == "--version") {
    std::printf("krug %s (instruction set: %s)\n", KRUG_VERSION, instruction_set != nullptr ? instruction_set : "portable");
    return 0;
  }
  if (words[0] == "materials") return list_materials(std::vector<std::string>(words.begin() + 1, words.end()));
  Arguments args;
  args.command = words[0];
  if (args.command != "run" && args.command != "validate" && args.command != "sweep" && args.command != "ballistic") {
    return fail_usage("unknown command \"" + args.command + "\"");
  }
  for (std::size_t i = 1; i < words.size(); ++i) {
    const std::string& w = words[i];
    auto value = [&]() -> const std::string* { return i + 1 < words.size() ? &words[++i] : nullptr; };
    if (w == "--out") {
      const std::string* v = value();
      if (!v) return fail_usage("--out needs a directory");
      args.out = *v;
    } else if (w == "--restart" && args.command == "run") {
      const std::string* v = value();
      if (!v) return fail_usage("--restart needs a checkpoint file (DIR/checkpoint.bin)");
      args.restart = *v;
    } else if (w == "--set" && args.command == "sweep") {
      const std::string* v = value();
      if (!v) return fail_usage("--set needs PATH=VALUE1,VALUE2,...");
      args.sets.push_back(*v);
    } else if (w == "--velocity" && args.command == "ballistic") {
      const std::string* v = value();
      if (!v) return fail_usage("--velocity needs MIN,MAX (m/s)");
      args.velocity = *v;
    } else if (w == "--tolerance" && args.command == "ballistic") {
      const std::string* v = value();
      char* end = nullptr;
      const double t = v ? std::strtod(v->c_str(), &end) : 0.0;
      if (!v || v->empty() || *end != '\0' || !(t > 0.0) || !std::isfinite(t)) {
        return fail_usage("--tolerance needs a positive speed (m/s)");
      }
      args.tolerance = t;
    } else if (w == "--points-above" && args.command == "ballistic") {
      const std::string* v = value();
      if (v && *v == "0") {
        args.points_above = 0;
      } else {
        args.points_above = count_in(v, 100);
        if (args.points_above == 0) return fail_usage("--points-above needs a number from 0 to 100");
      }
    } else if (w == "--keep-end-time" && args.command == "ballistic") {
      args.keep_end_time = true;
    } else if (w == "--end-time-factor" && args.command == "ballistic") {
      const std::string* v = value();
      char* end = nullptr;
      const double f = v ? std::strtod(v->c_str(), &end) : 0.0;
      if (!v || end == v->c_str() || *end != '\0' || !(f > 0.0) || !(f <= 100.0)) {
        return fail_usage("--end-time-factor needs a number in (0, 100]");
      }
      args.end_time_factor = f;
    } else if (w == "--pictures" && args.command == "ballistic") {
      args.run_pictures = true;
    } else if (w == "--mpi" && (args.command == "sweep" || args.command == "ballistic")) {
      args.mpi = true;
    } else if (w == "--jobs" && (args.command == "sweep" || args.command == "ballistic")) {
      args.jobs = count_in(value(), 1024);
      if (args.jobs == 0) return fail_usage("--jobs needs a number from 1 to 1024");
    } else if (w == "--threads" && args.command == "run") {
      args.threads = count_in(value(), 256);
      if (args.threads == 0) return fail_usage("--threads needs a number from 1 to 256");
    } else if (w == "--quiet") {
      args.quiet = true;
    } else if (w == "--verbose" && args.command == "run") {
      args.verbose = true;
    } else if (w == "--no-pictures" && args.command == "run") {
      args.pictures = false;
    } else if (w == "--no-plots" && args.command == "run") {
      args.plots = false;
    } else if (w == "--help" || w == "-h") {
      std::fputs(std::string(usage).c_str(), stdout);
      return 0;
    } else if (!w.empty() && w[0] == '-') {
      return fail_usage("unknown option \"" + w + "\" for krug " + args.command);
    } else if (args.scenario.empty()) {
      args.scenario = w;
    } else {
      return fail_usage("more than one scenario given");
    }
  }
  if (args.quiet && args.verbose) return fail_usage("--quiet and --verbose exclude each other");
  if (!args.restart.empty() && !args.scenario.empty()) {
    return fail_usage("--restart continues the scenario stored next to the checkpoint: give no scenario file");
  }
  if (args.scenario.empty() && args.restart.empty()) return fail_usage("no scenario file given");
  if (args.command == "sweep" && args.sets.empty()) return fail_usage("krug sweep needs at least one --set");
  if (args.command == "ballistic" && args.velocity.empty()) return fail_usage("krug ballistic needs --velocity MIN,MAX");
  // The study commands on MPI ranks: with an MPI build when an MPI launcher started this process (or
  // --mpi); a build without MPI refuses to run N copies of the whole study.
  std::unique_ptr<krug::app::MpiStudy> mpi;
  if (args.command == "sweep" || args.command == "ballistic") {
    const int ranks = krug::app::launched_ranks();
    if (!krug::app::mpi_built() && (args.mpi || ranks > 1)) {
      const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
      if (rank == nullptr) rank = std::getenv("PMI_RANK");
      if (rank == nullptr || std::string(rank) == "0") {
        if (ranks > 1) {
          std::fprintf(stderr, "krug: started as one of %d MPI ranks, but %s\n", ranks, krug::app::mpi_build_hint().c_str());
        } else {
          std::fprintf(stderr, "krug: --mpi: %s\n", krug::app::mpi_build_hint().c_str());
        }
      }
      return 2;
    }
    if (!krug::app::mpi_built() && ranks < 0) {
      std::fprintf(stderr, "krug: warning: started by an MPI launcher, but %s\n", krug::app::mpi_build_hint().c_str());
    }
    if (krug::app::mpi_built() && (args.mpi || ranks != 0)) {
      try {
        mpi = std::make_unique<krug::app::MpiStudy>();
      } catch (const std::exception& error) {
        std::fprintf(stderr, "krug: cannot start MPI: %s\n", error.what());
        return 3;
      }
      if (mpi->rank() != 0) {  // a worker: runs what rank 0 hands out, prints nothing of the study
        install_signal_handlers();
        mpi->serve(interrupted, signal_number);
        return 0;
      }
      if (args.command == "sweep" && args.jobs > 0 && !args.quiet) {
        std::fprintf(stderr, "krug: --jobs %d ignored: on MPI every rank runs one variant at a time (mpirun -np sets how many)\n",
                     args.jobs);
      }
    }
  }
  try {
    if (args.command == "validate") {
      const krug::scenario::Scenario scenario = krug::scenario::load_scenario(args.scenario);
      krug::run::validate_scenario(scenario);
      std::printf("krug: %s is valid (%zu bodies, %d zones)\n", args.scenario.c_str(), scenario.setup.bodies.size(),
                  scenario.setup.mesh.zones.size());
      if (!args.quiet) {  // what the run would start from, as `krug run` echoes it
        const krug::Simulation simulation(scenario.setup);
        for (const std::string& line : krug::run::start_up_lines(scenario, simulation)) {
          std::printf("krug: %s\n", line.c_str());
        }
      }
      return 0;
    }
    if (args.command == "sweep") {
      install_signal_handlers();
      krug::app::SweepArguments sweep;
      sweep.scenario = args.scenario;
      sweep.sets = args.sets;
      sweep.out = args.out;
      sweep.quiet = args.quiet;
      return krug::app::run_sweep(sweep, workers(args, mpi.get()), interrupted, signal_number);
    }
    if (args.command == "ballistic") {
      install_signal_handlers();
      krug::app::BallisticArguments ballistic;
      ballistic.scenario = args.scenario;
      ballistic.velocity = args.velocity;
      ballistic.tolerance = args.tolerance;
      ballistic.points_above = args.points_above;
      ballistic.jobs = args.jobs;
      ballistic.out = args.out;
      ballistic.quiet = args.quiet;
      ballistic.pictures = args.run_pictures;
      ballistic.scale_end_time = !args.keep_end_time;
      ballistic.end_time_factor = args.end_time_factor;
      return krug::app::run_ballistic(ballistic, workers(args, mpi.get()), interrupted, signal_number);
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
