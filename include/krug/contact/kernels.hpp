#pragma once
// Narrow-phase contact kernels (docs/theory.md §2 step 3): the reaction R found in a second stage
// from the predicted positions, by forward-increment Lagrange multipliers (Carpenter, Taylor & Katona
// 1991; Gulidov & Shabalin 1996).
//
// A point c (a node, or a particle centre with radius rho) against a segment ab with outward normal n:
// the contact point k = (1 - xi) a + xi b. The normal reaction R acts on c along +n and on a and b
// along -n, shared by the force and moment balance about k:
//     R_c = R n,  R_a = -(1 - xi) R n,  R_b = -xi R n.
// Applied over dt^n, it moves the predicted gap g* = (c* - k*) . n - rho by dt^n dt^{n+1/2} R w with
//     w = n.W_c n + (1 - xi)^2 n.W_a n + xi^2 n.W_b n      (W: per-DOF inverse masses),
// so R = max(0, -g* / (dt^n dt^{n+1/2} w)) closes the gap and makes the normal velocities at k equal.
// The same kernel with a or b absent is a point against a rigid wall.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "krug/core/vec2.hpp"

namespace krug::contact {

// Inverse masses of one point for its two degrees of freedom (0 where a condition holds the DOF).
struct InverseMass {
  double x = 0.0;
  double y = 0.0;
  double along(Vec2 direction) const { return direction.x * direction.x * x + direction.y * direction.y * y; }
};

struct SegmentProjection {
  double xi = 0.0;   // position of the contact point along ab, in [0, 1]
  double gap = 0.0;  // signed distance of c from the segment's line along n (m), minus the radius
  Vec2 normal;       // unit outward normal of the segment (to the right of a -> b)
  Vec2 tangent;      // unit vector a -> b
  bool inside = false;  // the projection of c falls within the segment
};

// Projection of the point c on the segment ab (positions as given, usually predicted ones).
inline SegmentProjection project(Vec2 c, Vec2 a, Vec2 b, double radius) {
  SegmentProjection p;
  const Vec2 ab = b - a;
  const double length_squared = dot(ab, ab);
  if (length_squared <= 0.0) return p;
  const double length = std::sqrt(length_squared);
  p.tangent = (1.0 / length) * ab;
  p.normal = {p.tangent.y, -p.tangent.x};
  const double along = dot(c - a, ab) / length_squared;
  p.inside = along >= 0.0 && along <= 1.0;
  p.xi = std::clamp(along, 0.0, 1.0);
  p.gap = dot(c - a, p.normal) - radius;
  return p;
}

// The feature of a segment a disc is measured against: the face while its centre projects within the
// segment (the signed distance from the face's line), else the nearer end point (a corner to roll
// over: the distance from it). The start gap of a contact is taken on the same feature as its
// predicted gap (docs/theory.md §2 step 3).
enum class SegmentFeature : std::uint8_t { face, end_a, end_b };

inline SegmentFeature closest_feature(const SegmentProjection& p) {
  if (p.inside) return SegmentFeature::face;
  return p.xi <= 0.0 ? SegmentFeature::end_a : SegmentFeature::end_b;
}

// A disc (a particle) against a segment or another disc: where the reaction acts and how far apart they are.
struct DiscContact {
  SegmentFeature feature = SegmentFeature::face;
  double xi = 0.0;   // contact point along the segment (0 against a disc: the whole reaction on it)
  double gap = 0.0;  // signed gap (m), negative where they overlap
  Vec2 normal;       // unit normal, from the segment (or the other disc) towards the disc's centre
};

// The disc (centre c, radius) against the segment ab: over the face, the signed distance from its line
// along its outward normal (negative once the centre is behind it); beside the face, the distance from
// the nearer end point, a convex corner to roll over.
inline DiscContact disc_segment_contact(Vec2 c, Vec2 a, Vec2 b, double radius) {
  const SegmentProjection p = project(c, a, b, 0.0);
  DiscContact k;
  k.xi = p.xi;
  k.feature = closest_feature(p);
  if (k.feature == SegmentFeature::face) {
    k.normal = p.normal;
    k.gap = p.gap - radius;
  } else {
    const Vec2 offset = c - (a + p.xi * (b - a));
    const double distance = norm(offset);
    k.normal = distance > 0.0 ? (1.0 / distance) * offset : p.normal;
    k.gap = distance - radius;
  }
  return k;
}

// The disc (centre c, radius) against another disc (centre other, radius other_radius).
inline DiscContact disc_disc_contact(Vec2 c, double radius, Vec2 other, double other_radius) {
  const Vec2 offset = c - other;
  const double distance = norm(offset);
  DiscContact k;
  k.normal = distance > 0.0 ? (1.0 / distance) * offset : Vec2{1.0, 0.0};
  k.gap = distance - radius - other_radius;
  return k;
}

// The effective inverse mass w of the contact along a direction (normal or tangent).
inline double contact_inverse_mass(Vec2 direction, double xi, const InverseMass& point, const InverseMass& a,
                                   const InverseMass& b) {
  return point.along(direction) + (1.0 - xi) * (1.0 - xi) * a.along(direction) + xi * xi * b.along(direction);
}

// Accumulated-impulse clamping of projected Gauss-Seidel: the new total normal reaction given the
// total so far and the increment that would close the current gap; never pulls.
inline double clamp_normal(double accumulated, double increment) { return std::max(0.0, accumulated + increment); }

// Coulomb: the new total tangential reaction within |T| <= f R.
inline double clamp_friction(double accumulated, double increment, double limit) {
  return std::clamp(accumulated + increment, -limit, limit);
}

}  // namespace krug::contact
