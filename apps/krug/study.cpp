#include "study.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <map>

#include <fmt/format.h>

#include "krug/output/outputs.hpp"
#include "mpi_workers.hpp"
#include "process.hpp"

namespace krug::app {

std::vector<std::string> job_arguments(const RunJob& job) {
  std::vector<std::string> arguments = {"run", job.scenario.string(), "--out", job.directory.string(), "--quiet"};
  arguments.insert(arguments.end(), job.extra.begin(), job.extra.end());
  return arguments;
}

std::vector<int> run_jobs(const std::vector<RunJob>& list, int jobs, const std::atomic<bool>& interrupted,
                          const volatile std::sig_atomic_t& signal_number, const JobDone& on_done) {
  const std::string self = self_executable().string();
  std::map<pid_t, std::size_t> running;
  std::vector<int> codes(list.size(), -1);
  std::size_t next = 0;
  bool forwarded = false;
  while (next < list.size() || !running.empty()) {
    while (!interrupted.load() && next < list.size() && running.size() < static_cast<std::size_t>(std::max(1, jobs))) {
      const RunJob& job = list[next];
      std::vector<std::string> arguments = {self};
      for (std::string& a : job_arguments(job)) arguments.push_back(std::move(a));
      const pid_t pid = spawn(arguments, job.directory / "log.txt", true);
      if (pid < 0) {
        codes[next] = 127;
        if (on_done) on_done(next, 127, "");
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
    if (on_done) on_done(index, codes[index], "");
  }
  return codes;
}

Workers local_workers(int jobs, const std::atomic<bool>& interrupted, const volatile std::sig_atomic_t& signal_number) {
  Workers workers;
  workers.slots = std::max(1, jobs);
  workers.description = fmt::format("{} at a time", workers.slots);
  workers.run = [jobs = workers.slots, &interrupted, &signal_number](const std::vector<RunJob>& list, const JobDone& on_done) {
    return run_jobs(list, jobs, interrupted, signal_number, on_done);
  };
  return workers;
}

std::optional<int> finished_run(const std::filesystem::path& directory, const std::string& resolved_json) {
  const std::optional<run::RunStatus> status = output::finished_run(directory, resolved_json);
  if (!status) return std::nullopt;
  return *status == run::RunStatus::completed ? 0 : 1;
}

int launched_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* value = std::getenv(name)) {
      const int n = std::atoi(value);
      if (n > 0) return n;
    }
  }
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
    if (std::getenv(name) != nullptr) return -1;
  }
  return 0;
}

std::string mpi_build_hint() {
  return "this krug was built without MPI. Install MPI (Debian: apt-get install libopenmpi-dev openmpi-bin, as "
         "scripts/install-deps.sh does) and configure again (cmake -S . -B build -DKRUG_MPI=ON; the default, AUTO, "
         "takes MPI when it is found), then start the study with mpirun -np N krug sweep|ballistic ... (docs/cluster.md). "
         "On one machine, krug sweep|ballistic --jobs N runs N at a time without MPI";
}

}  // namespace krug::app
