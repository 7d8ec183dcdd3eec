// The paper's case (2.6 g lead bullet at 355 m/s, the monolithic 3 mm plate and three 1 mm plates in
// contact) at the lead's erosion thresholds 0.05, 0.1 (the default) and 0.2: the whole bullet's velocity
// loss (every node and free element of its lead, mass-weighted; penetration.whole) may move by less
// than 0.01 between them, so that the headline does not depend on where the lead is eroded.
//
// Measured (docs/validation/headline_knobs_z5.csv and headline_knobs_z10.csv, scripts/paper_study.py
// --groups knobs): whole dU/U0 at 0.05 / 0.1 / 0.2,
//   5 zones per mm:  monolithic 0.1801 / 0.1794 / 0.1772 (spread 0.0029), layered 0.2101 / 0.2101 / 0.2065 (0.0036)
//   10 zones per mm: monolithic 0.1806 / 0.1779 / 0.1856 (0.0077), layered 0.2001 / 0.2002 / 0.1990 (0.0012)
// (before particles were inscribed in their zones: 0.016 and 0.006 at 10 zones per mm). The figures
// of the eroded share and of the lead moving backwards are reported, not asserted: they stay above
// the 5 % and 1 % a reviewer asks (docs/validation.md, "Lead erosion").
//
// The full study runs the 10 zones per mm scenarios of examples/paper/ (about 6 x 15 s of one core);
// with KRUG_CONVERGENCE_SCALE < 1 (CI) the 5 zones per mm ones of examples/paper/coarse/ (6 x 5 s).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "krug/scenario/scenario.hpp"
#include "krug/scenario/edit.hpp"
#include "krug/output/run_files.hpp"
#include "verification_support.hpp"

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

namespace {

struct Outcome {
  double whole = 0.0, piece = 0.0, eroded = 0.0, backward = 0.0;  // dU/U0, dU/U0, fractions of the bullet
  double energy_drift = 0.0;
  std::vector<double> hourglass_share;  // per body: hourglass work over internal plus converted energy
};

// The scenario `file` with its JSON paths set to the values of `edits`, run to its final answer.
Outcome run_with(const std::filesystem::path& file, const std::vector<scenario::ScenarioEdit>& edits,
                 const std::string& label) {
  const std::string text = verification::read_text(file);
  const scenario::Scenario scenario = scenario::scenario_variant(text, edits, file.string() + " (" + label + ")");
  REQUIRE(scenario.penetration.has_value());
  output::RunOptions options;
  options.output_directory = std::filesystem::current_path() / ("headline_knobs_" + std::to_string(::getpid())) /
                             (file.stem().string() + "_" + label);
  Outcome out;
  options.on_finish = [&](const Simulation& sim) {
    out.energy_drift = sim.ledger().relative_energy_drift();
    for (Index b = 0; b < static_cast<Index>(sim.bodies().size()); ++b) {
      const double put_in = sim.internal_energy(b) + sim.converted_energy(b);
      out.hourglass_share.push_back(put_in > 0.0 ? sim.hourglass_work(b) / put_in : 0.0);
    }
  };
  const run::RunResult result = output::run_scenario(scenario, options);
  std::filesystem::remove_all(options.output_directory.parent_path());
  REQUIRE(result.status == run::RunStatus::completed);
  REQUIRE(result.penetration.has_value());
  const run::PenetrationReport& p = *result.penetration;
  CHECK(p.final);
  out.whole = p.whole_velocity_loss;
  out.piece = p.piece_velocity_loss;
  out.eroded = p.eroded_mass / p.initial_mass;
  out.backward = p.backward_mass / p.initial_mass;
  return out;
}

// The paper's 2.6 g scenario of a target (monolithic_3mm, layered_3x1mm): 10 zones per mm for the
// full study, 5 (examples/paper/coarse/) otherwise.
std::filesystem::path headline_scenario(const std::string& target, bool full) {
  const std::filesystem::path folder = std::filesystem::path(KRUG_EXAMPLES_DIR) / "paper" / (full ? "" : "coarse");
  return folder / (target + (full ? "_2.6g.json" : "_2.6g_z5.json"));
}

Outcome run_with_erosion(const std::filesystem::path& file, double altitude_ratio) {
  const std::string value = format_number("%g", altitude_ratio);
  return run_with(file, {{"materials.lead.erosion.altitude_ratio", value}}, "erosion_" + value);
}

}  // namespace

TEST_CASE("Headline: the whole bullet's loss moves less than 0.01 over lead erosion thresholds 0.05 to 0.2",
          "[paper][erosion][headline]") {
  const bool full = verification::convergence_scale() >= 1.0;
  for (const std::string target : {"monolithic_3mm", "layered_3x1mm"}) {
    double lowest = 1.0, highest = -1.0;
    for (const double ratio : {0.05, 0.1, 0.2}) {
      const Outcome o = run_with_erosion(headline_scenario(target, full), ratio);
      INFO(target << ", erosion " << ratio << ": whole " << o.whole << ", piece " << o.piece << ", eroded " << o.eroded
                  << ", backward " << o.backward);
      report("Headline, " + target + (full ? " (10 zones/mm)" : " (5 zones/mm)"),
             "erosion " + format_number("%g", ratio) + ": whole dU/U0; piece, eroded and backward share", "-", o.whole,
             format_number("piece %.4f", o.piece) + format_number(", eroded %.3f", o.eroded) +
                 format_number(", backward %.3f", o.backward),
             0, 0.0);
      CHECK(o.energy_drift < 1e-12);
      lowest = std::min(lowest, o.whole);
      highest = std::max(highest, o.whole);
    }
    INFO(target << ": whole dU/U0 from " << lowest << " to " << highest);
    CHECK(highest - lowest < 0.01);
  }
}

// The hourglass coefficients (viscous and stiffness together) at 0.02 and 0.15, against the default
// 0.05: the largest piece's loss may move by less than 0.005 between 0.02 and 0.15, so that the
// headline does not depend on the hourglass control. Measured, piece dU/U0 at 0.02 / 0.15 (the
// stiffness state bounded by the flow stress, hourglass.plastic_limit 1; scripts/paper_study.py
// --groups knobs, docs/validation/headline_knobs_z5.csv and headline_knobs_z10.csv):
//   5 zones per mm:  monolithic 0.1324 / 0.1322 (0.0001), layered 0.1889 / 0.1938 (0.0048)
//   10 zones per mm: monolithic 0.1187 / 0.1183 (0.0004), layered 0.1759 / 0.1812 (0.0052: the full
//                    run fails here, by 0.0002)
// (unbounded, as before: 0.044 and 0.040 at 5 zones per mm, 0.013 and 0.026 at 10). The default 0.05
// lies outside the two in some cases (layered at 10 zones per mm: 0.168): the spread between
// variants is scatter of about 0.01, no longer a trend with the coefficient. Each body's hourglass
// work, as a share of its internal plus converted energy, is reported (the bullet's stays above 10 %:
// 11.1 % at 5, 12.9 % at 10 zones per mm, monolithic).
// The case is chaotic: eight runs whose impact speeds differ by 1e-9 give the layered piece a sample
// standard deviation of 0.0028 at 5 and 0.0081 at 10 zones per mm (docs/validation.md, "The case's own
// scatter", headline_scatter.csv), so the difference of two single runs scatters by about 0.004 and
// 0.011 (root mean square) whatever the coefficients: this bound on one pair of runs is met or missed
// partly by chance, and an effect of the coefficients is seen only on means of such sets.
TEST_CASE("Headline: the largest piece's loss moves less than 0.005 between hourglass coefficients 0.02 and 0.15",
          "[paper][hourglass][headline]") {
  const bool full = verification::convergence_scale() >= 1.0;
  for (const std::string target : {"monolithic_3mm", "layered_3x1mm"}) {
    std::vector<double> piece;
    for (const char* k : {"0.02", "0.15"}) {
      const Outcome o =
          run_with(headline_scenario(target, full), {{"controls.hourglass.viscous", k}, {"controls.hourglass.stiffness", k}},
                   std::string("hourglass_") + k);
      std::string shares;
      for (const double share : o.hourglass_share) shares += format_number(" %.3f", share);
      INFO(target << ", hourglass " << k << ": piece " << o.piece << ", whole " << o.whole << "; hourglass shares"
                  << shares);
      report("Headline, " + target + (full ? " (10 zones/mm)" : " (5 zones/mm)"),
             std::string("hourglass ") + k + ": piece dU/U0; whole, hourglass share per body", "-", o.piece,
             format_number("whole %.4f;", o.whole) + shares, 0, 0.0);
      CHECK(o.energy_drift < 1e-12);
      // 0.02 is the paper scenarios' own setting: there every body's hourglass work stays under 10 % of
      // the energy put into it (a mode that carried more would have carried part of the deformation).
      if (std::string(k) == "0.02") {
        for (const double share : o.hourglass_share) CHECK(share < 0.10);
      }
      piece.push_back(o.piece);
    }
    INFO(target << ": piece dU/U0 " << piece[0] << " at 0.02, " << piece[1] << " at 0.15");
    CHECK(std::abs(piece[1] - piece[0]) < 0.005);
  }
}
