#pragma once
// What the parts of the corner-force kernel share (krug/hydro/zone_forces.hpp, artificial_forces.hpp):
// the kernel's parameters and its artificial power, the batch of zones gathered for one pass
// (ZoneBatch), the settings derived once per call, the RZ corner-force forms and the edge limiter,
// and the batch's geometry.
#include <algorithm>
#include <cmath>

#include "krug/core/geometry_kind.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/hydro/parameters.hpp"
#include "krug/hydro/corner_batch.hpp"

namespace krug {

struct ZoneForceParams {
  double shock_slope = 0.5;            // of the body's EOS
  double shear_modulus = 0.0;          // Pa, for stiffness hourglass
  double flow_stress = 0.0;            // Pa, initial flow stress, for the stiffness state's plastic bound
  double bending_modulus = 0.0;        // Pa, plane-strain E' = 4 mu (3K + mu) / (3K + 4 mu), physical hourglass stiffness
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

// The tensor viscosity's damping at the nodes (batch_tensor_viscosity; damping_bound in zone_forces.hpp).
struct DampingRows {
  const double* node_scale = nullptr;  // per node: 1 / sqrt(m_p), 0 for a node held in both components
                                       // (area-weighted RZ form: m_p = M_p / s_p, 0 where s_p <= 0)
  double* rows = nullptr;              // 4 per zone, written: for each corner's node p, sum_q |C_pq| / sqrt(m_q)
                                       // over the zone's nodes q that move
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
// started at zone_begin) where that zone computed it, else computed and kept for a later zone. A slot
// holding NaN was not computed this step (the tensor viscosity marks the edges it skips so).
inline double zone_edge_limiter(const Mesh& mesh, Index z, int k, Index zone_begin, Vec2 du, Vec2 dx,
                                SharedEdgeLimiters shared) {
  const std::size_t slot = 4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(k);
  const Index mirror = shared.mirror ? shared.mirror[slot] : -1;
  if (mirror >= 4 * zone_begin && mesh.zones.active[mirror / 4] && !std::isnan(shared.value[mirror])) {
    return shared.value[mirror];
  }
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
  double shock[zone_batch];  // tensor viscosity: 1 - psi of the zone's most active compressing corner, else 0
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
  double stiffness_modulus = 0.0;  // k_s mu (coefficient form), E'/3 (physical form)
  bool physical_stiffness = false; // the stiffness from the zone's bending (HourglassStiffness::physical)
  double hourglass_bound = 0.0;    // k_p Y0: the bound of |Q| / |b| (Pa); 0: none
  double cq_s = 0.0;               // c_q x the EOS shock slope
  double cl = 0.0;                 // c_l
  double subzonal = 0.0;           // subzonal pressure coefficient; 0: off
  bool subzonal_at_shocks = false; // the subzonal pressures scaled by `shock` (after the tensor viscosity)
  double collapse = 0.0;           // corner-collapse pressure coefficient; 0: off
  double collapse_threshold = 1.5; // the corner density, over the zone's, where it starts
  bool consistent_deviator = false;  // RZ control volume with strength: the r-weighted operator B_p
};

// Reads hydro.pressure; writes the batch's dA/dx_p, area and pressure, and for the edge viscosity
// du . dx of every edge (< 0: compressing).
template <ViscosityModel Visc>
[[gnu::noinline]] inline void batch_geometry(ZoneBatch& batch, int count, Index first, const HydroZoneFields& hydro) {
  for (int i = 0; i < count; ++i) {
    const quad::Corners x = batch.corners(i);
    const double area = quad::area(x);
    const std::array<Vec2, 4> b = quad::area_gradient(x);
    for (int p = 0; p < 4; ++p) {
      batch.bx[p][i] = b[p].x;
      batch.by[p][i] = b[p].y;
    }
    batch.area[i] = area;
    batch.pressure[i] = hydro.pressure[first + i];
    if constexpr (Visc == ViscosityModel::edge) {
      const std::array<Vec2, 4> u = batch.velocities(i);
      for (int k = 0; k < 4; ++k) {
        batch.edge_compression[k][i] = dot(u[quad::next(k)] - u[k], x[quad::next(k)] - x[k]);
      }
    }
  }
}

}  // namespace detail

}  // namespace krug
