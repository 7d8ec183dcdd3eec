#pragma once
// Gauges: what a run samples at points and boundaries as it goes (docs/outputs.md, gauges.csv).
//   * tracers: material points found by their initial position (the zone that held it at t = 0 and its
//     bilinear coordinates there), followed through the run: position and velocity interpolated from
//     the zone's corner nodes, the zone's own quantities (pressure, stress, ...);
//   * surface probes: the boundary node of a body nearest a given initial position, its velocity along
//     a direction (the surface's initial outward normal there, or a given one): a VISAR trace;
//   * forces: the force each contact pair applied to its first body, each rigid wall applied, and each
//     body's held velocity components took (-F - R on the held nodes), per step and integrated over the
//     run (impulse), for whole bodies (x 2 pi in axisymmetric geometry).
// Sampling only reads the simulation; nothing here runs inside the step.
#include <optional>
#include <string>
#include <vector>

#include "krug/core/vec2.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/solver/simulation.hpp"

namespace krug {

// What a tracer reports; each a group of columns (docs/outputs.md).
enum class TracerQuantity : std::uint8_t {
  position, velocity, pressure, stress, von_mises, plastic_strain, density, specific_energy, temperature, damage
};
// The scenario names of the quantities, in the order of TracerQuantity.
const std::vector<std::string>& tracer_quantity_names();

struct TracerGauge {
  std::string name;
  Vec2 position;                             // initial position (m)
  std::vector<TracerQuantity> quantities;    // in column order; empty: all the scene provides
};

struct SurfaceGauge {
  std::string name;
  Index body = 0;
  Vec2 position;                   // initial position near the surface (m)
  std::optional<Vec2> direction;   // unit vector; none: the surface's initial outward normal at the node
};

struct GaugeSettings {
  double interval = 0.0;  // s between rows (> 0 when there are gauges)
  std::vector<TracerGauge> tracers;
  std::vector<SurfaceGauge> surfaces;
  bool forces = false;
  bool empty() const { return tracers.empty() && surfaces.empty() && !forces; }
};

// The zone holding `position` in the initial configuration (the mesh's x0, y0, or x, y with
// `current_positions`), and the bilinear coordinates (xi, eta) in [-1, 1]^2 there: corner p of the zone
// sits at ((-1, -1), (1, -1), (1, 1), (-1, 1))[p]. The first zone in zone order that holds it; none
// when no zone does.
struct TracerLocation {
  Index zone = -1;
  double xi = 0.0, eta = 0.0;
};
std::optional<TracerLocation> locate_tracer(const Mesh& mesh, Vec2 position, bool current_positions = false);

// The boundary node of `body` nearest `position` in the initial configuration (boundary: edges used by
// one zone of the body, whatever has left the grid since), and the outward unit normal there (the
// normalised sum of the normals of its boundary edges; at a corner, their bisector).
struct SurfaceLocation {
  Index node = -1;
  Vec2 normal;
};
SurfaceLocation locate_surface_node(const Mesh& mesh, const Body& body, Vec2 position, bool current_positions = false);

// True when some material of the simulation carries a temperature (Johnson-Cook: T from the energy).
bool has_temperature(const Simulation& simulation);

class GaugeSampler {
 public:
  // Locates the gauges in the simulation's initial configuration (a restored state too: nodes keep
  // their initial positions). Throws InputError naming gauges.tracers[i] for a tracer in no zone or
  // asking for a temperature no material carries.
  GaugeSampler(const GaugeSettings& settings, const Simulation& simulation);

  // The CSV columns after time and cycle, each with its unit in docs/outputs.md.
  const std::vector<std::string>& columns() const { return columns_; }
  bool needs_every_step() const { return settings_.forces; }
  // After every step (forces only): the step's forces and the impulses dt^n x force.
  void accumulate(const Simulation& simulation);
  // The values of the current state, in column order (NaN where a tracer's zone has left the grid).
  void sample(const Simulation& simulation, std::vector<double>& values) const;

  // Checkpoint state: the impulses so far (per radian or per m, two per force channel).
  const std::vector<double>& impulses() const { return impulse_; }
  void restore_impulses(const std::vector<double>& impulses);

 private:
  struct Channel {
    enum class Kind : std::uint8_t { pair, wall, held } kind;
    Index index;  // pair, wall or body
  };
  GaugeSettings settings_;
  std::vector<TracerLocation> tracers_;
  std::vector<SurfaceLocation> surfaces_;  // direction in `normal`
  std::vector<Channel> channels_;
  std::vector<std::vector<NodeConstraint>> held_;  // per held channel: the body's held DOFs
  std::vector<double> force_;    // 2 per channel: the last step's force (per radian or per m)
  std::vector<double> impulse_;  // 2 per channel
  std::vector<std::string> columns_;
  contact::ContactSolver::SourceForces scratch_;
};

}  // namespace krug
