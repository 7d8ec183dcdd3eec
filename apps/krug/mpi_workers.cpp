// The MPI side of the study commands (mpi_workers.hpp). Messages: rank 0 sends a job (tag task: the
// job's index, then the child's arguments after the executable and its log file, '\0'-separated) or
// stop (tag stop, empty); a worker answers (tag result: index and exit code). Waiting is done by
// polling with short sleeps, not in blocking MPI calls, which spin on a core with Open MPI's
// shared-memory transport and would take it from the runs.
#include "mpi_workers.hpp"

#include <mpi.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "process.hpp"

namespace krug::app {

namespace {

constexpr int tag_task = 1;
constexpr int tag_result = 2;
constexpr int tag_stop = 3;

void nap(long milliseconds) {
  timespec t{0, milliseconds * 1000000L};
  nanosleep(&t, nullptr);  // an interruption cuts it short: fine
}

// A child's exit code without blocking: nullopt while it runs.
std::optional<int> ended(pid_t pid) {
  int status = 0;
  const pid_t r = waitpid(pid, &status, WNOHANG);
  if (r == 0) return std::nullopt;
  if (r < 0) return errno == EINTR ? std::nullopt : std::optional<int>(255);
  return WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 255;
}

std::string pack(std::size_t index, const RunJob& job) {
  std::string message = std::to_string(index);
  message.push_back('\0');
  message += (job.directory / "log.txt").string();
  for (const std::string& a : job_arguments(job)) {
    message.push_back('\0');
    message += a;
  }
  return message;
}

std::vector<std::string> unpack(const std::string& message) {
  std::vector<std::string> words;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = message.find('\0', start);
    words.push_back(message.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return words;
}

// Starts a job's child of this executable; -1 when it could not be started.
pid_t start(const std::vector<std::string>& child_arguments, const std::filesystem::path& log) {
  std::vector<std::string> arguments = {self_executable().string()};
  arguments.insert(arguments.end(), child_arguments.begin(), child_arguments.end());
  return spawn(arguments, log, true);
}

int signal_to_pass(const volatile std::sig_atomic_t& signal_number) {
  return signal_number > 0 ? static_cast<int>(signal_number) : SIGTERM;
}

}  // namespace

bool mpi_built() { return true; }

MpiStudy::MpiStudy() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised && MPI_Init(nullptr, nullptr) != MPI_SUCCESS) throw std::runtime_error("MPI_Init failed");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiStudy::~MpiStudy() {
  if (rank_ == 0) {
    for (int r = 1; r < size_; ++r) MPI_Send(nullptr, 0, MPI_CHAR, r, tag_stop, MPI_COMM_WORLD);
  }
  MPI_Finalize();
}

Workers MpiStudy::workers(const std::atomic<bool>& interrupted, const volatile std::sig_atomic_t& signal_number) {
  Workers w;
  w.slots = size_;
  w.description = fmt::format("one at a time on each of {} MPI rank{}", size_, size_ == 1 ? "" : "s");
  w.run = [size = size_, &interrupted, &signal_number](const std::vector<RunJob>& list, const JobDone& on_done) {
    std::vector<int> codes(list.size(), -1);
    std::vector<long> busy(static_cast<std::size_t>(size), -1);  // the job each rank runs; rank 0 runs its own child
    pid_t local = -1;
    bool forwarded = false;
    std::size_t next = 0;
    auto finish = [&](std::size_t index, int code, int rank) {
      codes[index] = code;
      if (on_done) on_done(index, code, fmt::format("rank {}", rank));
    };
    while (true) {
      bool progress = false;
      if (!interrupted.load()) {
        // Rank 0 first takes one itself, then every idle rank one; the next goes to whichever ends first.
        if (local < 0 && next < list.size()) {
          local = start(job_arguments(list[next]), list[next].directory / "log.txt");
          busy[0] = static_cast<long>(next);
          if (local < 0) {
            busy[0] = -1;
            finish(next, 127, 0);
          }
          ++next;
          progress = true;
        }
        for (int r = 1; r < size && next < list.size(); ++r) {
          if (busy[static_cast<std::size_t>(r)] >= 0) continue;
          const std::string message = pack(next, list[next]);
          MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, r, tag_task,
                   MPI_COMM_WORLD);
          busy[static_cast<std::size_t>(r)] = static_cast<long>(next);
          ++next;
          progress = true;
        }
      } else if (!forwarded && local > 0) {
        kill(local, signal_to_pass(signal_number));
        forwarded = true;
      }
      int waiting = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, &waiting, &status);
      if (waiting) {
        int answer[2] = {0, 0};
        MPI_Recv(answer, 2, MPI_INT, status.MPI_SOURCE, tag_result, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        busy[static_cast<std::size_t>(status.MPI_SOURCE)] = -1;
        finish(static_cast<std::size_t>(answer[0]), answer[1], status.MPI_SOURCE);
        progress = true;
      }
      if (local > 0) {
        if (const std::optional<int> code = ended(local)) {
          const auto index = static_cast<std::size_t>(busy[0]);
          local = -1;
          busy[0] = -1;
          finish(index, *code, 0);
          progress = true;
        }
      }
      bool idle = local < 0;
      for (long b : busy) idle = idle && b < 0;
      if (idle && (next >= list.size() || interrupted.load())) break;
      if (!progress) nap(2);
    }
    return codes;
  };
  return w;
}

void MpiStudy::serve(const std::atomic<bool>& interrupted, const volatile std::sig_atomic_t& signal_number) {
  while (true) {
    int waiting = 0;
    MPI_Status status;
    MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status);
    if (!waiting) {
      nap(5);
      continue;
    }
    int count = 0;
    MPI_Get_count(&status, MPI_CHAR, &count);
    std::string message(static_cast<std::size_t>(count), '\0');
    MPI_Recv(message.data(), count, MPI_CHAR, 0, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (status.MPI_TAG == tag_stop) return;
    if (status.MPI_TAG != tag_task) continue;
    const std::vector<std::string> words = unpack(message);
    int answer[2] = {std::atoi(words[0].c_str()), -1};
    if (!interrupted.load() && words.size() >= 3) {
      const pid_t pid = start(std::vector<std::string>(words.begin() + 2, words.end()), words[1]);
      if (pid < 0) {
        answer[1] = 127;
      } else {
        bool forwarded = false;
        std::optional<int> code;
        while (!(code = ended(pid))) {
          if (interrupted.load() && !forwarded) {
            kill(pid, signal_to_pass(signal_number));
            forwarded = true;
          }
          nap(5);
        }
        answer[1] = *code;
      }
    }
    MPI_Send(answer, 2, MPI_INT, 0, tag_result, MPI_COMM_WORLD);
  }
}

}  // namespace krug::app
