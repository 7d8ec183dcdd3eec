#pragma once
// Support for the whole-scenario verification tests (docs/verification.md, verification.md E2):
// load an example scenario (optionally at another resolution), run it through the library API,
// read an exact profile (tests/data/exact/*.csv) and measure the result: profiles along the rows of
// a structured patch, shock positions, L1 errors and plateau values.
//
// No test framework here, so the same code serves the tests and one-off measurement programs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "krug/core/error.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/krug.hpp"

namespace krug::verification {

// A body over a generated patch of the mesh (tests that build their setup in code).
inline Body body_from(const std::string& name, Index material, const generate::Patch& patch) {
  Body body;
  body.name = name;
  body.material = material;
  body.node_begin = patch.node_begin;
  body.node_end = patch.node_end;
  body.zone_begin = patch.zone_begin;
  body.zone_end = patch.zone_end;
  return body;
}

inline std::filesystem::path example_path(const std::string& file) {
  return std::filesystem::path(KRUG_EXAMPLES_DIR) / "verification" / file;
}

inline std::filesystem::path exact_path(const std::string& file) {
  return std::filesystem::path(KRUG_TEST_DATA_DIR) / "exact" / file;
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot open " + file.string());
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// A textual change applied to a scenario file before it is parsed (for example a zone count):
// `from` must occur exactly once, so a test never silently edits the wrong line.
struct Substitution {
  std::string from, to;
};

inline std::string substitute(std::string text, const std::vector<Substitution>& substitutions) {
  for (const Substitution& s : substitutions) {
    const std::size_t at = text.find(s.from);
    if (at == std::string::npos || text.find(s.from, at + 1) != std::string::npos) {
      throw std::runtime_error("substitution: \"" + s.from + "\" does not occur exactly once");
    }
    text.replace(at, s.from.size(), s.to);
  }
  return text;
}

// The example examples/verification/<file>, with the substitutions applied.
inline scenario::Scenario load_example(const std::string& file, const std::vector<Substitution>& substitutions = {}) {
  const std::filesystem::path path = example_path(file);
  if (substitutions.empty()) return scenario::load_scenario(path);
  return scenario::parse_scenario(substitute(read_text(path), substitutions), path.string());
}

// "zones": n for the given n, as written in the example files (one space after the colon).
inline Substitution zones(int from, int to) {
  return {"\"zones\": " + std::to_string(from), "\"zones\": " + std::to_string(to)};
}

// KRUG_CONVERGENCE_SCALE (default 1, the full study) scales the resolutions of the convergence
// studies; CI sets a fraction to keep the label short.
inline double convergence_scale() {
  const char* value = std::getenv("KRUG_CONVERGENCE_SCALE");
  if (value == nullptr || *value == '\0') return 1.0;
  const double scale = std::strtod(value, nullptr);
  return scale > 0.0 ? scale : 1.0;
}

// A finished (or failed) run.
struct Run {
  explicit Run(SimulationSetup setup) : simulation(std::move(setup)) {}
  Simulation simulation;
  double seconds = 0.0;
  std::string failure;  // empty: reached the end time
  bool completed() const { return failure.empty(); }
};

// Steps the simulation to its end time (controls().end_time); a NumericalFailure is recorded in
// `failure`, with the state left at the failure for inspection.
inline void advance(Run& run, const std::function<void(const Simulation&)>& observe = {}) {
  const auto start = std::chrono::steady_clock::now();
  try {
    while (!run.simulation.finished()) {
      run.simulation.step();
      if (observe) observe(run.simulation);
    }
    if (run.simulation.time() < run.simulation.controls().end_time * (1.0 - 1e-12)) {
      run.failure = "reached max_cycles before the end time";
    }
  } catch (const NumericalFailure& failure) {
    run.failure = failure.what();
  }
  run.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline Run run_to_end(const scenario::Scenario& scenario, const std::function<void(const Simulation&)>& observe = {}) {
  Run run(scenario.setup);
  advance(run, observe);
  return run;
}

// ---- exact profiles ----------------------------------------------------------------------------

// One of tests/data/exact/*.csv: a header comment, a column line, then position, density,
// velocity, pressure, specific internal energy on increasing positions.
struct ExactProfile {
  std::vector<double> position, density, velocity, pressure, specific_energy;

  // Linear interpolation of a column; constant beyond the ends.
  double at(const std::vector<double>& column, double x) const {
    if (x <= position.front()) return column.front();
    if (x >= position.back()) return column.back();
    const auto upper = std::upper_bound(position.begin(), position.end(), x);
    const std::size_t k = static_cast<std::size_t>(upper - position.begin());
    const double w = (x - position[k - 1]) / (position[k] - position[k - 1]);
    return (1.0 - w) * column[k - 1] + w * column[k];
  }
  // Mean of a column over [a, b] (midpoint rule on `samples` sub-intervals).
  double mean(const std::vector<double>& column, double a, double b, int samples = 32) const {
    double sum = 0.0;
    for (int k = 0; k < samples; ++k) sum += at(column, a + (b - a) * (k + 0.5) / samples);
    return sum / samples;
  }
  // First position, scanning from the right end leftwards, where the column crosses `level`.
  double crossing_from_right(const std::vector<double>& column, double level) const {
    for (std::size_t k = position.size() - 1; k > 0; --k) {
      const double a = column[k - 1] - level, b = column[k] - level;
      if ((a >= 0.0) != (b >= 0.0)) return position[k - 1] + a / (a - b) * (position[k] - position[k - 1]);
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
};

inline ExactProfile read_exact(const std::string& file) {
  std::ifstream in(exact_path(file));
  if (!in) throw std::runtime_error("cannot open " + exact_path(file).string());
  ExactProfile profile;
  std::string line;
  bool header_seen = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header_seen) { header_seen = true; continue; }
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    double x, rho, u, p, e;
    if (!(fields >> x >> rho >> u >> p >> e)) throw std::runtime_error("bad line in " + file + ": " + line);
    profile.position.push_back(x);
    profile.density.push_back(rho);
    profile.velocity.push_back(u);
    profile.pressure.push_back(p);
    profile.specific_energy.push_back(e);
  }
  return profile;
}

// ---- profiles of a structured patch ------------------------------------------------------------

// Zones of a generated patch are stored row by row (z = zone_begin + j * zones_i + i, with i along
// x/z or the radius and j across); the row length is where corner 0 stops following corner 1.
struct PatchShape {
  int zones_i = 0, zones_j = 0;
};

inline PatchShape patch_shape(const Mesh& mesh, const Body& body) {
  const Index count = body.zone_end - body.zone_begin;
  Index row = 1;
  while (row < count && mesh.zones.corners[body.zone_begin + row][0] == mesh.zones.corners[body.zone_begin + row - 1][1]) ++row;
  return {static_cast<int>(row), static_cast<int>(count / row)};
}

// Where along a row a zone sits: its centre's first coordinate (strips and rods) or its distance
// from the origin (polar meshes, and spherical problems on a rectangle).
enum class Coordinate { first_axis, radius };

struct ZoneSample {
  Index zone = 0;
  double position = 0.0;  // centre, in the chosen coordinate
  double low = 0.0;       // smallest and largest corner coordinate: the zone's extent along the row
  double high = 0.0;
  double density = 0.0, pressure = 0.0, specific_energy = 0.0;
  double velocity = 0.0;  // mean of the corner velocities along the coordinate (x, or radial)
  double width() const { return high - low; }
};

inline double coordinate_of(Vec2 p, Coordinate c) { return c == Coordinate::first_axis ? p.x : norm(p); }

inline ZoneSample sample_zone(const Simulation& simulation, Index z, Coordinate c) {
  const Mesh& mesh = simulation.mesh();
  ZoneSample s;
  s.zone = z;
  const quad::Corners x = mesh.corner_positions(z);
  s.position = coordinate_of(quad::centre(x), c);
  s.low = std::numeric_limits<double>::infinity();
  s.high = -s.low;
  double velocity = 0.0;
  for (int p = 0; p < 4; ++p) {
    const double q = coordinate_of(x[p], c);
    s.low = std::min(s.low, q);
    s.high = std::max(s.high, q);
    const Index n = mesh.zones.corners[z][static_cast<std::size_t>(p)];
    const Vec2 u = mesh.nodes.velocity(n);
    const double r = norm(x[p]);
    velocity += c == Coordinate::first_axis ? u.x : (r > 0.0 ? dot(u, x[p]) / r : 0.0);
  }
  s.velocity = 0.25 * velocity;
  s.density = mesh.zones.density[z];
  s.pressure = simulation.zone_state().hydro.pressure[z];
  s.specific_energy = mesh.zones.specific_energy[z];
  return s;
}

// Row j of the patch (i increasing).
inline std::vector<ZoneSample> row_profile(const Simulation& simulation, const Body& body, int j, Coordinate c) {
  const Mesh& mesh = simulation.mesh();
  const PatchShape shape = patch_shape(mesh, body);
  std::vector<ZoneSample> row;
  for (int i = 0; i < shape.zones_i; ++i) row.push_back(sample_zone(simulation, body.zone_begin + j * shape.zones_i + i, c));
  return row;
}

// All zones of a body, sorted by position.
inline std::vector<ZoneSample> body_profile(const Simulation& simulation, const Body& body, Coordinate c) {
  std::vector<ZoneSample> all;
  for (Index z = body.zone_begin; z < body.zone_end; ++z) all.push_back(sample_zone(simulation, z, c));
  std::sort(all.begin(), all.end(), [](const ZoneSample& a, const ZoneSample& b) { return a.position < b.position; });
  return all;
}

// Position of a front along a row: scanning from the outer end (last zone) inwards, the first pair of
// neighbouring zone centres between which density crosses `level`, interpolated linearly. NaN if none.
// Also gives the index of the zone on the inner side of the crossing.
struct Front {
  double position = std::numeric_limits<double>::quiet_NaN();
  std::size_t inner = 0;  // row index of the zone just inside the crossing
  double spacing = 0.0;   // distance between the two zone centres around the crossing: the local zone size
  bool found() const { return std::isfinite(position); }
};

inline Front front_from_outside(const std::vector<ZoneSample>& row, double level) {
  Front f;
  for (std::size_t k = row.size() - 1; k > 0; --k) {
    const double a = row[k - 1].density - level, b = row[k].density - level;
    if ((a >= 0.0) != (b >= 0.0)) {
      f.position = row[k - 1].position + a / (a - b) * (row[k].position - row[k - 1].position);
      f.inner = k - 1;
      f.spacing = std::abs(row[k].position - row[k - 1].position);
      return f;
    }
  }
  return f;
}

// A shock located on every row of a patch (the rays of a polar mesh, the rows of a strip): its
// position on each row, and the worst distance from the exact position in local zone sizes.
struct ShockSurvey {
  std::vector<double> positions;   // per row; NaN where no crossing was found
  double smallest = std::numeric_limits<double>::infinity();
  double largest = -std::numeric_limits<double>::infinity();
  double mean = 0.0;
  double worst_zones = 0.0;        // max over rows of |position - exact| / local zone size
  double zone_size = 0.0;          // the local zone size on the row with the worst error
  bool all_found = true;
  double spread() const { return largest - smallest; }
};

// `level(row)` gives the density level that marks the shock on a row.
inline ShockSurvey survey_shock(const Simulation& simulation, const Body& body, Coordinate c, double exact,
                                const std::function<double(const std::vector<ZoneSample>&)>& level) {
  const Mesh& mesh = simulation.mesh();
  ShockSurvey s;
  const PatchShape shape = patch_shape(mesh, body);
  int found = 0;
  for (int j = 0; j < shape.zones_j; ++j) {
    const auto row = row_profile(simulation, body, j, c);
    const Front f = front_from_outside(row, level(row));
    s.positions.push_back(f.position);
    if (!f.found()) { s.all_found = false; continue; }
    ++found;
    s.mean += f.position;
    s.smallest = std::min(s.smallest, f.position);
    s.largest = std::max(s.largest, f.position);
    const double zones = std::abs(f.position - exact) / f.spacing;
    if (zones >= s.worst_zones) { s.worst_zones = zones; s.zone_size = f.spacing; }
  }
  if (found > 0) s.mean /= found;
  return s;
}

// The largest density along a row.
inline double peak_density(const std::vector<ZoneSample>& row) {
  double peak = 0.0;
  for (const ZoneSample& z : row) peak = std::max(peak, z.density);
  return peak;
}

// L1 norm of (density - exact density) over the rows of a strip, per unit length across: the sum
// over zones of |rho_z - mean of exact over the zone's extent| times the zone's share of the row
// length, averaged over the rows.
inline double density_l1_error(const Simulation& simulation, const Body& body, const ExactProfile& exact) {
  const Mesh& mesh = simulation.mesh();
  const PatchShape shape = patch_shape(mesh, body);
  double sum = 0.0;
  for (int j = 0; j < shape.zones_j; ++j) {
    for (const ZoneSample& s : row_profile(simulation, body, j, Coordinate::first_axis)) {
      sum += std::abs(s.density - exact.mean(exact.density, s.low, s.high)) * s.width();
    }
  }
  return sum / shape.zones_j;
}

// Mean and largest relative deviation from `reference` of a zone quantity over the zones whose
// centre lies in [from, to].
struct PlateauFit {
  double mean = 0.0;
  double largest_deviation = 0.0;  // max |q / reference - 1|
  int zones = 0;
};

inline PlateauFit plateau(const std::vector<ZoneSample>& samples, double from, double to, double reference,
                          double ZoneSample::*quantity) {
  PlateauFit fit;
  for (const ZoneSample& s : samples) {
    if (s.position < from || s.position > to) continue;
    fit.mean += s.*quantity;
    fit.largest_deviation = std::max(fit.largest_deviation, std::abs(s.*quantity / reference - 1.0));
    ++fit.zones;
  }
  if (fit.zones > 0) fit.mean /= fit.zones;
  return fit;
}

// ---- the table of docs/verification.md --------------------------------------------------------

// With KRUG_VERIFICATION_REPORT set, prints one Markdown row
// | problem | quantity | reference | Krug | error | zones | seconds |
// so that the table in docs/verification.md can be regenerated from a test run.
inline void report(const std::string& problem, const std::string& quantity, const std::string& reference,
                   double value, const std::string& error, long zones, double seconds) {
  const char* flag = std::getenv("KRUG_VERIFICATION_REPORT");
  if (flag == nullptr || *flag == '\0') return;
  char value_text[64], seconds_text[32];
  std::snprintf(value_text, sizeof value_text, "%.6g", value);
  std::snprintf(seconds_text, sizeof seconds_text, "%.2f", seconds);
  std::cout << "| " << problem << " | " << quantity << " | " << reference << " | " << value_text << " | " << error
            << " | " << zones << " | " << seconds_text << " |\n" << std::flush;
}

inline std::string format_number(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// A row for a run that stopped before its end time: where, and why.
inline void report_failure(const std::string& problem, const Run& run) {
  if (run.completed()) return;
  const Simulation& sim = run.simulation;
  report(problem, "reaches the end time (" + run.failure + ")", format_number("%g", sim.controls().end_time),
         sim.time(), "FAILED", sim.mesh().zones.size(), run.seconds);
}

}  // namespace krug::verification
