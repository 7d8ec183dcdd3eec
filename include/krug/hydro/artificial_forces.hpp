#pragma once
// Step 1's artificial forces on a batch of zones (the parts of compute_corner_forces, zone_forces.hpp):
// the scalar and the edge viscosity, subzonal pressures and hourglass control (the tensor viscosity is
// in tensor_viscosity.hpp).
//
// Artificial viscosity, edge form (Caramana, Shashkov & Whalen 1998): on each compressing edge
// (du . dx < 0) the damper force kappa du acts between its nodes,
//   kappa |du| = rho (1 - psi) [c_q s |du| + sqrt(c_q^2 s^2 |du|^2 + c_l^2 c^2)] |S| |cos| (x w_S in RZ CV),
// S the median-mesh segment from the zone centre to the edge midpoint, cos the cosine between du and
// the normal of S (a velocity difference along S, a shear across the edge, gets no viscosity: without
// this factor Saltzman's skewed grid tangled, docs/verification.md F5); psi the limiter built from the
// velocity gradients of the continuing edges (psi = 1 for a velocity field linear along the edge), so
// the viscosity stays off in uniform compression. The damper only dissipates: power = -kappa |du|^2.
//
// Hourglass (Flanagan & Belytschko 1981): f_p = -(Q_visc + Q_stiff) gamma_p with
// Q_visc = k_v rho c sqrt(A) q, dQ_stiff = k_s mu dt (b.b/A) q, q = sum_p gamma_p u_p.
#include <algorithm>
#include <cstdint>
#include <cmath>
#include <limits>

#include "krug/hydro/zone_batch.hpp"

namespace krug {
namespace detail {

// Scalar viscosity: Wilkins' q from the volumetric strain rate div u = (dV/dt)/V, compression only,
// added to the batch's pressure; writes hydro.viscous_speed and adds its dissipation q (-dV/dt) to
// `viscous_power` in zone order (the rate of work the edge model books as its dampers' dissipation).
template <GeometryKind G>
[[gnu::noinline]] inline void batch_scalar_viscosity(ZoneBatch& batch, int count, Index first, const ZoneFields& zones,
                                                          HydroZoneFields& hydro, const ForceSettings settings,
                                                          double& viscous_power) {
  double power = viscous_power;
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    if (!zones.active[z]) continue;
    const quad::Corners x = batch.corners(i);
    const std::array<Vec2, 4> u = batch.velocities(i);
    const std::array<Vec2, 4> b = batch.area_gradient(i);
    const double area = batch.area[i];
    double volume = area;
    std::array<Vec2, 4> volume_gradient = b;
    if constexpr (G == GeometryKind::axisymmetric) {
      volume = quad::axisymmetric_volume(x);
      volume_gradient = quad::axisymmetric_volume_gradient(x);
    }
    double volume_rate = 0.0;
    for (int p = 0; p < 4; ++p) volume_rate += dot(u[p], volume_gradient[p]);
    const double divergence = volume_rate / volume;
    const double rho = zones.density[z];
    if (divergence < 0.0) {
      const double length = quad::smallest_altitude(x, area);
      const double speed = settings.cq_s * length * -divergence;
      const double q = rho * length * -divergence * (settings.cq_s * length * -divergence + settings.cl * hydro.sound_speed[z]);
      batch.pressure[i] += q;
      hydro.viscous_speed[z] = 2.0 * speed;
      power += q * -volume_rate;
    } else {
      hydro.viscous_speed[z] = 0.0;
    }
  }
  viscous_power = power;
}

// Corner p's region of the median mesh (quad::corner_region), built from its components: an aggregate
// copy of x would not vectorise.
[[gnu::always_inline]] inline quad::Corners corner_region_of(const quad::Corners& x, Vec2 middle, int p) {
  const Vec2 corner{x[p].x, x[p].y};
  return {corner, 0.5 * (corner + x[quad::next(p)]), Vec2{middle.x, middle.y}, 0.5 * (x[quad::prev(p)] + corner)};
}

// Its volume measure: area, or the integral of r dA in axisymmetric geometry.
template <GeometryKind G>
[[gnu::always_inline]] inline double corner_region_volume(const quad::Corners& region) {
  if constexpr (G == GeometryKind::axisymmetric) {
    return quad::axisymmetric_volume(region);
  } else {
    return quad::area(region);
  }
}

// Subzonal pressure forces (Caramana & Shashkov, J. Comput. Phys. 142, 1998), added to the batch's
// forces. Corner p's region of the median mesh, S_p = (x_p, (x_p + x_p+1)/2, centre, (x_p-1 + x_p)/2),
// keeps its initial mass m_p (zones.subzone_mass); its density m_p / V(S_p) differs from the zone's
// when the zone distorts, and the difference dp_p = k c^2 (rho_p - rho) acts on the nodes as the
// pressure of a region does: f_q += dp_p dV(S_p)/dx_q, with V the zone's volume measure (area, or
// integral of r dA in axisymmetric geometry). These are corner forces like the others, so the
// compatible update books their work in the zone's internal energy: momentum and energy stay exact.
// For motion that keeps the regions' volume ratios (affine motion; in RZ also a uniform scaling about
// the origin) every dp_p is zero.
//
// The corner-collapse pressure (settings.collapse) is the same force with a dead band: it adds
// dp_p = k_c c^2 (rho_p - theta rho) where that is positive, theta the threshold (1.5 by default), and
// nothing elsewhere. A corner region whose density reaches theta times its zone's is a corner folding
// into the zone; the one-point hourglass control sees only the zone's mean mode and lets it fold.
template <GeometryKind G>
[[gnu::noinline]] inline void batch_subzonal_pressure(ZoneBatch& batch, int count, Index first, const ZoneFields& zones,
                                                         const HydroZoneFields& hydro, const ForceSettings settings) {
  // Without branches over the batch (it vectorises): a region that the zone-by-zone form skips (a zone
  // without these pressures, a collapsed region, dp = 0) is masked, with the same values bit for bit.
  const bool collapse = settings.collapse > 0.0;
  const double collapse_on = collapse ? 1.0 : 0.0;
  // The zones' fields first, into the batch's own arrays (the loop below then reads no array that the
  // compiler must assume its stores could change).
  constexpr int N = zone_batch;
  double density[N], sound_speed[N], live[N], subzone_mass[4][N];
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    density[i] = zones.density[z];
    sound_speed[i] = hydro.sound_speed[z];
    live[i] = zones.active[z] != 0 ? 1.0 : 0.0;
    for (int p = 0; p < 4; ++p) subzone_mass[p][i] = zones.subzone_mass[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p)];
  }
  // The collapse pressure alone acts only where a corner region is denser than theta times its zone:
  // a batch without one adds nothing (the loop below would mask every region) but +0 to each live
  // zone's forces (which turns a -0 into +0), and that is all it does, so that a zone's bits do not
  // depend on the other zones of its batch.
  if (settings.subzonal == 0.0) {
    if (!collapse) return;
    std::int64_t beyond = 0;
    for (int i = 0; i < count; ++i) {
      const quad::Corners x = batch.corners(i);
      const Vec2 middle = quad::centre(x);
      const double collapse_density = settings.collapse_threshold * density[i];
#pragma GCC unroll 4
      for (int p = 0; p < 4; ++p) {
        const double volume = corner_region_volume<G>(corner_region_of(x, middle, p));
        const std::int64_t dense = (live[i] != 0.0) & (volume > 0.0) & (subzone_mass[p][i] / volume > collapse_density);
        beyond = beyond | dense;
      }
    }
    if (beyond == 0) {
      for (int i = 0; i < count; ++i) {
        for (int p = 0; p < 4; ++p) {
          batch.fx[p][i] = live[i] != 0.0 ? batch.fx[p][i] + 0.0 : batch.fx[p][i];
          batch.fy[p][i] = live[i] != 0.0 ? batch.fy[p][i] + 0.0 : batch.fy[p][i];
        }
      }
      return;
    }
  }
  for (int i = 0; i < count; ++i) {
    const quad::Corners x = batch.corners(i);
    const double rho = density[i];
    const double switch_on = settings.subzonal_at_shocks ? batch.shock[i] : 1.0;
    const double subzonal_on = (settings.subzonal > 0.0 ? 1.0 : 0.0) * (switch_on > 0.0 ? 1.0 : 0.0);
    const double zone_on = live[i] * (subzonal_on + collapse_on > 0.0 ? 1.0 : 0.0);
    const double c2 = sound_speed[i] * sound_speed[i];
    const double stiffness = subzonal_on != 0.0 ? switch_on * settings.subzonal * c2 : 0.0;
    const double collapse_stiffness = settings.collapse * c2;
    const double collapse_density = settings.collapse_threshold * rho;
    const Vec2 middle = quad::centre(x);
    std::array<Vec2, 4> force{};
#pragma GCC unroll 4
    for (int p = 0; p < 4; ++p) {
      const quad::Corners region = corner_region_of(x, middle, p);
      const double volume = corner_region_volume<G>(region);
      std::array<Vec2, 4> g;  // dV(S_p)/d(region corner j)
      if constexpr (G == GeometryKind::axisymmetric) {
        g = quad::axisymmetric_volume_gradient(region);
      } else {
        g = quad::area_gradient(region);
      }
      const double corner_density = subzone_mass[p][i] / volume;
      const double subzonal_dp = subzonal_on != 0.0 ? stiffness * (corner_density - rho) : 0.0;
      const double excess = collapse_stiffness * (corner_density - collapse_density);
      const double dp = collapse_on * (corner_density > collapse_density ? 1.0 : 0.0) != 0.0 ? subzonal_dp + excess : subzonal_dp;
      // Not a collapsed region (the axis corner of a degenerate quad), and a pressure to apply.
      const bool on = zone_on * (volume > 0.0 ? 1.0 : 0.0) * (dp != 0.0 ? 1.0 : 0.0) != 0.0;
      // Region corner j as a combination of the zone's nodes: x_p; (x_p + x_p+1)/2; the centre; (x_p-1 + x_p)/2.
      const Vec2 quarter = 0.25 * g[2];
      const int n = quad::next(p), o = quad::next(n), m = quad::prev(p);
      const Vec2 at_p = dp * (g[0] + 0.5 * g[1] + quarter + 0.5 * g[3]);
      const Vec2 at_n = dp * (0.5 * g[1] + quarter);
      const Vec2 at_o = dp * quarter;
      const Vec2 at_m = dp * (quarter + 0.5 * g[3]);
      force[p] = {on ? force[p].x + at_p.x : force[p].x, on ? force[p].y + at_p.y : force[p].y};
      force[n] = {on ? force[n].x + at_n.x : force[n].x, on ? force[n].y + at_n.y : force[n].y};
      force[o] = {on ? force[o].x + at_o.x : force[o].x, on ? force[o].y + at_o.y : force[o].y};
      force[m] = {on ? force[m].x + at_m.x : force[m].x, on ? force[m].y + at_m.y : force[m].y};
    }
    for (int p = 0; p < 4; ++p) {
      batch.fx[p][i] = zone_on != 0.0 ? batch.fx[p][i] + force[p].x : batch.fx[p][i];
      batch.fy[p][i] = zone_on != 0.0 ? batch.fy[p][i] + force[p].y : batch.fy[p][i];
    }
  }
}

// Edge viscosity (CSW 1998) on the compressing edges, added to the batch's forces; writes
// hydro.viscous_speed and adds each damper's dissipation to `viscous_power` in zone and edge order.
template <GeometryKind G>
[[gnu::noinline]] inline void batch_edge_viscosity(ZoneBatch& batch, int count, Index first, const Mesh& mesh,
                                                        HydroZoneFields& hydro, Index zone_begin,
                                                        const ZoneForceParams& params, const ForceSettings settings,
                                                        AreaWeightedArrays area_weighted_arrays,
                                                        SharedEdgeLimiters shared_limiters, double& viscous_power) {
  constexpr bool axisymmetric = G == GeometryKind::axisymmetric;
  const bool area_weighted = axisymmetric && settings.area_weighted;  // a constant false in planar code
  const ZoneFields& zones = mesh.zones;
  double power = viscous_power;  // a local running sum (in a register), added to in the same order
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    if (!zones.active[z]) continue;
    bool expanding = true;  // no edge compressing: no viscosity
    for (int k = 0; k < 4; ++k) expanding = expanding && batch.edge_compression[k][i] >= 0.0;
    if (expanding) {
      hydro.viscous_speed[z] = 0.0;
      continue;
    }
    const ZoneCorners& n = zones.corners[z];
    const quad::Corners x = batch.corners(i);
    const std::array<Vec2, 4> u = batch.velocities(i);
    const double rho = zones.density[z];
    const double c = hydro.sound_speed[z];
    const Vec2 centre = quad::centre(x);
    double viscous_speed = 0.0;
#pragma GCC unroll 4  // constant corner indices: the corner arrays stay in registers
    for (int k = 0; k < 4; ++k) {
      const int k1 = quad::next(k);
      if (n[k] == n[k1]) continue;
      const Vec2 du = u[k1] - u[k];
      const Vec2 dx = x[k1] - x[k];
      if (batch.edge_compression[k][i] >= 0.0) continue;  // expanding or shearing edge: no viscosity
      const double du_norm = norm(du);
      if (!(du_norm > 1e-150)) continue;  // a negligible difference: no viscosity (and no denormals)
      const double psi = params.viscosity.limiter ? zone_edge_limiter(mesh, z, k, zone_begin, du, dx, shared_limiters)
                                                  : 0.0;
      const double active = 1.0 - psi;
      if (!(active > 0.0)) continue;
      const Vec2 median = 0.5 * (x[k] + x[k1]) - centre;  // S, from the zone centre to the edge midpoint
      // |S| x |cos(du, n_S)|: the damper acts on the part of du across the median segment (CSW98).
      double face = std::abs(du.y * median.x - du.x * median.y) / du_norm;
      // RZ control volume: the radius weight w_S = (r_edge + 2 r_centre) / 3, not the radius of S's midpoint
      // (r_edge + r_centre) / 2. The CV pressure force on corner p along z is p b_p,z (r_{p-1} + r_p + r_{p+1}) / 3
      // (dV/dz_p), and w_S is the mean of that weight over the edge's two nodes, so that a viscous pressure
      // acts through the same r-weights as the pressure, which the consistent nodal mass (F1) matches.
      // Interior nodes of a uniform grid see the same sum as before; an axis node saw 3/4 of the
      // deceleration of its neighbours off the axis (the spherical Noh's axis row, docs/verification.md).
      if (axisymmetric && !area_weighted) face *= centre.y + median.y / 3.0;
      const double quadratic = settings.cq_s * du_norm;
      const double q_over_du =
          rho * active * (quadratic + std::sqrt(quadratic * quadratic + settings.cl * settings.cl * c * c));
      const double kappa = q_over_du * face;  // force per unit velocity difference
      batch.fx[k][i] += kappa * du.x;
      batch.fy[k][i] += kappa * du.y;
      batch.fx[k1][i] -= kappa * du.x;
      batch.fy[k1][i] -= kappa * du.y;
      double dissipation = kappa * dot(du, du);
      if (area_weighted) {
        // The planar damper's work with the nodes' booking weights: in J per radian, like the other
        // forms; their mean over the edge is an approximation.
        dissipation *= 0.5 * (area_weighted_arrays.booking[n[k]] + area_weighted_arrays.booking[n[k1]]);
      }
      power += dissipation;
      viscous_speed = std::max(viscous_speed, 2.0 * active * quadratic);
    }
    hydro.viscous_speed[z] = viscous_speed;
  }
  viscous_power = power;
}

// The physical hourglass stiffness of a zone, in units of E'/3 (symmetric, global components): the
// stiffness against the hourglass rate q = sum_p gamma_p u_p of a rectangle with half-sides a (along
// its unit axis t) and b, deformed in pure bending. With u = q_t (xi eta) t / 2 the fibres along t bend
// (strain q_t eta / 2a, the shear taken up by the incompatible modes xi^2 and eta^2), storing
// E' q_t^2 b / 6a: stiffness (E'/3)(b/a) along t, and by the same count (E'/3)(a/b) across it. For a
// quadrilateral, t and a from each of its two mid-line half-vectors e (xi: the mean of the edges 0-1 and
// 3-2, halved; eta: of 0-3 and 1-2), b = A / 4a, and the two results averaged, so that the form does
// not depend on which mid-line is named first and is exact for a rectangle:
//   K_e = (A / 4|e|^4) e e^T + (4|e|^2 / A)(I - e e^T / |e|^2).
// A mid-line of (near) zero length (a triangle's collapsed edge pair) is skipped for the other.
//
// The same rectangle fully plastic in bending (the bending stress +-Y' on either side of its mid-line,
// Y' = 2 Y0 / sqrt(3) in plane strain) resists the mode along t with Y' b and across it with Y' a (the
// generalised force of that stress on q); the physical form bounds the state by that, through the metric
// M with Q^T M Q = (Q_t / b)^2 + (Q_n / a)^2 on a rectangle, from the mid-lines likewise:
//   M_e = (16 / A^2) e e^T + (I - e e^T / |e|^2) / |e|^2.
struct Bending {
  double xx = 0.0, xy = 0.0, yy = 0.0;
};
struct ZoneBending {
  Bending stiffness;  // K / (E'/3)
  Bending metric;     // M: Q^T M Q / Y'^2 <= 1 within the fully plastic bound
};
inline ZoneBending zone_bending(const quad::Corners& x, double area) {
  if (!(area > 0.0)) return {};
  const Vec2 xi = 0.25 * ((x[1] - x[0]) + (x[2] - x[3]));
  const Vec2 eta = 0.25 * ((x[3] - x[0]) + (x[2] - x[1]));
  ZoneBending z;
  int axes = 0;
  for (const Vec2& e : {xi, eta}) {
    const double e2 = dot(e, e);
    if (!(e2 > 1e-6 * area)) continue;
    const double along = area / (4.0 * e2 * e2);  // (b/a) / a^2
    const double across = 4.0 * e2 / area;         // a/b
    z.stiffness.xx += along * e.x * e.x + across * (1.0 - e.x * e.x / e2);
    z.stiffness.xy += along * e.x * e.y - across * e.x * e.y / e2;
    z.stiffness.yy += along * e.y * e.y + across * (1.0 - e.y * e.y / e2);
    const double plastic_along = 16.0 / (area * area), plastic_across = 1.0 / e2;
    z.metric.xx += plastic_along * e.x * e.x + plastic_across * (1.0 - e.x * e.x / e2);
    z.metric.xy += plastic_along * e.x * e.y - plastic_across * e.x * e.y / e2;
    z.metric.yy += plastic_along * e.y * e.y + plastic_across * (1.0 - e.y * e.y / e2);
    ++axes;
  }
  if (axes == 2) {
    for (Bending* b : {&z.stiffness, &z.metric}) {
      b->xx *= 0.5;
      b->xy *= 0.5;
      b->yy *= 0.5;
    }
  }
  return z;
}

// Hourglass forces (Flanagan & Belytschko 1981) added to the batch's forces: the shape vectors and
// rates, the stiffness state (hourglass.hourglass_x/y, intact zones only), and the batch's hourglass power.
template <GeometryKind G>
[[gnu::noinline]] inline void batch_hourglass_forces(ZoneBatch& batch, int count, Index first, const ZoneFields& zones,
                                                          const HydroZoneFields& hydro, HourglassZoneFields& hourglass,
                                                          const FractureZoneFields& fracture,
                                                          const ZoneForceParams& params, const ForceSettings settings) {
  for (int i = 0; i < count; ++i) {
    const quad::Corners x = batch.corners(i);
    const std::array<Vec2, 4> u = batch.velocities(i);
    const std::array<Vec2, 4> b = batch.area_gradient(i);
    const std::array<double, 4> gamma = quad::hourglass_shape(x, b, batch.area[i]);
    Vec2 rate{};
    for (int p = 0; p < 4; ++p) rate += gamma[p] * u[p];
    double bb = 0.0;
    for (int p = 0; p < 4; ++p) bb += dot(b[p], b[p]);
    for (int p = 0; p < 4; ++p) batch.gamma[p][i] = gamma[p];
    batch.rate_x[i] = rate.x;
    batch.rate_y[i] = rate.y;
    batch.bb[i] = bb;
  }
  // The stiffness state's increment of this step (Q^n - Q^{n-1} = k dt^{n-1/2} q), kept for the power.
  double increment_x[zone_batch], increment_y[zone_batch];
  for (int i = 0; i < count; ++i) increment_x[i] = increment_y[i] = 0.0;
  if (settings.hourglass_stiff) {
    for (int i = 0; i < count; ++i) {
      const Index z = first + i;
      if (!zones.active[z] || fracture.damaged[z]) continue;  // damaged: no shear stiffness
      const double area = batch.area[i];
      ZoneBending bending;  // the physical form's stiffness and plastic metric
      if (settings.physical_stiffness) {
        bending = zone_bending(batch.corners(i), area);
        const Bending& k = bending.stiffness;
        const double factor = settings.stiffness_modulus * params.previous_time_step;
        increment_x[i] = factor * (k.xx * batch.rate_x[i] + k.xy * batch.rate_y[i]);
        increment_y[i] = factor * (k.xy * batch.rate_x[i] + k.yy * batch.rate_y[i]);
      } else {
        increment_x[i] = settings.stiffness_modulus * params.previous_time_step * batch.bb[i] / area * batch.rate_x[i];
        increment_y[i] = settings.stiffness_modulus * params.previous_time_step * batch.bb[i] / area * batch.rate_y[i];
      }
      double qx = hourglass.hourglass_x[z] + increment_x[i];
      double qy = hourglass.hourglass_y[z] + increment_y[i];
      if (settings.hourglass_bound > 0.0) {
        // |Q| <= k_p Y0 |b|; in the physical form sqrt(Q^T M Q) <= k_p Y', k_p times the zone's fully
        // plastic bending (Y' = 2 Y0 / sqrt(3)).
        double size = 0.0, bound = 0.0;
        if (settings.physical_stiffness) {
          const Bending& m = bending.metric;
          bound = settings.hourglass_bound * (2.0 / std::sqrt(3.0));
          size = std::sqrt(qx * (m.xx * qx + m.xy * qy) + qy * (m.xy * qx + m.yy * qy));
        } else {
          bound = settings.hourglass_bound * std::sqrt(batch.bb[i]);
          size = std::sqrt(qx * qx + qy * qy);
        }
        if (size > bound) {
          qx *= bound / size;
          qy *= bound / size;
          increment_x[i] = qx - hourglass.hourglass_x[z];
          increment_y[i] = qy - hourglass.hourglass_y[z];
        }
      }
      hourglass.hourglass_x[z] = qx;
      hourglass.hourglass_y[z] = qy;
    }
  }
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    const double viscous = params.hourglass.viscous * zones.density[z] * hydro.sound_speed[z] * std::sqrt(batch.area[i]);
    const double scale = G == GeometryKind::axisymmetric && !settings.area_weighted ? batch.mean_radius[i] : 1.0;
    const Vec2 generalised{scale * (viscous * batch.rate_x[i] + hourglass.hourglass_x[z]),
                           scale * (viscous * batch.rate_y[i] + hourglass.hourglass_y[z])};
    for (int p = 0; p < 4; ++p) {
      batch.fx[p][i] -= batch.gamma[p][i] * generalised.x;
      batch.fy[p][i] -= batch.gamma[p][i] * generalised.y;
    }
    // The power booked on the hourglass line takes the stiffness state at the step's middle,
    // (Q^{n-1} + Q^n) / 2: its sum over steps is then the change of the stored energy |Q|^2 / 2k, which
    // the exact work of these forces at the mid-step velocity also telescopes to. With Q^n alone, each
    // step booked k dt^2 |q|^2 / 2 more, a sum that grows without bound in a long vibration although
    // the forces store the energy and give it back.
    const Vec2 booked{generalised.x - 0.5 * scale * increment_x[i], generalised.y - 0.5 * scale * increment_y[i]};
    batch.hourglass_power[i] = dot(booked, Vec2{batch.rate_x[i], batch.rate_y[i]});
  }
}

}  // namespace detail

}  // namespace krug
