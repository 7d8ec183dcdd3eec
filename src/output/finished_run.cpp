// Whether a folder holds a finished run of a scenario (resuming `krug sweep` and `krug ballistic`).
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "krug/output/outputs.hpp"

namespace krug::output {

namespace {

using Json = nlohmann::json;

std::optional<std::string> read_whole(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return buffer.str();
}

}  // namespace

std::optional<RunStatus> finished_run(const std::filesystem::path& directory, const std::string& resolved_json) {
  const std::optional<std::string> resolved = read_whole(directory / "scenario.resolved.json");
  if (!resolved || *resolved != resolved_json + "\n") return std::nullopt;
  const std::optional<std::string> text = read_whole(directory / "summary.json");
  if (!text) return std::nullopt;
  const Json summary = Json::parse(*text, nullptr, false);
  if (summary.is_discarded() || !summary.is_object()) return std::nullopt;
  const auto string_at = [&](const char* key) {
    const auto found = summary.find(key);
    return found != summary.end() && found->is_string() ? found->get<std::string>() : std::string();
  };
  const std::string status = string_at("status");
  const std::string stopped_by = string_at("stopped_by");
  if (stopped_by.empty() || stopped_by == "interrupted" || stopped_by == "request") return std::nullopt;
  if (status == "completed") return RunStatus::completed;
  if (status == "failed") return RunStatus::failed;
  return std::nullopt;
}

}  // namespace krug::output
