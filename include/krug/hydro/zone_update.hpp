#pragma once
// Step 5 of the time step for one body: new geometry at t^{n+1}, density, compatible internal energy
// m de = -dt^n sum_p f_p . ubar_p (ubar = mid-step velocity), pressure and sound speed from the EOS,
// and each zone's stable time step for step 8 (docs/theory.md §2).
#include <algorithm>
#include <cmath>
#include <limits>

#include <type_traits>

#include "krug/core/geometry_kind.hpp"
#include "krug/material/strength.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/hydro/corner_batch.hpp"

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
  double plastic_work = 0.0;      // plastic work of this step (J per radian or per m)
};

// Velocity gradient, strain rate and spin of a zone from u^{n+1/2} on the mid-step geometry
// x^{n+1/2} = x^{n+1} - dt^{n+1/2} u^{n+1/2} / 2. In-plane: L = (1/A) sum_p u_p (x) dA/dx_p (Wilkins);
// hoop (RZ): D_tt = (dV/dt)/V - (dA/dt)/A with the same mid-step gradients (never divides by r).
template <GeometryKind G>
[[gnu::always_inline]] inline void mid_step_rates(const quad::Corners& x_new, const std::array<Vec2, 4>& u, double dt,
                           StrainRate& rate, double& spin) {
  quad::Corners mid;
  for (int p = 0; p < 4; ++p) mid[p] = x_new[p] - (0.5 * dt) * u[p];
  rate.zz = 0.0;
  if constexpr (G == GeometryKind::axisymmetric) {
    // The adjoint of the deviatoric corner force: the velocity gradient (1/V) sum_p u_p (x) B_p with
    // the r-weighted operator B_p, and the hoop rate (dV/dt)/V minus its trace.
    const std::array<Vec2, 4> in_plane = quad::axisymmetric_gradient_integrals(mid);
    const std::array<Vec2, 4> c = quad::axisymmetric_volume_gradient(mid);
    double volume_rate = 0.0;
    for (int p = 0; p < 4; ++p) volume_rate += dot(u[p], c[p]);
    const quad::Tensor2 g = quad::outer_sum(u, in_plane);
    const double inv_volume = 1.0 / quad::axisymmetric_volume(mid);
    rate.xx = g.xx * inv_volume;
    rate.yy = g.yy * inv_volume;
    rate.xy = 0.5 * (g.xy + g.yx) * inv_volume;
    rate.zz = volume_rate * inv_volume - (g.xx + g.yy) * inv_volume;
    spin = in_plane_spin(g.yx * inv_volume, g.xy * inv_volume);
  } else {
    const quad::Tensor2 g = quad::outer_sum(u, quad::area_gradient(mid));  // A times the velocity gradient
    const double inv_area = 1.0 / quad::area(mid);
    rate.xx = g.xx * inv_area;
    rate.yy = g.yy * inv_area;
    rate.xy = 0.5 * (g.xy + g.yx) * inv_area;
    spin = in_plane_spin(g.yx * inv_area, g.xy * inv_area);
  }
}

namespace detail {

// With strength, the strain rate and spin (and the area and volume at t^{n+1}) of a batch of zones,
// from their corner positions and velocities gathered into arrays: a loop without branches that the
// compiler vectorises (the same operations as for one zone at a time).
constexpr int update_batch = 32;

struct UpdateBatch : CornerBatch<update_batch> {  // corner positions x^{n+1}, velocities u^{n+1/2}
  double area[update_batch], volume[update_batch];
  double rate_xx[update_batch], rate_yy[update_batch], rate_xy[update_batch], rate_zz[update_batch];
  double spin[update_batch];
};

}  // namespace detail

// Updates the zones of [zone_begin, zone_end); writes nothing outside them, so that blocks of zones can
// be updated on different threads. `work_correction` (8 per zone, area-weighted RZ form only, else
// null) is added to the corner forces' work: it makes the work the zone's own control-volume stress work.
// Reads the positions and velocities, hydro.corner_force and viscous_speed and fracture.damaged; writes
// the zones' geometry, density and specific energy, the rest of `hydro` and (with strength) `strength`.
template <GeometryKind G, class EquationOfState, class StrengthModel>
ZoneUpdateResult update_zones(Mesh& mesh, HydroZoneFields& hydro, StrengthZoneFields& strength,
                              const FractureZoneFields& fracture, Index zone_begin, Index zone_end,
                              const EquationOfState& material_eos,
                              const StrengthModel& material_strength, const ZoneUpdateParams& params,
                              const double* work_correction = nullptr) {
  // Local copies: the compiler then knows that the zone stores do not change the material
  // parameters, and keeps what depends only on them (such as the EOS's compression limit) out of the loop.
  const EquationOfState eos = material_eos;
  const StrengthModel strength_model = material_strength;
  constexpr bool has_strength = !std::is_same_v<StrengthModel, NoStrength>;
  constexpr bool axisymmetric = G == GeometryKind::axisymmetric;
  const NodeFields& nodes = mesh.nodes;
  ZoneFields& zones = mesh.zones;
  ZoneUpdateResult result;
  double result_plastic_work = 0.0;
  detail::UpdateBatch batch;

  for (Index first = zone_begin; first < zone_end; first += detail::update_batch) {
    const int count = static_cast<int>(std::min<Index>(detail::update_batch, zone_end - first));

    // With strength, the strain rate and spin of the step (the mid-step geometry), batched.
    if constexpr (has_strength) {
      batch.gather(mesh, first, count);
      for (int i = 0; i < count; ++i) {
        const quad::Corners x = batch.corners(i);
        batch.area[i] = quad::area(x);
        batch.volume[i] = axisymmetric ? quad::axisymmetric_volume(x) : batch.area[i];
        StrainRate rate;
        double spin = 0.0;
        mid_step_rates<G>(x, batch.velocities(i), params.time_step_next, rate, spin);
        batch.rate_xx[i] = rate.xx;
        batch.rate_yy[i] = rate.yy;
        batch.rate_xy[i] = rate.xy;
        batch.rate_zz[i] = rate.zz;
        batch.spin[i] = spin;
      }
    }

    for (int i = 0; i < count; ++i) {
      const Index z = first + i;
      if (!zones.active[z]) continue;
      const ZoneCorners& n = zones.corners[z];
      const quad::Corners x = mesh.corner_positions(z);
      const double area = has_strength ? batch.area[i] : quad::area(x);
      const double volume = has_strength ? batch.volume[i] : axisymmetric ? quad::axisymmetric_volume(x) : area;

      // Compatible energy: the work of the corner forces over the step at the mid-step velocity.
      const double* corner = &hydro.corner_force[8 * static_cast<std::size_t>(z)];
      const auto work_of = [&](auto force) {  // force(j): component j of the 8 corner values
        double sum = 0.0;
        for (int p = 0; p < 4; ++p) {
          const double ubar = 0.5 * (nodes.u_old[n[p]] + nodes.u[n[p]]);
          const double vbar = 0.5 * (nodes.v_old[n[p]] + nodes.v[n[p]]);
          sum += force(2 * p) * ubar + force(2 * p + 1) * vbar;
        }
        return sum;
      };
      const double* correction = work_correction ? &work_correction[8 * static_cast<std::size_t>(z)] : nullptr;
      const double work = correction ? work_of([&](int j) { return corner[j] + correction[j]; })
                                     : work_of([&](int j) { return corner[j]; });
      const double energy = zones.specific_energy[z] - params.time_step_mid * work / zones.mass[z];

      if (!(area > 0.0) || !(volume > 0.0) || !std::isfinite(energy)) {
        if (result.failed_zone < 0) result.failed_zone = z;
        continue;
      }
      const double old_volume = zones.volume[z];
      const double density = zones.mass[z] / volume;

      const bool damaged = fracture.damaged[z] != 0;
      if constexpr (has_strength) {
        if (!damaged) {  // a damaged zone keeps s = 0
          // Deviator over [t^n, t^{n+1}]: rotate by the spin, Hooke trial, radial return (material/strength.hpp).
          const StrainRate rate{batch.rate_xx[i], batch.rate_yy[i], batch.rate_xy[i], batch.rate_zz[i]};
          const Deviator previous{strength.deviator_xx[z], strength.deviator_yy[z], strength.deviator_xy[z],
                                  strength.deviator_zz[z]};
          PlasticState state;
          state.plastic_strain = strength.plastic_strain[z];
          if constexpr (std::is_same_v<StrengthModel, JohnsonCook>) {
            state.strain_rate = equivalent_strain_rate(rate);
            state.temperature = strength_model.temperature_from_energy(energy);
          }
          const PlasticReturn plastic =
              update_deviator(strength_model, previous, rate, batch.spin[i], params.time_step_next, state);
          strength.deviator_xx[z] = plastic.deviator.xx;
          strength.deviator_yy[z] = plastic.deviator.yy;
          strength.deviator_xy[z] = plastic.deviator.xy;
          strength.deviator_zz[z] = plastic.deviator.zz;
          strength.plastic_strain[z] += plastic.plastic_strain_increment;
          result_plastic_work += plastic.plastic_work_density * 0.5 * (volume + old_volume);
        }
      }
      // A damaged zone resists only volumetric compression (docs/theory.md §2 step 6).
      const double pressure = damaged ? std::max(eos.pressure(density, energy), 0.0) : eos.pressure(density, energy);
      double wave_speed_squared = eos.sound_speed_squared(density, energy, pressure);
      if constexpr (has_strength) {  // a gas has no shear wave: no division for it
        wave_speed_squared += damaged ? 0.0 : 4.0 * params.shear_modulus / (3.0 * density);
      }
      const double sound_speed = std::sqrt(std::max(wave_speed_squared, 0.0));

      zones.area[z] = area;
      zones.volume[z] = volume;
      zones.density[z] = density;
      zones.specific_energy[z] = energy;
      hydro.pressure[z] = pressure;
      hydro.sound_speed[z] = sound_speed;
      hydro.volume_change[z] = std::abs(volume - old_volume) / old_volume;
      result.internal_energy += zones.mass[z] * energy;

      // Stable step: CFL with the viscous signal speed b (Wilkins), and the |dV/V| limit.
      const double length = quad::stable_length(x, area);
      const double b = hydro.viscous_speed[z];
      const double signal = b + std::sqrt(b * b + sound_speed * sound_speed);
      double dt = signal > 0.0 ? params.cfl * length / signal : std::numeric_limits<double>::infinity();
      if (hydro.volume_change[z] > 0.0) {
        dt = std::min(dt, params.max_volume_change * params.time_step_next / hydro.volume_change[z]);
      }
      hydro.stable_time_step[z] = dt;
      if (dt < result.stable_time_step) {
        result.stable_time_step = dt;
        result.controlling_zone = z;
      }
    }
  }
  result.plastic_work = result_plastic_work;
  return result;
}

}  // namespace krug
