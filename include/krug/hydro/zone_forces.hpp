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
#include <cmath>

#include "krug/core/geometry_kind.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/hydro/parameters.hpp"
#include "krug/hydro/corner_batch.hpp"

namespace krug {

struct ZoneForceParams {
  double shock_slope = 0.5;            // of the body's EOS
  double shear_modulus = 0.0;          // Pa, for stiffness hourglass
  double flow_stress = 0.0;            // Pa, initial flow stress, for the stiffness state's plastic bound
  ViscosityParams viscosity;
  HourglassParams hourglass;
  AxisymmetricForm axisymmetric_form = AxisymmetricForm::control_volume;
  double previous_time_step = 0.0;     // dt^{n-1/2}, increment of the stiffness hourglass state
};

// Rates of artificial work at the velocities the forces were built from (for the ledger's split of IE).
struct ArtificialPower {
  double viscous = 0.0;
  double hourglass = 0.0;
};

// The limiter of an edge is a function of its nodes and its continuations only. Where the two zones
// of an edge continue it through the same nodes, the first zone (in zone order) computes it and the
// second reads it: the values are bitwise the same (every difference and product changes sign
// exactly, and psi is symmetric in the two ratios).
struct SharedEdgeLimiters {
  const Index* mirror = nullptr;  // 4 per zone: mirrored_edge_slots(); null: every zone computes its own
  double* value = nullptr;        // 4 per zone: psi of the compressing edges of the current step
};

// The area-weighted RZ form's per-step arrays (area_weighted_scale in solver/hydro_step.hpp); unused otherwise.
struct AreaWeightedArrays {
  const double* scale = nullptr;    // per node: s_p = M_p / M^A_p, the factor of the node's forces
  const double* booking = nullptr;  // per node: the weight of its viscous and hourglass work in the zone's
                                    // energy: s_p, which stands for the node's radius, but 0 on the axis
  double* work_correction = nullptr;  // 8 per zone, written: what turns the work of the stored corner
                                      // forces into the zone's own energy increment
};

namespace detail {

// The axisymmetric control-volume stress force on a corner, f_p = -[(V/A)(sigma_2D - sigma_tt I) b_p + sigma_tt c_p]
// (b_p = dA/dx_p, c_p = dV/dx_p), from the stress components sigma_xx, sigma_yy, sigma_xy, sigma_tt.
[[gnu::always_inline]] inline Vec2 control_volume_force(double sxx, double syy, double sxy, double stt,
                                                        double mean_radius, Vec2 b, Vec2 c) {
  return {-(mean_radius * ((sxx - stt) * b.x + sxy * b.y) + stt * c.x),
          -(mean_radius * (sxy * b.x + (syy - stt) * b.y) + stt * c.y)};
}

// The same force with the r-weighted in-plane operator B_p = integral of grad N_p r dA
// (quad::axisymmetric_gradient_integrals) in place of (V/A) b_p: f_p = -[(sigma_2D - sigma_tt I) B_p + sigma_tt c_p].
// The pressure part (sigma_2D - sigma_tt I = 0) is the same; the deviatoric part is then consistent with
// the nodal masses integral N_p r dA on every row, the axis row included (where (V/A) b_p gives 1.5 x
// the axial force for a stress linear in z).
[[gnu::always_inline]] inline Vec2 consistent_control_volume_force(double sxx, double syy, double sxy, double stt,
                                                                   Vec2 in_plane, Vec2 c) {
  return {-((sxx - stt) * in_plane.x + sxy * in_plane.y + stt * c.x),
          -(sxy * in_plane.x + (syy - stt) * in_plane.y + stt * c.y)};
}

// Limiter of the edge viscosity: ratios of the velocity gradient along the continuing edges to the
// gradient along the edge itself, psi = max(0, min(1, (r_b + r_a)/2, 2 r_b, 2 r_a)).
inline double edge_limiter(const NodeFields& nodes, Index before, Index a, Index b, Index after,
                           Vec2 gradient, Vec2 direction) {
  const double g2 = dot(gradient, gradient);
  if (!(g2 > 0.0)) return 0.0;
  // The continuing edge's extent is its projection on this edge's direction, so that psi = 1
  // exactly for a linear velocity field also on curved grid lines (CSW 1998).
  auto ratio = [&](Index from, Index to) {
    const Vec2 dx = nodes.position(to) - nodes.position(from);
    const double length = dot(dx, direction);
    if (!(length > 0.0)) return 0.0;
    const Vec2 du = nodes.velocity(to) - nodes.velocity(from);
    return dot(du, gradient) / (length * g2);
  };
  const bool has_before = before >= 0, has_after = after >= 0;
  if (!has_before && !has_after) return 0.0;
  double r_before = has_before ? ratio(before, a) : 0.0;
  double r_after = has_after ? ratio(b, after) : 0.0;
  if (!has_before) r_before = r_after;
  if (!has_after) r_after = r_before;
  const double psi = std::min({0.5 * (r_before + r_after), 2.0 * r_before, 2.0 * r_after});
  return std::isfinite(psi) ? std::clamp(psi, 0.0, 1.0) : 0.0;
}

// The limiter of edge k of zone z, from the mirrored edge of an earlier zone of this loop (which
// started at zone_begin) where there is one, else computed and kept for a later zone.
inline double zone_edge_limiter(const Mesh& mesh, Index z, int k, Index zone_begin, Vec2 du, Vec2 dx,
                                SharedEdgeLimiters shared) {
  const std::size_t slot = 4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(k);
  const Index mirror = shared.mirror ? shared.mirror[slot] : -1;
  if (mirror >= 4 * zone_begin && mesh.zones.active[mirror / 4]) return shared.value[mirror];
  const ZoneCorners& n = mesh.zones.corners[z];
  const double dx_norm = norm(dx);
  const double psi = edge_limiter(mesh.nodes, mesh.zones.edge_before[z][k], n[k], n[quad::next(k)],
                                  mesh.zones.edge_after[z][k], (1.0 / dx_norm) * du, (1.0 / dx_norm) * dx);
  if (shared.value) shared.value[slot] = psi;
  return psi;
}

}  // namespace detail

// Zones are processed in batches: their corner positions and velocities are gathered into arrays
// (structure of arrays), the geometry, stress and hourglass corner forces are computed in loops
// without branches over the batch (vectorised by the compiler), the edge viscosity zone by zone,
// and the corner forces are added to the nodes in zone order. Every value is computed by the same
// operations as one zone at a time, so the result does not depend on the batching.
namespace detail {

constexpr int zone_batch = 32;

struct ZoneBatch : CornerBatch<zone_batch> {
  double bx[4][zone_batch], by[4][zone_batch];              // dA/dx_p
  double area[zone_batch], mean_radius[zone_batch];         // A, V/A (RZ)
  double pressure[zone_batch];                              // p (+ q for the scalar viscosity)
  double fx[4][zone_batch], fy[4][zone_batch];              // corner forces
  double gamma[4][zone_batch];                              // hourglass shape vector
  double rate_x[zone_batch], rate_y[zone_batch];            // hourglass rate q = sum gamma_p u_p
  double bb[zone_batch];                                    // sum b_p . b_p
  double hourglass_power[zone_batch];
  double edge_compression[4][zone_batch];                   // du . dx of edge (p, p+1), < 0: compressing
  // Area-weighted RZ form only: the zone's control-volume stress forces (its thermodynamic work) and
  // its area-weighted stress forces, whose difference corrects the work booked to the zone.
  double work_x[4][zone_batch], work_y[4][zone_batch];
  double planar_x[4][zone_batch], planar_y[4][zone_batch];

  std::array<Vec2, 4> area_gradient(int i) const {
    return {Vec2{bx[0][i], by[0][i]}, Vec2{bx[1][i], by[1][i]}, Vec2{bx[2][i], by[2][i]}, Vec2{bx[3][i], by[3][i]}};
  }
};

}  // namespace detail

// The parts of the force kernel, each a loop over one batch of `count` zones starting at zone `first`,
// in the order compute_corner_forces runs them. They read the batch's gathered corners and velocities
// and write the batch's arrays (and the zone fields named in each); the sums they add to run in zone
// order, so that composing them gives the same bits as one loop. Each part is compiled on its own
// (noinline; one call per 32 zones): that ran at the speed of the single loop, where inlining all
// of them into one function ran 5-10 % slower (docs/performance.md), and a profile names each part.
namespace detail {

// What every part reads: flags and coefficients derived from the parameters once per call.
struct ForceSettings {
  bool area_weighted = false;
  bool hourglass_on = false;
  bool hourglass_stiff = false;
  double stiffness_modulus = 0.0;  // k_s mu
  double plastic_limit = 0.0;      // bound of |Q| / |b| (Pa); 0: none
  double cq_s = 0.0;               // c_q x the EOS shock slope
  double cl = 0.0;                 // c_l
  double subzonal = 0.0;           // subzonal pressure coefficient; 0: off
  bool consistent_deviator = false;  // RZ control volume with strength: the r-weighted operator B_p
};

// Reads zones.pressure; writes the batch's dA/dx_p, area and pressure, and for the edge viscosity
// du . dx of every edge (< 0: compressing).
template <ViscosityModel Visc>
[[gnu::noinline]] inline void batch_geometry(ZoneBatch& batch, int count, Index first, const ZoneFields& zones) {
  for (int i = 0; i < count; ++i) {
    const quad::Corners x = batch.corners(i);
    const double area = quad::area(x);
    const std::array<Vec2, 4> b = quad::area_gradient(x);
    for (int p = 0; p < 4; ++p) {
      batch.bx[p][i] = b[p].x;
      batch.by[p][i] = b[p].y;
    }
    batch.area[i] = area;
    batch.pressure[i] = zones.pressure[first + i];
    if constexpr (Visc == ViscosityModel::edge) {
      const std::array<Vec2, 4> u = batch.velocities(i);
      for (int k = 0; k < 4; ++k) {
        batch.edge_compression[k][i] = dot(u[quad::next(k)] - u[k], x[quad::next(k)] - x[k]);
      }
    }
  }
}

// Scalar viscosity: Wilkins' q from the volumetric strain rate div u = (dV/dt)/V, compression only,
// added to the batch's pressure; writes zones.viscous_speed and adds its dissipation q (-dV/dt) to
// `viscous_power` in zone order (the rate of work the edge model books as its dampers' dissipation).
template <GeometryKind G>
[[gnu::noinline]] inline void batch_scalar_viscosity(ZoneBatch& batch, int count, Index first, ZoneFields& zones,
                                                          const ForceSettings settings, double& viscous_power) {
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
      const double q = rho * length * -divergence * (settings.cq_s * length * -divergence + settings.cl * zones.sound_speed[z]);
      batch.pressure[i] += q;
      zones.viscous_speed[z] = 2.0 * speed;
      power += q * -volume_rate;
    } else {
      zones.viscous_speed[z] = 0.0;
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
template <GeometryKind G>
[[gnu::noinline]] inline void batch_subzonal_pressure(ZoneBatch& batch, int count, Index first, const ZoneFields& zones,
                                                         const ForceSettings settings) {
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    if (!zones.active[z]) continue;
    const quad::Corners x = batch.corners(i);
    const double rho = zones.density[z];
    const double stiffness = settings.subzonal * zones.sound_speed[z] * zones.sound_speed[z];
    const double* subzone_mass = &zones.subzone_mass[4 * static_cast<std::size_t>(z)];
    const Vec2 middle = quad::centre(x);
    std::array<Vec2, 4> force{};
    for (int p = 0; p < 4; ++p) {
      const quad::Corners region = quad::corner_region(x, p, middle);
      double volume = 0.0;
      std::array<Vec2, 4> g;  // dV(S_p)/d(region corner j)
      if constexpr (G == GeometryKind::axisymmetric) {
        volume = quad::axisymmetric_volume(region);
        g = quad::axisymmetric_volume_gradient(region);
      } else {
        volume = quad::area(region);
        g = quad::area_gradient(region);
      }
      if (!(volume > 0.0)) continue;  // a collapsed region (the axis corner of a degenerate quad)
      const double dp = stiffness * (subzone_mass[p] / volume - rho);
      // Region corner j as a combination of the zone's nodes: x_p; (x_p + x_p+1)/2; the centre; (x_p-1 + x_p)/2.
      const Vec2 quarter = 0.25 * g[2];
      const int n = quad::next(p), o = quad::next(n), m = quad::prev(p);
      force[p] += dp * (g[0] + 0.5 * g[1] + quarter + 0.5 * g[3]);
      force[n] += dp * (0.5 * g[1] + quarter);
      force[o] += dp * quarter;
      force[m] += dp * (quarter + 0.5 * g[3]);
    }
    for (int p = 0; p < 4; ++p) {
      batch.fx[p][i] += force[p].x;
      batch.fy[p][i] += force[p].y;
    }
  }
}

// Stress corner forces, sigma = s - p I, into the batch's forces (and mean radius V/A); one loop per
// form, so that each has no branch. Area-weighted RZ form: also the control-volume forces (work_x/y)
// and the area-weighted stress forces alone (planar_x/y).
template <GeometryKind G, bool AreaWeighted, bool ConsistentDeviator = false>
[[gnu::noinline]] inline void batch_stress_forces(ZoneBatch& batch, int count, Index first, const ZoneFields& zones) {
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    const std::array<Vec2, 4> b = batch.area_gradient(i);
    const double pressure = batch.pressure[i];
    const double sxx = zones.deviator_xx[z] - pressure;
    const double syy = zones.deviator_yy[z] - pressure;
    const double sxy = zones.deviator_xy[z];
    const double stt = zones.deviator_zz[z] - pressure;
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

// Edge viscosity (CSW 1998) on the compressing edges, added to the batch's forces; writes
// zones.viscous_speed and adds each damper's dissipation to `viscous_power` in zone and edge order.
template <GeometryKind G>
[[gnu::noinline]] inline void batch_edge_viscosity(ZoneBatch& batch, int count, Index first, Mesh& mesh,
                                                        Index zone_begin, const ZoneForceParams& params,
                                                        const ForceSettings settings,
                                                        AreaWeightedArrays area_weighted_arrays,
                                                        SharedEdgeLimiters shared_limiters, double& viscous_power) {
  constexpr bool axisymmetric = G == GeometryKind::axisymmetric;
  const bool area_weighted = axisymmetric && settings.area_weighted;  // a constant false in planar code
  ZoneFields& zones = mesh.zones;
  double power = viscous_power;  // a local running sum (in a register), added to in the same order
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    if (!zones.active[z]) continue;
    bool expanding = true;  // no edge compressing: no viscosity
    for (int k = 0; k < 4; ++k) expanding = expanding && batch.edge_compression[k][i] >= 0.0;
    if (expanding) {
      zones.viscous_speed[z] = 0.0;
      continue;
    }
    const ZoneCorners& n = zones.corners[z];
    const quad::Corners x = batch.corners(i);
    const std::array<Vec2, 4> u = batch.velocities(i);
    const double rho = zones.density[z];
    const double c = zones.sound_speed[z];
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
    zones.viscous_speed[z] = viscous_speed;
  }
  viscous_power = power;
}

// Hourglass forces (Flanagan & Belytschko 1981) added to the batch's forces: the shape vectors and
// rates, the stiffness state (zones.hourglass_x/y, intact zones only), and the batch's hourglass power.
template <GeometryKind G>
[[gnu::noinline]] inline void batch_hourglass_forces(ZoneBatch& batch, int count, Index first, ZoneFields& zones,
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
      if (!zones.active[z] || zones.damaged[z]) continue;  // damaged: no shear stiffness
      const double area = batch.area[i];
      increment_x[i] = settings.stiffness_modulus * params.previous_time_step * batch.bb[i] / area * batch.rate_x[i];
      increment_y[i] = settings.stiffness_modulus * params.previous_time_step * batch.bb[i] / area * batch.rate_y[i];
      double qx = zones.hourglass_x[z] + increment_x[i];
      double qy = zones.hourglass_y[z] + increment_y[i];
      if (settings.plastic_limit > 0.0) {
        const double bound = settings.plastic_limit * std::sqrt(batch.bb[i]);
        const double size = std::sqrt(qx * qx + qy * qy);
        if (size > bound) {
          qx *= bound / size;
          qy *= bound / size;
          increment_x[i] = qx - zones.hourglass_x[z];
          increment_y[i] = qy - zones.hourglass_y[z];
        }
      }
      zones.hourglass_x[z] = qx;
      zones.hourglass_y[z] = qy;
    }
  }
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    const double viscous = params.hourglass.viscous * zones.density[z] * zones.sound_speed[z] * std::sqrt(batch.area[i]);
    const double scale = G == GeometryKind::axisymmetric && !settings.area_weighted ? batch.mean_radius[i] : 1.0;
    const Vec2 generalised{scale * (viscous * batch.rate_x[i] + zones.hourglass_x[z]),
                           scale * (viscous * batch.rate_y[i] + zones.hourglass_y[z])};
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

// Stores the batch's corner forces in zones.corner_force (+0 for an inactive zone; the nodes add them
// up in zone order, `sum_corner_forces`) and adds the active zones' hourglass power, in zone order.
// Area-weighted RZ form: the node gets s_p times the area-weighted force, and the work correction
// turns that into the zone's own control-volume stress work plus its booked viscous and hourglass work.
template <GeometryKind G>
[[gnu::noinline]] inline void store_corner_forces(const ZoneBatch& batch, int count, Index first, ZoneFields& zones,
                                                       const ForceSettings settings,
                                                       AreaWeightedArrays area_weighted_arrays,
                                                       double& hourglass_power) {
  const bool area_weighted = G == GeometryKind::axisymmetric && settings.area_weighted;
  double power = hourglass_power;  // a local running sum, added to in the same order
  for (int i = 0; i < count; ++i) {
    const Index z = first + i;
    double* corner = &zones.corner_force[8 * static_cast<std::size_t>(z)];
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

// Stores the corner forces of the zones in [zone_begin, zone_end) in zones.corner_force (zero for an
// inactive zone) and the viscous signal speed in zones.viscous_speed; `sum_corner_forces` then adds
// them up at the nodes. Velocities are read from nodes.u/v (t^{n-1/2}). Writes nothing outside its
// zones, so that blocks of zones can be computed on different threads. Area-weighted RZ form only: the
// stored forces are the nodes' (s_p times the area-weighted ones), and `area_weighted_arrays.work_correction`
// receives what turns their work into the zone's own (control-volume) stress work plus its booked
// viscous and hourglass work.
template <GeometryKind G, ViscosityModel Visc>
ArtificialPower compute_corner_forces(Mesh& mesh, Index zone_begin, Index zone_end, const ZoneForceParams& params,
                                      AreaWeightedArrays area_weighted_arrays = {},
                                      SharedEdgeLimiters shared_limiters = {}) {
  detail::ForceSettings settings;
  settings.area_weighted = G == GeometryKind::axisymmetric && params.axisymmetric_form == AxisymmetricForm::area_weighted;
  settings.hourglass_on = params.hourglass.viscous > 0.0 || params.hourglass.stiffness > 0.0;
  // k_s mu: without shear stiffness (a gas, or k_s = 0) the stiffness state never changes.
  settings.stiffness_modulus = params.hourglass.stiffness * params.shear_modulus;
  settings.hourglass_stiff = settings.stiffness_modulus != 0.0;
  if (std::isfinite(params.flow_stress)) settings.plastic_limit = params.hourglass.plastic_limit * params.flow_stress;
  settings.cq_s = params.viscosity.quadratic * params.shock_slope;
  settings.cl = params.viscosity.linear;
  // Subzonal pressures: bodies without strength, compatible forms only.
  settings.consistent_deviator = G == GeometryKind::axisymmetric && !settings.area_weighted && params.shear_modulus != 0.0;
  settings.subzonal = params.shear_modulus == 0.0 && !settings.area_weighted ? params.hourglass.subzonal_pressure : 0.0;
  ZoneFields& zones = mesh.zones;
  ArtificialPower power;
  detail::ZoneBatch batch;

  for (Index first = zone_begin; first < zone_end; first += detail::zone_batch) {
    const int count = static_cast<int>(std::min<Index>(detail::zone_batch, zone_end - first));
    batch.gather(mesh, first, count);
    detail::batch_geometry<Visc>(batch, count, first, zones);
    if constexpr (Visc == ViscosityModel::scalar) detail::batch_scalar_viscosity<G>(batch, count, first, zones, settings, power.viscous);
    if (settings.area_weighted) {
      detail::batch_stress_forces<G, true>(batch, count, first, zones);
    } else if (settings.consistent_deviator) {
      detail::batch_stress_forces<G, false, true>(batch, count, first, zones);
    } else {
      detail::batch_stress_forces<G, false>(batch, count, first, zones);
    }
    if (settings.subzonal > 0.0) detail::batch_subzonal_pressure<G>(batch, count, first, zones, settings);
    if constexpr (Visc == ViscosityModel::edge) {
      detail::batch_edge_viscosity<G>(batch, count, first, mesh, zone_begin, params, settings, area_weighted_arrays,
                                      shared_limiters, power.viscous);
    }
    if (settings.hourglass_on) detail::batch_hourglass_forces<G>(batch, count, first, zones, params, settings);
    detail::store_corner_forces<G>(batch, count, first, zones, settings, area_weighted_arrays, power.hourglass);
  }
  return power;
}

// The force on each node of [node_begin, node_end): the sum of the corner forces of its zones, in zone
// order (`corners` lists each node's corner slots 4 z + p, sorted by zone). An inactive zone's corner
// forces are +0 (compute_corner_forces), and adding +0 leaves a sum started at +0 bitwise unchanged, so
// no test of `active` is needed.
inline void sum_corner_forces(Mesh& mesh, const NodeCorners& corners, Index node_begin, Index node_end) {
  NodeFields& nodes = mesh.nodes;
  const double* corner_force = mesh.zones.corner_force.data();
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

}  // namespace krug
