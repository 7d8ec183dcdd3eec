// Ballistic limit: reading a run's outcome, the search, the outputs and the scenario variants (the
// Lambert-Jonas fit is in ballistic_fit.cpp).
#include "krug/run/ballistic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "krug/core/error.hpp"
#include "krug/scenario/edit.hpp"

namespace krug::run {

namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

bool counts(const BallisticOutcome& o) {
  return o.result == ImpactResult::stopped || o.result == ImpactResult::perforated;
}

}  // namespace

const char* to_string(ImpactResult result) {
  switch (result) {
    case ImpactResult::stopped: return "stopped";
    case ImpactResult::perforated: return "perforated";
    case ImpactResult::unfinished: return "unfinished";
    case ImpactResult::failed: return "failed";
  }
  return "failed";
}

BallisticOutcome outcome_from_summary(const std::string& summary_json, double velocity) {
  BallisticOutcome o;
  o.velocity = velocity;
  o.status = "not run";
  Json s;
  try {
    s = Json::parse(summary_json);
  } catch (const nlohmann::json::exception&) {
    o.message = "no readable summary.json";
    return o;
  }
  if (!s.is_object()) {
    o.message = "no readable summary.json";
    return o;
  }
  auto number = [](const Json& j, const char* key, double fallback = 0.0) {
    return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
  };
  auto text = [](const Json& j, const char* key) {
    return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string();
  };
  o.status = text(s, "status");
  o.stopped_by = text(s, "stopped_by");
  o.message = text(s, "message");
  o.cycles = static_cast<long>(number(s, "cycles"));
  o.wall_seconds = number(s, "wall_seconds");
  if (!s.contains("penetration") || !s["penetration"].is_object()) {
    if (o.message.empty()) o.message = "the summary has no penetration block";
    o.result = ImpactResult::failed;
    return o;
  }
  const Json& p = s["penetration"];
  o.residual_velocity = number(p, "residual_velocity");
  o.residual_mass = number(p, "residual_mass");
  o.initial_mass = number(p, "initial_mass");
  o.eroded_mass = number(p, "eroded_mass");
  o.target_energy = number(p, "target_energy_absorbed");
  o.whole_velocity = p.contains("whole") ? number(p["whole"], "velocity", nan) : nan;
  o.plug_mass = p.contains("plug") && p["plug"].is_object() ? number(p["plug"], "mass") : 0.0;
  const bool final = p.contains("final") && p["final"].is_boolean() && p["final"].get<bool>();
  const bool perforated = p.contains("perforated") && p["perforated"].is_boolean() && p["perforated"].get<bool>();
  if (o.status != "completed") {
    o.result = ImpactResult::failed;
    if (o.message.empty()) o.message = "status " + o.status;
  } else if (!final) {
    o.result = ImpactResult::unfinished;
    if (o.message.empty()) o.message = "ended by " + o.stopped_by + " without a final answer";
  } else {
    // A perforation for the ballistic limit: the largest piece has passed the targets and still
    // flies on. A piece whose nose is through but that moves backwards (caught in the hole, or
    // rebounding from it) has been stopped: counting it as a perforation put the limit at the speed
    // where the nose first gets through, below the speed at which anything flies out.
    o.result = perforated && o.residual_velocity > 0.0 ? ImpactResult::perforated : ImpactResult::stopped;
  }
  return o;
}

// ---- the search ----

namespace {

// `count` new points in (low, high), spread over the gaps between low, the `taken` points inside and
// high: each goes to the gap that would be left widest, and a gap with m points is cut in m + 1
// equal parts (with nothing taken, an equal N-section).
std::vector<double> fill_gaps(double low, double high, std::vector<double> taken, int count) {
  std::vector<double> edges = {low, high};
  for (double v : taken) {
    if (v > low && v < high) edges.push_back(v);
  }
  std::sort(edges.begin(), edges.end());
  std::vector<int> assigned(edges.size() - 1, 0);
  for (int c = 0; c < count; ++c) {
    std::size_t best = 0;
    double widest = -1.0;
    for (std::size_t g = 0; g + 1 < edges.size(); ++g) {
      const double part = (edges[g + 1] - edges[g]) / (assigned[g] + 2);
      if (part > widest) {
        widest = part;
        best = g;
      }
    }
    ++assigned[best];
  }
  std::vector<double> points;
  for (std::size_t g = 0; g + 1 < edges.size(); ++g) {
    for (int m = 1; m <= assigned[g]; ++m) {
      points.push_back(edges[g] + (edges[g + 1] - edges[g]) * m / (assigned[g] + 1));
    }
  }
  return points;
}

}  // namespace

BallisticStudy ballistic_search(const BallisticOptions& options, const BallisticEvaluate& evaluate,
                                const std::function<void(const BallisticStudy&)>& on_round) {
  if (!(options.v_min > 0.0) || !(options.v_max > options.v_min)) {
    throw InputError(fmt::format("ballistic: the speed range must satisfy 0 < MIN < MAX (got {}, {})", options.v_min,
                                 options.v_max));
  }
  if (!(options.tolerance > 0.0)) throw InputError("ballistic: the tolerance must be positive");
  if (options.batch < 1) throw InputError("ballistic: the batch must be at least 1");
  if (options.points_above < 0) throw InputError("ballistic: --points-above must not be negative");
  BallisticStudy study;
  study.options = options;
  const double quantum = options.velocity_quantum > 0.0 ? options.velocity_quantum : 0.01;
  int round = 0;
  auto already = [&](double v) {
    return std::any_of(study.runs.begin(), study.runs.end(),
                       [&](const BallisticOutcome& o) { return std::abs(o.velocity - v) < 0.5 * quantum; });
  };
  // Runs a batch (rounded, new speeds only); false when nothing was left to run.
  auto run_batch = [&](const std::vector<double>& wanted) {
    std::vector<double> speeds;
    for (double v : wanted) {
      const double rounded = std::round(v / quantum) * quantum;
      if (rounded <= 0.0 || already(rounded)) continue;
      if (std::any_of(speeds.begin(), speeds.end(), [&](double s) { return std::abs(s - rounded) < 0.5 * quantum; })) continue;
      speeds.push_back(rounded);
    }
    const std::size_t room = static_cast<std::size_t>(std::max(0, options.max_runs - static_cast<int>(study.runs.size())));
    if (speeds.size() > room) speeds.resize(room);
    if (speeds.empty()) return false;
    std::vector<BallisticOutcome> outcomes = evaluate(speeds);
    if (outcomes.size() != speeds.size()) throw std::logic_error("ballistic: the evaluator returned a wrong count");
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      outcomes[i].velocity = speeds[i];
      study.runs.push_back(outcomes[i]);
      study.round.push_back(round);
    }
    if (on_round) on_round(study);
    ++round;
    return true;
  };
  auto note = [&](std::string text) {
    if (std::find(study.notes.begin(), study.notes.end(), text) == study.notes.end()) study.notes.push_back(std::move(text));
  };

  // Round 0: the ends of the range and, with more workers, points between them.
  {
    const int n = std::max(2, options.batch);
    std::vector<double> speeds;
    for (int i = 0; i < n; ++i) speeds.push_back(options.v_min + (options.v_max - options.v_min) * i / (n - 1));
    run_batch(speeds);
  }
  // Bisection (N-section) of the bracket.
  double last_width = std::numeric_limits<double>::infinity();
  int idle_rounds = 0;
  for (;;) {
    double low = -1.0, high = std::numeric_limits<double>::infinity();
    for (const BallisticOutcome& o : study.runs) {
      if (o.result == ImpactResult::perforated) high = std::min(high, o.velocity);
    }
    for (const BallisticOutcome& o : study.runs) {
      if (o.result == ImpactResult::stopped && o.velocity < high) low = std::max(low, o.velocity);
    }
    if (!std::isfinite(high)) {
      note(fmt::format("no run perforated up to {:.2f} m/s: the ballistic limit is above the range, or the runs there "
                       "did not finish",
                       options.v_max));
      break;
    }
    if (low < 0.0) {
      note(fmt::format("no run stopped below the slowest perforation ({:.2f} m/s): the ballistic limit is below the "
                       "range, or the runs there did not finish",
                       high));
      break;
    }
    study.bracketed = true;
    study.bracket_low = low;
    study.bracket_high = high;
    // Runs without an answer inside the bracket: said, and left out.
    std::vector<double> unknown;
    for (const BallisticOutcome& o : study.runs) {
      if (!counts(o) && o.velocity > low && o.velocity < high) {
        unknown.push_back(o.velocity);
        note(fmt::format("the run at {:.2f} m/s inside the bracket {}: not counted, the search goes around it",
                         o.velocity, o.result == ImpactResult::failed ? "failed" : "ended without a final answer"));
      }
    }
    if (high - low <= options.tolerance) {
      study.converged = true;
      break;
    }
    if (high - low < last_width) {
      last_width = high - low;
      idle_rounds = 0;
    } else if (++idle_rounds >= 3) {
      note(fmt::format("the bracket [{:.2f}, {:.2f}] m/s could not be narrowed: three rounds of runs inside it gave no "
                       "answer",
                       low, high));
      break;
    }
    if (static_cast<int>(study.runs.size()) >= options.max_runs) {
      note(fmt::format("stopped at the bound of {} runs", options.max_runs));
      break;
    }
    if (!run_batch(fill_gaps(low, high, unknown, options.batch))) {
      note(fmt::format("the bracket [{:.2f}, {:.2f}] m/s is as narrow as the speeds' rounding allows", low, high));
      break;
    }
  }
  // Points above the bracket for the fit.
  const double upper_start = study.bracketed ? study.bracket_high : options.v_min;
  auto perforations_above = [&]() {
    std::vector<double> above;
    for (const BallisticOutcome& o : study.runs) {
      if (o.result == ImpactResult::perforated && o.velocity > upper_start + 0.5 * quantum) above.push_back(o.velocity);
    }
    return above;
  };
  bool any_perforation = std::any_of(study.runs.begin(), study.runs.end(),
                                     [](const BallisticOutcome& o) { return o.result == ImpactResult::perforated; });
  for (int attempt = 0; any_perforation && attempt < 3; ++attempt) {
    const std::vector<double> above = perforations_above();
    const int missing = options.points_above - static_cast<int>(above.size());
    if (missing <= 0) break;
    std::vector<double> taken;
    for (const BallisticOutcome& o : study.runs) {
      if (o.velocity > upper_start) taken.push_back(o.velocity);
    }
    // Up to the range's top, or beyond the fastest run when the top is taken.
    if (!run_batch(fill_gaps(upper_start, options.v_max, taken, missing))) break;
  }
  if (any_perforation && static_cast<int>(perforations_above().size()) < options.points_above) {
    note(fmt::format("only {} perforating runs above {:.2f} m/s, {} wanted", perforations_above().size(), upper_start,
                     options.points_above));
  }
  // The figures.
  double highest_stop = -1.0, lowest_perforation = std::numeric_limits<double>::infinity();
  for (const BallisticOutcome& o : study.runs) {
    if (o.result == ImpactResult::stopped) highest_stop = std::max(highest_stop, o.velocity);
    if (o.result == ImpactResult::perforated) lowest_perforation = std::min(lowest_perforation, o.velocity);
  }
  if (study.bracketed) {
    study.highest_stop = highest_stop;
    study.lowest_perforation = lowest_perforation;
    study.v50 = 0.5 * (highest_stop + lowest_perforation);
    study.v_bl = 0.5 * (study.bracket_low + study.bracket_high);
    if (highest_stop > lowest_perforation) {
      note(fmt::format("a zone of mixed results: a stop at {:.2f} m/s above the perforation at {:.2f} m/s",
                       highest_stop, lowest_perforation));
    }
  }
  // The fits, on the perforating runs.
  std::vector<double> v_i, v_r;
  double plug_sum = 0.0;
  for (const BallisticOutcome& o : study.runs) {
    if (o.initial_mass > 0.0) study.projectile_mass = o.initial_mass;
    if (o.result != ImpactResult::perforated) continue;
    v_i.push_back(o.velocity);
    v_r.push_back(o.residual_velocity);
    plug_sum += o.plug_mass;
  }
  if (!v_i.empty()) {
    study.mean_plug_mass = plug_sum / static_cast<double>(v_i.size());
    const double lowest = *std::min_element(v_i.begin(), v_i.end());
    CurveFitOptions start;
    start.v_bl = study.bracketed ? std::min(study.v_bl, 0.999 * lowest) : 0.9 * lowest;
    if (v_i.size() >= 4) {
      study.fit = fit_lambert_jonas(v_i, v_r, start);
    } else {
      start.free_p = false;
      study.fit = fit_lambert_jonas(v_i, v_r, start);
      study.fit.note = fmt::format("{} perforating runs: p fixed at 2{}", v_i.size(),
                                   study.fit.note.empty() ? "" : "; " + study.fit.note);
    }
    if (study.projectile_mass > 0.0) {
      CurveFitOptions ri;
      ri.free_a = false;
      ri.free_p = false;
      ri.a = study.projectile_mass / (study.projectile_mass + study.mean_plug_mass);
      ri.p = 2.0;
      ri.v_bl = start.v_bl;
      study.recht_ipson = fit_lambert_jonas(v_i, v_r, ri);
    } else {
      study.recht_ipson.note = "no projectile mass known";
    }
  } else {
    study.fit.note = "no perforating run";
    study.recht_ipson.note = "no perforating run";
  }
  return study;
}

std::vector<std::string> ballistic_summary_lines(const BallisticStudy& study) {
  std::vector<std::string> lines;
  std::size_t stopped = 0, perforated = 0, other = 0;
  double seconds = 0.0;
  for (const BallisticOutcome& o : study.runs) {
    stopped += o.result == ImpactResult::stopped;
    perforated += o.result == ImpactResult::perforated;
    other += !counts(o);
    seconds += o.wall_seconds;
  }
  lines.push_back(fmt::format("{} runs ({} stopped, {} perforated, {} without an answer), {:.1f} s of runs", study.runs.size(),
                              stopped, perforated, other, seconds));
  if (study.bracketed) {
    lines.push_back(fmt::format("ballistic limit V_bl = {:.1f} +- {:.1f} m/s (bracket {:.2f} to {:.2f} m/s{})", study.v_bl,
                                0.5 * (study.bracket_high - study.bracket_low), study.bracket_low, study.bracket_high,
                                study.converged ? "" : ", wider than the tolerance"));
    lines.push_back(fmt::format("V50 = {:.1f} m/s (highest stop {:.2f}, lowest perforation {:.2f} m/s)", study.v50,
                                study.highest_stop, study.lowest_perforation));
  } else {
    lines.push_back("no ballistic limit in the range");
  }
  if (study.fit.valid) {
    lines.push_back(fmt::format("Lambert-Jonas fit on {} points: v_bl = {:.1f} +- {:.1f} m/s, a = {:.3f} +- {:.3f}, p = {:.2f} "
                                "+- {:.2f}, rms {:.2f} m/s{}",
                                study.fit.points, study.fit.v_bl, study.fit.sigma_v_bl, study.fit.a, study.fit.sigma_a,
                                study.fit.p, study.fit.sigma_p, study.fit.rms,
                                study.fit.note.empty() ? "" : " (" + study.fit.note + ")"));
  } else {
    lines.push_back("Lambert-Jonas fit: none (" + study.fit.note + ")");
  }
  if (study.recht_ipson.valid) {
    lines.push_back(fmt::format("Recht-Ipson reference (p = 2, a = m_p/(m_p + m_plug) = {:.3f}, mean plug {:.4g} g): v_bl = "
                                "{:.1f} +- {:.1f} m/s, rms {:.2f} m/s",
                                study.recht_ipson.a, study.mean_plug_mass * 1e3, study.recht_ipson.v_bl,
                                study.recht_ipson.sigma_v_bl, study.recht_ipson.rms));
  } else {
    lines.push_back("Recht-Ipson reference: none (" + study.recht_ipson.note + ")");
  }
  for (const std::string& n : study.notes) lines.push_back("note: " + n);
  return lines;
}

// ---- the scenario variants ----

BallisticProjectile ballistic_projectile(const std::string& scenario_text, const std::string& origin) {
  Json s;
  try {
    s = Json::parse(scenario_text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not JSON: {}", origin, e.what()));
  }
  if (!s.is_object() || !s.contains("penetration") || !s["penetration"].is_object() ||
      !s["penetration"].contains("projectile") || !s["penetration"]["projectile"].is_string()) {
    throw InputError(fmt::format("{}: krug ballistic needs a scenario with a \"penetration\" block naming the projectile "
                                 "(docs/scenario-format.md, Penetration)",
                                 origin));
  }
  BallisticProjectile projectile;
  projectile.name = s["penetration"]["projectile"].get<std::string>();
  if (!s.contains("bodies") || !s["bodies"].is_array()) throw InputError(fmt::format("{}: no \"bodies\" array", origin));
  bool found = false;
  for (std::size_t k = 0; k < s["bodies"].size(); ++k) {
    const Json& body = s["bodies"][k];
    if (body.is_object() && body.contains("name") && body["name"] == projectile.name) {
      projectile.body = k;
      found = true;
      break;
    }
  }
  if (!found) throw InputError(fmt::format("{}: penetration.projectile \"{}\" is not a body", origin, projectile.name));
  const std::string where = fmt::format("bodies[{}].initial.velocity", projectile.body);
  const Json& body = s["bodies"][projectile.body];
  if (!body.contains("initial") || !body["initial"].is_object() || !body["initial"].contains("velocity")) {
    throw InputError(fmt::format("{}: {} is missing: the projectile must be given an initial velocity", origin, where));
  }
  const Json& v = body["initial"]["velocity"];
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number()) {
    throw InputError(fmt::format("{}: {} is {}: krug ballistic scales a velocity given as two numbers [first, second] "
                                 "(m/s); an expression cannot be scaled safely",
                                 origin, where, v.dump()));
  }
  projectile.velocity = {v[0].get<double>(), v[1].get<double>()};
  projectile.speed = std::hypot(projectile.velocity[0], projectile.velocity[1]);
  if (!(projectile.speed > 0.0)) throw InputError(fmt::format("{}: {} is zero: no direction to scale", origin, where));
  projectile.end_time = s.contains("end_time") && s["end_time"].is_number() ? s["end_time"].get<double>() : 0.0;
  return projectile;
}

std::string ballistic_variant(const std::string& scenario_text, const BallisticProjectile& projectile, double speed,
                              bool scale_end_time, const std::string& origin, double end_time_factor) {
  const double factor = speed / projectile.speed;
  const OrderedJson velocity = {projectile.velocity[0] * factor, projectile.velocity[1] * factor};
  std::vector<scenario::ScenarioEdit> edits = {
      {fmt::format("bodies[{}].initial.velocity", projectile.body), velocity.dump()}};
  const bool stretched = scale_end_time && speed < projectile.speed;
  if (projectile.end_time > 0.0 && (stretched || end_time_factor != 1.0)) {
    const double end_time = projectile.end_time * (stretched ? projectile.speed / speed : 1.0) * end_time_factor;
    edits.push_back({"end_time", OrderedJson(end_time).dump()});
  }
  const OrderedJson document = OrderedJson::parse(scenario_text);
  const std::string base_title = document.contains("title") && document["title"].is_string()
                                     ? document["title"].get<std::string>()
                                     : std::string();
  const std::string title = fmt::format("{}{}ballistic run at {:.2f} m/s", base_title, base_title.empty() ? "" : " - ", speed);
  edits.push_back({"title", OrderedJson(title).dump()});
  return scenario::edit_scenario(scenario_text, edits, origin);
}

std::string ballistic_run_name(double speed) { return fmt::format("v{:07.2f}", speed); }

}  // namespace krug::run
