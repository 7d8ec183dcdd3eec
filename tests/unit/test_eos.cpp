// Point-wise tests of the equations of state (krug/material/eos.hpp): hand values, the adiabatic
// sound speed against finite differences, and the shocked states of verification.md E3 and E4.
#include <catch2/catch.hpp>

#include <cmath>
#include <variant>

#include "krug/material/eos.hpp"
#include "krug/material/material.hpp"

namespace {

// Copper of verification.md E3.
krug::MieGruneisen e3_copper() { return {8930.0, 3940.0, 1.49, 2.0}; }
// Wilkins aluminium of verification.md E4.
krug::MieGruneisen e4_aluminium() { return {2785.0, 5328.0, 1.338, 2.0}; }

// Specific internal energy behind a steady compressive wave from state (rho_a, e_a, P_a) to
// (rho_b, P_b), P = -sigma_xx the longitudinal compressive stress (Rankine–Hugoniot energy jump):
// e_b = e_a + (P_a + P_b) / 2 (1/rho_a - 1/rho_b).
double energy_behind_wave(double rho_a, double e_a, double stress_a, double rho_b, double stress_b) {
  return e_a + 0.5 * (stress_a + stress_b) * (1.0 / rho_a - 1.0 / rho_b);
}

}  // namespace

TEST_CASE("ideal gas: pressure and sound speed against hand values", "[eos]") {
  const krug::IdealGas gas{1.4};
  // Sod's left state (verification.md E2): rho = 1, p = 1 means e = p / ((gamma - 1) rho) = 2.5.
  CHECK(gas.pressure(1.0, 2.5) == Approx(1.0).epsilon(1e-14));
  // c^2 = gamma p / rho = 1.4.
  CHECK(gas.sound_speed_squared(1.0, 2.5, 1.0) == Approx(1.4).epsilon(1e-14));
  // Strong-shock viscosity slope (gamma + 1) / 4 = 0.6.
  CHECK(gas.shock_slope() == Approx(0.6).epsilon(1e-14));
  // Noh post-shock state (E2): gamma 5/3, rho = 4, e = 0.5 gives p = (2/3)(4)(0.5) = 4/3.
  CHECK(krug::IdealGas{5.0 / 3.0}.pressure(4.0, 0.5) == Approx(4.0 / 3.0).epsilon(1e-14));
}

TEST_CASE("linear bulk: pressure and sound speed against hand values", "[eos]") {
  // Wilkins aluminium of E1: K = 7.906e10, rho0 = 2785; 1 % compression gives p = 0.01 K = 7.906e8.
  const krug::LinearBulk bulk{7.906e10, 2785.0};
  CHECK(bulk.pressure(1.01 * 2785.0, 123.0) == Approx(7.906e8).epsilon(1e-12));
  CHECK(bulk.sound_speed_squared(2785.0, 0.0, 0.0) == Approx(7.906e10 / 2785.0).epsilon(1e-14));
}

TEST_CASE("Mie-Gruneisen: pressure and sound speed against hand values", "[eos]") {
  const krug::MieGruneisen copper = e3_copper();
  const double rho0 = 8930.0;
  const double stiffness = 8930.0 * 3940.0 * 3940.0;  // rho0 c0^2 = 1.38625748e11 Pa

  CHECK(krug::MieGruneisen::name == "mie_gruneisen");
  CHECK(copper.shock_slope() == Approx(0.745).epsilon(1e-14));  // s / 2 = 1.49 / 2

  SECTION("reference state: p = 0 and c = c0") {
    CHECK(copper.pressure(rho0, 0.0) == Approx(0.0).margin(1e-6));
    CHECK(copper.sound_speed_squared(rho0, 0.0, 0.0) == Approx(3940.0 * 3940.0).epsilon(1e-14));
  }
  SECTION("compression mu = 0.1") {
    // Gamma0 = 2 zeroes the quadratic term 1 - Gamma0/2, so p = rho0 c0^2 mu / D^2 + rho0 Gamma0 e with
    // D = 1 - (s - 1) mu = 0.951: p(e = 0) = 1.38625748e10 / 0.904401 = 1.532790742159728e10 Pa.
    const double rho = 1.1 * rho0;
    const double p_cold = 1.532790742159728e10;
    CHECK(copper.pressure(rho, 0.0) == Approx(p_cold).epsilon(1e-13));
    // + rho0 Gamma0 e = 8930 * 2 * 1e5 = 1.786e9.
    CHECK(copper.pressure(rho, 1e5) == Approx(p_cold + 1.786e9).epsilon(1e-13));
    // dp/dmu = rho0 c0^2 (1/D^2 + 2 (s-1) mu / D^3) = 1.6907439416672498e11 Pa, so
    // c^2 = (dp/dmu)/rho0 + p rho0 Gamma0 / rho^2 = 2.1770411907576077e7 m^2/s^2 at e = 0.
    CHECK(copper.sound_speed_squared(rho, 0.0, p_cold) == Approx(2.1770411907576077e7).epsilon(1e-13));
    // Hugoniot: p_H = rho0 c0^2 mu (1 + mu) / D^2 = 1.1 * 1.532790742159728e10 = 1.686069816375701e10 Pa.
    CHECK(copper.hugoniot_pressure(rho) == Approx(1.686069816375701e10).epsilon(1e-13));
  }
  SECTION("tension mu = -0.01: the linear branch") {
    // p = rho0 c0^2 mu + rho0 Gamma0 e = -1.38625748e9 + 8930 * 2 * 100 = -1.38447148e9 Pa.
    const double rho = 0.99 * rho0;
    const double p = copper.pressure(rho, 100.0);
    CHECK(p == Approx(-0.01 * stiffness + 1.786e6).epsilon(1e-13));
    // c^2 = c0^2 + p rho0 Gamma0 / rho^2 = 1.5207232282420162e7 m^2/s^2.
    CHECK(copper.sound_speed_squared(rho, 100.0, p) == Approx(1.5207232282420162e7).epsilon(1e-13));
  }
}

TEST_CASE("Mie-Gruneisen: sound speed is the isentropic derivative (dp/drho)_e + p/rho^2 (dp/de)_rho",
          "[eos]") {
  // Independent check by central differences of pressure(rho, e), in both branches, across mu = 0,
  // beyond the tangent continuation (mu_L = 0.9 / 0.49 = 1.837) and past the singularity (2.04).
  const krug::MieGruneisen copper = e3_copper();
  const double rho0 = copper.reference_density;
  for (const double mu : {-0.1, -0.01, 0.0, 0.05, 0.5, 1.9, 3.0}) {
    for (const double e : {0.0, 1e5}) {
      const double rho = rho0 * (1.0 + mu);
      const double h_rho = 1e-6 * rho;
      const double h_e = 1e-3 * (e + 1e4);
      const double dp_drho = (copper.pressure(rho + h_rho, e) - copper.pressure(rho - h_rho, e)) / (2.0 * h_rho);
      const double dp_de = (copper.pressure(rho, e + h_e) - copper.pressure(rho, e - h_e)) / (2.0 * h_e);
      const double p = copper.pressure(rho, e);
      const double expected = dp_drho + p / (rho * rho) * dp_de;
      INFO("mu = " << mu << ", e = " << e);
      // Central-difference truncation error ~ h^2 p''' / 6, about 1e-10 relative here; the kink of the
      // second derivative at mu = 0 and mu_L gives O(h) = 1e-6 relative at most.
      CHECK(copper.sound_speed_squared(rho, e, p) == Approx(expected).epsilon(2e-6));
    }
  }
}

TEST_CASE("Mie-Gruneisen: on the Hugoniot pressure(rho, e_H) = p_H", "[eos]") {
  // Identity of the Hugoniot-referenced form: p_H (1 - Gamma0 eta / 2) + rho0 Gamma0 e_H = p_H with
  // e_H = p_H eta / (2 rho0), eta = 1 - rho0/rho; holds for 0 <= mu < mu_L.
  const krug::MieGruneisen copper = e3_copper();
  for (const double mu : {1e-4, 0.01, 0.1, 0.5, 1.0, 1.8}) {
    const double rho = copper.reference_density * (1.0 + mu);
    INFO("mu = " << mu);
    CHECK(copper.pressure(rho, copper.hugoniot_energy(rho)) ==
          Approx(copper.hugoniot_pressure(rho)).epsilon(1e-12));
  }
}

TEST_CASE("Mie-Gruneisen: E3 copper states lie on the model", "[eos]") {
  const krug::MieGruneisen copper = e3_copper();
  const double rho0 = 8930.0;
  // verification.md E3 plastic state.
  const double rho_plastic = 8973.453;
  const double p_plastic = 6.8159e8;

  SECTION("single-shock Rankine–Hugoniot energy reproduces p within 0.1 %") {
    // e_H = p (1/rho0 - 1/rho) / 2 = 184.80 J/kg treats the state as reached by one shock. In E3 it is
    // reached through the elastic precursor and with the deviator -2Y/3 on top of p, so the true energy
    // is 213.53 J/kg (next section); the 28.7 J/kg deficit lowers p by rho0 Gamma0 * 28.7 = 5.1e5 Pa,
    // i.e. -0.075 % (hand derivation), inside the 0.1 % asked.
    const double e_single_shock = 0.5 * p_plastic * (1.0 / rho0 - 1.0 / rho_plastic);
    CHECK(e_single_shock == Approx(184.80).epsilon(1e-4));
    CHECK(copper.pressure(rho_plastic, e_single_shock) == Approx(p_plastic).epsilon(1e-3));
    // The deficit is of the sign and size derived above: -0.0755 % within 0.005 %.
    CHECK((copper.pressure(rho_plastic, e_single_shock) - p_plastic) / p_plastic == Approx(-7.55e-4).margin(5e-5).epsilon(0.0));
  }
  SECTION("two-wave energy reproduces the tabulated p to its 5 digits") {
    // Precursor: 0 -> (rho_y, P = 1.9903e8); plastic wave: -> (8973.453, P = 7.4159e8) (E3 table,
    // P = -sigma_xx). Energy jumps by Rankine–Hugoniot: e1 = 11.14 J/kg, e2 = 213.53 J/kg.
    const double rho_yield = rho0 * std::exp(9e7 / (2.0 * 4.5e10));  // rho0 exp(Y / 2 mu), E3
    const double e_precursor = energy_behind_wave(rho0, 0.0, 0.0, rho_yield, 1.9903e8);
    const double e_plastic = energy_behind_wave(rho_yield, e_precursor, 1.9903e8, rho_plastic, 7.4159e8);
    CHECK(e_plastic == Approx(213.53).epsilon(1e-4));
    // Table values have 5 significant digits: half a unit of the last is 7e-6 (p) and 4e-5 (precursor).
    CHECK(copper.pressure(rho_plastic, e_plastic) == Approx(p_plastic).epsilon(1e-5));
    CHECK(copper.pressure(rho_yield, e_precursor) == Approx(1.3903e8).epsilon(4e-5));
  }
}

TEST_CASE("Mie-Gruneisen: E4 aluminium plastic state lies on the model", "[eos]") {
  // verification.md E4: precursor at rho_y = rho0 exp(Y / 2 mu) with P = 0.63588 GPa, plastic state
  // rho = 2985.63, P = -sigma_xx = 6.6359 GPa, p = 6.4359 GPa. Energy by the two Rankine–Hugoniot
  // jumps (8.13e4 J/kg); the table has 5 significant digits (half a unit: 8e-6 relative).
  const krug::MieGruneisen aluminium = e4_aluminium();
  const double rho0 = 2785.0;
  const double rho_yield = rho0 * std::exp(3e8 / (2.0 * 2.76e10));
  const double e_precursor = energy_behind_wave(rho0, 0.0, 0.0, rho_yield, 0.63588e9);
  const double e_plastic = energy_behind_wave(rho_yield, e_precursor, 0.63588e9, 2985.63, 6.6359e9);
  CHECK(aluminium.pressure(2985.63, e_plastic) == Approx(6.4359e9).epsilon(1e-5));
}

TEST_CASE("Mie-Gruneisen: the guard past the Hugoniot singularity is finite, monotone and C1", "[eos]") {
  // Singular compression mu* = 1/(s - 1) = 2.0408 (rho = 3.04 rho0); the tangent continuation starts at
  // mu_L = 0.9 mu* = 1.8367.
  const krug::MieGruneisen copper = e3_copper();
  const double rho0 = copper.reference_density;
  const double mu_limit = copper.compression_limit();
  CHECK(mu_limit == Approx(0.9 / 0.49).epsilon(1e-14));

  double previous = copper.pressure(rho0, 0.0);
  for (double mu = 0.01; mu <= 9.0; mu += 0.01) {
    const double rho = rho0 * (1.0 + mu);
    const double p = copper.pressure(rho, 0.0);
    INFO("mu = " << mu);
    REQUIRE(std::isfinite(p));
    REQUIRE(p > previous);
    REQUIRE(copper.sound_speed_squared(rho, 0.0, p) > 0.0);
    previous = p;
  }
  // Continuity of value and slope at mu_L: one-sided values 2e-9 apart in mu differ by about
  // 2e-9 * (d ln p / d mu = 10.3) = 2e-8 (value) and 2e-9 * (d ln p' / d mu = 15) = 3e-8 (slope).
  const double below = copper.reference_curve(mu_limit - 1e-9).pressure;
  const double above = copper.reference_curve(mu_limit + 1e-9).pressure;
  CHECK(above == Approx(below).epsilon(1e-7));
  CHECK(copper.reference_curve(mu_limit + 1e-9).slope ==
        Approx(copper.reference_curve(mu_limit - 1e-9).slope).epsilon(1e-6));
  // Past the singularity the raw Hugoniot is undefined: reported as +infinity, not a sign flip.
  CHECK(std::isinf(copper.hugoniot_pressure(3.1 * rho0)));
}

TEST_CASE("Eos variant and Material dispatch reach Mie-Gruneisen", "[eos]") {
  krug::Material copper;
  copper.reference_density = 8930.0;
  copper.eos = e3_copper();
  const double p = std::visit([](const auto& eos) { return eos.pressure(1.1 * 8930.0, 0.0); }, copper.eos);
  CHECK(p == Approx(1.532790742159728e10).epsilon(1e-13));  // hand value of the hand-value test
  CHECK(copper.shock_slope() == Approx(0.745).epsilon(1e-14));
  const std::string_view name = std::visit([](const auto& eos) { return eos.name; }, copper.eos);
  CHECK(name == "mie_gruneisen");
}

// The scenario reader's plausibility checks (docs/scenario-format.md) ask each model for its bulk
// modulus at the reference state; a model without the member does not compile (the concept in eos.hpp).
TEST_CASE("each equation of state answers its reference bulk modulus", "[eos][plausibility]") {
  STATIC_REQUIRE(krug::all_equations_of_state<krug::Eos>);
  // A gas: 0, not checked as condensed matter.
  CHECK(krug::IdealGas{1.4}.reference_bulk_modulus() == 0.0);
  CHECK(krug::StiffenedGas{1.4, 0.0}.reference_bulk_modulus() == 0.0);  // p_inf = 0: the ideal gas
  // Water as a stiffened gas (Saurel & Abgrall 1999): gamma p_inf = 4.4 x 6e8 = 2.64e9 Pa, so that
  // sqrt(K / rho0) = 1 625 m/s at 1 000 kg/m^3 (the sound speed eos.hpp quotes).
  CHECK(krug::StiffenedGas{4.4, 6.0e8}.reference_bulk_modulus() == Approx(2.64e9).epsilon(1e-15));
  CHECK(std::sqrt(krug::StiffenedGas{4.4, 6.0e8}.reference_bulk_modulus() / 1000.0) == Approx(1624.8).epsilon(1e-4));
  CHECK(krug::LinearBulk{7.3e10, 2700.0}.reference_bulk_modulus() == 7.3e10);
  // E3 copper: rho0 c0^2 = 8930 x 3940^2 = 1.3862e11 Pa.
  CHECK(e3_copper().reference_bulk_modulus() == Approx(1.3862e11).epsilon(1e-4));
  // Through the variant, each alternative's own answer.
  CHECK(krug::reference_bulk_modulus(krug::Eos{e3_copper()}) == e3_copper().reference_bulk_modulus());
  CHECK(krug::reference_bulk_modulus(krug::Eos{krug::IdealGas{1.4}}) == 0.0);
}
