#include "krug/output/text_file.hpp"

#include <fstream>

#include <fmt/format.h>

#include "krug/core/error.hpp"

namespace krug::output {

void write_text_atomically(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path temporary = file.string() + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(fmt::format("{}: cannot write", temporary.string()));
    out << text;
    out.flush();
    if (!out) throw InputError(fmt::format("{}: write failed (disk full?)", temporary.string()));
  }
  std::filesystem::rename(temporary, file);
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c == '\n' ? ' ' : c;
  }
  return quoted + "\"";
}

}  // namespace krug::output
