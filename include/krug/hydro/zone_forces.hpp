#pragma once
// Step 1 of the time step: corner forces F^n of each zone on its four nodes (docs/theory.md §2).
//
// Stress: the corner forces are the exact adjoint of the zone's discrete strain rate,
// sum_p f_p . u_p = -V sigma : D for every velocity field, so that the internal-energy update
// m de = -dt sum_p f_p . ubar_p is both compatible (total energy to round-off) and thermodynamic.
//   planar:          f_p = -sigma b_p,                         b_p = dA/dx_p
//   axisymmetric CV: f_p = -[(V/A)(sigma_2D - sigma_tt I) b_p + sigma_tt c_p],   c_p = dV/dx_p
// where the hoop rate D_tt = dV/dt / V - dA/dt / A never divides by r. For a pressure f_p = p c_p.
// Axial forces of a zone sum to zero exactly (sum b_p = 0, sum c_p.z = 0).
//   axisymmetric area-weighted (Wilkins 1964): f_p = s_p [-sigma b_p + (A/4)(sigma_rr - sigma_tt)/rbar e_r],
//   s_p = M_p / M^A_p converting the area-weighted acceleration to a force on the nodal mass.
//
// The artificial forces (viscosity, subzonal pressures, hourglass control) are in
// krug/hydro/artificial_forces.hpp and tensor_viscosity.hpp; what the parts share is in
// krug/hydro/zone_batch.hpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "krug/hydro/artificial_forces.hpp"
#include "krug/hydro/tensor_viscosity.hpp"
#include "krug/hydro/zone_batch.hpp"

namespace krug {
namespace detail {

// Stress corner forces, sigma = s - p I, into the batch's forces (and mean radius V/A); one loop per
// form, so that each has no branch. Area-weighted RZ form: also the control-volume forces (work_x/y)
// and the area-weighted stress forces alone (planar_x/y).
template <GeometryKind G, bool AreaWeighted, bool ConsistentDeviator = false>
[[gnu::noinline]] inline void batch_stress_forces(ZoneBatch& batch, int count, Index first,
                                                     const StrengthZoneFields& strength) {
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    const std::array<Vec2, 4> b = batch.area_gradient(i);
    const double pressure = batch.pressure[i];
    const double sxx = strength.deviator_xx[z] - pressure;
    const double syy = strength.deviator_yy[z] - pressure;
    const double sxy = strength.deviator_xy[z];
    const double stt = strength.deviator_zz[z] - pressure;
    const double area = batch.area[i];
    if constexpr (G == GeometryKind::axisymmetric) {
      const quad::Corners x = batch.corners(i);
      const double volume = quad::axisymmetric_volume(x);
      const double mean_radius = volume / area;
      batch.mean_radius[i] = mean_radius;
      if constexpr (AreaWeighted) {
        // Accelerations from Wilkins' area-weighted forces (scaled by s_p at the scatter); the zone's
        // internal energy from the work of its control-volume forces, -V sigma : D (F4).
        const std::array<Vec2, 4> volume_gradient = quad::axisymmetric_volume_gradient(x);
        for (int p = 0; p < 4; ++p) {
          batch.fx[p][i] = -(sxx * b[p].x + sxy * b[p].y);
          batch.fy[p][i] = -(sxy * b[p].x + syy * b[p].y) + 0.25 * area * (syy - stt) / mean_radius;
          batch.planar_x[p][i] = batch.fx[p][i];
          batch.planar_y[p][i] = batch.fy[p][i];
          const Vec2 work = control_volume_force(sxx, syy, sxy, stt, mean_radius, b[p], volume_gradient[p]);
          batch.work_x[p][i] = work.x;
          batch.work_y[p][i] = work.y;
        }
      } else if constexpr (ConsistentDeviator) {
        const std::array<Vec2, 4> volume_gradient = quad::axisymmetric_volume_gradient(x);
        const std::array<Vec2, 4> in_plane = quad::axisymmetric_gradient_integrals(x);
        for (int p = 0; p < 4; ++p) {
          const Vec2 f = consistent_control_volume_force(sxx, syy, sxy, stt, in_plane[p], volume_gradient[p]);
          batch.fx[p][i] = f.x;
          batch.fy[p][i] = f.y;
        }
      } else {  // no deviator (a gas): only the pressure part, sigma_tt c_p, which both operators share
        const std::array<Vec2, 4> volume_gradient = quad::axisymmetric_volume_gradient(x);
        for (int p = 0; p < 4; ++p) {
          const Vec2 f = control_volume_force(sxx, syy, sxy, stt, mean_radius, b[p], volume_gradient[p]);
          batch.fx[p][i] = f.x;
          batch.fy[p][i] = f.y;
        }
      }
    } else {
      batch.mean_radius[i] = 1.0;
      for (int p = 0; p < 4; ++p) {
        batch.fx[p][i] = -(sxx * b[p].x + sxy * b[p].y);
        batch.fy[p][i] = -(sxy * b[p].x + syy * b[p].y);
      }
    }
  }
}

// Stores the batch's corner forces in hydro.corner_force (+0 for an inactive zone; the nodes add them
// up in zone order, `sum_corner_forces`) and adds the active zones' hourglass power, in zone order.
// Area-weighted RZ form: the node gets s_p times the area-weighted force, and the work correction
// turns that into the zone's own control-volume stress work plus its booked viscous and hourglass work.
template <GeometryKind G>
[[gnu::noinline]] inline void store_corner_forces(const ZoneBatch& batch, int count, Index first, const ZoneFields& zones,
                                                       HydroZoneFields& hydro, const ForceSettings settings,
                                                       AreaWeightedArrays area_weighted_arrays,
                                                       double& hourglass_power) {
  const bool area_weighted = G == GeometryKind::axisymmetric && settings.area_weighted;
  double power = hourglass_power;  // a local running sum, added to in the same order
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    double* corner = &hydro.corner_force[8 * static_cast<std::size_t>(z)];
    if (!zones.active[z]) {
      std::fill(corner, corner + 8, 0.0);
      continue;
    }
    if (settings.hourglass_on) power += batch.hourglass_power[i];
    if (area_weighted) {
      // Only approximately conservative: the booking weight w_p stands for the node's radius.
      const ZoneCorners& n = zones.corners[z];
      double* correction = &area_weighted_arrays.work_correction[8 * static_cast<std::size_t>(z)];
      for (int p = 0; p < 4; ++p) {
        const double s = area_weighted_arrays.scale[n[p]];
        const double w = area_weighted_arrays.booking[n[p]];
        corner[2 * p] = s * batch.fx[p][i];
        corner[2 * p + 1] = s * batch.fy[p][i];
        correction[2 * p] = batch.work_x[p][i] + w * (batch.fx[p][i] - batch.planar_x[p][i]) - corner[2 * p];
        correction[2 * p + 1] = batch.work_y[p][i] + w * (batch.fy[p][i] - batch.planar_y[p][i]) - corner[2 * p + 1];
      }
    } else {
      for (int p = 0; p < 4; ++p) {
        corner[2 * p] = batch.fx[p][i];
        corner[2 * p + 1] = batch.fy[p][i];
      }
    }
  }
  hourglass_power = power;
}

}  // namespace detail

// Stores the corner forces of the zones in [zone_begin, zone_end) in hydro.corner_force (zero for an
// inactive zone) and the viscous signal speed in hydro.viscous_speed; `sum_corner_forces` then adds
// them up at the nodes. Velocities are read from nodes.u/v (t^{n-1/2}). Writes nothing outside its
// zones, so that blocks of zones can be computed on different threads. Area-weighted RZ form only: the
// stored forces are the nodes' (s_p times the area-weighted ones), and `area_weighted_arrays.work_correction`
// receives what turns their work into the zone's own (control-volume) stress work plus its booked
// viscous and hourglass work. Reads the mesh, hydro.pressure and sound_speed, `strength` and
// fracture.damaged; writes hydro.corner_force and viscous_speed and `hourglass`, and with the tensor
// viscosity, where `damping.rows` is given, its damping's row sums (4 per zone, batch_tensor_viscosity).
template <GeometryKind G, ViscosityModel Visc>
ArtificialPower compute_corner_forces(const Mesh& mesh, HydroZoneFields& hydro, const StrengthZoneFields& strength,
                                      HourglassZoneFields& hourglass, const FractureZoneFields& fracture,
                                      Index zone_begin, Index zone_end, const ZoneForceParams& params,
                                      AreaWeightedArrays area_weighted_arrays = {},
                                      SharedEdgeLimiters shared_limiters = {}, DampingRows damping = {}) {
  detail::ForceSettings settings;
  settings.area_weighted = G == GeometryKind::axisymmetric && params.axisymmetric_form == AxisymmetricForm::area_weighted;
  // k_s mu, or E'/3 in the physical form: without shear stiffness (a gas, or k_s = 0 in the coefficient
  // form) the stiffness state never changes.
  settings.physical_stiffness = params.hourglass.stiffness_form == HourglassStiffness::physical;
  settings.stiffness_modulus = settings.physical_stiffness ? params.bending_modulus / 3.0
                                                           : params.hourglass.stiffness * params.shear_modulus;
  settings.hourglass_on = params.hourglass.viscous > 0.0 || settings.stiffness_modulus > 0.0;
  settings.hourglass_stiff = settings.stiffness_modulus != 0.0;
  if (std::isfinite(params.flow_stress)) settings.hourglass_bound = params.hourglass.plastic_limit * params.flow_stress;
  settings.cq_s = params.viscosity.quadratic * params.shock_slope;
  settings.cl = params.viscosity.linear;
  // Subzonal pressures: bodies without strength, compatible forms only.
  settings.consistent_deviator = G == GeometryKind::axisymmetric && !settings.area_weighted && params.shear_modulus != 0.0;
  settings.subzonal = params.shear_modulus == 0.0 && !settings.area_weighted ? params.hourglass.subzonal_pressure : 0.0;
  // Only the tensor viscosity marks the shocks; with another model (which the scenario reader refuses)
  // the subzonal pressures act everywhere rather than nowhere.
  settings.subzonal_at_shocks = Visc == ViscosityModel::tensor && params.hourglass.subzonal_at_shocks;
  // The corner-collapse pressure: every body, compatible forms only.
  settings.collapse = !settings.area_weighted ? params.hourglass.collapse_pressure.value_or(0.0) : 0.0;
  settings.collapse_threshold = params.hourglass.collapse_threshold;
  const bool corner_pressures = settings.subzonal > 0.0 || settings.collapse > 0.0;
  const ZoneFields& zones = mesh.zones;
  ArtificialPower power;
  detail::ZoneBatch batch;

  for (Index first = zone_begin; first < zone_end; first += detail::zone_batch) {
    const int count = static_cast<int>(std::min<Index>(detail::zone_batch, zone_end - first));
    batch.gather(mesh, first, count);
    detail::batch_geometry<Visc>(batch, count, first, hydro);
    if constexpr (Visc == ViscosityModel::scalar) {
      detail::batch_scalar_viscosity<G>(batch, count, first, zones, hydro, settings, power.viscous);
    }
    if (settings.area_weighted) {
      detail::batch_stress_forces<G, true>(batch, count, first, strength);
    } else if (settings.consistent_deviator) {
      detail::batch_stress_forces<G, false, true>(batch, count, first, strength);
    } else {
      detail::batch_stress_forces<G, false>(batch, count, first, strength);
    }
    if (corner_pressures && !settings.subzonal_at_shocks) {
      detail::batch_subzonal_pressure<G>(batch, count, first, zones, hydro, settings);
    }
    if constexpr (Visc == ViscosityModel::edge) {
      detail::batch_edge_viscosity<G>(batch, count, first, mesh, hydro, zone_begin, params, settings, area_weighted_arrays,
                                      shared_limiters, power.viscous);
    }
    if constexpr (Visc == ViscosityModel::tensor) {
      detail::batch_tensor_viscosity<G>(batch, count, first, mesh, hydro, zone_begin, params, settings,
                                        area_weighted_arrays, shared_limiters, power.viscous, damping);
      // At shocks only: after the tensor viscosity, which marks them (batch.shock).
      if (corner_pressures && settings.subzonal_at_shocks) {
        detail::batch_subzonal_pressure<G>(batch, count, first, zones, hydro, settings);
      }
    }
    if (settings.hourglass_on) {
      detail::batch_hourglass_forces<G>(batch, count, first, zones, hydro, hourglass, fracture, params, settings);
    }
    detail::store_corner_forces<G>(batch, count, first, zones, hydro, settings, area_weighted_arrays, power.hourglass);
  }
  return power;
}

// The force on each node of [node_begin, node_end): the sum of the corner forces of its zones, in zone
// order (`corners` lists each node's corner slots 4 z + p, sorted by zone). An inactive zone's corner
// forces are +0 (compute_corner_forces), and adding +0 leaves a sum started at +0 bitwise unchanged, so
// no test of `active` is needed.
inline void sum_corner_forces(NodeFields& nodes, const HydroZoneFields& hydro, const NodeCorners& corners,
                              Index node_begin, Index node_end) {
  const double* corner_force = hydro.corner_force.data();
  for (Index node = node_begin; node < node_end; ++node) {
    double fx = 0.0, fy = 0.0;
    for (Index k = corners.offset[node]; k < corners.offset[node + 1]; ++k) {
      const std::size_t slot = static_cast<std::size_t>(corners.slot[k]);
      fx += corner_force[2 * slot];
      fy += corner_force[2 * slot + 1];
    }
    nodes.force_x[node] = fx;
    nodes.force_y[node] = fy;
  }
}

// The scale of each node's damping rows (DampingRows::node_scale) for the nodes in [node_begin, node_end):
// 1 / sqrt(m_p), 0 for a node held in both components; `mass_scale`: the area-weighted RZ form's s_p (its
// nodes move as if of mass M_p / s_p, so sqrt(s_p / M_p); 0 where s_p <= 0), else null.
inline void damping_node_scale(const NodeFields& nodes, Index node_begin, Index node_end, double* node_scale,
                               const double* mass_scale = nullptr) {
  for (Index node = node_begin; node < node_end; ++node) {
    const bool held = nodes.inv_mass_x[node] == 0.0 && nodes.inv_mass_y[node] == 0.0;
    const double s = mass_scale ? mass_scale[node] : 1.0;
    const double root = mass_scale ? std::sqrt(s / nodes.mass[node]) : 1.0 / std::sqrt(nodes.mass[node]);
    node_scale[node] = held || !(s > 0.0) ? 0.0 : root;
  }
}

// The tensor viscosity's damping at the nodes of a range: the largest step over which it alone stays
// stable there, and the node that sets it (-1 where no node is damped).
struct DampingBound {
  double step = std::numeric_limits<double>::infinity();
  Index node = -1;

  // The bound of two ranges, this one's nodes first.
  void merge(const DampingBound& other) {
    if (other.step < step) {
      step = other.step;
      node = other.node;
    }
  }
};

// The damping bound over the nodes in [node_begin, node_end) with a free component: 2 min sqrt(m_p) / R_p,
// R_p the sum of the damping rows (batch_tensor_viscosity) of the node's corners, in the node's corner
// order. R_p / sqrt(m_p) is the radius of the node's Gershgorin disc of M^-1/2 C M^-1/2 (C symmetric, so
// its eigenvalues are those of M^-1 C), and forward Euler on M du/dt = -C u is stable while dt times the
// largest eigenvalue stays within 2. `node_scale` as damping_node_scale wrote it; `mass_scale` as given there.
inline DampingBound damping_bound(const NodeFields& nodes, const double* damping_rows, const double* node_scale,
                                  const NodeCorners& corners, Index node_begin, Index node_end,
                                  const double* mass_scale = nullptr) {
  DampingBound bound;
  for (Index node = node_begin; node < node_end; ++node) {
    if (!(node_scale[node] > 0.0)) continue;
    double row = 0.0;
    for (Index k = corners.offset[node]; k < corners.offset[node + 1]; ++k) {
      row += damping_rows[static_cast<std::size_t>(corners.slot[k])];
    }
    if (!(row > 0.0)) continue;
    const double s = mass_scale ? mass_scale[node] : 1.0;
    const double step = 2.0 * std::sqrt(nodes.mass[node] / s) / row;
    if (step < bound.step) {
      bound.step = step;
      bound.node = node;
    }
  }
  return bound;
}

}  // namespace krug
