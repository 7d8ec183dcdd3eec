#pragma once
// Reading the bodies of a scenario (private to the io library) into their descriptions
// (setup/scene.hpp): meshes (graded axes, generator parameters, position maps), boundary conditions
// on named sides, and initial fields. Nothing is built here. Used by scenario.cpp's
// parse_scenario; every error names the JSON path, as in the rest of the reader.
#include <map>
#include <string>
#include <vector>

#include "json_reader.hpp"
#include "krug/core/geometry_kind.hpp"
#include "krug/setup/scene.hpp"

namespace krug::scenario::detail {

struct AxisNames {
  std::string first, second;
};

inline AxisNames axis_names(GeometryKind g) {
  return {std::string(axis_name(g, 0)), std::string(axis_name(g, 1))};
}

// allow_radian_angles: the scenario allows sector angles that look like radians ("allow_unusual").
setup::MeshDescription read_mesh(JsonObject spec, GeometryKind geometry, bool allow_radian_angles);
std::vector<setup::SideBoundary> read_boundary(JsonObject spec, const setup::MeshDescription& mesh, GeometryKind geometry);
setup::InitialState read_initial(JsonObject spec, GeometryKind geometry);

}  // namespace krug::scenario::detail
