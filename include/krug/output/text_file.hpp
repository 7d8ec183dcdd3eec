#pragma once
// A whole text file written under a temporary name and renamed, so that a reader never sees half of
// it (the run's outputs, checkpoints, sweep variants and tables), and the CSV cell of a text.
#include <filesystem>
#include <string>

namespace krug::output {

// InputError when the file cannot be written.
void write_text_atomically(const std::filesystem::path& file, const std::string& text);

// A CSV cell: the text as it is, or quoted (inner quotes doubled, newlines as spaces) where it holds a
// comma, a quote or a newline.
std::string csv_field(const std::string& text);

}  // namespace krug::output
