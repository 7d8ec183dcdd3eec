#pragma once
// The files of a ballistic-limit study (`krug ballistic`, docs/outputs.md "Ballistic"); the search
// itself is krug/run/ballistic.hpp.
#include <filesystem>
#include <string>

#include "krug/run/ballistic.hpp"

namespace krug::output {

// Writes DIR/ballistic.csv (every run, by speed) and DIR/ballistic.json (the study). `scenario` is
// recorded in the JSON.
void write_ballistic_results(const std::filesystem::path& directory, const run::BallisticStudy& study,
                             const std::string& scenario);

}  // namespace krug::output
