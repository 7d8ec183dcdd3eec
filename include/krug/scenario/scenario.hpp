#pragma once
// Scenario files (JSON, SI units) -> a scene description (setup/scene.hpp) and the SimulationSetup
// built from it, ready to run, plus output settings.
// The format is documented in docs/scenario-format.md. Every error is an InputError naming the
// JSON path, the value found and what was expected.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "krug/setup/scene.hpp"
#include "krug/solver/gauges.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::scenario {

// PNG pictures of the bodies and particles coloured by one field (written by the app when it is built
// with Cairo; see docs/outputs.md).
struct PictureSettings {
  bool enabled = true;
  std::string field = "density";  // one of picture_fields()
  bool every_snapshot = false;    // false: the initial and the final state only
  int width = 1200;               // pixels
  bool mirror = false;            // axisymmetric: also draw the mirror image below the axis
  std::optional<std::pair<double, double>> range;  // fixed colour range; default: the field's extent
  // Fixed view (m): first axis from..to, second axis from..to; default: what is drawn. With
  // every_snapshot, a window and a range make the pictures of a run compare frame by frame.
  std::optional<std::array<double, 4>> window;
};

// Names of the fields a picture can show.
const std::vector<std::string>& picture_fields();

// How VTK files store their arrays: compressed binary (zlib, appended) or text.
enum class VtkEncoding { binary, ascii };

struct OutputSettings {
  std::string directory;            // default: "out/<scenario file stem>"; `krug run --out` overrides
  double history_interval = 0.0;    // s between rows of history.csv (0: every cycle)
  double snapshot_interval = 0.0;   // s between VTK snapshots (0: initial and final state only)
  double checkpoint_interval = 0.0; // s between checkpoints (0: none, apart from an interruption)
  VtkEncoding vtk_format = VtkEncoding::binary;
  PictureSettings pictures;
  bool plots = true;                // plots of history.csv (by the app, with Python and matplotlib)
};

// Ends a projectile run early (status "completed", summary "stopped_by": "stop rule") once the named
// body has felt no contact for `no_contact_time`: its mass-weighted mean velocity (momentum / mass,
// which only external forces change) has stayed within `velocity_change` x its initial speed over
// that window, after having changed by more than that (the rule arms at the first interaction).
// The exact rule is in docs/scenario-format.md ("Stop rule").
struct StopRule {
  std::string body;
  Index body_index = 0;
  double no_contact_time = 0.0;   // s
  double velocity_change = 0.01;  // fraction of the body's initial speed
  // Optional: a plane of constant first coordinate (m) that every node of the body still carrying mass
  // must have passed, the way the body first moved along that axis, before the run may stop (a long
  // projectile still sliding through its hole is not done).
  std::optional<double> clear_of;
  // Penetration scenarios (default true there, refused elsewhere): the run also waits until the
  // projectile's piece has cleared every target's main piece, or has stopped advancing (its speed
  // along the impact direction no more than velocity_change x its initial speed). No headline figure
  // of a penetration run is then a bound.
  bool clear_of_targets = false;
};

// Scenario key "penetration": the projectile and the bodies it is to perforate (the figures measured
// over the run: krug/run/penetration.hpp).
struct PenetrationSetup {
  Index projectile = 0;
  std::vector<Index> targets;  // never empty, never the projectile
};

struct Scenario {
  std::string title;
  std::filesystem::path source;
  setup::SceneDescription scene;  // the scenario in C++ types, as read
  SimulationSetup setup;          // built from `scene` (setup::build_simulation)
  OutputSettings output;
  std::optional<StopRule> stop;
  std::optional<PenetrationSetup> penetration;  // scenario key "penetration": which body is the projectile
  GaugeSettings gauges;           // scenario key "gauges" (empty: none; gauges.csv is not written)
  std::string resolved_json;  // the scenario as read, every default filled in
};

Scenario load_scenario(const std::filesystem::path& file);
// Limits a program reading scenarios sets over the scenarios' own (a service or a fuzzer).
struct ReadLimits {
  long max_zones = 0;  // > 0: at most this many zones, whatever the scenario's controls.max_zones says
};

Scenario parse_scenario(const std::string& json_text, const std::string& origin, const ReadLimits& limits = {});

}  // namespace krug::scenario
