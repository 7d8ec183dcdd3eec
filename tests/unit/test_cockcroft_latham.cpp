// The Cockcroft-Latham failure law (krug/fracture/cockcroft_latham.hpp), point-wise and as the scenario
// reader makes it: W = sum max(sigma_1, 0) d eps_p against W_c, with values chosen to be exact in binary
// floating point, so that the step it fires on is known exactly.
#include <catch2/catch.hpp>

#include <string>
#include <variant>

#include "krug/core/error.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/scenario/scenario.hpp"

using namespace krug::fracture;

namespace {

PointState point(double largest_stress, double increment) {
  PointState p;
  p.stress.largest = largest_stress;
  p.stress.smallest = -largest_stress;
  p.plastic_strain_increment = increment;
  return p;
}

std::string scenario_with(const std::string& fracture) {
  return R"({
    "geometry": "planar",
    "end_time": 1e-6,
    "materials": { "m": { "density": 7830, "eos": { "model": "linear", "bulk_modulus": 1.627e11 },
      "strength": { "model": "perfectly_plastic", "shear_modulus": 7.95e10, "yield_stress": 7.92e8 },
      "fracture": )" + fracture + R"( } },
    "bodies": [ { "name": "bar", "material": "m",
                  "mesh": { "type": "rectangle", "x": { "from": 0, "to": 0.01, "zones": 4 },
                                                 "y": { "from": 0, "to": 0.002, "zones": 2 } } } ]
  })";
}

}  // namespace

TEST_CASE("Cockcroft-Latham: the plastic work of tension fires at W_c, compression and elastic steps add nothing",
          "[unit][failure_laws]") {
  CockcroftLatham law;
  law.critical_work = 67108864.0;  // 2^26 Pa
  // sigma_1 = 2^27 Pa and d eps_p = 2^-4 add 2^23 Pa a step: W reaches W_c on the eighth step exactly.
  double damage = 0.0;
  for (int step = 1; step <= 7; ++step) {
    CHECK(test(law, point(134217728.0, 0.0625), damage) == Criterion::none);
    CHECK(damage == step / 8.0);
  }
  CHECK(test(law, point(134217728.0, 0.0625), damage) == Criterion::cockcroft_latham);
  CHECK(damage == 1.0);
  // Plastic flow under all-round compression (sigma_1 < 0) and an elastic step under tension add nothing.
  double other = 0.5;
  CHECK(test(law, point(-1.0e9, 0.5), other) == Criterion::none);
  CHECK(test(law, point(1.0e9, 0.0), other) == Criterion::none);
  CHECK(other == 0.5);
  CHECK(criterion_name(Criterion::cockcroft_latham) == "cockcroft_latham");
  const FailureLaw variant = law;
  CHECK(enabled(variant));
  CHECK(loosening_limit(variant) == 0.03);
}

TEST_CASE("reading the Cockcroft-Latham law: its critical work, the default loosening, a missing key named",
          "[unit][failure_laws][scenario]") {
  const auto scenario = krug::scenario::parse_scenario(
      scenario_with(R"({ "model": "cockcroft_latham", "critical_work": 4e7, "loosening": 0.05 })"), "test.json");
  REQUIRE(scenario.setup.fracture.size() == 1);
  REQUIRE(std::holds_alternative<CockcroftLatham>(scenario.setup.fracture.at(0)));
  const auto& law = std::get<CockcroftLatham>(scenario.setup.fracture.at(0));
  CHECK(law.critical_work == 4e7);
  CHECK(law.loosening == 0.05);
  std::string error = "(no error)";
  try {
    (void)krug::scenario::parse_scenario(scenario_with(R"({ "model": "cockcroft_latham" })"), "test.json");
  } catch (const krug::InputError& e) {
    error = e.what();
  }
  CHECK(error.find("materials.m.fracture.critical_work") != std::string::npos);
}
