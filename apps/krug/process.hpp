#pragma once
// Child processes for the app (sweep variants, the plotting script): spawned without a shell,
// output optionally sent to a log file.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace krug::app {

// Starts `arguments[0]` (a path, or a name looked up in PATH) with `arguments`; stdout and stderr go
// to `log` (created or truncated) unless it is empty. With `own_group` the child leads a process
// group of its own, so a Ctrl-C at the terminal reaches only this process, which passes it on once.
// Returns the process id, or -1 if it could not be started.
pid_t spawn(const std::vector<std::string>& arguments, const std::filesystem::path& log, bool own_group = false);

// Waits for one child: its exit code, or 128 + the signal that ended it.
int wait_for(pid_t pid);

// Waits for whichever child ends first: (pid, exit code as above); nullopt when there is none.
std::optional<std::pair<pid_t, int>> wait_any();

// This executable (Linux: /proc/self/exe), for re-running itself.
std::filesystem::path self_executable();

// The first of `candidates` that exists and is executable, or PATH's `name`.
std::optional<std::filesystem::path> find_program(const std::vector<std::filesystem::path>& candidates,
                                                  const std::string& name);

}  // namespace krug::app
