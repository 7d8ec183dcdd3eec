// The failure-law registry (krug/fracture/failure_law.hpp) and the Johnson-Cook damage law
// (krug/fracture/johnson_cook.hpp), point-wise: the fracture strain against hand values of the published
// constants, the accumulation of D, the limits where the von Mises stress is zero, and the scenario
// reader (model names, defaults, the library's D1..D5, temperatures from the strength block).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <variant>

#include "krug/core/error.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/scenario/scenario.hpp"

using namespace krug::fracture;

namespace {

// Johnson & Cook (1985), Table 1: 4340 steel (Rc 30) and OFHC copper; 2024-T351 aluminium.
JohnsonCookDamage steel_4340() {
  JohnsonCookDamage law;
  law.d1 = 0.05;
  law.d2 = 3.44;
  law.d3 = -2.12;
  law.d4 = 0.002;
  law.d5 = 0.61;
  law.room_temperature = 293.0;
  law.melt_temperature = 1793.0;  // JC83 (4340 steel), T_melt
  return law;
}

JohnsonCookDamage al_2024_t351() {
  JohnsonCookDamage law;
  law.d1 = 0.13;
  law.d2 = 0.13;
  law.d3 = -1.5;
  law.d4 = 0.011;
  law.d5 = 0.0;
  return law;
}

constexpr double tight = 1e-12;

}  // namespace

TEST_CASE("Johnson-Cook fracture strain against hand values of JC85's constants", "[unit][failure_laws]") {
  const JohnsonCookDamage steel = steel_4340();
  // Uniaxial tension, eta = 1/3, reference rate, room temperature:
  // 0.05 + 3.44 exp(-2.12 / 3) = 0.05 + 3.44 x 0.4932857 = 1.7469030.
  CHECK(steel.fracture_strain(1.0 / 3.0, 1.0, 293.0) == Approx(0.05 + 3.44 * std::exp(-2.12 / 3.0)).epsilon(tight));
  CHECK(steel.fracture_strain(1.0 / 3.0, 1.0, 293.0) == Approx(1.7469030).epsilon(1e-7));
  // Pure shear, eta = 0: D1 + D2 = 3.49.
  CHECK(steel.fracture_strain(0.0, 1.0, 293.0) == Approx(3.49).epsilon(tight));
  // Rate 1000/s: x (1 + 0.002 ln 1000) = x 1.0138155.
  CHECK(steel.fracture_strain(0.0, 1000.0, 293.0) == Approx(3.49 * 1.0138155).epsilon(1e-7));
  // Below the reference rate the factor is 1 (as in the strength model).
  CHECK(steel.fracture_strain(0.0, 1e-3, 293.0) == Approx(3.49).epsilon(tight));
  // T = 1043 K: T* = (1043 - 293) / (1793 - 293) = 0.5, x (1 + 0.61 x 0.5) = x 1.305.
  CHECK(steel.fracture_strain(0.0, 1.0, 1043.0) == Approx(3.49 * 1.305).epsilon(tight));
  // Beyond the melt T* = 1; no temperature (NaN) or below room: factor 1.
  CHECK(steel.fracture_strain(0.0, 1.0, 5000.0) == Approx(3.49 * 1.61).epsilon(tight));
  CHECK(steel.fracture_strain(0.0, 1.0, std::numeric_limits<double>::quiet_NaN()) == Approx(3.49).epsilon(tight));
  CHECK(steel.fracture_strain(0.0, 1.0, 200.0) == Approx(3.49).epsilon(tight));

  const JohnsonCookDamage al = al_2024_t351();
  // 2024-T351, eta = 1/3: 0.13 + 0.13 exp(-0.5) = 0.13 + 0.13 x 0.6065307 = 0.2088490.
  CHECK(al.fracture_strain(1.0 / 3.0, 1.0, 293.0) == Approx(0.2088490).epsilon(1e-6));
  // eta = 1/sqrt(3) (plane-strain tension): 0.13 + 0.13 exp(-0.8660254) = 0.13 + 0.13 x 0.4206200 = 0.1846806.
  CHECK(al.fracture_strain(1.0 / std::sqrt(3.0), 1.0, 293.0) == Approx(0.1846806).epsilon(1e-6));
}

TEST_CASE("Johnson-Cook triaxiality, its limits and the fracture-strain floor", "[unit][failure_laws]") {
  // eta = -p / sigma_vm: tension (p < 0) positive.
  CHECK(JohnsonCookDamage::triaxiality(-100.0, 300.0) == Approx(1.0 / 3.0).epsilon(tight));
  CHECK(JohnsonCookDamage::triaxiality(50.0, 100.0) == Approx(-0.5).epsilon(tight));
  // No deviator: +inf under tension, -inf under compression, 0 at p = 0.
  CHECK(JohnsonCookDamage::triaxiality(-1.0, 0.0) == std::numeric_limits<double>::infinity());
  CHECK(JohnsonCookDamage::triaxiality(1.0, 0.0) == -std::numeric_limits<double>::infinity());
  CHECK(JohnsonCookDamage::triaxiality(0.0, 0.0) == 0.0);
  const JohnsonCookDamage steel = steel_4340();
  // The exponential's limits: D3 < 0, eta -> +inf: D1 = 0.05; eta -> -inf: infinite (no damage).
  CHECK(steel.fracture_strain(std::numeric_limits<double>::infinity(), 1.0, 293.0) == Approx(0.05).epsilon(tight));
  CHECK(steel.fracture_strain(-std::numeric_limits<double>::infinity(), 1.0, 293.0) ==
        std::numeric_limits<double>::infinity());
  // D3 = 0 with an infinite eta: D1 + D2 (exp(0)), not NaN.
  JohnsonCookDamage flat = steel;
  flat.d3 = 0.0;
  CHECK(flat.fracture_strain(std::numeric_limits<double>::infinity(), 1.0, 293.0) == Approx(3.49).epsilon(tight));
  // 6061-T6 (Lesuer et al. 2001: D1 -0.77, D2 1.45, D3 -0.47) goes negative beyond eta = ln(1.45/0.77)/0.47
  // = 1.3467: the floor (default 0) holds it, and a given minimum replaces it.
  JohnsonCookDamage al6061;
  al6061.d1 = -0.77;
  al6061.d2 = 1.45;
  al6061.d3 = -0.47;
  CHECK(al6061.fracture_strain(2.0, 1.0, 293.0) == 0.0);
  al6061.minimum_fracture_strain = 0.01;
  CHECK(al6061.fracture_strain(2.0, 1.0, 293.0) == 0.01);
  CHECK(al6061.fracture_strain(1.0, 1.0, 293.0) == Approx(-0.77 + 1.45 * std::exp(-0.47)).epsilon(tight));
}

TEST_CASE("Johnson-Cook damage accumulates d eps_p / eps_f and fires at D >= 1", "[unit][failure_laws]") {
  const JohnsonCookDamage al = al_2024_t351();
  PointState point;
  point.pressure = -100.0;  // eta = 1/3
  point.equivalent_stress = 300.0;
  point.plastic_strain_rate = 1.0;
  const double strain = 0.13 + 0.13 * std::exp(-0.5);
  double damage = 0.0;
  // An elastic step adds nothing.
  CHECK(test(al, point, damage) == Criterion::none);
  CHECK(damage == 0.0);
  // Ten equal increments of eps_f / 10 reach D = 1 on the tenth (to round-off: 1 - 1e-12 tolerated
  // by stepping an increment a hair larger).
  point.plastic_strain_increment = strain / 10.0 * (1.0 + 1e-12);
  for (int k = 1; k <= 9; ++k) {
    CHECK(test(al, point, damage) == Criterion::none);
    CHECK(damage == Approx(0.1 * k).epsilon(1e-11));
  }
  CHECK(test(al, point, damage) == Criterion::johnson_cook);
  CHECK(damage >= 1.0);
  // At eps_f <= 0 (no ductility left) a plastic step sets D = 1 at once.
  JohnsonCookDamage brittle;
  brittle.d1 = -1.0;
  double d = 0.2;
  point.plastic_strain_increment = 1e-9;
  CHECK(test(brittle, point, d) == Criterion::johnson_cook);
  CHECK(d == 1.0);
  CHECK(criterion_name(Criterion::johnson_cook) == "johnson_cook");
}

TEST_CASE("the failure-law variant: criteria (1) first, enabled and loosening per law", "[unit][failure_laws]") {
  FailureLaw law;  // the first alternative: criteria (1) with every limit off
  CHECK(std::holds_alternative<FractureLimits>(law));
  CHECK_FALSE(enabled(law));
  FractureLimits limits;
  limits.elongation = 0.4;
  limits.loosening = 0.05;
  law = limits;
  CHECK(enabled(law));
  CHECK(loosening_limit(law) == 0.05);
  law = al_2024_t351();
  CHECK(enabled(law));
  CHECK(loosening_limit(law) == 0.03);
  CHECK(std::string(FractureLimits::name) == "criteria");
  CHECK(std::string(JohnsonCookDamage::name) == "johnson_cook");
}

namespace {

std::string scenario_with(const std::string& material) {
  return R"({
    "geometry": "planar",
    "end_time": 1e-6,
    "materials": { "m": )" + material + R"( },
    "bodies": [ { "name": "bar", "material": "m",
                  "mesh": { "type": "rectangle", "x": { "from": 0, "to": 0.01, "zones": 4 },
                                                 "y": { "from": 0, "to": 0.002, "zones": 2 } } } ]
  })";
}

FailureLaw law_of(const std::string& material) {
  const auto scenario = krug::scenario::parse_scenario(scenario_with(material), "test.json");
  REQUIRE(scenario.setup.fracture.size() == 1);
  return scenario.setup.fracture.at(0);
}

std::string error_of(const std::string& material) {
  try {
    (void)krug::scenario::parse_scenario(scenario_with(material), "test.json");
  } catch (const krug::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const std::string steel_block = R"({ "density": 7830, "eos": { "model": "linear", "bulk_modulus": 1.627e11 },
  "strength": { "model": "perfectly_plastic", "shear_modulus": 7.95e10, "yield_stress": 7.92e8 }, )";

}  // namespace

TEST_CASE("reading failure laws: the default model, Johnson-Cook constants and their sources",
          "[unit][failure_laws][scenario]") {
  // No "model": criteria (1), as every scenario before the registry.
  {
    const FailureLaw law = law_of(steel_block + R"("fracture": { "elongation": 0.4 } })");
    REQUIRE(std::holds_alternative<FractureLimits>(law));
    CHECK(std::get<FractureLimits>(law).elongation == 0.4);
    CHECK(std::get<FractureLimits>(law).loosening == 0.03);
    CHECK(std::get<FractureLimits>(law).tensile_stress == disabled);
  }
  // Johnson-Cook with its constants given; no Johnson-Cook strength: rate0 1/s, T_room 293 K, no melt.
  {
    const FailureLaw law = law_of(steel_block + R"("fracture": { "model": "johnson_cook", "d1": 0.05, "d2": 3.44,
        "d3": -2.12, "d4": 0.002, "d5": 0.61 } })");
    REQUIRE(std::holds_alternative<JohnsonCookDamage>(law));
    const auto& jc = std::get<JohnsonCookDamage>(law);
    CHECK(jc.d1 == 0.05);
    CHECK(jc.d3 == -2.12);
    CHECK(jc.d5 == 0.61);
    CHECK(jc.reference_strain_rate == 1.0);
    CHECK(jc.room_temperature == 293.0);
    CHECK(jc.melt_temperature == std::numeric_limits<double>::infinity());
    CHECK(jc.loosening == 0.03);
  }
  // A missing constant is an error naming its path.
  CHECK(error_of(steel_block + R"("fracture": { "model": "johnson_cook", "d1": 0.05 } })").find("materials.m.fracture.d2") !=
        std::string::npos);
  // An unknown model lists the registry's names.
  const std::string unknown = error_of(steel_block + R"("fracture": { "model": "gurson" } })");
  CHECK(unknown.find("criteria") != std::string::npos);
  CHECK(unknown.find("johnson_cook") != std::string::npos);
  // Criteria (1) without a limit is still refused.
  CHECK(error_of(steel_block + R"("fracture": { "loosening": 0.05 } })").find("expected at least one limit") !=
        std::string::npos);
}

TEST_CASE("reading failure laws: a library set's D1..D5 and its Johnson-Cook strength's temperatures",
          "[unit][failure_laws][scenario]") {
  // ofhc-copper (JC85: D1 0.54, D2 4.89, D3 -3.03, D4 0.014, D5 1.12; JC83: T_melt 1356 K, rate0 1/s).
  {
    const FailureLaw law = law_of(R"({ "base": "ofhc-copper", "fracture": { "model": "johnson_cook" } })");
    REQUIRE(std::holds_alternative<JohnsonCookDamage>(law));
    const auto& jc = std::get<JohnsonCookDamage>(law);
    CHECK(jc.d1 == 0.54);
    CHECK(jc.d2 == 4.89);
    CHECK(jc.d3 == -3.03);
    CHECK(jc.d4 == 0.014);
    CHECK(jc.d5 == 1.12);
    CHECK(jc.melt_temperature == 1356.0);
    CHECK(jc.room_temperature == 293.0);
    CHECK(jc.reference_strain_rate == 1.0);
  }
  // A constant given beside the set's overrides it; the strength's melt temperature can be overridden too.
  {
    const FailureLaw law = law_of(
        R"({ "base": "steel-4340", "fracture": { "model": "johnson_cook", "d1": 0.1, "melt_temperature": 1700 } })");
    const auto& jc = std::get<JohnsonCookDamage>(law);
    CHECK(jc.d1 == 0.1);
    CHECK(jc.d2 == 3.44);  // JC85 (4340)
    CHECK(jc.melt_temperature == 1700.0);
  }
  // The string form of a set has no fracture at all (the library never turns fracture on by itself).
  CHECK_FALSE(enabled(law_of(R"("ofhc-copper")")));
  // A set without published constants (tungsten-alloy) asks for them.
  CHECK(error_of(R"({ "base": "tungsten-alloy", "fracture": { "model": "johnson_cook" } })").find("fracture.d1") !=
        std::string::npos);
}
