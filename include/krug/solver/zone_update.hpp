#pragma once
// Step 5 of the time step for one body: new geometry at t^{n+1}, density, compatible internal energy
// m de = -dt^n sum_p f_p . ubar_p (ubar = mid-step velocity), pressure and sound speed from the EOS,
// and each zone's stable time step for step 8 (DESIGN.md section 2).
#include <cmath>
#include <limits>

#include "krug/core/geometry_kind.hpp"
#include "krug/mesh/mesh.hpp"

namespace krug {

struct ZoneUpdateParams {
  double time_step_mid = 0.0;     // dt^n = (dt^{n-1/2} + dt^{n+1/2}) / 2
  double time_step_next = 0.0;    // dt^{n+1/2}, the step just taken by the positions
  double cfl = 0.5;
  double max_volume_change = 0.1;
  double shear_modulus = 0.0;     // adds 4 mu / (3 rho) to the squared wave speed
};

struct ZoneUpdateResult {
  double stable_time_step = std::numeric_limits<double>::infinity();
  Index controlling_zone = -1;
  Index failed_zone = -1;         // first zone that tangled or produced a non-finite value
  double internal_energy = 0.0;   // sum m e after the update
};

template <GeometryKind G, class EquationOfState>
ZoneUpdateResult update_zones(Mesh& mesh, Index zone_begin, Index zone_end, const EquationOfState& eos,
                              const ZoneUpdateParams& params) {
  constexpr bool axisymmetric = G == GeometryKind::axisymmetric;
  const NodeFields& nodes = mesh.nodes;
  ZoneFields& zones = mesh.zones;
  ZoneUpdateResult result;

  for (Index z = zone_begin; z < zone_end; ++z) {
    if (!zones.active[z]) continue;
    const ZoneCorners& n = zones.corners[z];
    const quad::Corners x = mesh.corner_positions(z);
    const double area = quad::area(x);
    const double volume = axisymmetric ? quad::axisymmetric_volume(x) : area;

    // Compatible energy: the work of the corner forces over the step at the mid-step velocity.
    const double* corner = &zones.corner_force[8 * static_cast<std::size_t>(z)];
    double work = 0.0;
    for (int p = 0; p < 4; ++p) {
      const double ubar = 0.5 * (nodes.u_old[n[p]] + nodes.u[n[p]]);
      const double vbar = 0.5 * (nodes.v_old[n[p]] + nodes.v[n[p]]);
      work += corner[2 * p] * ubar + corner[2 * p + 1] * vbar;
    }
    const double energy = zones.specific_energy[z] - params.time_step_mid * work / zones.mass[z];

    if (!(area > 0.0) || !(volume > 0.0) || !std::isfinite(energy)) {
      if (result.failed_zone < 0) result.failed_zone = z;
      continue;
    }
    const double old_volume = zones.volume[z];
    const double density = zones.mass[z] / volume;
    const double pressure = eos.pressure(density, energy);
    const double wave_speed_squared =
        eos.sound_speed_squared(density, energy, pressure) + 4.0 * params.shear_modulus / (3.0 * density);
    const double sound_speed = std::sqrt(std::max(wave_speed_squared, 0.0));

    zones.area[z] = area;
    zones.volume[z] = volume;
    zones.density[z] = density;
    zones.specific_energy[z] = energy;
    zones.pressure[z] = pressure;
    zones.sound_speed[z] = sound_speed;
    zones.volume_change[z] = std::abs(volume - old_volume) / old_volume;
    result.internal_energy += zones.mass[z] * energy;

    // Stable step: CFL with the viscous signal speed b (Wilkins), and the |dV/V| limit.
    const double length = quad::smallest_altitude(x, area);
    const double b = zones.viscous_speed[z];
    const double signal = b + std::sqrt(b * b + sound_speed * sound_speed);
    double dt = signal > 0.0 ? params.cfl * length / signal : std::numeric_limits<double>::infinity();
    if (zones.volume_change[z] > 0.0) {
      dt = std::min(dt, params.max_volume_change * params.time_step_next / zones.volume_change[z]);
    }
    if (dt < result.stable_time_step) {
      result.stable_time_step = dt;
      result.controlling_zone = z;
    }
  }
  return result;
}

}  // namespace krug
