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

// A zone's stable step (docs/theory.md §2 step 8): the CFL step over its stable length with the
// viscous signal speed b (Wilkins), b + (b^2 + c^2)^1/2, and the limit on |dV/V| per step.
[[gnu::always_inline]] inline double zone_stable_step(double length, double sound_speed, double viscous_speed,
                                                      double volume_change, double cfl, double max_volume_change,
                                                      double time_step_next) {
  const double b = viscous_speed;
  const double signal = b + std::sqrt(b * b + sound_speed * sound_speed);
  const double dt = signal > 0.0 ? cfl * length / signal : std::numeric_limits<double>::infinity();
  return volume_change > 0.0 ? std::min(dt, max_volume_change * time_step_next / volume_change) : dt;
}

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

// The zones are updated in batches: their corner positions and velocities (u^{n-1/2} and u^{n+1/2})
// are gathered into arrays, everything a zone's update computes is computed for the whole batch in
// loops without branches that the compiler vectorises (the same operations as for one zone at a
// time, so the results do not depend on the batching), and a last loop in zone order stores the
// results of the active zones, books the sums and finds the controlling zone.
constexpr int update_batch = 32;

struct UpdateBatch : CornerBatch<update_batch> {  // corner positions x^{n+1}, velocities u^{n+1/2}
  double u_old[4][update_batch], v_old[4][update_batch];  // corner velocities u^{n-1/2}
  double area[update_batch], volume[update_batch], length[update_batch];
  double rate_xx[update_batch], rate_yy[update_batch], rate_xy[update_batch], rate_zz[update_batch];
  double spin[update_batch];
  // What the update computes (stored for the active zones only).
  double energy[update_batch], density[update_batch], pressure[update_batch], sound_speed[update_batch];
  double volume_change[update_batch], stable_step[update_batch];
  double s_xx[update_batch], s_yy[update_batch], s_xy[update_batch], s_zz[update_batch];
  double plastic_increment[update_batch], plastic_work_density[update_batch];
  // 1 where cos_sin's polynomial does not hold: the zone's deviator is redone. Flags are doubles, not
  // bools, in these loops: GCC 12 does not vectorise a loop that mixes byte and double elements.
  double large_rotation[update_batch];
  double damaged[update_batch];  // 1 for a damaged zone

  void gather_old_velocities_and_damage(const Mesh& mesh, const FractureZoneFields& fracture, Index first,
                                        int count) {
    const NodeFields& nodes = mesh.nodes;
    for (int i = 0; i < count; ++i) {
      damaged[i] = fracture.damaged[first + i] != 0 ? 1.0 : 0.0;
      const ZoneCorners& n = mesh.zones.corners[first + i];
      for (int p = 0; p < 4; ++p) {
        u_old[p][i] = nodes.u_old[n[p]];
        v_old[p][i] = nodes.v_old[n[p]];
      }
    }
  }
};

// The deviator update of material/strength.hpp (update_deviator, exact rotation), with cos and sin of
// the doubled angle by cos_sin's polynomial only, so that it has no branch to a library call; where
// the polynomial does not hold (|2 omega dt| > 1/16, `large`) the caller redoes the zone with
// update_deviator. Otherwise the same operations in the same order.
template <class StrengthModel>
[[gnu::always_inline]] inline PlasticReturn update_deviator_small_rotation(const StrengthModel& model,
                                                                           const Deviator& s, const StrainRate& rate,
                                                                           double spin, double dt,
                                                                           const PlasticState& state, double& large) {
  const double x = 2.0 * rotation_angle(spin, dt);
  large = std::abs(x) <= 0.0625 ? 0.0 : 1.0;
  const double x2 = x * x;
  const double cos2 = 1.0 + x2 * (-1.0 / 2.0 + x2 * (1.0 / 24.0 + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40320.0))));
  const double sin2 = x + x * (x2 * (-1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362880.0)))));
  const double mean = 0.5 * (s.xx + s.yy);
  const double half_difference = 0.5 * (s.xx - s.yy);
  const double axial = half_difference * cos2 - s.xy * sin2;
  const Deviator rotated{mean + axial, mean - axial, half_difference * sin2 + s.xy * cos2, s.zz};
  const Deviator trial = hooke_trial(rotated, rate, model.shear_modulus, dt);
  return radial_return(model, trial, state);
}

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
  const ZoneUpdateParams step = params;
  constexpr bool has_strength = !std::is_same_v<StrengthModel, NoStrength>;
  constexpr bool axisymmetric = G == GeometryKind::axisymmetric;
  ZoneFields& zones = mesh.zones;
  ZoneUpdateResult result;
  double result_plastic_work = 0.0;
  detail::UpdateBatch batch;

  // The batch's update in three loops (each vectorised on its own), the first with or without the
  // area-weighted form's work correction: geometry, density and energy; the deviator; the EOS, the
  // sound speed and the stable step.
  const auto geometry_and_energy = [&](Index first, int count, auto corrected) {
    for (int i = 0; i < count; ++i) {
      const Index z = first + i;
      const quad::Corners x = batch.corners(i);
      const double area = quad::area(x);
      const double volume = axisymmetric ? quad::axisymmetric_volume(x) : area;
      batch.area[i] = area;
      batch.volume[i] = volume;
      batch.length[i] = quad::stable_length(x, area);

      // Compatible energy: the work of the corner forces over the step at the mid-step velocity.
      const double* corner = &hydro.corner_force[8 * static_cast<std::size_t>(z)];
      double work = 0.0;
      for (int p = 0; p < 4; ++p) {
        const double ubar = 0.5 * (batch.u_old[p][i] + batch.u[p][i]);
        const double vbar = 0.5 * (batch.v_old[p][i] + batch.v[p][i]);
        if constexpr (decltype(corrected)::value) {
          const double* correction = &work_correction[8 * static_cast<std::size_t>(z)];
          work += (corner[2 * p] + correction[2 * p]) * ubar + (corner[2 * p + 1] + correction[2 * p + 1]) * vbar;
        } else {
          work += corner[2 * p] * ubar + corner[2 * p + 1] * vbar;
        }
      }
      const double old_volume = zones.volume[z];
      batch.energy[i] = zones.specific_energy[z] - step.time_step_mid * work / zones.mass[z];
      batch.density[i] = zones.mass[z] / volume;
      batch.volume_change[i] = std::abs(volume - old_volume) / old_volume;
    }
  };
  // Zone z's deviator and its yield law's inputs (batch index i) at the start of the step.
  const auto start_deviator = [&](Index z) {
    return Deviator{strength.deviator_xx[z], strength.deviator_yy[z], strength.deviator_xy[z],
                    strength.deviator_zz[z]};
  };
  const auto start_state = [&](Index z, [[maybe_unused]] int i, [[maybe_unused]] const StrainRate& rate) {
    PlasticState state;
    state.plastic_strain = strength.plastic_strain[z];
    if constexpr (std::is_same_v<StrengthModel, JohnsonCook>) {
      state.strain_rate = equivalent_strain_rate(rate);
      state.temperature = strength_model.temperature_from_energy(batch.energy[i]);
    }
    return state;
  };
  // Deviator over [t^n, t^{n+1}]: rotate by the spin, Hooke trial, radial return (material/strength.hpp).
  const auto deviator = [&](Index first, int count) {
    for (int i = 0; i < count; ++i) {
      const Index z = first + i;
      StrainRate rate;
      double spin = 0.0;
      mid_step_rates<G>(batch.corners(i), batch.velocities(i), step.time_step_next, rate, spin);
      batch.rate_xx[i] = rate.xx;
      batch.rate_yy[i] = rate.yy;
      batch.rate_xy[i] = rate.xy;
      batch.rate_zz[i] = rate.zz;
      batch.spin[i] = spin;
      const Deviator previous = start_deviator(z);
      const PlasticState state = start_state(z, i, rate);
      double large = 0.0;
      const PlasticReturn plastic = detail::update_deviator_small_rotation(strength_model, previous, rate, spin,
                                                                           step.time_step_next, state, large);
      batch.large_rotation[i] = large;
      batch.s_xx[i] = plastic.deviator.xx;
      batch.s_yy[i] = plastic.deviator.yy;
      batch.s_xy[i] = plastic.deviator.xy;
      batch.s_zz[i] = plastic.deviator.zz;
      batch.plastic_increment[i] = plastic.plastic_strain_increment;
      batch.plastic_work_density[i] = plastic.plastic_work_density;
    }
  };
  const auto state_and_step = [&](Index first, int count) {
    for (int i = 0; i < count; ++i) {
      const Index z = first + i;
      const double density = batch.density[i];
      const double energy = batch.energy[i];
      // A damaged zone resists only volumetric compression (docs/theory.md §2 step 6).
      const bool damaged = batch.damaged[i] != 0.0;
      const double eos_pressure = eos.pressure(density, energy);
      const double pressure = damaged ? std::max(eos_pressure, 0.0) : eos_pressure;
      double wave_speed_squared = eos.sound_speed_squared(density, energy, pressure);
      if constexpr (has_strength) {  // a gas has no shear wave: no division for it
        wave_speed_squared += damaged ? 0.0 : 4.0 * step.shear_modulus / (3.0 * density);
      }
      const double sound_speed = std::sqrt(std::max(wave_speed_squared, 0.0));
      batch.pressure[i] = pressure;
      batch.sound_speed[i] = sound_speed;

      batch.stable_step[i] = zone_stable_step(batch.length[i], sound_speed, hydro.viscous_speed[z], batch.volume_change[i],
                                              step.cfl, step.max_volume_change, step.time_step_next);
    }
  };

  for (Index first = zone_begin; first < zone_end; first += detail::update_batch) {
    const int count = static_cast<int>(std::min<Index>(detail::update_batch, zone_end - first));
    batch.gather(mesh, first, count);
    batch.gather_old_velocities_and_damage(mesh, fracture, first, count);
    if (work_correction) {
      geometry_and_energy(first, count, std::true_type{});
    } else {
      geometry_and_energy(first, count, std::false_type{});
    }
    if constexpr (has_strength) deviator(first, count);
    state_and_step(first, count);

    // Store, in zone order, what the active zones computed.
    for (int i = 0; i < count; ++i) {
      const Index z = first + i;
      if (!zones.active[z]) continue;
      if (!(batch.area[i] > 0.0) || !(batch.volume[i] > 0.0) || !std::isfinite(batch.energy[i])) {
        if (result.failed_zone < 0) result.failed_zone = z;
        continue;
      }
      const double volume = batch.volume[i];
      if constexpr (has_strength) {
        if (fracture.damaged[z] == 0) {  // a damaged zone keeps s = 0
          PlasticReturn plastic{{batch.s_xx[i], batch.s_yy[i], batch.s_xy[i], batch.s_zz[i]},
                                batch.plastic_increment[i], batch.plastic_work_density[i], false};
          if (batch.large_rotation[i] != 0.0) {
            const StrainRate rate{batch.rate_xx[i], batch.rate_yy[i], batch.rate_xy[i], batch.rate_zz[i]};
            plastic = update_deviator(strength_model, start_deviator(z), rate, batch.spin[i], step.time_step_next,
                                      start_state(z, i, rate));
          }
          strength.deviator_xx[z] = plastic.deviator.xx;
          strength.deviator_yy[z] = plastic.deviator.yy;
          strength.deviator_xy[z] = plastic.deviator.xy;
          strength.deviator_zz[z] = plastic.deviator.zz;
          strength.plastic_strain[z] += plastic.plastic_strain_increment;
          result_plastic_work += plastic.plastic_work_density * 0.5 * (volume + zones.volume[z]);
        }
      }
      zones.area[z] = batch.area[i];
      zones.volume[z] = volume;
      zones.density[z] = batch.density[i];
      zones.specific_energy[z] = batch.energy[i];
      hydro.pressure[z] = batch.pressure[i];
      hydro.sound_speed[z] = batch.sound_speed[i];
      hydro.volume_change[z] = batch.volume_change[i];
      result.internal_energy += zones.mass[z] * batch.energy[i];
      const double dt = batch.stable_step[i];
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
