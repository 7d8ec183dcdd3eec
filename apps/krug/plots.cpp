#include "plots.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "process.hpp"

namespace krug::app {

namespace {

// The script: $KRUG_PLOT_SCRIPT, next to an installed krug (PREFIX/share/krug), or the source tree.
std::filesystem::path plot_script() {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("KRUG_PLOT_SCRIPT")) candidates.emplace_back(env);
  candidates.push_back(self_executable().parent_path().parent_path() / "share" / "krug" / "plot_history.py");
  candidates.push_back(std::filesystem::path(KRUG_SOURCE_SCRIPTS_DIR) / "plot_history.py");
  for (const auto& c : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(c, error)) return c;
  }
  return {};
}

std::string last_line(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

}  // namespace

std::string make_plots(const std::filesystem::path& directory) {
  const std::filesystem::path script = plot_script();
  if (script.empty()) return "no plots: plot_history.py not found (set KRUG_PLOT_SCRIPT)";
  // $KRUG_PYTHON when set, else Debian's /usr/bin/python3 (which python3-matplotlib serves), else PATH's.
  std::optional<std::filesystem::path> python;
  if (const char* env = std::getenv("KRUG_PYTHON")) {
    if (access(env, X_OK) != 0) return std::string("no plots: KRUG_PYTHON=") + env + " is not an executable";
    python = env;
  } else {
    python = find_program({"/usr/bin/python3"}, "python3");
  }
  if (!python) return "no plots: python3 not found (install python3-matplotlib)";
  const std::filesystem::path out = directory / "plots";
  std::error_code error;
  std::filesystem::create_directories(out, error);
  const std::filesystem::path log = out / "plot.log";
  const pid_t pid = spawn({python->string(), script.string(), (directory / "history.csv").string(), out.string()}, log);
  if (pid < 0) return "no plots: could not start " + python->string();
  const int code = wait_for(pid);
  if (code == 0) {
    std::filesystem::remove(log, error);
    return "";
  }
  if (code == 3) return "no plots: " + python->string() + " has no matplotlib (install python3-matplotlib)";
  return "no plots: plot_history.py failed (" + last_line(log) + "; see " + log.string() + ")";
}

}  // namespace krug::app
