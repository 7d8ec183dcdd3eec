// E9 of verification.md, second law: Cockcroft-Latham ductile fracture (krug/fracture/cockcroft_latham.hpp)
// in a run. The rod of the Johnson-Cook case (an axisymmetric bar of Wilkins aluminium with linear
// hardening Y = 300 MPa + 2 GPa eps_p, pulled at 1000 /s by a velocity condition on one end, its other
// end on a symmetry plane, the initial velocity already the homogeneous stretching field; Considere's
// condition keeps it from necking up to eps_p = 0.225). In uniaxial tension sigma_1 = Y(eps_p), so the
// plastic work of tension is
//
//   W(eps_p) = int_0^eps_p (300 MPa + 2 GPa e) de = 300 MPa eps_p + 1 GPa eps_p^2,
//
// and with W_c = 40 MPa the zone fails at eps_p = 0.1 exactly (the root of 1e9 x^2 + 3e8 x - 4e7). The
// first damaged zone must fail within one step's plastic strain increment of 0.1 (the law tests at the
// end of a step), and its sigma_1 must be the flow stress (the premise: uniaxial stress). Pushed instead of
// pulled, the same rod flows past eps_p = 0.15 in compression with its damage still near zero (sigma_1 is
// the free lateral surface's, about 0). The ledgers close to round-off through the damage.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "krug/krug.hpp"
#include "verification_support.hpp"

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

namespace {

constexpr double length = 0.01;       // m
constexpr double radius = 0.002;      // m
constexpr double rate = 1000.0;       // 1/s, nominal v / L
constexpr double yield = 3.0e8;       // Pa
constexpr double hardening = 2.0e9;   // Pa
constexpr double critical_work = 4.0e7;  // Pa: W(0.1) = 3e7 + 1e7
constexpr double failure_strain = 0.1;

Simulation pulled_rod(double speed) {
  setup::SceneDescription scene;
  scene.geometry = GeometryKind::axisymmetric;
  scene.materials.push_back(Material{"aluminium", 2785.0, LinearBulk{7.906e10, 2785.0}, LinearHardening{2.76e10, yield, hardening}});
  fracture::CockcroftLatham law;
  law.critical_work = critical_work;
  scene.fracture.push_back(law);
  setup::BodyDescription rod;
  rod.name = "rod";
  rod.mesh.shape = setup::RectangleMesh{generate::graded_axis(0.0, {{length, 10, 1.0}}),
                                        generate::graded_axis(0.0, {{radius, 4, 1.0}})};
  rod.initial.velocity = std::array<setup::PointFunction, 2>{[speed](double x, double) { return speed * x / length; },
                                                             [](double, double) { return 0.0; }};
  rod.boundary = {{"z_min", setup::SideCondition::symmetry, {}}, {"z_max", setup::SideCondition::velocity, {speed, std::nullopt}}};
  scene.bodies.push_back(rod);
  scene.controls.end_time = 1.0;
  return Simulation(setup::build_simulation(scene));
}

double largest_principal_stress(const Simulation& sim, Index z) {
  const StrengthZoneFields& st = sim.zone_state().strength;
  return fracture::principal_stress(st.deviator_xx[z], st.deviator_yy[z], st.deviator_xy[z], st.deviator_zz[z],
                                    sim.zone_state().hydro.pressure[z])
      .largest;
}

}  // namespace

TEST_CASE("Cockcroft-Latham: a rod in uniaxial tension fails where the plastic work of tension reaches W_c (RZ)",
          "[verification][failure_laws]") {
  Simulation sim = pulled_rod(rate * length);
  const Index count = sim.mesh().zones.size();
  const StrengthZoneFields& strength = sim.zone_state().strength;
  const FractureZoneFields& fracture_state = sim.zone_state().fracture;
  Index failed = -1;
  double increment = 0.0, stress_ratio = 0.0, worst_drift = 0.0, worst_mass = 0.0;
  std::vector<double> before(static_cast<std::size_t>(count), 0.0);
  std::vector<double> ratio(static_cast<std::size_t>(count), 0.0);
  for (long cycle = 0; cycle < 100000 && failed < 0; ++cycle) {
    sim.step();
    worst_drift = std::max(worst_drift, sim.ledger().relative_energy_drift());
    worst_mass = std::max(worst_mass, sim.ledger().relative_mass_error());
    for (Index z = 0; z < count; ++z) {
      const auto k = static_cast<std::size_t>(z);
      if (fracture_state.damaged[z]) {
        failed = z;
        increment = strength.plastic_strain[z] - before[k];
        stress_ratio = ratio[k];  // of the step before: on the failing step the deviator is zeroed
        break;
      }
      before[k] = strength.plastic_strain[z];
      ratio[k] = largest_principal_stress(sim, z) / (yield + hardening * strength.plastic_strain[z]);
    }
  }
  REQUIRE(failed >= 0);
  CHECK(fracture_state.damage_criterion[failed] == static_cast<std::uint8_t>(fracture::Criterion::cockcroft_latham));
  const double strain = strength.plastic_strain[failed];
  report("Cockcroft-Latham, RZ uniaxial tension", "failure plastic strain", "W = W_c at eps_p = 0.1", strain,
         "one step " + format_number("%.2e", increment) + "; sigma_1 / Y the step before " + format_number("%.5f", stress_ratio),
         count, 0.0);
  // sigma_1 within 1 % of the flow stress (uniaxial stress), so W differs from the formula's by as
  // much at most: the failure strain within one step's increment, plus 1 % of 0.1.
  CHECK(std::abs(stress_ratio - 1.0) < 0.01);
  CHECK(strain >= failure_strain * 0.99);
  CHECK(strain <= failure_strain * 1.01 + increment);
  CHECK(worst_mass < 1e-13);
  CHECK(worst_drift < 1e-12);
}

TEST_CASE("Cockcroft-Latham: the same rod pushed flows in compression without damage (RZ)", "[verification][failure_laws]") {
  Simulation sim = pulled_rod(-rate * length);
  const Index count = sim.mesh().zones.size();
  const StrengthZoneFields& strength = sim.zone_state().strength;
  const FractureZoneFields& fracture_state = sim.zone_state().fracture;
  double strain = 0.0;
  for (long cycle = 0; cycle < 100000 && strain < 0.15; ++cycle) {
    sim.step();
    strain = *std::min_element(strength.plastic_strain.begin(), strength.plastic_strain.end());
  }
  REQUIRE(strain >= 0.15);
  double most = 0.0;
  long damaged = 0;
  for (Index z = 0; z < count; ++z) {
    most = std::max(most, fracture_state.damage[z]);
    damaged += fracture_state.damaged[z];
  }
  report("Cockcroft-Latham, RZ uniaxial compression", "largest damage at eps_p >= 0.15", "< 0.01", most, "", count, 0.0);
  CHECK(damaged == 0);
  CHECK(most < 0.01);
}
