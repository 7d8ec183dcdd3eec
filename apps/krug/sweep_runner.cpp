#include "sweep_runner.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "krug/scenario/scenario.hpp"
#include "krug/output/sweep_files.hpp"
#include "krug/scenario/edit.hpp"

namespace krug::app {

int run_sweep(const SweepArguments& arguments, const Workers& workers, const std::atomic<bool>& interrupted,
              const volatile std::sig_atomic_t& signal_number) {
  std::vector<scenario::SweepParameter> parameters;
  for (const std::string& set : arguments.sets) parameters.push_back(scenario::parse_sweep_set(set));
  const std::filesystem::path scenario(arguments.scenario);
  const std::filesystem::path out =
      arguments.out.empty() ? std::filesystem::path("out") / (scenario.stem().string() + "-sweep")
                            : std::filesystem::path(arguments.out);
  const std::vector<scenario::SweepVariant> variants = output::prepare_sweep(scenario, parameters, out);

  // Resuming: a variant whose folder holds a finished run of the same scenario keeps it.
  std::vector<int> codes(variants.size(), -1);
  std::vector<RunJob> list;
  std::vector<std::size_t> variant_of;  // list index -> variant index
  std::size_t kept = 0;
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const scenario::SweepVariant& v = variants[i];
    const std::optional<int> finished = finished_run(v.directory, scenario::load_scenario(v.scenario).resolved_json);
    if (finished) {
      codes[i] = *finished;
      ++kept;
    } else {
      std::error_code error;
      std::filesystem::remove(v.directory / "summary.json", error);  // a stale one must not stand for this run
      list.push_back({v.scenario, v.directory, {}});
      variant_of.push_back(i);
    }
  }
  if (!arguments.quiet) {
    std::fprintf(stderr, "krug: sweep of %zu variants, %s, into %s\n", variants.size(), workers.description.c_str(),
                 out.string().c_str());
    if (kept > 0) {
      std::fprintf(stderr, "krug: %zu of them finished in an earlier sweep into this folder (kept); %zu to run\n", kept,
                   list.size());
    }
  }
  std::size_t done = kept;
  const std::vector<int> run_codes = workers.run(list, [&](std::size_t index, int code, const std::string& where) {
    ++done;
    if (!arguments.quiet) {
      std::fprintf(stderr, "krug: %zu/%zu %s %s%s%s%s\n", done, variants.size(), variants[variant_of[index]].name.c_str(),
                   code == 0 ? "completed" : code == 1 ? "failed" : code >= 128 ? "interrupted" : "did not run (see log.txt)",
                   where.empty() ? "" : " (", where.c_str(), where.empty() ? "" : ")");
    }
  });
  for (std::size_t k = 0; k < run_codes.size(); ++k) codes[variant_of[k]] = run_codes[k];
  output::write_sweep_table(out, parameters, variants);
  const auto completed = static_cast<std::size_t>(std::count(codes.begin(), codes.end(), 0));
  const auto failed = static_cast<std::size_t>(std::count(codes.begin(), codes.end(), 1));
  const auto started = static_cast<std::size_t>(std::count_if(run_codes.begin(), run_codes.end(), [](int c) { return c >= 0; }));
  std::printf("krug: sweep of %zu variants: %zu completed, %zu failed, %zu did not finish (%zu run now, %zu kept from "
              "an earlier sweep); table in %s\n",
              variants.size(), completed, failed, variants.size() - completed - failed, started, kept,
              (out / "sweep.csv").string().c_str());
  if (interrupted.load()) return 128 + static_cast<int>(signal_number);
  return completed == variants.size() ? 0 : 1;
}

}  // namespace krug::app
