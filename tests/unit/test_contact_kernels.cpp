// Narrow-phase contact kernels (krug/contact/kernels.hpp; docs/theory.md §2 step 3) against hand
// computations: the projection of a point on a segment, the feature a disc is measured from, disc
// against segment and disc against disc, the effective inverse mass w of the header's formula and the
// accumulated-impulse clamps. Every expected number is worked out in the comment beside it.
#include <catch2/catch.hpp>

#include <cmath>

#include "krug/contact/kernels.hpp"
#include "krug/core/vec2.hpp"

using namespace krug;
using namespace krug::contact;

namespace {

// Round-off allowance for results of a few operations on numbers of order 1.
constexpr double tight = 1e-14;

void check_vec(Vec2 actual, Vec2 expected, double tolerance = tight) {
  CHECK(actual.x == Approx(expected.x).margin(tolerance).epsilon(0.0));
  CHECK(actual.y == Approx(expected.y).margin(tolerance).epsilon(0.0));
}

}  // namespace

TEST_CASE("project: point over the face of a horizontal segment", "[kernels][contact_kernels]") {
  // a = (0, 0), b = (2, 0): tangent a -> b = (1, 0); the normal to its right is (t.y, -t.x) = (0, -1).
  const Vec2 a{0.0, 0.0}, b{2.0, 0.0};
  // c = (0.5, -1): along = (c - a).(b - a) / |b - a|^2 = 1 / 4 = 0.25; gap = (c - a).n = 1.
  const SegmentProjection p = project({0.5, -1.0}, a, b, 0.0);
  check_vec(p.tangent, {1.0, 0.0});
  check_vec(p.normal, {0.0, -1.0});
  CHECK(p.xi == Approx(0.25).margin(tight));
  CHECK(p.gap == Approx(1.0).margin(tight));
  CHECK(p.inside);
  // The radius is subtracted from the gap: 1 - 0.25 = 0.75; xi and the normal are unchanged.
  const SegmentProjection q = project({0.5, -1.0}, a, b, 0.25);
  CHECK(q.gap == Approx(0.75).margin(tight));
  CHECK(q.xi == Approx(0.25).margin(tight));
  // Behind the face (on the left of a -> b): c = (1.5, 0.5): xi = 3/4, gap = (1.5, 0.5).(0, -1) = -0.5.
  const SegmentProjection r = project({1.5, 0.5}, a, b, 0.0);
  CHECK(r.xi == Approx(0.75).margin(tight));
  CHECK(r.gap == Approx(-0.5).margin(tight));
  CHECK(r.inside);
}

TEST_CASE("project: oblique segment, normal to the right of a -> b", "[kernels][contact_kernels]") {
  // a = (1, 1), b = (4, 5): |b - a| = 5, t = (0.6, 0.8), n = (t.y, -t.x) = (0.8, -0.6).
  const Vec2 a{1.0, 1.0}, b{4.0, 5.0};
  // c = (5, 0): c - a = (4, -1); along = (4 * 3 + (-1) * 4) / 25 = 8/25 = 0.32;
  // gap = 4 * 0.8 + (-1) * (-0.6) = 3.8.
  const SegmentProjection p = project({5.0, 0.0}, a, b, 0.3);
  check_vec(p.tangent, {0.6, 0.8});
  check_vec(p.normal, {0.8, -0.6});
  CHECK(p.xi == Approx(0.32).margin(tight));
  CHECK(p.gap == Approx(3.8 - 0.3).margin(tight));
  CHECK(p.inside);
  // Reversing the segment reverses the tangent and the normal, so the gap changes sign and xi -> 1 - xi.
  const SegmentProjection q = project({5.0, 0.0}, b, a, 0.0);
  check_vec(q.normal, {-0.8, 0.6});
  CHECK(q.xi == Approx(1.0 - 0.32).margin(tight));
  CHECK(q.gap == Approx(-3.8).margin(tight));
}

TEST_CASE("project: beyond the end points xi is clamped and the point is not inside", "[kernels][contact_kernels]") {
  const Vec2 a{0.0, 0.0}, b{2.0, 0.0};  // n = (0, -1) as above
  // c = (-1, -0.5): along = -2 / 4 = -0.5 -> xi = 0; the gap stays the distance from the line: 0.5.
  const SegmentProjection before = project({-1.0, -0.5}, a, b, 0.0);
  CHECK(before.xi == 0.0);
  CHECK_FALSE(before.inside);
  CHECK(before.gap == Approx(0.5).margin(tight));
  CHECK(closest_feature(before) == SegmentFeature::end_a);
  // c = (3, 0.5): along = 6 / 4 = 1.5 -> xi = 1; gap = -0.5 (behind the line).
  const SegmentProjection after = project({3.0, 0.5}, a, b, 0.0);
  CHECK(after.xi == 1.0);
  CHECK_FALSE(after.inside);
  CHECK(after.gap == Approx(-0.5).margin(tight));
  CHECK(closest_feature(after) == SegmentFeature::end_b);
  // Exactly over an end point (along = 0 or 1, exact in binary) counts as inside: the face.
  const SegmentProjection at_a = project({0.0, -1.0}, a, b, 0.0);
  CHECK(at_a.xi == 0.0);
  CHECK(at_a.inside);
  CHECK(closest_feature(at_a) == SegmentFeature::face);
  const SegmentProjection at_b = project({2.0, -1.0}, a, b, 0.0);
  CHECK(at_b.xi == 1.0);
  CHECK(at_b.inside);
  CHECK(closest_feature(at_b) == SegmentFeature::face);
}

TEST_CASE("project: a zero-length segment gives the default projection", "[kernels][contact_kernels]") {
  // |b - a|^2 = 0: the function returns before computing anything (xi 0, gap 0, zero vectors, not
  // inside), so closest_feature treats it as the end point a.
  const SegmentProjection p = project({3.0, 4.0}, {1.0, 1.0}, {1.0, 1.0}, 0.5);
  CHECK(p.xi == 0.0);
  CHECK(p.gap == 0.0);
  CHECK_FALSE(p.inside);
  check_vec(p.normal, {0.0, 0.0}, 0.0);
  check_vec(p.tangent, {0.0, 0.0}, 0.0);
  CHECK(closest_feature(p) == SegmentFeature::end_a);
}

TEST_CASE("disc against segment: face, both corners and the radius", "[kernels][contact_kernels]") {
  const Vec2 a{0.0, 0.0}, b{2.0, 0.0};  // n = (0, -1)
  SECTION("over the face: signed distance from the line less the radius") {
    // c = (1, -0.5), radius 0.2: xi = 2 / 4 = 0.5, distance 0.5, gap 0.5 - 0.2 = 0.3.
    const DiscContact k = disc_segment_contact({1.0, -0.5}, a, b, 0.2);
    CHECK(k.feature == SegmentFeature::face);
    CHECK(k.xi == Approx(0.5).margin(tight));
    CHECK(k.gap == Approx(0.3).margin(tight));
    check_vec(k.normal, {0.0, -1.0});
  }
  SECTION("centre behind the face: negative gap of depth plus radius") {
    // c = (0.5, 0.25), radius 0.2: gap = -0.25 - 0.2 = -0.45; xi = 0.5 / 2 = 0.25.
    const DiscContact k = disc_segment_contact({0.5, 0.25}, a, b, 0.2);
    CHECK(k.feature == SegmentFeature::face);
    CHECK(k.xi == Approx(0.25).margin(tight));
    CHECK(k.gap == Approx(-0.45).margin(tight));
  }
  SECTION("beside a: distance from the corner, normal from the corner to the centre") {
    // c = (-0.3, -0.4): along = -0.6 / 4 < 0 -> end_a; offset c - a = (-0.3, -0.4), |offset| = 0.5
    // (3-4-5), normal (-0.6, -0.8), gap 0.5 - 0.2 = 0.3, xi 0.
    const DiscContact k = disc_segment_contact({-0.3, -0.4}, a, b, 0.2);
    CHECK(k.feature == SegmentFeature::end_a);
    CHECK(k.xi == 0.0);
    CHECK(k.gap == Approx(0.3).margin(tight));
    check_vec(k.normal, {-0.6, -0.8});
  }
  SECTION("beside b, on the back side of the line: still the distance from the corner") {
    // c = (2.6, 0.8): along = 5.2 / 4 > 1 -> end_b; offset c - b = (0.6, 0.8), distance 1,
    // normal (0.6, 0.8), gap 1 - 0.25 = 0.75, xi 1. (The face's line would give -0.8 - 0.25.)
    const DiscContact k = disc_segment_contact({2.6, 0.8}, a, b, 0.25);
    CHECK(k.feature == SegmentFeature::end_b);
    CHECK(k.xi == 1.0);
    CHECK(k.gap == Approx(0.75).margin(tight));
    check_vec(k.normal, {0.6, 0.8});
  }
  SECTION("the gap is continuous where the feature changes from the face to a corner") {
    // At c = (0, -0.5) the centre projects on a (face, gap 0.5 - r); just beside it, c = (-1e-9, -0.5),
    // the distance from a is sqrt(0.25 + 1e-18) = 0.5 + 1e-18: the same gap within 1e-15.
    const DiscContact on_face = disc_segment_contact({0.0, -0.5}, a, b, 0.1);
    const DiscContact on_corner = disc_segment_contact({-1e-9, -0.5}, a, b, 0.1);
    CHECK(on_face.feature == SegmentFeature::face);
    CHECK(on_corner.feature == SegmentFeature::end_a);
    CHECK(on_face.gap == Approx(0.4).margin(tight));
    CHECK(on_corner.gap == Approx(on_face.gap).margin(1e-15));
    check_vec(on_corner.normal, on_face.normal, 1e-8);  // normal (-2e-9, -1) against (0, -1)
  }
  SECTION("a zero-length segment acts as a point: the distance from it") {
    // a = b = (1, 1), c = (4, 5): offset (3, 4), distance 5, normal (0.6, 0.8), gap 5 - 1 = 4.
    const DiscContact k = disc_segment_contact({4.0, 5.0}, {1.0, 1.0}, {1.0, 1.0}, 1.0);
    CHECK(k.feature == SegmentFeature::end_a);
    CHECK(k.gap == Approx(4.0).margin(tight));
    check_vec(k.normal, {0.6, 0.8});
  }
}

TEST_CASE("disc against disc: distance of the centres less both radii", "[kernels][contact_kernels]") {
  // c = (3, 4), other = (0, 0): distance 5 (3-4-5), normal (c - other)/5 = (0.6, 0.8), gap 5 - 1 - 2 = 2.
  const DiscContact k = disc_disc_contact({3.0, 4.0}, 1.0, {0.0, 0.0}, 2.0);
  CHECK(k.gap == Approx(2.0).margin(tight));
  check_vec(k.normal, {0.6, 0.8});
  CHECK(k.xi == 0.0);  // the whole reaction on the other disc
  // Overlapping: centres 1 apart along -y, radii 0.75 each: gap 1 - 1.5 = -0.5, normal (0, -1).
  const DiscContact o = disc_disc_contact({2.0, 1.0}, 0.75, {2.0, 2.0}, 0.75);
  CHECK(o.gap == Approx(-0.5).margin(tight));
  check_vec(o.normal, {0.0, -1.0});
  // Swapping the discs reverses the normal and keeps the gap.
  const DiscContact s = disc_disc_contact({0.0, 0.0}, 2.0, {3.0, 4.0}, 1.0);
  CHECK(s.gap == Approx(2.0).margin(tight));
  check_vec(s.normal, {-0.6, -0.8});
  // Coincident centres: the documented fallback normal (1, 0), gap -(r1 + r2) = -3.
  const DiscContact c = disc_disc_contact({1.0, 1.0}, 1.0, {1.0, 1.0}, 2.0);
  check_vec(c.normal, {1.0, 0.0}, 0.0);
  CHECK(c.gap == Approx(-3.0).margin(tight));
}

TEST_CASE("InverseMass::along is n.W n for the diagonal per-DOF inverse mass", "[kernels][contact_kernels]") {
  const InverseMass w{2.0, 3.0};
  CHECK(w.along({1.0, 0.0}) == 2.0);
  CHECK(w.along({0.0, -1.0}) == 3.0);
  // n = (0.6, 0.8): 0.36 * 2 + 0.64 * 3 = 0.72 + 1.92 = 2.64.
  CHECK(w.along({0.6, 0.8}) == Approx(2.64).margin(tight));
  // A DOF held by a condition (W = 0) takes no share: roller free in x only, n = (0.6, 0.8): 0.36 * 5.
  CHECK(InverseMass{5.0, 0.0}.along({0.6, 0.8}) == Approx(1.8).margin(tight));
  // Default: both DOFs held (a rigid wall or an absent end point).
  CHECK(InverseMass{}.along({0.6, 0.8}) == 0.0);
}

TEST_CASE("contact_inverse_mass: w = n.W_c n + (1 - xi)^2 n.W_a n + xi^2 n.W_b n", "[kernels][contact_kernels]") {
  const Vec2 n{0.6, 0.8};
  const InverseMass wc{2.0, 3.0}, wa{1.0, 1.0}, wb{0.0, 4.0};
  // n.W_c n = 2.64 (above); n.W_a n = 0.36 + 0.64 = 1; n.W_b n = 0.64 * 4 = 2.56.
  // xi = 0.25: 2.64 + 0.75^2 * 1 + 0.25^2 * 2.56 = 2.64 + 0.5625 + 0.16 = 3.3625.
  CHECK(contact_inverse_mass(n, 0.25, wc, wa, wb) == Approx(3.3625).margin(tight));
  // xi = 0: the whole segment share on a: 2.64 + 1 = 3.64; xi = 1: on b: 2.64 + 2.56 = 5.2.
  CHECK(contact_inverse_mass(n, 0.0, wc, wa, wb) == Approx(3.64).margin(tight));
  CHECK(contact_inverse_mass(n, 1.0, wc, wa, wb) == Approx(5.2).margin(tight));
  // A point against a rigid wall (a and b absent, W = 0): w is the point's own n.W_c n.
  CHECK(contact_inverse_mass(n, 0.5, wc, {}, {}) == Approx(2.64).margin(tight));
  // A node against a fixed segment, masses 1: w = 1 whatever xi.
  CHECK(contact_inverse_mass({0.0, 1.0}, 0.3, {1.0, 1.0}, {}, {}) == 1.0);
}

TEST_CASE("the reaction split (1 - xi, xi) changes the normal gap rate by dt R w", "[kernels][contact_kernels]") {
  // The header's derivation: R_c = R n, R_a = -(1 - xi) R n, R_b = -xi R n applied over dt change the
  // velocities by du_i = dt W_i R_i. The normal velocity of c relative to the contact point
  // k = (1 - xi) a + xi b then changes by
  //   n.(du_c - (1 - xi) du_a - xi du_b) = dt R [n.W_c n + (1 - xi)^2 n.W_a n + xi^2 n.W_b n] = dt R w
  // (an exact identity), while the total momentum sum_i m_i du_i = dt (R_c + R_a + R_b) = 0.
  const Vec2 n{0.6, 0.8};
  const double xi = 0.25, reaction = 7.0, dt = 0.5;
  // Per-DOF masses m = 1/W, with distinct x and y values so a wrong pairing of components shows.
  const InverseMass wc{0.5, 0.25}, wa{2.0, 1.0}, wb{0.125, 4.0};
  const auto du = [&](const InverseMass& w, double share) {
    return Vec2{dt * share * reaction * n.x * w.x, dt * share * reaction * n.y * w.y};
  };
  const Vec2 du_c = du(wc, 1.0), du_a = du(wa, -(1.0 - xi)), du_b = du(wb, -xi);
  const double rate_change = dot(n, du_c - (1.0 - xi) * du_a - xi * du_b);
  const double w = contact_inverse_mass(n, xi, wc, wa, wb);
  // w by hand: n.W_c n = 0.36*0.5 + 0.64*0.25 = 0.34; n.W_a n = 0.72 + 0.64 = 1.36;
  // n.W_b n = 0.045 + 2.56 = 2.605; w = 0.34 + 0.5625*1.36 + 0.0625*2.605 = 0.34 + 0.765 + 0.1628125.
  CHECK(w == Approx(1.2678125).margin(tight));
  CHECK(rate_change == Approx(dt * reaction * w).margin(1e-13));
  // Momentum: per DOF m du = dt share R n, and the shares 1 - (1 - xi) - xi sum to zero.
  const Vec2 momentum = Vec2{du_c.x / wc.x + du_a.x / wa.x + du_b.x / wb.x, du_c.y / wc.y + du_a.y / wa.y + du_b.y / wb.y};
  check_vec(momentum, {0.0, 0.0}, 1e-13);
  // The reaction that closes a predicted gap g* < 0 over dt_mid dt_next: R = -g* / (dt_mid dt_next w).
  // g* = -0.03, dt_mid = 0.01, dt_next = 0.02, w = 1.5: R = 0.03 / (2e-4 * 1.5) = 100, and the gap then
  // moves by dt_mid dt_next R w = 2e-4 * 100 * 1.5 = 0.03: closed.
  const double closing = -(-0.03) / (0.01 * 0.02 * 1.5);
  CHECK(closing == Approx(100.0).margin(1e-11));
  CHECK(clamp_normal(0.0, closing) == Approx(100.0).margin(1e-11));
}

TEST_CASE("clamp_normal never pulls; clamp_friction stays within the Coulomb cone", "[kernels][contact_kernels]") {
  CHECK(clamp_normal(3.0, -1.0) == 2.0);  // 3 - 1
  CHECK(clamp_normal(3.0, -5.0) == 0.0);  // max(0, -2): the accumulated push is withdrawn, never reversed
  CHECK(clamp_normal(0.0, 2.5) == 2.5);
  CHECK(clamp_normal(0.0, -2.5) == 0.0);  // a separating contact gets nothing
  CHECK(clamp_friction(1.0, 0.5, 2.0) == 1.5);    // within |T| <= 2
  CHECK(clamp_friction(1.0, 3.0, 2.0) == 2.0);    // 4 clamped to +2
  CHECK(clamp_friction(-1.0, -3.0, 2.0) == -2.0); // -4 clamped to -2
  CHECK(clamp_friction(0.5, 0.5, 0.0) == 0.0);    // no normal reaction: no friction
}
