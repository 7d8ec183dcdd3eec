#pragma once
// PNG pictures of a run (output.pictures, docs/outputs.md): the active zones of every body filled
// with the colour of one field, free particles as circles, a colour bar, a scale bar and the time,
// like the figures of Gulidov & Shabalin. Drawn with Cairo when krug is built with it (optional,
// app only); without Cairo pictures_available() is false and nothing is drawn.
#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <string>

#include "krug/scenario/scenario.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::app {

bool pictures_available();

// Writes DIR/pictures/NAME.png (under a temporary name, then renamed). Returns false (and writes
// nothing) when there is nothing to draw or Cairo is missing.
bool write_picture(const Simulation& simulation, const scenario::PictureSettings& settings, const std::string& title,
                   const std::filesystem::path& directory, const std::string& name);

// The default fixed view of `pictures.every_snapshot` (when no `pictures.window` is given): what the
// first picture shows (active zones and particles), widened on every side by a quarter of its larger
// side, and not below the axis in axisymmetric geometry. Material that leaves it later is cut.
inline std::array<double, 4> default_fixed_window(const Simulation& simulation) {
  const Mesh& mesh = simulation.mesh();
  const Particles& particles = simulation.particles();
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    if (!mesh.zones.active[z]) continue;
    for (Index n : mesh.zones.corners[z]) {
      x0 = std::min(x0, mesh.nodes.x[n]);
      x1 = std::max(x1, mesh.nodes.x[n]);
      y0 = std::min(y0, mesh.nodes.y[n]);
      y1 = std::max(y1, mesh.nodes.y[n]);
    }
  }
  for (Index i = 0; i < particles.size(); ++i) {
    x0 = std::min(x0, particles.x[i] - particles.radius[i]);
    x1 = std::max(x1, particles.x[i] + particles.radius[i]);
    y0 = std::min(y0, particles.y[i] - particles.radius[i]);
    y1 = std::max(y1, particles.y[i] + particles.radius[i]);
  }
  const double pad = 0.25 * std::max(x1 - x0, y1 - y0);
  std::array<double, 4> window{x0 - pad, x1 + pad, y0 - pad, y1 + pad};
  if (simulation.geometry() == GeometryKind::axisymmetric) window[2] = std::max(window[2], 0.0);
  return window;
}

}  // namespace krug::app
