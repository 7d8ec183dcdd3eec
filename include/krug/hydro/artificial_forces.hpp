#pragma once
// Step 1's artificial forces on a batch of zones (the parts of compute_corner_forces, zone_forces.hpp):
// the scalar and the edge viscosity, subzonal pressures and hourglass control.
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
      // quad::corner_region, built from its components (an aggregate copy of x would not vectorise).
      const Vec2 corner{x[p].x, x[p].y};
      const quad::Corners region{corner, 0.5 * (corner + x[quad::next(p)]), Vec2{middle.x, middle.y},
                                 0.5 * (x[quad::prev(p)] + corner)};
      double volume = 0.0;
      std::array<Vec2, 4> g;  // dV(S_p)/d(region corner j)
      if constexpr (G == GeometryKind::axisymmetric) {
        volume = quad::axisymmetric_volume(region);
        g = quad::axisymmetric_volume_gradient(region);
      } else {
        volume = quad::area(region);
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

// Tensor viscosity (Campbell & Shashkov, J. Comput. Phys. 172, 2001), added to the batch's forces; writes
// hydro.viscous_speed and adds the dissipation of every side force to `viscous_power` in zone and edge order.
//
// Each corner c (node p, edges e1 = (p-1, p) and e2 = (p, p+1)) has its region of the median mesh: x_p,
// the midpoint of e2, the zone centre, the midpoint of e1 (area A_c). Where the divergence of the velocity
// over that region (its boundary integral, with the midpoint and centre velocities the means of the
// nodes') is negative, the corner carries a viscous stress mu_c grad u with
//   mu_c = rho (1 - psi_c) [c_q s du_c + sqrt(c_q^2 s^2 du_c^2 + c_l^2 c^2)] L_c,
// du_c the larger velocity difference across the region (between its opposite sides), L_c the region's
// extent along that difference (sqrt(4 A_c l_along / l_across), at most twice the shorter edge), and grad u
// known along the two edges, g_1 = (u_p - u_p-1) / |e1|, g_2 = (u_p+1 - u_p) / |e2|. The force across the
// median segment of edge e (between its corners c at its start and c' at its end) is
//   F_e = [w_c (mu_c g_2 + cos_c mu_c g_1) + w_c' (mu_c' g_1' + cos_c' mu_c' g_2')] / |e|,
// w = A / sin^2 of the corner's angle, cos the cosine between the corner's two edges; +F_e on the edge's
// first node, -F_e on its second. The work rate of a corner's share is
//   -mu_c w_c (|g_1|^2 + |g_2|^2 + 2 cos g_1 . g_2) = -mu_c A_c |grad u|^2 <= 0
// (the Frobenius norm of the gradient from its two edge projections), so the viscosity only dissipates,
// and it damps every part of grad u, shear included, in a compressing corner; the edge viscosity damps
// only du across each median segment. The limiter psi_c is the edge limiter (CSW98, detail::edge_limiter)
// of the corner's two edges, weighted by |g|^2: 1 for a velocity field linear along both edges, so the
// viscosity is off in uniform compression, and in one-dimensional flow the limiter of the edge along it.
// RZ control volume: A_c is replaced by the corner's consistent r-weighted volume, the integral of N_p r dA
// (quad::axisymmetric_corner_volumes, the nodal masses' share, docs/verification.md F1), so that each
// corner's work stays -mu_c V_c |grad u|^2 <= 0; with the median segment's weight (r_edge + 2 r_centre) / 3
// of the edge viscosity on the side forces instead, the results were the same on F7's rectangles.
// The time step sees the signal speed 2 (1 - psi_c) c_q s du_c max(1, L_c / h) of the strongest
// compressing corner, h the zone's stable length: L_c reaches twice the shorter edge, and without the
// factor the damping of a thin zone (the polar mesh's slivers along the axis) outran the CFL step and
// oscillated with a growing amplitude.
template <GeometryKind G>
[[gnu::noinline]] inline void batch_tensor_viscosity(ZoneBatch& batch, int count, Index first, const Mesh& mesh,
                                                          HydroZoneFields& hydro, Index zone_begin,
                                                          const ZoneForceParams& params, const ForceSettings settings,
                                                          AreaWeightedArrays area_weighted_arrays,
                                                          SharedEdgeLimiters shared_limiters, double& viscous_power) {
  constexpr bool axisymmetric = G == GeometryKind::axisymmetric;
  constexpr int N = zone_batch;
  const bool area_weighted = axisymmetric && settings.area_weighted;
  const bool consistent_volumes = axisymmetric && !area_weighted;
  const ZoneFields& zones = mesh.zones;
  // The zones are taken a batch at a time in phases, each a loop over the batch: the corners' regions and
  // compression, the edges' gradients, their limiters (zone by zone: they read the neighbours), the
  // corners' coefficients, the side forces, and the dissipation summed in zone and edge order. A corner
  // or edge that the zone-by-zone form skips is masked: the values are those of that form, bit for bit.
  // Masks as 64-bit integers (0 or 1), the width of the values they select, so that the loops vectorise.
  std::int64_t open[4][N], compressing[4][N], any[N], live[N];
  double cx[N], cy[N], cu[N], cv[N];
  double mx[4][N], my[4][N], mu_[4][N], mv[4][N], length[4][N], region_area[4][N];
  for (int i = 0; i < count; ++i) {
    const ZoneCorners& n = zones.corners[first + i];
    for (int k = 0; k < 4; ++k) open[k][i] = n[k] != n[quad::next(k)] ? 1 : 0;
    live[i] = zones.active[first + i] ? 1 : 0;
  }
  for (int i = 0; i < count; ++i) {
    const quad::Corners x = batch.corners(i);
    const std::array<Vec2, 4> u = batch.velocities(i);
    const Vec2 centre = quad::centre(x);
    const Vec2 centre_velocity = 0.25 * (u[0] + u[1] + u[2] + u[3]);
    cx[i] = centre.x;
    cy[i] = centre.y;
    cu[i] = centre_velocity.x;
    cv[i] = centre_velocity.y;
    std::array<Vec2, 4> mid, mid_velocity;
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      const int k1 = quad::next(k);
      mid[k] = 0.5 * (x[k] + x[k1]);
      mid_velocity[k] = 0.5 * (u[k] + u[k1]);
      mx[k][i] = mid[k].x;
      my[k][i] = mid[k].y;
      mu_[k][i] = mid_velocity[k].x;
      mv[k][i] = mid_velocity[k].y;
      const double edge = norm(x[k1] - x[k]);
      length[k][i] = open[k][i] != 0 ? edge : 0.0;
    }
    // The compression test: the divergence over each corner's region (x_p, mid of e2, centre, mid of e1).
    std::int64_t zone_any = 0;
#pragma GCC unroll 4
    for (int p = 0; p < 4; ++p) {
      const int m = quad::prev(p);
      const Vec2 diagonal_a = centre - x[p], diagonal_b = mid[m] - mid[p];
      const double a = 0.5 * cross(diagonal_a, diagonal_b);
      region_area[p][i] = a;
      const double flux = cross(centre_velocity - u[p], diagonal_b) - cross(mid_velocity[m] - mid_velocity[p], diagonal_a);
      compressing[p][i] = (a > 0.0) & (flux < 0.0) ? 1 : 0;
      zone_any = zone_any | compressing[p][i];
    }
    any[i] = zone_any & live[i];
  }
  // Velocity gradient along each edge.
  double gx[4][N], gy[4][N], gradient2[4][N], psi[4][N];
  std::int64_t graded[4][N];
  for (int i = 0; i < count; ++i) {
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      const int k1 = quad::next(k);
      const double dux = batch.u[k1][i] - batch.u[k][i], duy = batch.v[k1][i] - batch.v[k][i];
      // A negligible difference: no gradient (and no denormals).
      const bool ok = (length[k][i] > 0.0) & (std::sqrt(dux * dux + duy * duy) > 1e-150);
      const double inverse = 1.0 / length[k][i];
      const double x_part = inverse * dux, y_part = inverse * duy;
      gx[k][i] = ok ? x_part : 0.0;
      gy[k][i] = ok ? y_part : 0.0;
      gradient2[k][i] = ok ? x_part * x_part + y_part * y_part : 0.0;
      graded[k][i] = ok ? 1 : 0;
      psi[k][i] = 0.0;
    }
  }
  // The limiter only of an edge a compressing corner reads (its corners k and k + 1), taken from the
  // mirrored edge of an earlier zone where that zone computed it (the same value, seen from the other
  // side); a slot not computed this step is marked NaN for the zones after it.
  if (params.viscosity.limiter) {
    constexpr double not_computed = std::numeric_limits<double>::quiet_NaN();
    for (int i = 0; i < count; ++i) {
      const Index z = first + i;
      const quad::Corners x = batch.corners(i);
      const std::array<Vec2, 4> u = batch.velocities(i);
      for (int k = 0; k < 4; ++k) {
        const int k1 = quad::next(k);
        const std::size_t slot = 4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(k);
        if (!(any[i] != 0 && graded[k][i] != 0 && (compressing[k][i] | compressing[k1][i]) != 0)) {
          if (shared_limiters.value) shared_limiters.value[slot] = not_computed;
          continue;
        }
        const Index mirror = shared_limiters.mirror ? shared_limiters.mirror[slot] : -1;
        if (mirror >= 4 * zone_begin && zones.active[mirror / 4] && !std::isnan(shared_limiters.value[mirror])) {
          psi[k][i] = shared_limiters.value[mirror];
          continue;
        }
        psi[k][i] = zone_edge_limiter(mesh, z, k, zone_begin, u[k1] - u[k], x[k1] - x[k], {});
        if (shared_limiters.value) shared_limiters.value[slot] = psi[k][i];
      }
    }
  }
  // Each corner's coefficient mu_c w_c and cosine; its stress along e1 (before) and e2 (after).
  double before_x[4][N], before_y[4][N], after_x[4][N], after_y[4][N], cosine[4][N];
  double speed[N], stable_length[N], volume[4][N];
  for (int i = 0; i < count; ++i) stable_length[i] = quad::stable_length(batch.corners(i), batch.area[i]);
  if (consistent_volumes) {
    for (int i = 0; i < count; ++i) {
      const std::array<double, 4> corner_volume = quad::axisymmetric_corner_volumes(batch.corners(i));
      for (int p = 0; p < 4; ++p) volume[p][i] = corner_volume[p];
    }
  } else {
    for (int i = 0; i < count; ++i) {
      for (int p = 0; p < 4; ++p) volume[p][i] = region_area[p][i];
    }
  }
  for (int i = 0; i < count; ++i) {
    const quad::Corners x = batch.corners(i);
    const std::array<Vec2, 4> u = batch.velocities(i);
    const Vec2 centre{cx[i], cy[i]}, centre_velocity{cu[i], cv[i]};
    const double rho = zones.density[first + i];
    const double c = hydro.sound_speed[first + i];
    double shock = 0.0, viscous_speed = 0.0;
#pragma GCC unroll 4
    for (int p = 0; p < 4; ++p) {
      const int m = quad::prev(p), p1 = quad::next(p);
      const double l1 = length[m][i], l2 = length[p][i];
      const double weights = gradient2[m][i] + gradient2[p][i];
      const double limiter = (psi[m][i] * gradient2[m][i] + psi[p][i] * gradient2[p][i]) / weights;
      const double active = 1.0 - limiter;
      // 1 or 0 as doubles: the vectorised loop selects with them.
      const double acting = ((any[i] & compressing[p][i]) != 0 ? 1.0 : 0.0) * (weights > 0.0 ? 1.0 : 0.0) * (active > 0.0 ? 1.0 : 0.0);
      shock = acting != 0.0 ? std::max(shock, active) : shock;
      // A corner of a triangle stored as a quadrilateral has one edge of zero length: its other edge only.
      const double low = std::min(l1, l2), high = std::max(l1, l2);
      const bool two_edges = low > 0.0;  // the lengths are >= 0
      const Vec2 e1 = x[m] - x[p], e2 = x[p1] - x[p];
      const double cos_both = dot(e1, e2) / (l1 * l2);
      const double cos_c = two_edges ? cos_both : 0.0;
      const double shortest = two_edges ? low : high;
      const double sin2 = 1.0 - cos_c * cos_c;
      // The region's two extents (between its opposite sides) and the velocity differences across them.
      const Vec2 mid_p{mx[p][i], my[p][i]}, mid_m{mx[m][i], my[m][i]};
      const Vec2 mid_velocity_p{mu_[p][i], mv[p][i]}, mid_velocity_m{mu_[m][i], mv[m][i]};
      const Vec2 extent_1 = 0.5 * (mid_p + centre - x[p] - mid_m);  // from e1's side to the opposite side
      const Vec2 extent_2 = 0.5 * (centre + mid_m - x[p] - mid_p);  // from e2's side to the opposite side
      const Vec2 jump_1 = mid_velocity_p + centre_velocity - u[p] - mid_velocity_m;
      const Vec2 jump_2 = centre_velocity + mid_velocity_m - u[p] - mid_velocity_p;
      const double j1 = dot(jump_1, jump_1), j2 = dot(jump_2, jump_2);
      const bool first_jump = j1 >= j2;
      const Vec2 jump{first_jump ? jump_1.x : jump_2.x, first_jump ? jump_1.y : jump_2.y};
      const double du = std::sqrt(std::max(j1, j2));
      const double n1 = norm(extent_1), n2 = norm(extent_2);
      // The region's extent along the velocity difference: the extent whose direction is closer to it.
      const bool along_1 = std::abs(dot(extent_1, jump)) * n2 >= std::abs(dot(extent_2, jump)) * n1;
      const double ratio_1 = n1 / n2, ratio_2 = n2 / n1;
      const double ratio = along_1 ? ratio_1 : ratio_2;
      const double extent = std::min(std::sqrt(4.0 * region_area[p][i] * ratio), 2.0 * shortest);
      const double quadratic = settings.cq_s * du;
      const double mu = rho * active * (quadratic + std::sqrt(quadratic * quadratic + settings.cl * settings.cl * c * c)) *
                        extent;
      const double w = mu * volume[p][i] / sin2;
      // Not a flat corner, and a region of two extents.
      const bool on = acting * (sin2 >= 1e-4 ? 1.0 : 0.0) * (shortest > 0.0 ? 1.0 : 0.0) * (n1 > 0.0 ? 1.0 : 0.0) * (n2 > 0.0 ? 1.0 : 0.0) != 0.0;
      const double bx = w * gx[m][i], by = w * gy[m][i], ax = w * gx[p][i], ay = w * gy[p][i];
      before_x[p][i] = on ? bx : 0.0;
      before_y[p][i] = on ? by : 0.0;
      after_x[p][i] = on ? ax : 0.0;
      after_y[p][i] = on ? ay : 0.0;
      cosine[p][i] = on ? cos_c : 0.0;
      const double corner_speed = 2.0 * active * quadratic * std::max(1.0, extent / stable_length[i]);
      viscous_speed = on ? std::max(viscous_speed, corner_speed) : viscous_speed;
    }
    batch.shock[i] = shock;
    speed[i] = viscous_speed;
  }
  // The side forces: +F_e on the edge's first node, -F_e on its second; their dissipation.
  double dissipation[4][N];
  std::int64_t pushed[4][N];
  for (int i = 0; i < count; ++i) {
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      const int k1 = quad::next(k);
      const double inverse = 1.0 / length[k][i];
      const double fx = inverse * (after_x[k][i] + cosine[k][i] * before_x[k][i] + before_x[k1][i] +
                                   cosine[k1][i] * after_x[k1][i]);
      const double fy = inverse * (after_y[k][i] + cosine[k][i] * before_y[k][i] + before_y[k1][i] +
                                   cosine[k1][i] * after_y[k1][i]);
      const bool on = (any[i] != 0) & (length[k][i] > 0.0) & !((fx == 0.0) & (fy == 0.0));
      batch.fx[k][i] = on ? batch.fx[k][i] + fx : batch.fx[k][i];
      batch.fy[k][i] = on ? batch.fy[k][i] + fy : batch.fy[k][i];
      batch.fx[k1][i] = on ? batch.fx[k1][i] - fx : batch.fx[k1][i];
      batch.fy[k1][i] = on ? batch.fy[k1][i] - fy : batch.fy[k1][i];
      dissipation[k][i] = fx * (batch.u[k1][i] - batch.u[k][i]) + fy * (batch.v[k1][i] - batch.v[k][i]);
      pushed[k][i] = on ? 1 : 0;
    }
  }
  double power = viscous_power;
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    if (!zones.active[z]) continue;
    hydro.viscous_speed[z] = any[i] ? speed[i] : 0.0;
    if (!any[i]) continue;
    const ZoneCorners& n = zones.corners[z];
    for (int k = 0; k < 4; ++k) {
      if (!pushed[k][i]) continue;
      double work = dissipation[k][i];
      if (area_weighted) {
        work *= 0.5 * (area_weighted_arrays.booking[n[k]] + area_weighted_arrays.booking[n[quad::next(k)]]);
      }
      power += work;
    }
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
