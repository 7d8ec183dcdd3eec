// Point-wise tests of the strength laws (krug/material/strength.hpp): deviator algebra, objective
// rotation, the Hooke trial, radial return (verification.md E3, E4, E6 materials), Johnson–Cook and
// dispatch through the Strength variant.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <numbers>
#include <variant>

#include "krug/material/material.hpp"
#include "krug/material/strength.hpp"

namespace {

using krug::Deviator;
using krug::StrainRate;

// Trace-free deviators of assorted shapes and signs (Pa); zz = -(xx + yy).
const std::array<Deviator, 4> sample_deviators{{
    {2.0e8, -1.0e8, 0.0, -1.0e8},      // uniaxial
    {-3.0e7, 5.0e7, 4.0e7, -2.0e7},    // general
    {0.0, 0.0, 6.0e7, 0.0},            // pure in-plane shear
    {1.1e8, 2.3e7, -7.7e7, -1.33e8},   // general, negative shear
}};

// Uniaxial strain along the first axis: D = (rate, 0, 0, 0).
StrainRate uniaxial_strain_rate(double rate) { return {rate, 0.0, 0.0, 0.0}; }

// Component-wise equality within an absolute tolerance (Pa); the relative epsilon is switched off so
// the stated margin is the whole allowance.
void check_same(const Deviator& actual, const Deviator& expected, double tolerance) {
  CHECK(actual.xx == Approx(expected.xx).margin(tolerance).epsilon(0.0));
  CHECK(actual.yy == Approx(expected.yy).margin(tolerance).epsilon(0.0));
  CHECK(actual.xy == Approx(expected.xy).margin(tolerance).epsilon(0.0));
  CHECK(actual.zz == Approx(expected.zz).margin(tolerance).epsilon(0.0));
}

}  // namespace

TEST_CASE("deviator algebra: contraction, equivalent stress, determinant", "[strength]") {
  // Uniaxial stress sigma = 3: s = sigma (2/3, -1/3, -1/3) = (2, -1, -1); s:s = 6, sqrt(3/2 * 6) = 3 = sigma.
  const Deviator uniaxial{2.0, -1.0, 0.0, -1.0};
  CHECK(krug::double_contraction(uniaxial, uniaxial) == Approx(6.0).epsilon(1e-15));
  CHECK(krug::equivalent_stress(uniaxial) == Approx(3.0).epsilon(1e-15));
  CHECK(krug::determinant(uniaxial) == Approx(2.0).epsilon(1e-15));  // 2 * (-1) * (-1)
  // Pure shear tau = 5: s:s = 2 tau^2 = 50, equivalent sqrt(3) tau.
  const Deviator shear{0.0, 0.0, 5.0, 0.0};
  CHECK(krug::double_contraction(shear, shear) == Approx(50.0).epsilon(1e-15));
  CHECK(krug::equivalent_stress(shear) == Approx(5.0 * std::sqrt(3.0)).epsilon(1e-15));
  // Equivalent strain rate of incompressible uniaxial stress D = (1, -1/2, 0, -1/2): sqrt(2/3 * 3/2) = 1.
  CHECK(krug::equivalent_strain_rate({1.0, -0.5, 0.0, -0.5}) == Approx(1.0).epsilon(1e-15));
}

TEST_CASE("objective rotation: hand values of rotations by 45 and 90 degrees", "[strength]") {
  const Deviator uniaxial{2.0, -1.0, 0.0, -1.0};
  // R s R^T with the principal axis turned from x to the bisector: xx = yy = mean = 0.5,
  // xy = (s_xx - s_yy)/2 sin(2 theta) = 1.5; zz does not rotate.
  check_same(krug::rotate_deviator(uniaxial, std::numbers::pi / 4.0), {0.5, 0.5, 1.5, -1.0}, 1e-15);
  // By 90 degrees xx and yy swap.
  check_same(krug::rotate_deviator(uniaxial, std::numbers::pi / 2.0), {-1.0, 2.0, 0.0, -1.0}, 1e-15);
}

TEST_CASE("objective rotation: rotating by theta and back restores the deviator", "[strength]") {
  for (const Deviator& s : sample_deviators) {
    for (const double angle : {1e-6, 0.3, 1.0, 2.5, -4.0}) {
      INFO("angle = " << angle);
      // Two rotations, each a few round-offs of |s| ~ 2e8 Pa: 1e-6 Pa is 5e-15 relative.
      check_same(krug::rotate_deviator(krug::rotate_deviator(s, angle), -angle), s, 1e-6);
    }
  }
}

TEST_CASE("objective rotation: invariants and trace are preserved by any rotation", "[strength]") {
  for (const Deviator& s : sample_deviators) {
    const double contraction = krug::double_contraction(s, s);
    const double determinant = krug::determinant(s);
    for (const double angle : {0.1, 0.7, 1.5707963267948966, 3.0, -2.2}) {
      for (const auto method : {krug::StressRotation::exact, krug::StressRotation::hughes_winget}) {
        // A spin of 1 rad/s over dt = angle: exact rotation by the angle, Hughes–Winget by 2 atan(angle/2).
        const Deviator rotated = krug::rotate_objectively(s, 1.0, angle, method);
        INFO("angle = " << angle);
        // Orthogonal rotation: invariants to round-off (relative 1e-14 of s:s ~ 1e16, det ~ 1e24).
        CHECK(krug::double_contraction(rotated, rotated) == Approx(contraction).epsilon(1e-14));
        CHECK(krug::determinant(rotated) == Approx(determinant).margin(1e-14 * std::pow(contraction, 1.5)).epsilon(0.0));
        // Trace-free in, trace-free out: round-off of |s| ~ 2e8 Pa.
        CHECK(krug::trace(rotated) == Approx(0.0).margin(1e-7));
        CHECK(rotated.zz == s.zz);
      }
    }
  }
}

TEST_CASE("objective rotation: rigid spin from the velocity gradient, exact and Hughes–Winget", "[strength]") {
  // Rigid rotation v = Omega (-y, x): dv_y/dx = Omega, dv_x/dy = -Omega, so the spin is Omega.
  const double omega_rigid = 2.0e4;  // rad/s
  const double spin = krug::in_plane_spin(omega_rigid, -omega_rigid);
  CHECK(spin == Approx(omega_rigid).epsilon(1e-15));

  const Deviator initial = sample_deviators[1];
  const double dt = 1e-6;  // Omega dt = 0.02 rad per step
  const int steps = 100;   // total 2 rad
  Deviator exact = initial;
  Deviator midpoint = initial;
  for (int step = 0; step < steps; ++step) {
    exact = krug::rotate_objectively(exact, spin, dt);
    midpoint = krug::rotate_objectively(midpoint, spin, dt, krug::StressRotation::hughes_winget);
  }
  // Exact rotation: the stress co-rotates with the body, R(Omega t) s0 R^T; 100 steps of round-off.
  check_same(exact, krug::rotate_deviator(initial, omega_rigid * dt * steps), 1e-5);
  // Hughes–Winget: rotation by 2 atan(Omega dt / 2) per step (Cayley transform), angle error
  // (Omega dt)^3 / 12 per step = 6.7e-7 rad, 6.7e-5 rad after 100 steps.
  check_same(midpoint, krug::rotate_deviator(initial, steps * 2.0 * std::atan(0.5 * omega_rigid * dt)), 1e-5);
  const double angle_error = omega_rigid * dt * steps - steps * 2.0 * std::atan(0.5 * omega_rigid * dt);
  CHECK(angle_error == Approx(steps * std::pow(omega_rigid * dt, 3) / 12.0).epsilon(1e-3));
}

TEST_CASE("objective rotation: small angles follow the Jaumann rate W s - s W", "[strength]") {
  // d/dt (R s R^T) at t = 0 with W = [[0, -omega], [omega, 0]]: d s_xx = -2 omega s_xy,
  // d s_yy = 2 omega s_xy, d s_xy = omega (s_xx - s_yy) (hand derivation).
  const Deviator s = sample_deviators[1];
  const double omega = 3.0;
  const double dt = 1e-7;
  const Deviator rotated = krug::rotate_objectively(s, omega, dt);
  // One-sided difference of rates ~ 2.4e8 Pa/s: truncation (2 omega dt)^2 / 2 |s| / dt ~ 90 Pa/s,
  // round-off 1e-16 * 5e7 Pa / dt ~ 0.05 Pa/s; allowance 300 Pa/s (1e-6 of omega * 1e8 Pa).
  const double allowance = 1e-6 * omega * 1e8;
  CHECK((rotated.xx - s.xx) / dt == Approx(-2.0 * omega * s.xy).margin(allowance).epsilon(0.0));
  CHECK((rotated.yy - s.yy) / dt == Approx(2.0 * omega * s.xy).margin(allowance).epsilon(0.0));
  CHECK((rotated.xy - s.xy) / dt == Approx(omega * (s.xx - s.yy)).margin(allowance).epsilon(0.0));
}

TEST_CASE("Hooke trial: hand value and trace-free increment", "[strength]") {
  // 2 mu dt = 2 * 4.5e10 * 1e-8 = 900 Pa s; D = (-1000, 0, 200, 500) 1/s has tr D / 3 = -500/3, so
  // D' = (-2500/3, 500/3, 200, 2000/3) and the increment 900 D' = (-750000, 150000, 180000, 600000) Pa.
  const Deviator start{1.0e6, -4.0e5, 3.0e5, -6.0e5};
  const Deviator trial = krug::hooke_trial(start, {-1000.0, 0.0, 200.0, 500.0}, 4.5e10, 1e-8);
  check_same(trial, {1.0e6 - 750000.0, -4.0e5 + 150000.0, 3.0e5 + 180000.0, -6.0e5 + 600000.0}, 1e-8);
  CHECK(krug::trace(trial) == Approx(0.0).margin(1e-8));  // round-off of 1e6 Pa
}

TEST_CASE("radial return: lands on the yield surface along the trial direction", "[strength]") {
  const double mu = 4.5e10;  // E3 copper
  const double yield = 9e7;
  for (const Deviator& s : sample_deviators) {
    const Deviator trial = krug::scaled(s, 3.0);  // equivalent 2.9e8 .. 7.0e8 Pa > Y
    const double trial_equivalent = krug::equivalent_stress(trial);
    const krug::PlasticReturn result = krug::radial_return(trial, mu, yield);
    REQUIRE(result.yielded);
    // sqrt(3/2 s:s) = Y to round-off (brief: 1e-12 relative).
    CHECK(krug::equivalent_stress(result.deviator) == Approx(yield).epsilon(1e-12));
    // d eps_p = (q_trial - Y) / (3 mu) (docs/theory.md §2 step 5 with H = 0).
    CHECK(result.plastic_strain_increment == Approx((trial_equivalent - yield) / (3.0 * mu)).epsilon(1e-13));
    // Radial: s = (Y / q_trial) s_trial, component by component.
    check_same(result.deviator, krug::scaled(trial, yield / trial_equivalent), 1e-12 * yield);
    CHECK(krug::trace(result.deviator) == Approx(0.0).margin(1e-12 * yield));
    // Perfect plasticity: W_p = Y d eps_p, which equals the exact s^{n+1} : d eps^p with
    // d eps^p = (s_trial - s^{n+1}) / (2 mu) (hand: (Y/q)(1 - Y/q)(2 q^2/3) / (2 mu) = Y (q - Y) / (3 mu)).
    const Deviator plastic_strain_tensor = krug::scaled(
        {trial.xx - result.deviator.xx, trial.yy - result.deviator.yy, trial.xy - result.deviator.xy,
         trial.zz - result.deviator.zz},
        1.0 / (2.0 * mu));
    CHECK(result.plastic_work_density == Approx(yield * result.plastic_strain_increment).epsilon(1e-14));
    CHECK(result.plastic_work_density ==
          Approx(krug::double_contraction(result.deviator, plastic_strain_tensor)).epsilon(1e-10));
  }
  // A trial inside the surface is returned unchanged, with no plastic strain or work.
  const Deviator inside = krug::scaled(sample_deviators[0], 0.1);  // equivalent 3e7 < 9e7
  const krug::PlasticReturn elastic = krug::radial_return(inside, mu, yield);
  CHECK_FALSE(elastic.yielded);
  check_same(elastic.deviator, inside, 0.0);
  CHECK(elastic.plastic_strain_increment == 0.0);
  CHECK(elastic.plastic_work_density == 0.0);
}

TEST_CASE("radial return: E3 uniaxial strain loading of copper", "[strength]") {
  // verification.md E3: mu = 4.5e10, Y = 9e7. Uniaxial compression, logarithmic strain eps = ln(rho/rho0)
  // loaded in equal steps up to the E3 plastic density 8973.453.
  const krug::PerfectlyPlastic copper{4.5e10, 9e7};
  const double mu = copper.shear_modulus;
  const double yield = copper.yield_stress;
  const double rho0 = 8930.0;
  const double yield_strain = yield / (2.0 * mu);         // 1e-3: elastic q = 2 mu eps reaches Y
  const double rho_yield = rho0 * std::exp(yield_strain);  // E3: rho_y = rho0 exp(Y / (2 mu))
  CHECK(rho_yield == Approx(8938.934).margin(5e-4).epsilon(0.0));     // the E3 precursor density (table, 3 decimals)

  const double final_strain = std::log(8973.453 / rho0);
  const int steps = 400;
  const double dt = 1e-9;
  const double strain_step = final_strain / steps;
  const StrainRate rate = uniaxial_strain_rate(-strain_step / dt);  // compression

  Deviator s{};
  double plastic_strain = 0.0;
  double plastic_work = 0.0;
  int first_yield_step = -1;
  for (int step = 1; step <= steps; ++step) {
    const krug::PlasticReturn result = krug::update_deviator(copper, s, rate, 0.0, dt, {plastic_strain});
    s = result.deviator;
    plastic_strain += result.plastic_strain_increment;
    plastic_work += result.plastic_work_density;
    const double strain = step * strain_step;
    if (result.yielded) {
      if (first_yield_step < 0) first_yield_step = step;
      // Behind the plastic wave: s_xx = -2Y/3, s_yy = s_zz = Y/3 to round-off, every step.
      REQUIRE(s.xx == Approx(-2.0 * yield / 3.0).epsilon(1e-12));
      REQUIRE(s.yy == Approx(yield / 3.0).epsilon(1e-12));
      REQUIRE(s.zz == Approx(yield / 3.0).epsilon(1e-12));
    } else {
      // Elastic uniaxial strain: s_xx = -(4/3) mu eps (2 mu times the deviatoric strain -2/3 eps).
      REQUIRE(s.xx == Approx(-4.0 / 3.0 * mu * strain).epsilon(1e-12));
    }
    REQUIRE(krug::trace(s) == Approx(0.0).margin(1e-12 * yield));
  }
  // Yielding starts in the step whose density interval contains rho_y.
  REQUIRE(first_yield_step > 1);
  CHECK(rho0 * std::exp((first_yield_step - 1) * strain_step) < rho_yield);
  CHECK(rho0 * std::exp(first_yield_step * strain_step) >= rho_yield);
  // E3 table: s_xx = -6.0e7 Pa at the plastic state.
  CHECK(s.xx == Approx(-6.0e7).epsilon(1e-12));
  // Past yield the whole deviatoric strain rate is plastic: d eps_p = sqrt(2/3 D':D') dt = (2/3) d eps,
  // so eps_p = (2/3)(eps - eps_y) (the straddling step's return gives exactly its plastic part).
  CHECK(plastic_strain == Approx(2.0 / 3.0 * (final_strain - yield_strain)).epsilon(1e-10));
  // Perfect plasticity: W_p = Y eps_p.
  CHECK(plastic_work == Approx(yield * plastic_strain).epsilon(1e-12));
}

TEST_CASE("radial return: E4 release swings the deviator from -2Y/3 to +2Y/3 elastically", "[strength]") {
  // verification.md E4 (Wilkins aluminium, mu = 2.76e10, Y = 3e8). Load in uniaxial compression to twice
  // the yield strain, then release: s_xx = -2Y/3 + (4/3) mu * (release strain) while elastic, which
  // reaches +2Y/3 after a release strain of Y / mu = 1.087e-2, then yields in tension.
  const krug::PerfectlyPlastic aluminium{2.76e10, 3e8};
  const double mu = aluminium.shear_modulus;
  const double yield = aluminium.yield_stress;
  const double dt = 1e-9;
  const double strain_step = 1.3e-4;  // Y / mu = 83.6 steps: the swing ends inside step 84

  Deviator s{};
  const int loading_steps = 2 * static_cast<int>(yield / (2.0 * mu) / strain_step) + 2;
  for (int step = 0; step < loading_steps; ++step) {
    s = krug::update_deviator(aluminium, s, uniaxial_strain_rate(-strain_step / dt), 0.0, dt, {}).deviator;
  }
  REQUIRE(s.xx == Approx(-2.0 * yield / 3.0).epsilon(1e-12));

  const int swing_steps = static_cast<int>(yield / mu / strain_step);  // 83
  for (int step = 1; step <= swing_steps + 3; ++step) {
    const krug::PlasticReturn result =
        krug::update_deviator(aluminium, s, uniaxial_strain_rate(strain_step / dt), 0.0, dt, {});
    s = result.deviator;
    INFO("release step " << step);
    if (step <= swing_steps) {
      REQUIRE_FALSE(result.yielded);
      // Round-off of 2e8 Pa over up to 83 additions: 1e-5 Pa.
      REQUIRE(s.xx == Approx(-2.0 * yield / 3.0 + 4.0 / 3.0 * mu * step * strain_step).margin(1e-5).epsilon(0.0));
    } else {
      REQUIRE(result.yielded);
      REQUIRE(s.xx == Approx(2.0 * yield / 3.0).epsilon(1e-12));
    }
  }
}

TEST_CASE("radial return: linear hardening consistency (E6 copper)", "[strength]") {
  // verification.md E6: mu = 43.3e9, Y0 = 400 MPa, H = 100 MPa.
  const krug::LinearHardening copper{43.3e9, 4e8, 1e8};
  const double mu = copper.shear_modulus;
  const double hardening = copper.hardening_modulus;

  SECTION("one return: hand value") {
    // q_trial = 5e8 along a uniaxial direction, eps_p = 0.2: Y_n = 4.2e8,
    // d eps_p = (5e8 - 4.2e8) / (3 * 43.3e9 + 1e8) = 6.153846153846154e-4, Y_{n+1} = 4.2006153846153843e8.
    const Deviator trial{5e8 * 2.0 / 3.0, -5e8 / 3.0, 0.0, -5e8 / 3.0};
    const krug::PlasticReturn result = krug::radial_return(copper, trial, {0.2});
    REQUIRE(result.yielded);
    CHECK(result.plastic_strain_increment == Approx(6.153846153846154e-4).epsilon(1e-13));
    const double end_yield = 4.2006153846153843e8;
    // Y grows by H d eps_p exactly: the returned state lies on Y0 + H (eps_p + d eps_p).
    CHECK(krug::equivalent_stress(result.deviator) == Approx(end_yield).epsilon(1e-12));
    CHECK(copper.flow_stress(0.2 + result.plastic_strain_increment) == Approx(end_yield).epsilon(1e-14));
    // Consistency: q_trial - 3 mu d eps_p = Y_{n+1}.
    CHECK(5e8 - 3.0 * mu * result.plastic_strain_increment == Approx(end_yield).epsilon(1e-12));
    // Work of the flow stress along the path: (Y_n + Y_{n+1}) / 2 d eps_p.
    CHECK(result.plastic_work_density ==
          Approx(0.5 * (4.2e8 + end_yield) * 6.153846153846154e-4).epsilon(1e-13));
  }
  SECTION("many steps: the surface follows eps_p and W_p is a state function") {
    // Uniaxial strain loading to 2 % strain in 1000 steps.
    const double dt = 1e-9;
    const double strain_step = 2e-5;
    Deviator s{};
    double plastic_strain = 0.0;
    double plastic_work = 0.0;
    for (int step = 0; step < 1000; ++step) {
      const krug::PlasticReturn result =
          krug::update_deviator(copper, s, uniaxial_strain_rate(-strain_step / dt), 0.0, dt, {plastic_strain});
      s = result.deviator;
      plastic_strain += result.plastic_strain_increment;
      plastic_work += result.plastic_work_density;
      if (result.yielded) {
        REQUIRE(krug::equivalent_stress(s) == Approx(copper.flow_stress(plastic_strain)).epsilon(1e-12));
      }
    }
    REQUIRE(plastic_strain > 0.01);
    // W_p = integral of (Y0 + H eps) d eps = Y0 eps_p + H eps_p^2 / 2, exact for the trapezoid rule.
    CHECK(plastic_work == Approx(4e8 * plastic_strain + 0.5 * hardening * plastic_strain * plastic_strain)
                              .epsilon(1e-12));
    // Uniaxial strain keeps s along (-2, 1, 1)/3: on the surface s_xx = -2Y/3 with the hardened Y.
    CHECK(s.xx == Approx(-2.0 / 3.0 * copper.flow_stress(plastic_strain)).epsilon(1e-12));
  }
}

TEST_CASE("Johnson-Cook: flow stress and return", "[strength]") {
  // Parameters of the order of Johnson & Cook (1983) OFHC copper; the asserted numbers are the formula.
  krug::JohnsonCook copper;
  copper.shear_modulus = 4.5e10;
  copper.yield_stress = 90e6;            // A
  copper.hardening_coefficient = 292e6;  // B
  copper.hardening_exponent = 0.31;      // n
  copper.strain_rate_coefficient = 0.025;
  copper.reference_strain_rate = 1.0;
  copper.thermal_softening_exponent = 1.09;
  copper.room_temperature = 293.0;
  copper.melt_temperature = 1356.0;
  copper.specific_heat = 383.0;

  SECTION("flow stress: hand value") {
    // (A + B 0.1^0.31) = 2.330154152555863e8; rate factor 1 + 0.025 ln 1000 = 1.1726938819745534;
    // T* = 207 / 1063 = 0.19473189087488240, 1 - T*^1.09 = 0.8319314635538784; product 2.273300575827045e8.
    CHECK(copper.flow_stress(0.1, 1e3, 500.0) == Approx(2.273300575827045e8).epsilon(1e-13));
    // dY/d eps_p = B n eps^(n-1) * factors = 4.325305169350203e8.
    CHECK(copper.hardening_slope(0.1, 1e3, 500.0) == Approx(4.325305169350203e8).epsilon(1e-13));
    // Below the reference rate and below room temperature the factors are 1; at melt Y = 0.
    CHECK(copper.flow_stress(0.0, 1e-3, 200.0) == Approx(90e6).epsilon(1e-15));
    CHECK(copper.flow_stress(0.1, 1.0, 1356.0) == Approx(0.0).margin(1e-6));
    // T = T_room + e / c_v = 293 + 38300 / 383 = 393 K.
    CHECK(copper.temperature_from_energy(38300.0) == Approx(393.0).epsilon(1e-15));
  }
  SECTION("return satisfies the consistency condition, also from eps_p = 0 (infinite slope)") {
    for (const double plastic_strain : {0.0, 0.05, 1.0}) {
      const krug::PlasticState state{plastic_strain, 1e3, 400.0};
      const Deviator trial{4e8, -1.5e8, 1e8, -2.5e8};
      const double trial_equivalent = krug::equivalent_stress(trial);
      const krug::PlasticReturn result = krug::radial_return(copper, trial, state);
      INFO("eps_p = " << plastic_strain);
      REQUIRE(result.yielded);
      const double end_yield = copper.flow_stress(plastic_strain + result.plastic_strain_increment, 1e3, 400.0);
      // g(d) = q_trial - 3 mu d - Y(eps_p + d) = 0 to a few round-offs of q_trial.
      CHECK(trial_equivalent - 3.0 * copper.shear_modulus * result.plastic_strain_increment ==
            Approx(end_yield).epsilon(1e-12));
      CHECK(krug::equivalent_stress(result.deviator) == Approx(end_yield).epsilon(1e-12));
    }
  }
  SECTION("reduces to the closed forms: perfectly plastic (B = 0) and linear hardening (n = 1)") {
    const Deviator trial{4e8, -1.5e8, 1e8, -2.5e8};
    krug::JohnsonCook constant_flow;
    constant_flow.shear_modulus = 4.5e10;
    constant_flow.yield_stress = 9e7;
    const krug::PlasticReturn jc_constant = krug::radial_return(constant_flow, trial, {0.3});
    const krug::PlasticReturn perfect = krug::radial_return(krug::PerfectlyPlastic{4.5e10, 9e7}, trial, {0.3});
    check_same(jc_constant.deviator, perfect.deviator, 1e-12 * 9e7);
    CHECK(jc_constant.plastic_strain_increment == Approx(perfect.plastic_strain_increment).epsilon(1e-12));

    krug::JohnsonCook linear_flow = constant_flow;
    linear_flow.hardening_coefficient = 1e8;
    linear_flow.hardening_exponent = 1.0;
    const krug::PlasticReturn jc_linear = krug::radial_return(linear_flow, trial, {0.3});
    const krug::PlasticReturn linear = krug::radial_return(krug::LinearHardening{4.5e10, 9e7, 1e8}, trial, {0.3});
    check_same(jc_linear.deviator, linear.deviator, 1e-12 * 1.2e8);
    CHECK(jc_linear.plastic_strain_increment == Approx(linear.plastic_strain_increment).epsilon(1e-12));
    CHECK(jc_linear.plastic_work_density == Approx(linear.plastic_work_density).epsilon(1e-12));
  }
}

TEST_CASE("strength dispatch: variant, Material shear modulus, none and elastic", "[strength]") {
  const Deviator previous{2e7, -1e7, 5e6, -1e7};
  const StrainRate rate{-1e3, 2e2, 3e2, 4e2};
  const double spin = 50.0;
  const double dt = 1e-8;

  krug::Material material;
  material.strength = krug::LinearHardening{4.5e10, 9e7, 1e8};
  CHECK(material.shear_modulus() == 4.5e10);
  material.strength = krug::NoStrength{};
  CHECK(material.shear_modulus() == 0.0);

  // No strength: the deviator is zero whatever the history.
  const krug::PlasticReturn none = krug::update_deviator(krug::NoStrength{}, previous, rate, spin, dt, {});
  check_same(none.deviator, {}, 0.0);

  // Elastic: rotate then Hooke, never a return, whatever the size of the stress.
  const krug::Elastic elastic{4.5e10};
  const krug::PlasticReturn elastic_step = krug::update_deviator(elastic, krug::scaled(previous, 1e4), rate, spin, dt, {});
  CHECK_FALSE(elastic_step.yielded);
  check_same(elastic_step.deviator,
             krug::hooke_trial(krug::rotate_objectively(krug::scaled(previous, 1e4), spin, dt), rate, 4.5e10, dt),
             0.0);

  // update_deviator = rotate, Hooke trial, radial return, in that order, through std::visit.
  material.strength = krug::PerfectlyPlastic{4.5e10, 1e7};
  const krug::PlasticReturn visited = std::visit(
      [&](const auto& model) { return krug::update_deviator(model, previous, rate, spin, dt, {}); }, material.strength);
  const Deviator trial = krug::hooke_trial(krug::rotate_objectively(previous, spin, dt), rate, 4.5e10, dt);
  const krug::PlasticReturn by_hand = krug::radial_return(trial, 4.5e10, 1e7);
  REQUIRE(visited.yielded);
  check_same(visited.deviator, by_hand.deviator, 0.0);
  CHECK(visited.plastic_strain_increment == by_hand.plastic_strain_increment);
  const std::string_view name = std::visit([](const auto& model) { return model.name; }, material.strength);
  CHECK(name == "perfectly_plastic");
}
