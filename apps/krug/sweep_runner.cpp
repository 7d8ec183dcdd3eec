#include "sweep_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <map>
#include <thread>

#include "krug/io/sweep.hpp"
#include "process.hpp"

namespace krug::app {

std::vector<int> run_jobs(const std::vector<RunJob>& list, int jobs, const std::atomic<bool>& interrupted,
                          const volatile std::sig_atomic_t& signal_number,
                          const std::function<void(std::size_t, int)>& on_done) {
  const std::string self = self_executable().string();
  std::map<pid_t, std::size_t> running;
  std::vector<int> codes(list.size(), -1);
  std::size_t next = 0;
  bool forwarded = false;
  while (next < list.size() || !running.empty()) {
    while (!interrupted.load() && next < list.size() && running.size() < static_cast<std::size_t>(std::max(1, jobs))) {
      const RunJob& job = list[next];
      std::vector<std::string> arguments = {self, "run", job.scenario.string(), "--out", job.directory.string(), "--quiet"};
      arguments.insert(arguments.end(), job.extra.begin(), job.extra.end());
      const pid_t pid = spawn(arguments, job.directory / "log.txt", true);
      if (pid < 0) {
        codes[next] = 127;
        if (on_done) on_done(next, 127);
      } else {
        running[pid] = next;
      }
      ++next;
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno != EINTR) break;
      if (interrupted.load() && !forwarded) {  // the children lead their own process groups: pass it on once
        for (const auto& [child, _] : running) kill(child, signal_number > 0 ? static_cast<int>(signal_number) : SIGTERM);
        forwarded = true;
      }
      continue;
    }
    const auto found = running.find(pid);
    if (found == running.end()) continue;
    const std::size_t index = found->second;
    running.erase(found);
    codes[index] = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (on_done) on_done(index, codes[index]);
  }
  return codes;
}

int run_sweep(const SweepArguments& arguments, const std::atomic<bool>& interrupted,
              const volatile std::sig_atomic_t& signal_number) {
  std::vector<io::SweepParameter> parameters;
  for (const std::string& set : arguments.sets) parameters.push_back(io::parse_sweep_set(set));
  const std::filesystem::path scenario(arguments.scenario);
  const std::filesystem::path out =
      arguments.out.empty() ? std::filesystem::path("out") / (scenario.stem().string() + "-sweep")
                            : std::filesystem::path(arguments.out);
  const std::vector<io::SweepVariant> variants = io::prepare_sweep(scenario, parameters, out);
  const int jobs = arguments.jobs > 0 ? arguments.jobs : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  if (!arguments.quiet) {
    std::fprintf(stderr, "krug: sweep of %zu variants, %d at a time, into %s\n", variants.size(), jobs, out.string().c_str());
  }
  std::vector<RunJob> list;
  for (const io::SweepVariant& v : variants) list.push_back({v.scenario, v.directory, {}});
  std::size_t done = 0;
  const std::vector<int> codes = run_jobs(list, jobs, interrupted, signal_number, [&](std::size_t index, int code) {
    ++done;
    if (!arguments.quiet) {
      std::fprintf(stderr, "krug: %zu/%zu %s %s\n", done, variants.size(), variants[index].name.c_str(),
                   code == 0 ? "completed" : code == 1 ? "failed" : code >= 128 ? "interrupted" : "did not run (see log.txt)");
    }
  });
  io::write_sweep_table(out, parameters, variants);
  const auto completed = static_cast<std::size_t>(std::count(codes.begin(), codes.end(), 0));
  std::printf("krug: sweep of %zu variants: %zu completed, %zu not; table in %s\n", variants.size(), completed,
              variants.size() - completed, (out / "sweep.csv").string().c_str());
  if (interrupted.load()) return 128 + static_cast<int>(signal_number);
  return completed == variants.size() ? 0 : 1;
}

}  // namespace krug::app
