// The files of a ballistic-limit study: DIR/ballistic.csv and DIR/ballistic.json (docs/outputs.md,
// "Ballistic").
#include "krug/output/ballistic_files.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "krug/output/text_file.hpp"

namespace krug::output {

using run::BallisticOutcome;
using run::BallisticStudy;
using run::CurveFit;
using run::ImpactResult;

namespace {

using Json = nlohmann::json;

// A run that answers the question (stopped or perforated); the others are not counted.
bool counts(const BallisticOutcome& o) {
  return o.result == ImpactResult::stopped || o.result == ImpactResult::perforated;
}

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json fit_json(const CurveFit& fit) {
  Json j;
  j["valid"] = fit.valid;
  j["note"] = fit.note;
  j["a"] = number_or_null(fit.a);
  j["p"] = number_or_null(fit.p);
  j["v_bl"] = number_or_null(fit.v_bl);
  j["sigma_a"] = number_or_null(fit.sigma_a);
  j["sigma_p"] = number_or_null(fit.sigma_p);
  j["sigma_v_bl"] = number_or_null(fit.sigma_v_bl);
  Json covariance = Json::array();
  for (const auto& row : fit.covariance) {
    Json r = Json::array();
    for (double v : row) r.push_back(number_or_null(v));
    covariance.push_back(r);
  }
  j["covariance"] = covariance;
  j["points"] = fit.points;
  j["free_parameters"] = fit.free_parameters;
  j["iterations"] = fit.iterations;
  j["rms"] = number_or_null(fit.rms);
  Json residuals = Json::array();
  for (std::size_t i = 0; i < fit.residuals.size(); ++i) {
    residuals.push_back({{"velocity", fit.velocities[i]}, {"residual", number_or_null(fit.residuals[i])}});
  }
  j["residuals"] = residuals;
  return j;
}

std::string csv_number(double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : std::string(); }

}  // namespace

void write_ballistic_results(const std::filesystem::path& directory, const BallisticStudy& study,
                             const std::string& scenario) {
  std::vector<std::size_t> order(study.runs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t i, std::size_t j) { return study.runs[i].velocity < study.runs[j].velocity; });
  std::string csv =
      "velocity,result,perforated,final,residual_velocity,whole_velocity,residual_mass,initial_mass,plug_mass,"
      "eroded_mass,target_energy_absorbed,status,stopped_by,cycles,wall_seconds,round,directory,message\n";
  for (std::size_t i : order) {
    const BallisticOutcome& o = study.runs[i];
    const bool answered = counts(o);
    const bool has_figures = o.result != ImpactResult::failed || o.status == "failed";
    csv += fmt::format("{:.2f},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", o.velocity, to_string(o.result),
                       answered ? (o.result == ImpactResult::perforated ? "true" : "false") : "",
                       answered ? "true" : "false",
                       has_figures ? csv_number(o.residual_velocity) : "", has_figures ? csv_number(o.whole_velocity) : "",
                       has_figures ? csv_number(o.residual_mass) : "", has_figures ? csv_number(o.initial_mass) : "",
                       has_figures ? csv_number(o.plug_mass) : "", has_figures ? csv_number(o.eroded_mass) : "",
                       has_figures ? csv_number(o.target_energy) : "", csv_field(o.status), csv_field(o.stopped_by),
                       o.cycles, csv_number(o.wall_seconds), study.round[i], csv_field(o.directory),
                       csv_field(o.message));
  }
  write_text_atomically(directory / "ballistic.csv", csv);

  Json j;
  j["scenario"] = scenario;
  j["range"] = {study.options.v_min, study.options.v_max};
  j["tolerance"] = study.options.tolerance;
  j["points_above"] = study.options.points_above;
  j["batch"] = study.options.batch;
  j["runs"] = study.runs.size();
  std::size_t stopped = 0, perforated = 0, unfinished = 0, failed = 0;
  double seconds = 0.0;
  for (const BallisticOutcome& o : study.runs) {
    stopped += o.result == ImpactResult::stopped;
    perforated += o.result == ImpactResult::perforated;
    unfinished += o.result == ImpactResult::unfinished;
    failed += o.result == ImpactResult::failed;
    seconds += o.wall_seconds;
  }
  j["counts"] = {{"stopped", stopped}, {"perforated", perforated}, {"unfinished", unfinished}, {"failed", failed}};
  j["run_seconds"] = seconds;
  j["rounds"] = study.round.empty() ? 0 : study.round.back() + 1;
  j["bracketed"] = study.bracketed;
  j["converged"] = study.converged;
  if (study.bracketed) {
    j["bracket"] = {study.bracket_low, study.bracket_high};
    j["v_bl"] = study.v_bl;
    j["v_bl_half_width"] = 0.5 * (study.bracket_high - study.bracket_low);
    j["highest_stop"] = study.highest_stop;
    j["lowest_perforation"] = study.lowest_perforation;
    j["v50"] = study.v50;
  } else {
    j["bracket"] = nullptr;
    j["v_bl"] = nullptr;
    j["v50"] = nullptr;
  }
  j["lambert_jonas"] = fit_json(study.fit);
  Json ri = fit_json(study.recht_ipson);
  ri["projectile_mass"] = study.projectile_mass;
  ri["mean_plug_mass"] = study.mean_plug_mass;
  j["recht_ipson"] = ri;
  j["notes"] = study.notes;
  write_text_atomically(directory / "ballistic.json", j.dump(2) + "\n");
}

}  // namespace krug::output
