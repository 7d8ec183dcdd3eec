// Point-wise fracture criteria (krug/fracture/criteria.hpp; Gulidov & Shabalin 1996, criteria (1);
// docs/theory.md §2 step 6) against hand values: principal stretches of pure stretch, rotated
// stretch and simple shear, the one-point deformation gradient of a quad under affine and hourglass
// motions, principal stresses, the order in which `exceeded` reports criteria, loosening, the
// fully-fractured rule and the erosion limits.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <numbers>

#include "krug/core/vec2.hpp"
#include "krug/fracture/criteria.hpp"
#include "krug/mesh/quad.hpp"

using namespace krug;
using namespace krug::fracture;

namespace {

constexpr double tight = 1e-14;

struct Matrix2 {
  double f11, f12, f21, f22;
};

Matrix2 product(const Matrix2& a, const Matrix2& b) {
  return {a.f11 * b.f11 + a.f12 * b.f21, a.f11 * b.f12 + a.f12 * b.f22,
          a.f21 * b.f11 + a.f22 * b.f21, a.f21 * b.f12 + a.f22 * b.f22};
}

Matrix2 rotation(double angle) { return {std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle)}; }

Stretches stretches_of(const Matrix2& f, double out_of_plane = 1.0) {
  return principal_stretches(f.f11, f.f12, f.f21, f.f22, out_of_plane);
}

Matrix2 gradient_of(const quad::Corners& current, const quad::Corners& initial) {
  Matrix2 f{};
  deformation_gradient(current, quad::area_gradient(initial), quad::area(initial), f.f11, f.f12, f.f21, f.f22);
  return f;
}

void check_matrix(const Matrix2& actual, const Matrix2& expected, double tolerance) {
  CHECK(actual.f11 == Approx(expected.f11).margin(tolerance).epsilon(0.0));
  CHECK(actual.f12 == Approx(expected.f12).margin(tolerance).epsilon(0.0));
  CHECK(actual.f21 == Approx(expected.f21).margin(tolerance).epsilon(0.0));
  CHECK(actual.f22 == Approx(expected.f22).margin(tolerance).epsilon(0.0));
}

}  // namespace

TEST_CASE("principal stretches of pure stretch, rotated stretch and a rigid rotation", "[kernels][fracture_criteria]") {
  // F = diag(1.5, 0.8): C = diag(2.25, 0.64), stretches sqrt(2.25) = 1.5 and sqrt(0.64) = 0.8.
  const Matrix2 stretch{1.5, 0.0, 0.0, 0.8};
  const Stretches s = stretches_of(stretch);
  CHECK(s.in_plane_max == Approx(1.5).margin(tight));
  CHECK(s.in_plane_min == Approx(0.8).margin(tight));
  CHECK(s.out_of_plane == 1.0);
  // Polar decomposition: F = R U and F = U R have C = U^2 and R^T U^2 R, the same eigenvalues, so the
  // stretches of a 30 degree rotation times the stretch are again 1.5 and 0.8.
  const Matrix2 r = rotation(std::numbers::pi / 6.0);
  for (const Matrix2& f : {product(r, stretch), product(stretch, r)}) {
    const Stretches rotated = stretches_of(f);
    CHECK(rotated.in_plane_max == Approx(1.5).margin(1e-14));
    CHECK(rotated.in_plane_min == Approx(0.8).margin(1e-14));
  }
  // A rigid rotation alone stretches nothing: both 1.
  const Stretches rigid = stretches_of(rotation(1.0));
  CHECK(rigid.in_plane_max == Approx(1.0).margin(1e-14));
  CHECK(rigid.in_plane_min == Approx(1.0).margin(1e-14));
  // Equal stretches F = 1.2 I (C = 1.44 I, radius 0): both 1.2.
  const Stretches uniform = stretches_of({1.2, 0.0, 0.0, 1.2});
  CHECK(uniform.in_plane_max == Approx(1.2).margin(tight));
  CHECK(uniform.in_plane_min == Approx(1.2).margin(tight));
}

TEST_CASE("principal stretches of simple shear: sqrt(1 + g^2/4) +- g/2", "[kernels][fracture_criteria]") {
  // F = [[1, g], [0, 1]]: C = [[1, g], [g, 1 + g^2]], eigenvalues 1 + g^2/2 +- g sqrt(1 + g^2/4), whose
  // square roots are sqrt(1 + g^2/4) +- g/2: product 1 (det F = 1), difference g.
  const double g = GENERATE(0.1, 0.5, 2.0);
  const Stretches s = stretches_of({1.0, g, 0.0, 1.0});
  const double root = std::sqrt(1.0 + 0.25 * g * g);
  CHECK(s.in_plane_max == Approx(root + 0.5 * g).margin(1e-14));
  CHECK(s.in_plane_min == Approx(root - 0.5 * g).margin(1e-14));
  CHECK(s.in_plane_max * s.in_plane_min == Approx(1.0).margin(1e-14));
  CHECK(s.in_plane_max - s.in_plane_min == Approx(g).margin(1e-14));
  // g = 0.5 by hand: sqrt(1.0625) = 1.0307764064..., stretches 1.2807764064 and 0.7807764064.
  if (g == 0.5) {
    CHECK(s.in_plane_max == Approx(1.2807764064044151).margin(1e-15));
    CHECK(s.in_plane_min == Approx(0.7807764064044151).margin(1e-15));
  }
}

TEST_CASE("Stretches: largest and smallest include the out-of-plane (hoop) stretch", "[kernels][fracture_criteria]") {
  // In-plane 1.1 and 0.95 with a hoop stretch 1.3: largest 1.3, smallest 0.95.
  const Stretches hoop_largest = stretches_of({1.1, 0.0, 0.0, 0.95}, 1.3);
  CHECK(hoop_largest.largest() == 1.3);
  CHECK(hoop_largest.smallest() == Approx(0.95).margin(tight));
  // Hoop 0.7: largest 1.1 (in plane), smallest 0.7.
  const Stretches hoop_smallest = stretches_of({1.1, 0.0, 0.0, 0.95}, 0.7);
  CHECK(hoop_smallest.largest() == Approx(1.1).margin(tight));
  CHECK(hoop_smallest.smallest() == 0.7);
}

TEST_CASE("deformation gradient of a quad under an affine map is the map", "[kernels][fracture_criteria]") {
  // x = M X + t. With b_p = dA0/dX_p, F = (1/A0) sum_p x_p (x) b_p = M (1/A0) sum_p X_p (x) b_p
  // + t (x) sum_p b_p. For any quad sum_p b_p = 0 (the differences telescope) and
  // sum_p X_p (x) b_p = A0 I (A is linear in the x's with sum_p x_p dA/dx_p = A, and a shear
  // y -> y + e x keeps the area, so sum_p x_p dA/dy_p = 0): F = M exactly, whatever the quad's shape.
  const Matrix2 m{1.2, 0.3, -0.1, 0.9};
  const Vec2 t{2.0, -1.0};
  const auto map = [&](Vec2 p) { return Vec2{m.f11 * p.x + m.f12 * p.y + t.x, m.f21 * p.x + m.f22 * p.y + t.y}; };
  SECTION("unit square") {
    const quad::Corners initial{Vec2{0.0, 0.0}, Vec2{1.0, 0.0}, Vec2{1.0, 1.0}, Vec2{0.0, 1.0}};
    // The area gradients of the unit square by hand: (y_{p+1} - y_{p-1}, x_{p-1} - x_{p+1}) / 2.
    const std::array<Vec2, 4> b = quad::area_gradient(initial);
    CHECK((b[0].x == -0.5 && b[0].y == -0.5 && b[1].x == 0.5 && b[1].y == -0.5));
    CHECK((b[2].x == 0.5 && b[2].y == 0.5 && b[3].x == -0.5 && b[3].y == 0.5));
    CHECK(quad::area(initial) == 1.0);
    const quad::Corners current{map(initial[0]), map(initial[1]), map(initial[2]), map(initial[3])};
    check_matrix(gradient_of(current, initial), m, 1e-15);
  }
  SECTION("trapezoid (not a parallelogram), where the bilinear map is not affine") {
    // Corners (0,0), (2,0), (1.5,1), (0.5,1): area (2 + 1)/2 = 1.5 = (1/2)(d02 x d13)
    // = (1/2) cross((1.5, 1), (-1.5, 1)) = (1/2)(1.5 + 1.5).
    const quad::Corners initial{Vec2{0.0, 0.0}, Vec2{2.0, 0.0}, Vec2{1.5, 1.0}, Vec2{0.5, 1.0}};
    CHECK(quad::area(initial) == 1.5);
    const quad::Corners current{map(initial[0]), map(initial[1]), map(initial[2]), map(initial[3])};
    check_matrix(gradient_of(current, initial), m, 1e-14);
  }
  SECTION("undeformed: F = I") {
    const quad::Corners initial{Vec2{0.3, 0.1}, Vec2{1.4, 0.2}, Vec2{1.1, 0.9}, Vec2{0.2, 1.3}};
    check_matrix(gradient_of(initial, initial), {1.0, 0.0, 0.0, 1.0}, 1e-14);
  }
}

TEST_CASE("deformation gradient by one-point quadrature does not see the hourglass mode", "[kernels][fracture_criteria]") {
  // Unit square with the corners displaced by d h_p, h = (1, -1, 1, -1) (the x-hourglass): with the
  // gradients above, sum_p h_p b_p = (-0.5 - 0.5 + 0.5 + 0.5, -0.5 + 0.5 + 0.5 - 0.5) = (0, 0), so
  // F = I although the quad is distorted: the one-point rule's known blind spot.
  const quad::Corners initial{Vec2{0.0, 0.0}, Vec2{1.0, 0.0}, Vec2{1.0, 1.0}, Vec2{0.0, 1.0}};
  const double d = 0.1;
  const quad::Corners current{Vec2{d, 0.0}, Vec2{1.0 - d, 0.0}, Vec2{1.0 + d, 1.0}, Vec2{-d, 1.0}};
  check_matrix(gradient_of(current, initial), {1.0, 0.0, 0.0, 1.0}, 1e-15);
}

TEST_CASE("principal stress of s - p I: in-plane pair and the zz value", "[kernels][fracture_criteria]") {
  // Pure shear deviator sxx = -syy = 3, sxy = 4, szz = 0: mean 0, radius sqrt(3^2 + 4^2) = 5 -> +5 / -5.
  const PrincipalStress shear = principal_stress(3.0, -3.0, 4.0, 0.0, 0.0);
  CHECK(shear.largest == Approx(5.0).margin(tight));
  CHECK(shear.smallest == Approx(-5.0).margin(tight));
  // Pure in-plane shear sxy = 6 with a pressure of 2: +-6 shifted by -2 -> 4 and -8 (zz = -2 between).
  const PrincipalStress pressed = principal_stress(0.0, 0.0, 6.0, 0.0, 2.0);
  CHECK(pressed.largest == Approx(4.0).margin(tight));
  CHECK(pressed.smallest == Approx(-8.0).margin(tight));
  // zz outside the in-plane pair: in-plane (-2, -2), szz = 4 (trace free), p = 1 -> largest 4 - 1 = 3
  // from zz, smallest -2 - 1 = -3.
  const PrincipalStress hoop = principal_stress(-2.0, -2.0, 0.0, 4.0, 1.0);
  CHECK(hoop.largest == Approx(3.0).margin(tight));
  CHECK(hoop.smallest == Approx(-3.0).margin(tight));
  // szz below the in-plane pair: in-plane (1, 1), szz = -2, p = 0 -> largest 1, smallest -2.
  const PrincipalStress low = principal_stress(1.0, 1.0, 0.0, -2.0, 0.0);
  CHECK(low.largest == Approx(1.0).margin(tight));
  CHECK(low.smallest == Approx(-2.0).margin(tight));
}

TEST_CASE("exceeded reports the first criterion in the order of (1)", "[kernels][fracture_criteria]") {
  // A state beyond every limit: elongation 1.3 - 1 = 0.3 > 0.1; largest stress 150 > 100;
  // -(smallest) = 250 > 200; shear 1.3 - 0.9 = 0.4 > 0.2; energy 2000 > 1000.
  const Stretches stretch = stretches_of({1.3, 0.0, 0.0, 0.9});
  const PrincipalStress stress{150.0, -250.0};
  const double energy = 2000.0;
  FractureLimits limits;
  CHECK_FALSE(limits.any());  // every limit infinite by default: nothing fires
  CHECK(exceeded(limits, stretch, stress, energy) == Criterion::none);
  limits.elongation = 0.1;
  limits.tensile_stress = 100.0;
  limits.compressive_stress = 200.0;
  limits.shear_strain = 0.2;
  limits.internal_energy = 1000.0;
  CHECK(limits.any());
  // Raising the limits one by one beyond the state walks down the documented order.
  CHECK(exceeded(limits, stretch, stress, energy) == Criterion::elongation);
  limits.elongation = 0.5;
  CHECK(exceeded(limits, stretch, stress, energy) == Criterion::tensile_stress);
  limits.tensile_stress = 1000.0;
  CHECK(exceeded(limits, stretch, stress, energy) == Criterion::compressive_stress);
  limits.compressive_stress = 1000.0;
  CHECK(exceeded(limits, stretch, stress, energy) == Criterion::shear_strain);
  limits.shear_strain = 1.0;
  CHECK(exceeded(limits, stretch, stress, energy) == Criterion::energy);
  limits.internal_energy = 1e4;
  CHECK(exceeded(limits, stretch, stress, energy) == Criterion::none);
  CHECK(criterion_name(Criterion::energy) == "internal_energy");
  CHECK(criterion_name(Criterion::none) == "none");
}

TEST_CASE("exceeded: each criterion alone, and the hoop stretch counts", "[kernels][fracture_criteria]") {
  const Stretches rest = stretches_of({1.0, 0.0, 0.0, 1.0});
  const PrincipalStress unloaded{0.0, 0.0};
  // Any one finite limit makes `any` true.
  FractureLimits only_energy;
  only_energy.internal_energy = 5.0;
  CHECK(only_energy.any());
  CHECK(exceeded(only_energy, rest, unloaded, 6.0) == Criterion::energy);
  CHECK(exceeded(only_energy, rest, unloaded, 4.0) == Criterion::none);
  // Hoop stretch 1.3 with the in-plane state at rest: elongation 0.3 > 0.25 and shear 1.3 - 1 = 0.3 > 0.2.
  FractureLimits strain;
  strain.elongation = 0.25;
  strain.shear_strain = 0.2;
  CHECK(exceeded(strain, stretches_of({1.0, 0.0, 0.0, 1.0}, 1.3), unloaded, 0.0) == Criterion::elongation);
  strain.elongation = disabled;
  CHECK(exceeded(strain, stretches_of({1.0, 0.0, 0.0, 1.0}, 1.3), unloaded, 0.0) == Criterion::shear_strain);
  // Simple shear g = 0.5: stretch difference exactly g (above), largest 1.2808: shear 0.5 > 0.4.
  FractureLimits shear_only;
  shear_only.shear_strain = 0.4;
  CHECK(exceeded(shear_only, stretches_of({1.0, 0.5, 0.0, 1.0}), unloaded, 0.0) == Criterion::shear_strain);
  shear_only.shear_strain = 0.6;
  CHECK(exceeded(shear_only, stretches_of({1.0, 0.5, 0.0, 1.0}), unloaded, 0.0) == Criterion::none);
  // The compressive limit acts on minus the smallest principal stress: -(-250) = 250 > 200, while a
  // tensile limit of 100 is not reached by a largest value of -50.
  FractureLimits brittle;
  brittle.tensile_stress = 100.0;
  brittle.compressive_stress = 200.0;
  CHECK(exceeded(brittle, rest, {-50.0, -250.0}, 0.0) == Criterion::compressive_stress);
  CHECK(exceeded(brittle, rest, {-50.0, -150.0}, 0.0) == Criterion::none);
}

TEST_CASE("loosening and the fully fractured rule", "[kernels][fracture_criteria]") {
  CHECK(loosening(900.0, 1000.0) == Approx(0.1).margin(tight));  // 1 - 900/1000
  CHECK(loosening(1000.0, 1000.0) == 0.0);                       // at the reference density
  CHECK(loosening(1100.0, 1000.0) == 0.0);                       // compressed: not loosened
  // chi beyond chi_* = 0.03: fully fractured whatever the altitude.
  CHECK(fully_fractured(0.05, 0.03, 1.0, 1.0, 0.1));
  CHECK_FALSE(fully_fractured(0.02, 0.03, 1.0, 1.0, 0.1));
  // chi below the limit but the altitude 0.05 collapsed below 0.1 x 1: fully fractured.
  CHECK(fully_fractured(0.02, 0.03, 0.05, 1.0, 0.1));
  CHECK_FALSE(fully_fractured(0.02, 0.03, 0.5, 1.0, 0.1));
  // A ratio of 0 turns the altitude rule off for any positive altitude.
  CHECK_FALSE(fully_fractured(0.0, 0.03, 1e-9, 1.0, 0.0));
}

TEST_CASE("ErosionLimits: off by default; collapse on the altitude ratio, strain on the plastic strain",
          "[kernels][fracture_criteria]") {
  const ErosionLimits off;
  CHECK_FALSE(off.any());
  CHECK_FALSE(off.collapsed(1e-9, 1.0));  // ratio 0: 1e-9 < 0 x 1 is false
  CHECK_FALSE(off.strained(1e6));         // limit infinite
  ErosionLimits altitude;
  altitude.altitude_ratio = 0.2;
  CHECK(altitude.any());
  CHECK(altitude.collapsed(0.1, 1.0));        // 0.1 < 0.2 x 1
  CHECK_FALSE(altitude.collapsed(0.3, 1.0));  // 0.3 > 0.2
  CHECK(altitude.collapsed(0.03, 0.2));       // 0.03 < 0.2 x 0.2 = 0.04
  CHECK_FALSE(altitude.strained(10.0));
  ErosionLimits strain;
  strain.plastic_strain = 1.5;
  CHECK(strain.any());
  CHECK(strain.strained(1.6));
  CHECK_FALSE(strain.strained(1.4));
  CHECK_FALSE(strain.collapsed(1e-9, 1.0));
}
