#pragma once
// Scenarios changed by JSON path, in memory: one edit is a value at a path written like
// materials.al6061.fracture.elongation or bodies[0].initial.velocity[0] (a missing object on the way is
// created, so a default can be overridden; a missing array item is an error). A variant is read from
// the edited text alone, so its scene, built setup and resolved JSON always agree. Parameter sweeps
// (`krug sweep`) are the cartesian product of values given for paths; their files are output's
// (krug/output/sweep_files.hpp).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "krug/scenario/scenario.hpp"

namespace krug::scenario {

// One edit of a scenario: the value at a JSON path. `value` is a JSON text ("0.3", "[350, 0]",
// "true", "\"steel\""), and a text that is not JSON is taken as a string (steel).
struct ScenarioEdit {
  std::string path;
  std::string value;
};

// The scenario `text` (JSON) with every edit applied in order, as JSON text (two-space indent, the
// file's key order kept, a final newline). A missing object on the way is created (so a default can
// be overridden); a missing array item, a key into something that is not an object or an index into
// something that is not an array is an InputError naming the path. `origin` names the text in
// messages. The result is not checked as a scenario: parse_scenario (scenario.hpp) does that.
std::string edit_scenario(const std::string& text, const std::vector<ScenarioEdit>& edits, const std::string& origin);

// The variant of the scenario `text` with `edits` applied, read as a scenario (InputError as the reader's):
// the one way to make a variant in memory (used by `krug ballistic` and the studies).
Scenario scenario_variant(const std::string& text, const std::vector<ScenarioEdit>& edits, const std::string& origin);

struct SweepParameter {
  std::string path;                 // as given
  std::vector<std::string> values;  // JSON texts (a value that is not JSON is taken as a string)
};

struct SweepVariant {
  std::string name;                 // "003_elongation=0.3_velocity0=350": index, then leaf=value
  std::vector<std::string> values;  // one JSON text per parameter
  std::filesystem::path directory;  // DIR/<name>
  std::filesystem::path scenario;   // DIR/<name>/scenario.json
  std::string title;                // the variant's scenario title: the base title, "sweep variant", the settings
};

// "PATH=V1,V2,..." (values split at commas outside brackets, braces and quotes). InputError when
// malformed.
SweepParameter parse_sweep_set(const std::string& argument);

// Every variant of a sweep (first parameter varies slowest) with its scenario text, each checked with
// the scenario reader (an InputError names the variant and the reader's complaint). Nothing is written.
struct SweepPlan {
  std::vector<SweepVariant> variants;
  std::vector<std::string> texts;  // each variant's scenario JSON
};
SweepPlan plan_sweep(const std::filesystem::path& scenario_file, const std::vector<SweepParameter>& parameters,
                     const std::filesystem::path& directory);

}  // namespace krug::scenario
