#include "krug/solver/initial_state.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string_view>
#include <variant>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/solver/hydro_step.hpp"

namespace krug {

void derive_masses(Mesh& mesh, const std::vector<Body>& bodies, const std::vector<Material>& materials,
                   GeometryKind geometry) {
  const bool axisymmetric = geometry == GeometryKind::axisymmetric;
  NodeFields& nodes = mesh.nodes;
  ZoneFields& zones = mesh.zones;
  std::fill(nodes.mass.begin(), nodes.mass.end(), 0.0);
  for (const Body& body : bodies) {
    const Material& material = materials.at(static_cast<std::size_t>(body.material));
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      const quad::Corners x = mesh.corner_positions(z);
      const double area = quad::area(x);
      const double volume = axisymmetric ? quad::axisymmetric_volume(x) : area;
      if (!(area > 0.0) || !(volume > 0.0)) {
        throw InputError(fmt::format("body '{}': zone {} has non-positive area {:.3e} m^2 (inverted corners "
                                     "or a node below the axis)", body.name, z - body.zone_begin, area));
      }
      if (zones.density[z] <= 0.0) zones.density[z] = material.reference_density;
      zones.area[z] = area;
      zones.volume[z] = volume;
      zones.mass[z] = zones.density[z] * volume;
      const ZoneCorners& n = zones.corners[z];
      zones.initial_altitude[z] = quad::smallest_altitude(x, area);
      const std::array<double, 4> axisymmetric_corners =
          axisymmetric ? quad::axisymmetric_corner_volumes(x) : std::array<double, 4>{};
      for (int p = 0; p < 4; ++p) {
        const quad::Corners region = quad::corner_region(x, p);
        const double corner_volume = axisymmetric ? axisymmetric_corners[p] : quad::area(region);
        zones.corner_mass[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p)] = zones.density[z] * corner_volume;
        // The corner's region of the median mesh (its subzone), with the zone's volume measure.
        zones.subzone_mass[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p)] =
            zones.density[z] * (axisymmetric ? quad::axisymmetric_volume(region) : quad::area(region));
        nodes.mass[n[p]] += zones.density[z] * corner_volume;
      }
    }
  }
  // Per-DOF inverse masses (the boundary then zeroes the held components).
  for (Index p = 0; p < nodes.size(); ++p) {
    const double inverse = nodes.mass[p] > 0.0 ? 1.0 / nodes.mass[p] : 0.0;
    nodes.inv_mass_x[p] = inverse;
    nodes.inv_mass_y[p] = inverse;
  }
}

std::vector<Index> count_zones_per_node(const Mesh& mesh) {
  const ZoneFields& zones = mesh.zones;
  std::vector<Index> count(static_cast<std::size_t>(mesh.nodes.size()), 0);
  for (Index z = 0; z < zones.size(); ++z) {
    if (!zones.active[z]) continue;
    const ZoneCorners& n = zones.corners[z];
    for (int p = 0; p < 4; ++p) {
      if (p > 0 && n[p] == n[p - 1]) continue;
      if (p == 3 && n[3] == n[0]) continue;
      ++count[static_cast<std::size_t>(n[p])];
    }
  }
  return count;
}

void evaluate_initial_eos(const ZoneFields& zones, HydroZoneFields& hydro, const std::vector<Body>& bodies,
                          const std::vector<Material>& materials) {
  for (const Body& body : bodies) {
    const Material& material = materials.at(static_cast<std::size_t>(body.material));
    const double mu = material.shear_modulus();
    std::visit([&](const auto& eos) {
      for (Index z = body.zone_begin; z < body.zone_end; ++z) {
        evaluate_eos(eos, mu, zones, hydro, z);
        const double rho = zones.density[z], e = zones.specific_energy[z];
        if (!std::isfinite(e) || !std::isfinite(hydro.pressure[z]) || !std::isfinite(hydro.sound_speed[z])) {
          throw InputError(fmt::format("body '{}': zone {} starts with a non-finite state (rho {}, e {}, p {})",
                                       body.name, z - body.zone_begin, rho, e, hydro.pressure[z]));
        }
      }
    }, material.eos);
  }
}

void initialise_zone_state(ZoneState& state, const ZoneFields& zones, const std::vector<Body>& bodies,
                           const std::vector<Material>& materials) {
  const auto count = static_cast<std::size_t>(zones.size());
  if (state.size() == 0) state.resize(zones.size());
  for_each_zone_state_field(state, [&](std::string_view name, const auto& field, std::size_t per, auto) {
    if (field.size() != per * count) {
      throw InputError(fmt::format("the initial zone field {} has {} entries for {} zones", name, field.size(), count));
    }
  });
  evaluate_initial_eos(zones, state.hydro, bodies, materials);
}

StableStep first_stable_time_step(const Mesh& mesh, const HydroZoneFields& hydro, const std::vector<Body>& bodies,
                                  const std::vector<Material>& materials, const Controls& controls) {
  const NodeFields& nodes = mesh.nodes;
  const ZoneFields& zones = mesh.zones;
  StableStep stable{std::numeric_limits<double>::infinity(), -1};
  for (const Body& body : bodies) {
    const double cfl = cfl_number(materials[static_cast<std::size_t>(body.material)], controls);
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      if (!zones.active[z]) continue;
      const ZoneCorners& n = zones.corners[z];
      const Vec2 mean = 0.25 * (nodes.velocity(n[0]) + nodes.velocity(n[1]) + nodes.velocity(n[2]) + nodes.velocity(n[3]));
      double spread = 0.0;
      for (int p = 0; p < 4; ++p) spread = std::max(spread, norm(nodes.velocity(n[p]) - mean));
      const double speed = hydro.sound_speed[z] + 2.0 * spread;
      if (speed <= 0.0) continue;
      const double dt = cfl * quad::stable_length(mesh.corner_positions(z), zones.area[z]) / speed;
      if (dt < stable.time_step) stable = {dt, z};
    }
  }
  return stable;
}

}  // namespace krug
