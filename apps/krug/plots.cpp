#include "plots.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "process.hpp"

namespace krug::app {

namespace {

// A script: $KRUG_PLOT_SCRIPT (plot_history.py only), next to an installed krug (PREFIX/share/krug),
// or the source tree.
std::filesystem::path plot_script(const std::string& name = "plot_history.py") {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("KRUG_PLOT_SCRIPT"); env && name == "plot_history.py") candidates.emplace_back(env);
  candidates.push_back(self_executable().parent_path().parent_path() / "share" / "krug" / name);
  candidates.push_back(std::filesystem::path(KRUG_SOURCE_SCRIPTS_DIR) / name);
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

// $KRUG_PYTHON when set, else Debian's /usr/bin/python3 (which python3-matplotlib serves), else PATH's.
// Empty with the reason in `why` when there is none.
std::optional<std::filesystem::path> python_program(std::string& why) {
  if (const char* env = std::getenv("KRUG_PYTHON")) {
    if (access(env, X_OK) != 0) {
      why = std::string("KRUG_PYTHON=") + env + " is not an executable";
      return std::nullopt;
    }
    return std::filesystem::path(env);
  }
  auto python = find_program({"/usr/bin/python3"}, "python3");
  if (!python) why = "python3 not found (install python3-matplotlib)";
  return python;
}

}  // namespace

std::string make_ballistic_plot(const std::filesystem::path& directory) {
  const std::filesystem::path script = plot_script("plot_ballistic.py");
  if (script.empty()) return "no ballistic.png: plot_ballistic.py not found";
  std::string why;
  const auto python = python_program(why);
  if (!python) return "no ballistic.png: " + why;
  const std::filesystem::path log = directory / "plot.log";
  const pid_t pid = spawn({python->string(), script.string(), directory.string()}, log);
  if (pid < 0) return "no ballistic.png: could not start " + python->string();
  const int code = wait_for(pid);
  std::error_code error;
  if (code == 0) {
    std::filesystem::remove(log, error);
    return "";
  }
  if (code == 3) return "no ballistic.png: " + python->string() + " has no matplotlib (install python3-matplotlib)";
  return "no ballistic.png: plot_ballistic.py failed (" + last_line(log) + "; see " + log.string() + ")";
}

std::string make_plots(const std::filesystem::path& directory) {
  const std::filesystem::path script = plot_script();
  if (script.empty()) return "no plots: plot_history.py not found (set KRUG_PLOT_SCRIPT)";
  std::string why;
  const auto python = python_program(why);
  if (!python) return "no plots: " + why;
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
