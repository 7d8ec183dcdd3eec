#pragma once
// Reading the bodies of a scenario (private to the io library): meshes (graded axes, generators,
// position maps), boundary conditions on named sides, and initial fields. Used by scenario.cpp's
// parse_scenario; every error names the JSON path, as in the rest of the reader.
#include <map>
#include <string>
#include <vector>

#include "json_reader.hpp"
#include "krug/core/geometry_kind.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::io::detail {

inline constexpr long max_zones = 20'000'000;  // about 10 GB of state: beyond this the machine runs out

struct AxisNames {
  std::string first, second;
};

inline AxisNames axis_names(GeometryKind g) {
  return {std::string(axis_name(g, 0)), std::string(axis_name(g, 1))};
}

// A body's generated patch and its sides by the names a scenario uses.
struct MeshedBody {
  generate::Patch patch;
  std::map<std::string, std::string> side_names;  // user side name -> generator side name
};

MeshedBody read_mesh(JsonObject spec, Mesh& mesh, Index body, GeometryKind geometry);
void read_boundary(JsonObject spec, const MeshedBody& meshed, const std::string& body_name, GeometryKind geometry,
                   Mesh& mesh, std::map<Index, NodeConstraint>& constraints);
void read_initial(JsonObject spec, const Body& body, GeometryKind geometry, Mesh& mesh);

}  // namespace krug::io::detail
