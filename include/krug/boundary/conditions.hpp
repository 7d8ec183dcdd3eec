#pragma once
// The condition kinds a side of a body may carry, in one registry: each kind's name (as scenario files
// write it), whether it holds velocity components or loads the face, and the function that applies it
// to a built side. The scenario reader offers the registry's names, the scene builder applies a side's
// condition through its entry; a new kind is one entry here (and its parameters in the reader and
// docs/scenario-format.md).
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "krug/boundary/boundary.hpp"

namespace krug::boundary {

enum class Kind : std::uint8_t {
  free,      // no condition
  symmetry,  // the normal velocity held at zero (the side must be a straight line along an axis)
  slip,      // the same as symmetry, for a rigid wall the body slides on
  fixed,     // both components held at zero
  velocity,  // the given components held at the given values or functions of time (an empty one stays free)
  pressure,  // a pressure p(t) on the face (and optionally a traction)
  traction   // a tangential traction tau(t) on the face (and optionally a pressure)
};

// A side's condition with its parameters.
struct Condition {
  Kind kind = Kind::free;
  std::array<std::optional<double>, 2> velocity;  // velocity: constant components (m/s)
  std::array<TimeFunction, 2> velocity_of_time;   // velocity: a component as a function of t (then velocity[k] is not used)
  TimeFunction pressure, traction;                // pressure, traction: Pa as functions of t (empty: 0)
};

// A built side of one body: its nodes (in the generator's order) and its boundary faces.
struct Side {
  std::string name;
  std::string body_name;
  std::string where;  // how errors name the side, e.g. "bodies[0].boundary.x_min"
  std::vector<Index> nodes;
  std::vector<BoundarySegment> segments;
};

// What applying a condition produces: held components (recorded by `hold`, with the condition that
// holds them), components driven by functions of time, and face loads.
struct Target {
  std::function<void(Index node, bool fix_x, bool fix_y)> hold;
  std::vector<DrivenComponent> driven;
  std::vector<FaceLoad> loads;
};

struct ConditionKind {
  Kind kind;
  std::string_view name;
  bool bare;   // may be written as the bare name ("slip") as well as {"type": "slip", ...}
  bool holds;  // holds velocity components
  bool loads;  // loads the face
  // Applies the condition to the side: holds components (setting the held velocities of `nodes`),
  // records driven components and loads. Throws InputError naming side.where.
  void (*apply)(const Condition& condition, const Side& side, GeometryKind geometry, NodeFields& nodes, Target& target);
};

// Every kind, in the order of Kind.
const std::vector<ConditionKind>& condition_kinds();
const ConditionKind& kind_of(Kind kind);
// The kind of that name, or nullptr.
const ConditionKind* find_kind(std::string_view name);
// The names of the kinds, all or only those that may be written bare.
std::vector<std::string> kind_names(bool bare_only = false);

}  // namespace krug::boundary
