#pragma once
// Step 1's tensor viscosity on a batch of zones (a part of compute_corner_forces, zone_forces.hpp; the
// other artificial forces are in artificial_forces.hpp, what the parts share in zone_batch.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "krug/hydro/zone_batch.hpp"

namespace krug {
namespace detail {

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
// The time step sees the signal speed 2 (1 - psi_c) c_q s du_c of the strongest compressing corner, and
// the damping at the nodes: the side forces are F = -C u per velocity component, C = E^T A E with E the
// edges' differences and A (symmetric) from the corners' w_c mu_c and cosines over the edges' lengths.
// Where `damping.rows` is given, each zone writes there, for each of its corners' nodes p, the row sum
// sum_q |C_pq| / sqrt(m_q) over its nodes q that move (m_q = M_q / s_q in the area-weighted RZ form);
// summed at a node and divided by sqrt(m_p) (damping_bound, zone_forces.hpp) they give the Gershgorin
// bound on the largest eigenvalue of M^-1/2 C M^-1/2 (that of M^-1 C), and so the step over which the
// damping alone stays stable.
// L_c reaches twice the shorter edge: across a thin zone (the polar mesh's slivers along the axis, its
// centre triangles) this damping outruns the CFL step, and without a bound it oscillated with a growing
// amplitude.
template <GeometryKind G>
[[gnu::noinline]] inline void batch_tensor_viscosity(ZoneBatch& batch, int count, Index first, const Mesh& mesh,
                                                          HydroZoneFields& hydro, Index zone_begin,
                                                          const ZoneForceParams& params, const ForceSettings settings,
                                                          AreaWeightedArrays area_weighted_arrays,
                                                          SharedEdgeLimiters shared_limiters, double& viscous_power,
                                                          DampingRows damping) {
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
  // A batch without a compressing corner (gas at rest, or expanding) takes no viscosity: what the phases
  // below would write for it, written at once.
  std::int64_t batch_any = 0;
  for (int i = 0; i < count; ++i) batch_any = batch_any | any[i];
  if (batch_any == 0) {
    for (int i = 0; i < count; ++i) {
      const Index z = first + i;
      batch.shock[i] = 0.0;
      if (zones.active[z]) hydro.viscous_speed[z] = 0.0;
      if (damping.rows != nullptr) {
        for (int k = 0; k < 4; ++k) damping.rows[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(k)] = 0.0;
      }
      if (params.viscosity.limiter && shared_limiters.value != nullptr) {
        for (int k = 0; k < 4; ++k) {
          shared_limiters.value[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(k)] =
              std::numeric_limits<double>::quiet_NaN();
        }
      }
    }
    return;
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
        psi[k][i] = zone_edge_limiter(mesh, z, k, zone_begin, u[k1] - u[k], x[k1] - x[k], shared_limiters);
      }
    }
  }
  // Each corner's coefficient mu_c w_c and cosine; its stress along e1 (before) and e2 (after).
  double before_x[4][N], before_y[4][N], after_x[4][N], after_y[4][N], cosine[4][N];
  double speed[N], volume[4][N], weight[4][N];
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
      weight[p][i] = on ? w : 0.0;
      const double corner_speed = 2.0 * active * quadratic;
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
  if (damping.rows != nullptr) {
    for (int i = 0; i < count; ++i) {
      double* rows = &damping.rows[4 * static_cast<std::size_t>(first + i)];
      if (!any[i]) {
        for (int k = 0; k < 4; ++k) rows[k] = 0.0;
        continue;
      }
      // a[k][j]: the side force of edge k per velocity difference of edge j (j = k - 1, k, k + 1).
      double a[4][4] = {};
      for (int k = 0; k < 4; ++k) {
        const double lk = length[k][i];
        if (!(lk > 0.0)) continue;
        const int k1 = quad::next(k), km = quad::prev(k);
        a[k][k] = (weight[k][i] + weight[k1][i]) / (lk * lk);
        if (length[km][i] > 0.0) a[k][km] = cosine[k][i] * weight[k][i] / (lk * length[km][i]);
        if (length[k1][i] > 0.0) a[k][k1] = cosine[k1][i] * weight[k1][i] / (lk * length[k1][i]);
      }
      // C = E^T A E, E[k] = (node k + 1) - (node k).
      double c[4][4] = {};
      for (int k = 0; k < 4; ++k) {
        for (int j = 0; j < 4; ++j) {
          const int kn[2] = {k, quad::next(k)}, jn[2] = {j, quad::next(j)};
          for (int s1 = 0; s1 < 2; ++s1) {
            for (int s2 = 0; s2 < 2; ++s2) c[kn[s1]][jn[s2]] += (s1 == s2 ? 1.0 : -1.0) * a[k][j];
          }
        }
      }
      // Rows of M^-1/2 C M^-1/2 times sqrt(m_p), over the nodes that move (scale 0: a node held in both
      // components drops out of the damped system).
      const ZoneCorners& n = zones.corners[first + i];
      const double scale[4] = {damping.node_scale[n[0]], damping.node_scale[n[1]], damping.node_scale[n[2]],
                               damping.node_scale[n[3]]};
      for (int p = 0; p < 4; ++p) {
        double row = 0.0;
        for (int q = 0; q < 4; ++q) row += std::abs(c[p][q]) * scale[q];
        rows[p] = row;
      }
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

}  // namespace detail
}  // namespace krug
