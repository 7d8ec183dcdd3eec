#pragma once
// Geometry of one quadrilateral zone with corners 0..3 counter-clockwise in the computational plane
// (planar (x, y) or axisymmetric (z, r) with r >= 0). Pure functions of the four corner positions.
//
// Area A = 1/2 (d02 x d13) with the diagonals d02, d13. Its gradient with respect to corner p is the
// planar "B matrix" of Wilkins (1964): dA/dx_p = (y_{p+1} - y_{p-1}) / 2, dA/dy_p = (x_{p-1} - x_{p+1}) / 2,
// and the velocity gradient of the zone is L = (1/A) sum_p u_p (x) dA/dx_p.
//
// Axisymmetric volume per radian V = integral of r dA over the quad, by the polygon formula
// V = 1/6 sum_i (z_i r_{i+1} - z_{i+1} r_i)(r_i + r_{i+1}). Its corner gradient gives the compatible
// axisymmetric corner forces (Caramana, Burton, Shashkov & Whalen 1998): for a pressure f_p = p dV/dx_p.
// A degenerate quad with a repeated corner (a triangle at the centre of a polar mesh) is allowed.
#include <array>
#include <algorithm>
#include <cmath>

#include "krug/core/vec2.hpp"

namespace krug::quad {

using Corners = std::array<Vec2, 4>;

constexpr int next(int p) { return (p + 1) & 3; }
constexpr int prev(int p) { return (p + 3) & 3; }

inline double area(const Corners& c) {
  return 0.5 * cross(c[2] - c[0], c[3] - c[1]);
}

// dA/dx_p for every corner.
inline std::array<Vec2, 4> area_gradient(const Corners& c) {
  std::array<Vec2, 4> b;
  for (int p = 0; p < 4; ++p) {
    const Vec2 n = c[next(p)];
    const Vec2 m = c[prev(p)];
    b[p] = {0.5 * (n.y - m.y), 0.5 * (m.x - n.x)};
  }
  return b;
}

// Volume per radian, integral of r dA (r = second coordinate).
inline double axisymmetric_volume(const Corners& c) {
  double v = 0.0;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = c[i];
    const Vec2 b = c[next(i)];
    v += cross(a, b) * (a.y + b.y);
  }
  return v / 6.0;
}

// dV/dx_p of the axisymmetric volume per radian.
[[gnu::always_inline]] inline std::array<Vec2, 4> axisymmetric_volume_gradient(const Corners& c) {
  std::array<double, 8> sixfold;  // 6 dV/dx_p, components in corner order
  for (int p = 0; p < 4; ++p) {
    const Vec2 m = c[prev(p)];
    const Vec2 x = c[p];
    const Vec2 n = c[next(p)];
    sixfold[2 * p] = n.y * (x.y + n.y) - m.y * (m.y + x.y);
    sixfold[2 * p + 1] = -n.x * (x.y + n.y) + cross(x, n) + m.x * (m.y + x.y) + cross(m, x);
  }
  // Eight independent divisions in one loop, which the compiler issues two or four at a time.
  std::array<double, 8> gradient;
  for (int i = 0; i < 8; ++i) gradient[i] = sixfold[i] / 6.0;
  return {Vec2{gradient[0], gradient[1]}, Vec2{gradient[2], gradient[3]}, Vec2{gradient[4], gradient[5]},
          Vec2{gradient[6], gradient[7]}};
}

inline Vec2 centre(const Corners& c) { return 0.25 * (c[0] + c[1] + c[2] + c[3]); }

// The corner region of p on the median mesh: p, the midpoint of edge (p, p+1), the centre, the
// midpoint of edge (p-1, p). The four corner regions tile the zone exactly.
inline Corners corner_region(const Corners& c, int p, Vec2 centre_point) {
  return {c[p], 0.5 * (c[p] + c[next(p)]), centre_point, 0.5 * (c[prev(p)] + c[p])};
}
inline Corners corner_region(const Corners& c, int p) { return corner_region(c, p, centre(c)); }

// Consistent r-weighted corner masses per unit density: integral of N_p r dA over the quad with the
// bilinear shape functions N_p, by 2 x 2 Gauss quadrature (exact: N_p r J is at most cubic in each
// direction). They sum to the axisymmetric volume, and for a uniform pressure they give axis and
// off-axis corners the same axial acceleration (force ~ dV/dz_p, mass ~ integral N_p r dA), which the
// median-mesh corner volumes do not (axis corners would accelerate 4/3 too fast).
inline std::array<double, 4> axisymmetric_corner_volumes(const Corners& c) {
  constexpr double g = 0.57735026918962576;  // 1/sqrt(3)
  constexpr std::array<double, 2> points{-g, g};
  constexpr std::array<double, 4> xi_sign{-1.0, 1.0, 1.0, -1.0}, eta_sign{-1.0, -1.0, 1.0, 1.0};
  std::array<double, 4> volumes{};
#pragma GCC unroll 2  // unrolled, so that the batched kernels that call it vectorise
  for (double xi : points) {
#pragma GCC unroll 2
    for (double eta : points) {
      std::array<double, 4> shape;
      Vec2 d_xi{}, d_eta{};
      Vec2 x{};
      for (int p = 0; p < 4; ++p) {
        shape[p] = 0.25 * (1.0 + xi_sign[p] * xi) * (1.0 + eta_sign[p] * eta);
        x += shape[p] * c[p];
        d_xi += (0.25 * xi_sign[p] * (1.0 + eta_sign[p] * eta)) * c[p];
        d_eta += (0.25 * eta_sign[p] * (1.0 + xi_sign[p] * xi)) * c[p];
      }
      const double jacobian = cross(d_xi, d_eta);
      for (int p = 0; p < 4; ++p) volumes[p] += shape[p] * x.y * jacobian;  // Gauss weights are 1
    }
  }
  return volumes;
}

// The r-weighted gradients of the bilinear shape functions, B_p = integral of grad N_p r dA over the
// quad: the axisymmetric in-plane operator with the quadrature of the consistent masses above. The
// deviatoric corner force is -(s_2D - s_tt I) B_p, and (1/V) sum_p u_p (x) B_p its adjoint velocity
// gradient. They sum to zero, and sum_p x_p (x) B_p = V I, so a linear velocity field is exact.
// Closed form, by the divergence theorem, grad(N_p r) = r grad N_p + N_p e_r:
//   B_p = (boundary integral of N_p r n ds) - e_r (integral of N_p dA).
// On an edge (a, b) with outward normal-times-length n_ab = (y_b - y_a, x_a - x_b), N_p and r are
// linear: the edge gives node a (r_a/3 + r_b/6) n_ab and node b (r_a/6 + r_b/3) n_ab. And for the
// bilinear N_p, whose Jacobian is linear, integral of N_p dA = (A + T_p)/6 with T_p the area of the
// triangle (x_p-1, x_p, x_p+1).
inline std::array<Vec2, 4> axisymmetric_gradient_integrals(const Corners& c) {
  std::array<Vec2, 4> integrals{};
  for (int a = 0; a < 4; ++a) {
    const int b = next(a);
    const Vec2 normal{c[b].y - c[a].y, c[a].x - c[b].x};
    const double ra = c[a].y, rb = c[b].y;
    integrals[a] += ((ra * 2.0 + rb) * (1.0 / 6.0)) * normal;
    integrals[b] += ((ra + rb * 2.0) * (1.0 / 6.0)) * normal;
  }
  const double zone_area = area(c);
  for (int p = 0; p < 4; ++p) {
    const double corner_triangle = 0.5 * cross(c[next(p)] - c[p], c[prev(p)] - c[p]);
    integrals[p].y -= (zone_area + corner_triangle) * (1.0 / 6.0);
  }
  return integrals;
}

// Smallest altitude, the length scale of the CFL condition: area over the longest edge
// (min(h, w) for an h x w rectangle, -> 0 for a sliver).
inline double smallest_altitude(const Corners& c, double zone_area) {
  double longest = 0.0;
  for (int p = 0; p < 4; ++p) {
    const Vec2 e = c[next(p)] - c[p];
    longest = std::max(longest, dot(e, e));
  }
  return longest > 0.0 ? zone_area / std::sqrt(longest) : 0.0;
}

// A triangle stored as a quadrilateral: two neighbouring corners at the same point (the centre ring
// of a sector mesh repeats the centre node).
inline bool is_triangle(const Corners& c) {
  bool triangle = false;  // without branches (the zone update's batches vectorise it)
  for (int p = 0; p < 4; ++p) triangle |= (c[next(p)].x == c[p].x) & (c[next(p)].y == c[p].y);
  return triangle;
}

// The length of the CFL condition: the zone's smallest altitude. A quadrilateral's is taken as its
// area over its longest edge (exact for a parallelogram); a triangle's is 2 area / longest edge,
// twice that.
inline double stable_length(const Corners& c, double zone_area) {
  return (is_triangle(c) ? 2.0 : 1.0) * smallest_altitude(c, zone_area);
}

// sum_p a_p (x) g_p, the 2 x 2 tensor whose ij component is sum_p a_p.i g_p.j (velocity or position
// against shape-function gradients: a velocity gradient or a deformation gradient times the area).
struct Tensor2 {
  double xx = 0.0, xy = 0.0, yx = 0.0, yy = 0.0;
};
inline Tensor2 outer_sum(const std::array<Vec2, 4>& a, const std::array<Vec2, 4>& g) {
  Tensor2 t;
  for (int p = 0; p < 4; ++p) {
    t.xx += a[p].x * g[p].x;
    t.xy += a[p].x * g[p].y;
    t.yx += a[p].y * g[p].x;
    t.yy += a[p].y * g[p].y;
  }
  return t;
}

// Flanagan & Belytschko (1981) hourglass shape vector gamma = (h - (h.x) b_x / A - (h.y) b_y / A) / 2
// with h = (1, -1, 1, -1); orthogonal to every linear field and summing to zero, so hourglass forces
// do no work on linear motions and exert no net force.
inline std::array<double, 4> hourglass_shape(const Corners& c, const std::array<Vec2, 4>& b,
                                             double zone_area) {
  constexpr std::array<double, 4> h{1.0, -1.0, 1.0, -1.0};
  double hx = 0.0, hy = 0.0;
  for (int p = 0; p < 4; ++p) {
    hx += h[p] * c[p].x;
    hy += h[p] * c[p].y;
  }
  std::array<double, 4> gamma;
  const double inv_area = 1.0 / zone_area;
  for (int p = 0; p < 4; ++p) {
    gamma[p] = 0.5 * (h[p] - (hx * b[p].x + hy * b[p].y) * inv_area);
  }
  return gamma;
}

}  // namespace krug::quad
