#pragma once
// Helpers shared by the app tests: files, the scenario documents the tests use, running the krug
// executable (its absolute path comes from CMake) and reading summary.json.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace krug::test {

using Json = nlohmann::json;

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) FAIL("cannot read " << file.string());
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
}

inline Json read_json(const std::filesystem::path& file) { return Json::parse(read_text(file)); }

// Every scenario the schema must describe: examples/**/*.json and this folder's data/*.json.
inline std::vector<std::filesystem::path> scenario_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(KRUG_EXAMPLES_DIR)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  }
  for (const auto& entry : std::filesystem::directory_iterator(KRUG_APP_TEST_DATA_DIR)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// A fresh scratch directory under the build tree for one test.
inline std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(KRUG_APP_TEST_WORK_DIR) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

struct ProcessResult {
  int exit_code = -1;  // 128 + signal when killed by a signal
  std::string output;  // stdout and stderr together
};

// Starts the krug executable with `arguments` (no shell), output to `log`, with extra environment
// variables ("NAME=VALUE"). Returns the process id.
inline pid_t start_krug(const std::vector<std::string>& arguments, const std::filesystem::path& log,
                        const std::vector<std::string>& environment = {}) {
  std::filesystem::create_directories(log.parent_path());
  const pid_t pid = fork();
  if (pid == 0) {
    for (const std::string& e : environment) {
      const auto eq = e.find('=');
      setenv(e.substr(0, eq).c_str(), e.substr(eq + 1).c_str(), 1);
    }
    const std::string log_name = log.string();
    FILE* out = std::freopen(log_name.c_str(), "w", stdout);
    if (!out || dup2(fileno(stdout), STDERR_FILENO) < 0) _exit(126);
    std::vector<std::string> words = {KRUG_APP_EXECUTABLE};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& w : words) argv.push_back(w.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

inline int wait_exit_code(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Runs the krug executable to its end; its output is returned with the exit code.
inline ProcessResult run_krug(const std::vector<std::string>& arguments, const std::filesystem::path& log,
                              const std::vector<std::string>& environment = {}) {
  const pid_t pid = start_krug(arguments, log, environment);
  ProcessResult result;
  result.exit_code = wait_exit_code(pid);
  result.output = read_text(log);
  return result;
}

// The app tests need the executable; without it (KRUG_BUILD_APP off) they are skipped.
inline bool have_app() { return std::string(KRUG_APP_EXECUTABLE).size() > 0; }

// summary.json without the fields that measure the machine rather than the run.
inline Json summary_without_timing(const std::filesystem::path& file) {
  Json s = read_json(file);
  s.erase("wall_seconds");
  return s;
}

// A CSV table written by the app (sweep.csv, ballistic.csv) as rows of cells by column name
// (RFC 4180 quoting: "a,b" and "" for a quote); every row has as many cells as the header.
inline std::vector<std::map<std::string, std::string>> read_csv_table(const std::filesystem::path& file) {
  std::stringstream in(read_text(file));
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  auto split = [](const std::string& text) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
      const char c = text[i];
      if (quoted && c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        cell += '"';
        ++i;
      } else if (c == '"') {
        quoted = !quoted;
      } else if (c == ',' && !quoted) {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += c;
      }
    }
    cells.push_back(cell);
    return cells;
  };
  while (std::getline(in, line)) {
    const auto cells = split(line);
    if (header.empty()) {
      header = cells;
      continue;
    }
    REQUIRE(cells.size() == header.size());
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace krug::test
