#include "krug/io/text_file.hpp"

#include <fstream>

#include <fmt/format.h>

#include "krug/core/error.hpp"

namespace krug::io {

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

}  // namespace krug::io
