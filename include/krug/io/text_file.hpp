#pragma once
// A whole text file written under a temporary name and renamed, so that a reader never sees half of
// it (scenario variants here; the run's outputs in krug/output/).
#include <filesystem>
#include <string>

namespace krug::io {

// InputError when the file cannot be written.
void write_text_atomically(const std::filesystem::path& file, const std::string& text);

}  // namespace krug::io
