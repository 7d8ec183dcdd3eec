#include "krug/boundary/conditions.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "krug/core/error.hpp"

namespace krug::boundary {

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw InputError(fmt::format("{}: {}", where, message));
}

void apply_free(const Condition&, const Side&, GeometryKind, NodeFields&, Target&) {}

// Symmetry and slip hold the side's normal component: the side must be a line of constant first or
// second coordinate.
void apply_normal(const Condition& condition, const Side& side, GeometryKind geometry, NodeFields& nodes, Target& target) {
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  for (const Index n : side.nodes) {
    min_x = std::min(min_x, nodes.x[n]);
    max_x = std::max(max_x, nodes.x[n]);
    min_y = std::min(min_y, nodes.y[n]);
    max_y = std::max(max_y, nodes.y[n]);
  }
  const double extent = std::max({max_x - min_x, max_y - min_y, 1e-300});
  const bool along_first = max_x - min_x <= 1e-9 * extent;    // the normal is the first axis
  const bool along_second = max_y - min_y <= 1e-9 * extent;
  if (!along_first && !along_second) {
    fail(side.where, fmt::format("side \"{}\" of body \"{}\" is not a straight line along an axis; a {} condition needs a "
                                 "side of constant {} or constant {}",
                                 side.name, side.body_name, condition.kind == Kind::slip ? "slip" : "symmetry",
                                 axis_name(geometry, 0), axis_name(geometry, 1)));
  }
  for (const Index n : side.nodes) {
    target.hold(n, along_first, along_second);
    if (along_first) nodes.u[n] = 0.0;
    if (along_second) nodes.v[n] = 0.0;
  }
}

void apply_fixed(const Condition&, const Side& side, GeometryKind, NodeFields& nodes, Target& target) {
  for (const Index n : side.nodes) {
    target.hold(n, true, true);
    nodes.u[n] = nodes.v[n] = 0.0;
  }
}

// Constant components are held at their value; a component given as a function of time is held at
// its value at t = 0 (u^{-1/2}) and driven by it from then on.
void apply_velocity(const Condition& condition, const Side& side, GeometryKind, NodeFields& nodes, Target& target) {
  std::array<bool, 2> held{};
  std::array<double, 2> initial{};
  for (std::size_t k = 0; k < 2; ++k) {
    held[k] = condition.velocity_of_time[k] || condition.velocity[k].has_value();
    if (condition.velocity_of_time[k]) {
      initial[k] = condition.velocity_of_time[k](0.0);
      target.driven.push_back({side.nodes, static_cast<int>(k), condition.velocity_of_time[k]});
    } else if (condition.velocity[k]) {
      initial[k] = *condition.velocity[k];
    }
  }
  for (const Index n : side.nodes) {
    target.hold(n, held[0], held[1]);
    if (held[0]) nodes.u[n] = initial[0];
    if (held[1]) nodes.v[n] = initial[1];
  }
}

// A pressure and/or traction on the side's faces. The axis (r = 0 in RZ) carries no face to load:
// its radial velocity is held, and a surface of revolution there has no area.
void apply_load(const Condition& condition, const Side& side, GeometryKind geometry, NodeFields& nodes, Target& target) {
  if (geometry == GeometryKind::axisymmetric &&
      std::all_of(side.nodes.begin(), side.nodes.end(), [&](Index n) { return nodes.y[n] == 0.0; })) {
    fail(side.where, fmt::format("side \"{}\" of body \"{}\" lies on the axis, where the radial velocity is held and a "
                                 "face has no area; a {} load needs a side off the axis",
                                 side.name, side.body_name, kind_of(condition.kind).name));
  }
  if (side.segments.empty()) {
    fail(side.where, fmt::format("side \"{}\" of body \"{}\" has no boundary face to load", side.name, side.body_name));
  }
  target.loads.push_back({side.segments, condition.pressure, condition.traction});
}

}  // namespace

const std::vector<ConditionKind>& condition_kinds() {
  static const std::vector<ConditionKind> kinds = {
      {Kind::free, "free", true, false, false, apply_free},
      {Kind::symmetry, "symmetry", true, true, false, apply_normal},
      {Kind::slip, "slip", true, true, false, apply_normal},
      {Kind::fixed, "fixed", true, true, false, apply_fixed},
      {Kind::velocity, "velocity", false, true, false, apply_velocity},
      {Kind::pressure, "pressure", false, false, true, apply_load},
      {Kind::traction, "traction", false, false, true, apply_load},
  };
  return kinds;
}

const ConditionKind& kind_of(Kind kind) { return condition_kinds().at(static_cast<std::size_t>(kind)); }

const ConditionKind* find_kind(std::string_view name) {
  for (const ConditionKind& k : condition_kinds()) {
    if (k.name == name) return &k;
  }
  return nullptr;
}

std::vector<std::string> kind_names(bool bare_only) {
  std::vector<std::string> names;
  for (const ConditionKind& k : condition_kinds()) {
    if (!bare_only || k.bare) names.emplace_back(k.name);
  }
  return names;
}

}  // namespace krug::boundary
