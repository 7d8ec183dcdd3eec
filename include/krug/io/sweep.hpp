#pragma once
// Parameter sweeps (`krug sweep`): variants of one scenario, the cartesian product of values given
// for JSON paths, each written to DIR/<variant>/scenario.json and run by the app in its own
// process; DIR/sweep.csv collects their inputs and summary figures. Paths are written like
// materials.al6061.fracture.elongation or bodies[0].initial.velocity[0]; a missing object on the
// way is created (so a default can be overridden), a missing array item is an error.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "krug/io/scenario.hpp"

namespace krug::io {

// One edit of a scenario: the value at a JSON path. `path` is written like
// materials.al6061.fracture.elongation or bodies[0].initial.velocity[0]; `value` is a JSON text
// ("0.3", "[350, 0]", "true", "\"steel\""), and a text that is not JSON is taken as a string (steel).
struct ScenarioEdit {
  std::string path;
  std::string value;
};

// The scenario `text` (JSON) with every edit applied in order, as JSON text (two-space indent, the
// file's key order kept, a final newline). A missing object on the way is created (so a default can
// be overridden); a missing array item, a key into something that is not an object or an index into
// something that is not an array is an InputError naming the path. `origin` names the text in
// messages. The result is not checked as a scenario: parse_scenario (scenario.hpp) does that.
// Used by `krug sweep` and `krug ballistic` to make variants in memory.
std::string edit_scenario(const std::string& text, const std::vector<ScenarioEdit>& edits, const std::string& origin);

// A CSV cell: the text as it is, or quoted (inner quotes doubled, newlines as spaces) where it holds a
// comma, a quote or a newline.
std::string csv_field(const std::string& text);

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

// Writes every variant's scenario under `directory` after checking it with the scenario reader
// (an InputError names the variant and the reader's complaint). First parameter varies slowest.
std::vector<SweepVariant> prepare_sweep(const std::filesystem::path& scenario_file,
                                        const std::vector<SweepParameter>& parameters,
                                        const std::filesystem::path& directory);

// Writes DIR/sweep.csv: variant, one column per parameter, then from each DIR/<variant>/summary.json
// status, stopped_by, time, cycles, wall_seconds, energy_drift, mass_error, particles, and per body
// velocity (both components) and active zones, then message. A variant without a summary has
// status "not run".
void write_sweep_table(const std::filesystem::path& directory, const std::vector<SweepParameter>& parameters,
                       const std::vector<SweepVariant>& variants);

}  // namespace krug::io
