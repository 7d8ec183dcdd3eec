// VTK XML files readable by ParaView: an UnstructuredGrid (.vtu) of the active zones of every body and
// a PolyData (.vtp) of the free particles. Cell fields are per zone, point fields per node;
// coordinates (x, y, 0) or (z, r, 0). The point and cell data are the output field registry's
// (include/krug/solver/output_fields.hpp), in its order; every field, with its units, is listed in
// docs/outputs.md.
//
// Binary (the default): every array in the file's appended section, raw bytes compressed with zlib
// (vtkZLibDataCompressor: per array a UInt64 header of block count, block size, last block size and
// compressed sizes, then the blocks). ASCII: every array written in place as text.
#include <zlib.h>

#include <fmt/format.h>

#include <cstdint>
#include <cstring>
#include <numeric>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <variant>

#include "krug/core/error.hpp"
#include "krug/output/outputs.hpp"
#include "krug/solver/output_fields.hpp"

namespace krug::output {

namespace {

// The VTK name of a C++ element type.
template <class T>
constexpr const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  else if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  else if constexpr (std::is_same_v<T, std::uint8_t>) return "UInt8";
  else static_assert(sizeof(T) == 0, "no VTK type for this element");
}

class VtkDocument {
 public:
  VtkDocument(VtkEncoding encoding, const char* type) : encoding_(encoding) {
    xml_ << R"(<?xml version="1.0"?>)" << '\n'
         << fmt::format(R"(<VTKFile type="{}" version="1.0" byte_order="LittleEndian" header_type="UInt64"{}>)", type,
                        encoding == VtkEncoding::binary ? R"( compressor="vtkZLibDataCompressor")" : "")
         << '\n';
  }

  std::ostringstream& xml() { return xml_; }

  template <class T>
  void array(std::string_view name, int components, const std::vector<T>& values) {
    const char* type = vtk_type<T>();
    if (encoding_ == VtkEncoding::ascii) {
      xml_ << fmt::format(R"(        <DataArray type="{}" Name="{}" NumberOfComponents="{}" format="ascii">)", type, name,
                          components)
           << '\n';
      for (std::size_t i = 0; i < values.size(); ++i) {
        xml_ << (i % 6 == 0 ? "          " : " ");
        if constexpr (std::is_same_v<T, double>) {
          xml_ << fmt::format("{:.10g}", values[i]);
        } else {
          xml_ << static_cast<long long>(values[i]);
        }
        xml_ << (i % 6 == 5 ? "\n" : "");
      }
      xml_ << "\n        </DataArray>\n";
      return;
    }
    xml_ << fmt::format(R"(        <DataArray type="{}" Name="{}" NumberOfComponents="{}" format="appended" offset="{}"/>)",
                        type, name, components, appended_.size())
         << '\n';
    append_compressed(reinterpret_cast<const unsigned char*>(values.data()), values.size() * sizeof(T));
  }

  std::string finish(const char* closing) {
    xml_ << closing;
    if (encoding_ == VtkEncoding::binary) {
      xml_ << "  <AppendedData encoding=\"raw\">\n   _";
      xml_.write(appended_.data(), static_cast<std::streamsize>(appended_.size()));
      xml_ << "\n  </AppendedData>\n";
    }
    xml_ << "</VTKFile>\n";
    return xml_.str();
  }

 private:
  // One zlib block per array (none for an empty array).
  void append_compressed(const unsigned char* data, std::size_t bytes) {
    std::uint64_t header[4] = {bytes > 0 ? 1u : 0u, bytes, bytes, 0};
    std::string block;
    if (bytes > 0) {
      uLongf size = compressBound(static_cast<uLong>(bytes));
      block.resize(size);
      if (compress2(reinterpret_cast<Bytef*>(block.data()), &size, data, static_cast<uLong>(bytes), Z_BEST_SPEED) != Z_OK) {
        throw std::runtime_error("VTK output: zlib could not compress an array");
      }
      block.resize(size);
      header[3] = size;
    }
    appended_.append(reinterpret_cast<const char*>(header), (bytes > 0 ? 4 : 3) * sizeof(std::uint64_t));
    appended_.append(block);
  }

  VtkEncoding encoding_;
  std::ostringstream xml_;
  std::string appended_;
};

// Text safe inside an XML attribute.
std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// Data set (field) data, written as text in either encoding: the time (ParaView's TimeValue, s) and
// one one-value array per body whose name reads "body I: NAME (MATERIAL)" and whose value is I, the
// index the `body` arrays hold. ParaView lists them under the data set's field data.
void write_field_data(VtkDocument& vtk, const Simulation& simulation) {
  vtk.xml() << "    <FieldData>\n"
            << fmt::format(R"(      <DataArray type="Float64" Name="TimeValue" NumberOfTuples="1" format="ascii">{:.17g}</DataArray>)",
                           simulation.time())
            << '\n';
  const auto& bodies = simulation.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string name =
        fmt::format("body {}: {} ({})", i, bodies[i].name, simulation.materials()[bodies[i].material].name);
    vtk.xml() << fmt::format(R"(      <DataArray type="Int32" Name="{}" NumberOfTuples="1" format="ascii">{}</DataArray>)",
                             xml_escaped(name), i)
              << '\n';
  }
  vtk.xml() << "    </FieldData>\n";
}

// The registry's fields of one location (include/krug/solver/output_fields.hpp), in its order, over
// `items` (the nodes, active zones or particles written).
void write_fields(VtkDocument& vtk, const Simulation& simulation, OutputLocation location, std::span<const Index> items) {
  for (const OutputField& field : output_fields()) {
    if (field.location != location) continue;
    const OutputValues values = field.fill(simulation, items);
    std::visit(
        [&](const auto& v) {
          if (v.size() != items.size() * static_cast<std::size_t>(field.components)) {
            throw std::logic_error(fmt::format("VTK output: the field {} gave {} values for {} entries of {} components",
                                               field.name, v.size(), items.size(), field.components));
          }
          vtk.array(field.name_in(simulation.geometry()), field.components, v);
        },
        values);
  }
}

// 0, 1, ..., n - 1.
std::vector<Index> all(Index n) {
  std::vector<Index> items(static_cast<std::size_t>(n));
  std::iota(items.begin(), items.end(), Index{0});
  return items;
}

}  // namespace

void write_vtu(const Simulation& simulation, const std::filesystem::path& file, VtkEncoding encoding) {
  const Mesh& mesh = simulation.mesh();
  std::vector<Index> zones;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    if (mesh.zones.active[z]) zones.push_back(z);
  }
  std::vector<double> points;
  for (Index p = 0; p < mesh.nodes.size(); ++p) points.insert(points.end(), {mesh.nodes.x[p], mesh.nodes.y[p], 0.0});
  std::vector<std::int32_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  for (Index z : zones) {
    for (Index n : mesh.zones.corners[z]) connectivity.push_back(n);
    offsets.push_back(static_cast<std::int32_t>(connectivity.size()));
    types.push_back(9);  // VTK_QUAD
  }
  VtkDocument vtk(encoding, "UnstructuredGrid");
  vtk.xml() << "  <UnstructuredGrid>\n";
  write_field_data(vtk, simulation);
  vtk.xml() << fmt::format(R"(    <Piece NumberOfPoints="{}" NumberOfCells="{}">)", mesh.nodes.size(), zones.size()) << '\n'
            << "      <Points>\n";
  vtk.array("coordinates", 3, points);
  vtk.xml() << "      </Points>\n      <Cells>\n";
  vtk.array("connectivity", 1, connectivity);
  vtk.array("offsets", 1, offsets);
  vtk.array("types", 1, types);
  vtk.xml() << "      </Cells>\n      <PointData Vectors=\"velocity\">\n";
  write_fields(vtk, simulation, OutputLocation::node, all(mesh.nodes.size()));
  vtk.xml() << "      </PointData>\n      <CellData Scalars=\"density\">\n";
  write_fields(vtk, simulation, OutputLocation::zone, zones);
  write_text_atomically(file, vtk.finish("      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n"));
}

void write_vtp(const Simulation& simulation, const std::filesystem::path& file, VtkEncoding encoding) {
  const Particles& particles = simulation.particles();
  std::vector<double> points;
  std::vector<std::int32_t> connectivity, offsets;
  for (Index i = 0; i < particles.size(); ++i) {
    points.insert(points.end(), {particles.x[i], particles.y[i], 0.0});
    connectivity.push_back(i);
    offsets.push_back(i + 1);
  }
  VtkDocument vtk(encoding, "PolyData");
  vtk.xml() << "  <PolyData>\n";
  write_field_data(vtk, simulation);
  vtk.xml() << fmt::format(R"(    <Piece NumberOfPoints="{}" NumberOfVerts="{}" NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="0">)",
                           particles.size(), particles.size())
            << "\n      <Points>\n";
  vtk.array("coordinates", 3, points);
  vtk.xml() << "      </Points>\n      <Verts>\n";
  vtk.array("connectivity", 1, connectivity);
  vtk.array("offsets", 1, offsets);
  vtk.xml() << "      </Verts>\n      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  write_fields(vtk, simulation, OutputLocation::particle, all(particles.size()));
  write_text_atomically(file, vtk.finish("      </PointData>\n    </Piece>\n  </PolyData>\n"));
}

}  // namespace krug::output
