// Reading a scenario's run settings (private to the io library): outputs, the stop rule and the
// penetration block. Used by scenario.cpp's parse_scenario; every error names the JSON path.
#include "scenario_run.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "krug/core/error.hpp"

namespace krug::scenario::detail {

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

namespace {

// A gauge's name becomes the prefix of its CSV columns: letters, digits, '_' and '-' only.
std::string gauge_name(JsonObject& spec, std::vector<std::string>& taken) {
  const std::string name = spec.text("name");
  const bool valid = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
  if (!valid) spec.fail("name", "a non-empty name of letters, digits, '_' and '-' (it prefixes the gauge's CSV columns)");
  if (std::find(taken.begin(), taken.end(), name) != taken.end()) spec.fail("name", "a name no other gauge has");
  taken.push_back(name);
  return name;
}

Vec2 gauge_vector(JsonObject& spec, std::string_view key, GeometryKind geometry) {
  const Json& v = spec.raw(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() || !std::isfinite(v[0].get<double>()) ||
      !std::isfinite(v[1].get<double>())) {
    spec.fail(key, fmt::format("an array [{}, {}] of two finite numbers", axis_name(geometry, 0), axis_name(geometry, 1)));
  }
  spec.resolve(key, v);
  return {v[0].get<double>(), v[1].get<double>()};
}

}  // namespace

GaugeSettings read_gauges(JsonObject spec, const std::vector<Body>& bodies, GeometryKind geometry) {
  GaugeSettings g;
  // An interval below the time step gives a row every cycle (at most controls.max_cycles rows).
  g.interval = spec.number("interval", Range::positive());
  std::vector<std::string> names;
  if (const Json* tracers = spec.optional_raw("tracers")) {
    if (!tracers->is_array()) spec.fail("tracers", "an array of {name, position, quantities}");
    Json resolved_list = Json::array();
    for (std::size_t i = 0; i < tracers->size(); ++i) {
      Json resolved = Json::object();
      JsonObject t((*tracers)[i], fmt::format("{}[{}]", spec.path_of("tracers"), i), &resolved);
      TracerGauge tracer;
      tracer.name = gauge_name(t, names);
      tracer.position = gauge_vector(t, "position", geometry);
      if (const Json* quantities = t.optional_raw("quantities")) {
        const std::vector<std::string>& known = tracer_quantity_names();
        if (!quantities->is_array() || quantities->empty()) t.fail("quantities", "a non-empty array of quantity names");
        for (std::size_t k = 0; k < quantities->size(); ++k) {
          const std::string path = fmt::format("{}[{}]", t.path_of("quantities"), k);
          const Json& q = (*quantities)[k];
          const auto found = q.is_string() ? std::find(known.begin(), known.end(), q.get<std::string>()) : known.end();
          if (found == known.end()) {
            std::string list;
            for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
            const auto guess = q.is_string() ? nearest(q.get<std::string>(), known) : std::nullopt;
            throw InputError(fmt::format("{}: unknown quantity {}; tracers report: {}{}", path, describe_value(q), list,
                                         guess ? fmt::format(" (did you mean \"{}\"?)", *guess) : ""));
          }
          const auto quantity = static_cast<TracerQuantity>(found - known.begin());
          if (std::find(tracer.quantities.begin(), tracer.quantities.end(), quantity) != tracer.quantities.end()) {
            throw InputError(fmt::format("{}: \"{}\" is listed twice", path, *found));
          }
          tracer.quantities.push_back(quantity);
        }
        t.resolve("quantities", *quantities);
      }
      t.finish();
      g.tracers.push_back(tracer);
      resolved_list.push_back(resolved);
    }
    spec.resolve("tracers", resolved_list);
  } else {
    spec.resolve("tracers", Json::array());
  }
  if (const Json* surfaces = spec.optional_raw("surfaces")) {
    if (!surfaces->is_array()) spec.fail("surfaces", "an array of {name, body, position, direction}");
    Json resolved_list = Json::array();
    for (std::size_t i = 0; i < surfaces->size(); ++i) {
      Json resolved = Json::object();
      JsonObject s((*surfaces)[i], fmt::format("{}[{}]", spec.path_of("surfaces"), i), &resolved);
      SurfaceGauge surface;
      surface.name = gauge_name(s, names);
      const Json& body = s.raw("body");
      surface.body = body_index(s, "body", body, bodies, s.path_of("body"));
      s.resolve("body", body);
      surface.position = gauge_vector(s, "position", geometry);
      if (s.has("direction")) {
        const Vec2 d = gauge_vector(s, "direction", geometry);
        if (!(norm(d) > 0.0)) s.fail("direction", "a non-zero vector (the velocity is taken along it)");
        surface.direction = (1.0 / norm(d)) * d;
      } else {
        s.optional_raw("direction");  // named among the valid keys
      }
      s.finish();
      g.surfaces.push_back(surface);
      resolved_list.push_back(resolved);
    }
    spec.resolve("surfaces", resolved_list);
  } else {
    spec.resolve("surfaces", Json::array());
  }
  g.forces = spec.flag("forces", false);
  spec.finish();
  if (g.empty()) spec.fail_here("expected at least one gauge: tracers, surfaces or \"forces\": true");
  return g;
}

void check_gauges(const GaugeSettings& gauges, const SimulationSetup& setup) {
  const bool temperature = std::any_of(setup.materials.begin(), setup.materials.end(),
                                       [](const Material& m) { return std::holds_alternative<JohnsonCook>(m.strength); });
  for (std::size_t i = 0; i < gauges.tracers.size(); ++i) {
    const TracerGauge& t = gauges.tracers[i];
    if (!locate_tracer(setup.mesh, t.position, true)) {
      throw InputError(fmt::format("gauges.tracers[{}].position: ({:.6g}, {:.6g}) lies in no zone of any body at t = 0; "
                                   "a tracer follows the material point it starts on",
                                   i, t.position.x, t.position.y));
    }
    for (std::size_t k = 0; k < t.quantities.size(); ++k) {
      if (t.quantities[k] == TracerQuantity::temperature && !temperature) {
        throw InputError(fmt::format("gauges.tracers[{}].quantities[{}]: \"temperature\": no material of this scenario "
                                     "carries a temperature (only the johnson_cook strength model does)", i, k));
      }
    }
  }
}

}  // namespace krug::scenario::detail
