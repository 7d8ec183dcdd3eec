// The library's OFHC copper (Johnson-Cook strength of Johnson & Cook 1983, Steinberg's EOS) in the
// Taylor test Johnson & Cook (1983) used to check their constants: annealed OFHC copper, L0 25.4 mm,
// D0 7.62 mm, onto a rigid anvil (examples/verification/taylor_ofhc_copper.json, 58 x 14 zones).
// Measured final lengths, 0.770, 0.736 and 0.638 L0 at 130, 146 and 190 m/s (19.6, 18.7 and 16.2 mm):
// Johnson & Cook (1983), the 190 m/s test also in Zerilli & Armstrong (1987), J. Appl. Phys. 61,
// 1816; read from a digitised compilation of those papers' figures, not from the printed pages.
// No uncertainty is published with the lengths. The band used here, 10 % of the measured length, is
// this test's: by Taylor's (1948) estimate L/L0 = exp(-rho U^2 / (2 Y)), a length error dL/L is
// ln(L0/L) dY/Y, 0.45 dY/Y at 190 m/s, so 10 % on the length is 22 % on the mean flow stress, the
// order of the extrapolation a 1983 fit (torsion and Hopkinson-bar data) makes to the 1e4-1e5 /s and
// strains above 1 at the impact face. Measured: 20.64, 19.78 and 17.33 mm (+5.3, +5.8 and +7.0 %;
// 116 x 28 zones at 190 m/s: 17.32 mm): longer than the tests, the law's copper too strong by about
// 15 % of flow stress on this estimate (docs/materials.md).
// Under the `convergence` label: about 15 s of one core.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "test_solid_measures.hpp"

using namespace krug;
using namespace krug::verification;
using namespace krug::verification::solid;

TEST_CASE("Taylor bar of the library's OFHC copper against Johnson & Cook's measured lengths",
          "[taylor_library][strength][axisymmetric]") {
  struct Test {
    double speed;          // m/s
    double length_ratio;   // measured L / L0
  };
  const double initial_length = 25.4e-3;
  for (const Test test : {Test{130.0, 0.770}, Test{146.0, 0.736}, Test{190.0, 0.638}}) {
    nlohmann::json document = nlohmann::json::parse(read_text(example_path("taylor_ofhc_copper.json")));
    document["bodies"][0]["initial"]["velocity"] = {-test.speed, 0.0};
    const scenario::Scenario scenario = scenario::parse_scenario(document.dump(), "taylor_ofhc_copper.json");
    Run run(scenario.setup);
    const TaylorMeasures m = advance_taylor(run);
    const Body& bar = run.simulation.bodies().front();
    const double measured = test.length_ratio * initial_length;
    INFO(test.speed << " m/s: length " << 1e3 * m.length << " mm against the measured " << 1e3 * measured
                    << " mm; impact-face radius " << 1e3 * m.face_radius << " mm");
    CHECK(std::abs(m.length - measured) <= 0.10 * measured);
    const Ledger& ledger = run.simulation.ledger();
    CHECK(ledger.relative_mass_error() == 0.0);
    CHECK(ledger.relative_energy_drift() < 1e-12);
    report("Taylor bar, library ofhc-copper at " + format_number("%.0f m/s", test.speed), "final length (mm)",
           format_number("%.1f (JC83, measured)", 1e3 * measured), 1e3 * m.length,
           format_number("%+.1f %%", 100.0 * (m.length / measured - 1.0)), bar.zone_end - bar.zone_begin, run.seconds);
  }
}
