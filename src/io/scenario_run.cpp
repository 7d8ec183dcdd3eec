// Reading a scenario's run settings (private to the io library): outputs, the stop rule and the
// penetration block. Used by scenario.cpp's parse_scenario; every error names the JSON path.
#include "scenario_run.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "krug/core/error.hpp"

namespace krug::io::detail {

Index body_index(JsonObject& spec, std::string_view key, const Json& name, const std::vector<Body>& bodies,
                 const std::string& path) {
  std::vector<std::string> names;
  for (const Body& b : bodies) names.push_back(b.name);
  if (name.is_string()) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].name == name.get<std::string>()) return static_cast<Index>(i);
    }
    const auto guess = nearest(name.get<std::string>(), names);
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "\"" : ", \"") + n + "\"";
    throw InputError(fmt::format("{}: unknown body \"{}\"; bodies: {}{}", path, name.get<std::string>(), list,
                                 guess ? fmt::format(" (did you mean \"{}\"?)", *guess) : ""));
  }
  spec.fail(key, "body names (strings)");
}

// `solids`: some material has a strength model (the pictures then show plastic strain by default).
OutputSettings read_output(JsonObject output, double end_time, GeometryKind geometry, bool solids) {
  OutputSettings o;
  o.directory = output.text("directory", "");
  o.history_interval = output.number("history_interval", end_time / 1000.0, Range::non_negative());
  o.snapshot_interval = output.number("snapshot_interval", end_time / 10.0, Range::non_negative());
  o.checkpoint_interval = output.number("checkpoint_interval", 0.0, Range::non_negative());
  // Intervals a run can honour: at most this many outputs of each kind over end_time (0: every cycle
  // for the history, none for snapshots and checkpoints).
  auto check_count = [&](const char* key, double interval, double most, const char* what) {
    if (interval > 0.0 && end_time / interval > most) {
      output.fail(key, fmt::format("an interval of at least end_time / {:g} = {:g} s (at most {:g} {}); {:g} s would "
                                   "write {:.3g}",
                                   most, end_time / most, most, what, interval, end_time / interval));
    }
  };
  check_count("history_interval", o.history_interval, 1e8, "rows; 0 writes every cycle");
  check_count("snapshot_interval", o.snapshot_interval, 1e5, "snapshots");
  check_count("checkpoint_interval", o.checkpoint_interval, 1e4, "checkpoints");
  o.vtk_format = output.choice("vtk_format", {"binary", "ascii"}, "binary") == "ascii" ? VtkEncoding::ascii : VtkEncoding::binary;
  o.plots = output.flag("plots", true);
  {
    JsonObject pictures = output.object_or_empty("pictures");
    PictureSettings& p = o.pictures;
    p.enabled = pictures.flag("enabled", true);
    p.field = pictures.choice("field", picture_fields(), solids ? "equivalent_plastic_strain" : "density");
    p.every_snapshot = pictures.flag("every_snapshot", false);
    p.width = static_cast<int>(pictures.integer("width", p.width, 200, 8000));
    p.mirror = pictures.flag("mirror", geometry == GeometryKind::axisymmetric);
    if (const Json* range = pictures.optional_raw("range")) {
      if (!range->is_array() || range->size() != 2 || !(*range)[0].is_number() || !(*range)[1].is_number() ||
          !std::isfinite((*range)[0].get<double>()) || !std::isfinite((*range)[1].get<double>()) ||
          !((*range)[0].get<double>() < (*range)[1].get<double>())) {
        pictures.fail("range", "an array [low, high] of two finite numbers with low < high");
      }
      p.range = std::make_pair((*range)[0].get<double>(), (*range)[1].get<double>());
      pictures.resolve("range", *range);
    }
    if (const Json* window = pictures.optional_raw("window")) {
      const std::string expected = "an array [first from, first to, second from, second to] of finite numbers (m) with "
                                   "from < to on both axes";
      if (!window->is_array() || window->size() != 4) pictures.fail("window", expected);
      std::array<double, 4> w{};
      for (std::size_t k = 0; k < 4; ++k) {
        if (!(*window)[k].is_number() || !std::isfinite((*window)[k].get<double>())) pictures.fail("window", expected);
        w[k] = (*window)[k].get<double>();
      }
      if (!(w[0] < w[1]) || !(w[2] < w[3])) pictures.fail("window", expected);
      p.window = w;
      pictures.resolve("window", *window);
    }
    pictures.finish();
  }
  output.finish();
  return o;
}

// The stop rule; in a penetration scenario the body defaults to the projectile and the run waits for
// it to clear the targets.
StopRule read_stop_rule(JsonObject spec, const std::vector<Body>& bodies, const std::optional<PenetrationSetup>& penetration) {
  StopRule rule;
  if (penetration && !spec.has("body")) {
    rule.body_index = penetration->projectile;
    rule.body = bodies[static_cast<std::size_t>(rule.body_index)].name;
    spec.optional_raw("body");
    spec.resolve("body", rule.body);
  } else {
    const Json& name = spec.raw("body");
    rule.body_index = body_index(spec, "body", name, bodies, spec.path_of("body"));
    rule.body = name.get<std::string>();
    spec.resolve("body", name);
  }
  const double default_window = penetration ? 5e-6 : 0.0;
  rule.no_contact_time = default_window > 0.0 ? spec.number("no_contact_time", default_window, Range::positive())
                                              : spec.number("no_contact_time", Range::positive());
  rule.velocity_change = spec.number("velocity_change", penetration ? 0.005 : rule.velocity_change, Range{0.0, 1.0, true});
  if (spec.has("clear_of")) {
    rule.clear_of = spec.number("clear_of");
  } else {
    spec.optional_raw("clear_of");  // named among the valid keys
  }
  rule.clear_of_targets = spec.flag("clear_of_targets", penetration.has_value());
  if (rule.clear_of_targets && !penetration) {
    spec.fail("clear_of_targets", "false here: clearing the targets needs a \"penetration\" block naming the projectile");
  }
  if (rule.clear_of_targets && rule.body_index != penetration->projectile) {
    spec.fail("body", fmt::format("the projectile \"{}\" when clear_of_targets is true",
                                  bodies[static_cast<std::size_t>(penetration->projectile)].name));
  }
  spec.finish();
  return rule;
}

// {"projectile": name, "targets": [names]}; the targets default to every other body.
PenetrationSetup read_penetration(JsonObject spec, const std::vector<Body>& bodies) {
  PenetrationSetup p;
  const Json& name = spec.raw("projectile");
  p.projectile = body_index(spec, "projectile", name, bodies, spec.path_of("projectile"));
  spec.resolve("projectile", name);
  Json resolved_targets = Json::array();
  if (const Json* targets = spec.optional_raw("targets")) {
    if (!targets->is_array() || targets->empty()) spec.fail("targets", "a non-empty array of body names");
    for (std::size_t i = 0; i < targets->size(); ++i) {
      const std::string path = fmt::format("{}[{}]", spec.path_of("targets"), i);
      const Index t = body_index(spec, "targets", (*targets)[i], bodies, path);
      if (t == p.projectile) throw InputError(fmt::format("{}: the projectile cannot be its own target", path));
      if (std::find(p.targets.begin(), p.targets.end(), t) != p.targets.end()) {
        throw InputError(fmt::format("{}: \"{}\" is listed twice", path, bodies[static_cast<std::size_t>(t)].name));
      }
      p.targets.push_back(t);
      resolved_targets.push_back(bodies[static_cast<std::size_t>(t)].name);
    }
  } else {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (static_cast<Index>(i) == p.projectile) continue;
      p.targets.push_back(static_cast<Index>(i));
      resolved_targets.push_back(bodies[i].name);
    }
    if (p.targets.empty()) spec.fail_here("a penetration scenario needs a target: at least one body besides the projectile");
  }
  spec.resolve("targets", resolved_targets);
  spec.finish();
  return p;
}

}  // namespace krug::io::detail
