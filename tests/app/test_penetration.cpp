// Penetration results (scenario key "penetration", include/krug/run/penetration.hpp) on E1
// (examples/verification/slab_impact.json), where the exact answers are known from 1D linear
// elasticity: a 5 mm flyer at 10 m/s strikes a 10 mm target of the same material (equal impedances).
//  - the interface moves at v/2 = 5 m/s for the contact time 2 h_f / c_L = 1.550 us, so the flyer's
//    nose reaches v/2 x 2 h_f / c_L = 7.752 um past the target's front face, and no further;
//  - the flyer is left at rest: it has stopped, it has not perforated;
//  - the target carries the whole pulse, half of its energy kinetic (a simple elastic wave): the
//    target's kinetic energy is half of the flyer's initial kinetic energy less what the contact (about
//    1/(4 N_f) = 1.25 %, E1) and the viscosity at the pulse's fronts dissipated; the elastic half is not
//    counted as absorbed.
// Then the geometry of perforation on a flyer that starts beyond the target and flies away.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "krug/core/error.hpp"
#include "krug/output/run_files.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using krug::test::Json;

namespace {

constexpr double flyer_speed = 10.0;                     // m/s
constexpr double flyer_length = 5e-3;                    // m
constexpr double wave_speed = 6449.9;                    // c_L = sqrt((K + 4/3 mu) / rho0), slab_impact.json
constexpr double contact_time = 2.0 * flyer_length / wave_speed;  // 1.550 us

Json slab_impact() { return krug::test::read_json(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json"); }

}  // namespace

TEST_CASE("penetration results of E1: the flyer stops at the analytic depth, the target takes the pulse", "[app][penetration]") {
  Json document = slab_impact();
  // A 20 mm target (same zone size), so that when the run stops (0.5 us after the separation) the whole
  // pulse is inside it, clear of its rear face.
  document["bodies"][1]["mesh"]["x"] = {{"from", 0.0}, {"to", 0.02}, {"zones", 80}};
  document["penetration"] = {{"projectile", "flyer"}};
  document["stop"] = {{"no_contact_time", 5e-7}};
  document["end_time"] = 6e-6;
  const auto scenario = krug::scenario::parse_scenario(document.dump(), "slab_penetration.json");
  REQUIRE(scenario.stop.has_value());  // a penetration scenario always has a stop rule
  CHECK(scenario.stop->clear_of_targets);
  CHECK(scenario.stop->body == "flyer");
  const fs::path dir = krug::test::scratch("penetration_e1");
  krug::output::RunOptions options;
  options.output_directory = dir;
  const auto result = krug::output::run_scenario(scenario, options);
  CHECK(result.stopped_by == "stop rule");  // the flyer stopped: final without passing the target
  const Json summary = krug::test::read_json(dir / "summary.json");
  const Json& p = summary["penetration"];
  CHECK(p["projectile"] == "flyer");
  CHECK(p["final"] == true);
  CHECK(p["perforated"] == false);
  CHECK(p["perforation_time"].is_null());
  const double depth = p["depth"].get<double>();
  INFO("depth " << depth << " m against " << 0.5 * flyer_speed * contact_time);
  CHECK(depth == Approx(0.5 * flyer_speed * contact_time).epsilon(0.03));
  CHECK(std::abs(p["residual_velocity"].get<double>()) < 0.02 * flyer_speed);
  CHECK(p["mass_lost"].get<double>() == Approx(0.0).margin(1e-12));
  CHECK(p["plug"].is_null());
  // A travelling elastic wave carries equal kinetic and strain energy, so the target's kinetic energy is
  // half of what the pulse holds: the initial energy less the contact's and the viscosity's dissipation
  // (the viscous heat at the pulse's two fronts is ~6 % of the energy here; the ledger books it).
  const Json& e = summary["ledger"]["energy"];
  const double in_pulse = e["initial_total"].get<double>() + e["contact"].get<double>() - e["viscous"].get<double>();
  INFO("target kinetic " << p["target_kinetic_energy"].get<double>() << " J; half the pulse's energy " << 0.5 * in_pulse << " J");
  CHECK(p["target_plastic_work"].get<double>() == 0.0);  // elastic material
  CHECK(p["target_kinetic_energy"].get<double>() == Approx(0.5 * in_pulse).epsilon(0.03));
  CHECK(p["target_energy_absorbed"].get<double>() == p["target_kinetic_energy"].get<double>());
  CHECK(summary["warnings"].empty());
  // The whole projectile: the flyer stays one piece, so the whole figures are the piece's; and the two
  // bodies' momenta sum to the flyer's initial momentum (no boundary conditions act here), which checks
  // the whole-projectile momentum against the target's, measured independently in the bodies block.
  const Json& whole = p["whole"];
  CHECK(whole["mass"].get<double>() == Approx(p["initial_mass"].get<double>()).epsilon(1e-12));
  CHECK(whole["free_element_mass"].get<double>() == 0.0);
  CHECK(p["initial_speed"].get<double>() == Approx(flyer_speed).epsilon(1e-12));
  CHECK(whole["velocity"].get<double>() == Approx(p["residual_velocity"].get<double>()).margin(1e-9 * flyer_speed));
  const Json& target = summary["bodies"]["target"];
  const double momentum = whole["mass"].get<double>() * whole["velocity"].get<double>() +
                          target["mass"].get<double>() * target["velocity"][0].get<double>();
  CHECK(momentum == Approx(p["initial_mass"].get<double>() * flyer_speed).epsilon(1e-10));
  CHECK(whole["velocity_loss"].get<double>() ==
        Approx((flyer_speed - whole["velocity"].get<double>()) / flyer_speed).epsilon(1e-12));
}

TEST_CASE("penetration geometry: a flyer beyond the target's rear face has perforated; a run cut short says so", "[app][penetration]") {
  Json document = slab_impact();
  // The flyer 1 mm behind the target's rear face (x = 10 mm), flying away from it along +x.
  document["bodies"][0]["mesh"]["x"] = {{"from", 0.011}, {"to", 0.016}, {"zones", 20}};
  document["penetration"] = {{"projectile", "flyer"}, {"targets", {"target"}}};
  document["end_time"] = 1e-6;
  const auto scenario = krug::scenario::parse_scenario(document.dump(), "slab_beyond.json");
  const fs::path dir = krug::test::scratch("penetration_beyond");
  krug::output::RunOptions options;
  options.output_directory = dir;
  const auto result = krug::output::run_scenario(scenario, options);
  CHECK(result.stopped_by == "end_time");  // no contact: the rule never arms
  const Json summary = krug::test::read_json(dir / "summary.json");
  const Json& p = summary["penetration"];
  CHECK(p["perforated"] == true);
  CHECK(p["perforation_time"].get<double>() < 1e-7);  // at the first look, within the first cycles
  CHECK(p["residual_velocity"].get<double>() == Approx(flyer_speed).epsilon(1e-12));
  CHECK(p["final"] == false);  // ended by the end time before the stop rule could confirm it
  CHECK(summary["warnings"].size() == 1);
  CHECK(p["target_energy_absorbed"].get<double>() == 0.0);
}

TEST_CASE("penetration blocks that cannot be honoured are refused with the JSON path", "[app][penetration]") {
  const auto refused = [](Json document) {
    try {
      (void)krug::scenario::parse_scenario(document.dump(), "bad.json");
    } catch (const krug::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  Json document = slab_impact();
  document["penetration"] = {{"projectile", "flier"}};
  CHECK(refused(document).find("penetration.projectile") != std::string::npos);
  document["penetration"] = {{"projectile", "flyer"}, {"targets", {"flyer"}}};
  CHECK(refused(document).find("penetration.targets[0]") != std::string::npos);
  document = slab_impact();
  document["stop"] = {{"body", "flyer"}, {"no_contact_time", 5e-7}, {"clear_of_targets", true}};
  CHECK(refused(document).find("stop.clear_of_targets") != std::string::npos);
  document["penetration"] = {{"projectile", "flyer"}};
  document["stop"] = {{"body", "target"}, {"no_contact_time", 5e-7}};
  CHECK(refused(document).find("stop.body") != std::string::npos);
}

TEST_CASE("erosion limits: a material's block is every body's default, a body's block overrides it", "[app][penetration]") {
  Json document = slab_impact();
  document["materials"]["aluminium"]["erosion"] = {{"altitude_ratio", 0.2}, {"plastic_strain", 3.0}};
  document["bodies"][1]["erosion"] = {{"plastic_strain", 1.5}};
  const auto scenario = krug::scenario::parse_scenario(document.dump(), "erosion.json");
  const auto& bodies = scenario.setup.bodies;
  CHECK(bodies[0].erosion().altitude_ratio == 0.2);
  CHECK(bodies[0].erosion().plastic_strain == 3.0);
  CHECK(bodies[1].erosion().altitude_ratio == 0.2);   // kept from the material
  CHECK(bodies[1].erosion().plastic_strain == 1.5);   // overridden
}

TEST_CASE("erosion on plastic strain: the Taylor bar's foot leaves the mesh and the ledgers still close", "[app][penetration]") {
  // examples/verification/taylor_bar.json (copper at 227 m/s on a rigid wall) with erosion at an
  // equivalent plastic strain of 0.5: the foot, where strains reach beyond 1, erodes; everything the
  // eroded zones carried is booked on the particles and the converted line.
  Json document = krug::test::read_json(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "taylor_bar.json");
  document["materials"]["copper"]["erosion"] = {{"plastic_strain", 0.5}};
  document["end_time"] = 2e-5;
  const auto scenario = krug::scenario::parse_scenario(document.dump(), "taylor_erosion.json");
  const fs::path dir = krug::test::scratch("taylor_erosion");
  krug::output::RunOptions options;
  options.output_directory = dir;
  double largest_strain = 0.0;  // of the zones still in the mesh, after every cycle
  options.on_cycle = [&](const krug::Simulation& s, double) {
    for (krug::Index z = 0; z < s.mesh().zones.size(); ++z) {
      if (s.mesh().zones.active[z]) largest_strain = std::max(largest_strain, s.zone_state().strength.plastic_strain[z]);
    }
    return true;
  };
  const auto result = krug::output::run_scenario(scenario, options);
  REQUIRE(result.status == krug::run::RunStatus::completed);
  const Json summary = krug::test::read_json(dir / "summary.json");
  const Json& bar = summary["bodies"]["bar"]["fracture"];
  INFO("eroded zones " << bar["eroded_zones"] << ", eroded mass " << bar["eroded_mass"]);
  CHECK(bar["eroded_zones"].get<long>() > 0);
  CHECK(largest_strain <= 0.5);  // no zone stays in the mesh beyond the limit after its step
  const Json& ledger = summary["ledger"];
  // Mass: the particles carry exactly what left the mesh.
  CHECK(summary["particles"]["mass"].get<double>() == Approx(bar["eroded_mass"].get<double>()).epsilon(1e-12));
  CHECK(ledger["mass"]["relative_error"].get<double>() < 1e-13);
  CHECK(ledger["energy"]["relative_drift"].get<double>() < 1e-12);
  CHECK(ledger["energy"]["converted"].get<double>() > 0.0);
}

TEST_CASE("a penetration run restarted from a checkpoint ends with the same penetration figures", "[app][penetration]") {
  // E1 with the flyer as the projectile (first test case), interrupted inside the contact (1 us of the
  // 1.55 us) and continued: the penetration record (deepest nose, perforation time), the time-step and
  // contact records travel in the checkpoint, so the summary is the uninterrupted run's, bit for bit.
  Json document = slab_impact();
  document["penetration"] = {{"projectile", "flyer"}};
  document["stop"] = {{"no_contact_time", 5e-7}};
  const auto scenario = krug::scenario::parse_scenario(document.dump(), "slab_penetration_restart.json");
  const fs::path whole = krug::test::scratch("penetration_whole");
  krug::output::RunOptions options;
  options.output_directory = whole;
  REQUIRE(krug::output::run_scenario(scenario, options).stopped_by == "stop rule");

  const fs::path parts = krug::test::scratch("penetration_parts");
  std::atomic<bool> interrupt{false};
  krug::output::RunOptions first;
  first.output_directory = parts;
  first.interrupt = &interrupt;
  first.on_cycle = [&](const krug::Simulation& s, double) {
    if (s.time() >= 1e-6) interrupt = true;
    return true;
  };
  REQUIRE(krug::output::run_scenario(scenario, first).message == "interrupted");
  krug::output::RunOptions second;
  second.output_directory = parts;
  CHECK(krug::output::restart_scenario(parts / "checkpoint.bin", second).stopped_by == "stop rule");
  const Json a = krug::test::summary_without_timing(whole / "summary.json");
  const Json b = krug::test::summary_without_timing(parts / "summary.json");
  CHECK(a["penetration"] == b["penetration"]);
  CHECK(a["time_step"] == b["time_step"]);
  // The contact record travels too: the flyer pushes on the plate in every cycle of the contact.
  CHECK(a["contact"]["active_cycles"].get<long>() > 0);
  CHECK(a["contact"]["most_sweeps"].get<int>() >= 1);
  CHECK(a["contact"] == b["contact"]);
  CHECK(a == b);
}
