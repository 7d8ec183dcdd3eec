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
#include <filesystem>
#include <string>
#include <vector>

#include "krug/io/scenario.hpp"
#include "krug/io/sweep.hpp"
#include "krug/output/run_files.hpp"
#include "verification_support.hpp"

using namespace krug;
using krug::verification::format_number;
using krug::verification::report;

namespace {

struct Outcome {
  double whole = 0.0, piece = 0.0, eroded = 0.0, backward = 0.0;  // dU/U0, dU/U0, fractions of the bullet
  double energy_drift = 0.0;
};

Outcome run_with_erosion(const std::filesystem::path& file, double altitude_ratio) {
  const std::string text = verification::read_text(file);
  const std::string edited = io::edit_scenario(
      text, {{"materials.lead.erosion.altitude_ratio", format_number("%g", altitude_ratio)}}, file.string());
  const io::Scenario scenario = io::parse_scenario(edited, file.string() + " (erosion " + format_number("%g", altitude_ratio) + ")");
  REQUIRE(scenario.penetration.has_value());
  output::RunOptions options;
  options.output_directory = std::filesystem::current_path() / ("headline_erosion_" + std::to_string(::getpid())) /
                             (file.stem().string() + "_" + format_number("%g", altitude_ratio));
  Outcome out;
  options.on_finish = [&](const Simulation& sim) { out.energy_drift = sim.ledger().relative_energy_drift(); };
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

}  // namespace

TEST_CASE("Headline: the whole bullet's loss moves less than 0.01 over lead erosion thresholds 0.05 to 0.2",
          "[paper][erosion][headline]") {
  const bool full = verification::convergence_scale() >= 1.0;
  const std::filesystem::path folder = std::filesystem::path(KRUG_EXAMPLES_DIR) / "paper" / (full ? "" : "coarse");
  const std::string suffix = full ? "_2.6g.json" : "_2.6g_z5.json";
  for (const std::string target : {"monolithic_3mm", "layered_3x1mm"}) {
    double lowest = 1.0, highest = -1.0;
    for (const double ratio : {0.05, 0.1, 0.2}) {
      const Outcome o = run_with_erosion(folder / (target + suffix), ratio);
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
