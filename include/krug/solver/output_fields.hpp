#pragma once
// The output field registry: every array the snapshots show (VTK point and cell data of the bodies,
// point data of the free particles), once, with its name, its components per entry, where it lives
// and the function that fills its values from the state. It knows no file format: the VTU and VTP
// writers (src/output/vtk.cpp) walk it in this order, so a new output field is one entry here plus its
// row in docs/outputs.md (docs/architecture.md, "Adding an output field").
#include <cstdint>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/mesh/mesh.hpp"

namespace krug {

class Simulation;

// Where an output field lives: per node and per active zone of the bodies (the .vtu's point and cell
// data), or per free particle (the .vtp's point data).
enum class OutputLocation : std::uint8_t { node, zone, particle };

// The values of one output field, entry after entry with their components interleaved; the element
// type is the file's (Float64, Int32, UInt8 in VTK).
using OutputValues = std::variant<std::vector<double>, std::vector<std::int32_t>, std::vector<std::uint8_t>>;

struct OutputField {
  std::string_view name;               // the array's name
  std::string_view axisymmetric_name;  // its name in axisymmetric geometry when that differs; empty otherwise
  int components;                      // values per entry
  OutputLocation location;
  // The values for `items` (node, active-zone or particle indices, in the file's order):
  // items.size() * components of them.
  OutputValues (*fill)(const Simulation& simulation, std::span<const Index> items);

  std::string_view name_in(GeometryKind geometry) const {
    return geometry == GeometryKind::axisymmetric && !axisymmetric_name.empty() ? axisymmetric_name : name;
  }
};

// Every output field, nodes first, then zones, then particles; within a location in the files' order.
std::span<const OutputField> output_fields();

}  // namespace krug
