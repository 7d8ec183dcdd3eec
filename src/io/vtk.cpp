// VTK XML files readable by ParaView: an UnstructuredGrid (.vtu) of the active zones of every body and
// a PolyData (.vtp) of the free particles. Cell fields are per zone, point fields per node;
// coordinates (x, y, 0) or (z, r, 0). Every field, with its units, is listed in docs/outputs.md.
//
// Binary (the default): every array in the file's appended section, raw bytes compressed with zlib
// (vtkZLibDataCompressor: per array a UInt64 header of block count, block size, last block size and
// compressed sizes, then the blocks). ASCII: every array written in place as text.
#include <zlib.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "krug/core/error.hpp"
#include "krug/io/outputs.hpp"

namespace krug::io {

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
  void array(const char* name, int components, const std::vector<T>& values) {
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

// The deviator's components named by the scenario's axes: (xx, yy, xy, zz) planar, with zz the
// out-of-plane component; (zz, rr, zr, tt) axisymmetric, with tt the hoop component.
std::array<std::string, 4> deviator_names(GeometryKind geometry) {
  if (geometry == GeometryKind::axisymmetric) {
    return {"deviatoric_stress_zz", "deviatoric_stress_rr", "deviatoric_stress_zr", "deviatoric_stress_tt"};
  }
  return {"deviatoric_stress_xx", "deviatoric_stress_yy", "deviatoric_stress_xy", "deviatoric_stress_zz"};
}

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

}  // namespace

void write_vtu(const Simulation& simulation, const std::filesystem::path& file, VtkEncoding encoding) {
  const Mesh& mesh = simulation.mesh();
  std::vector<Index> zones;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    if (mesh.zones.active[z]) zones.push_back(z);
  }
  std::vector<double> points, velocity;
  std::vector<std::int32_t> node_body;
  for (Index p = 0; p < mesh.nodes.size(); ++p) {
    points.insert(points.end(), {mesh.nodes.x[p], mesh.nodes.y[p], 0.0});
    velocity.insert(velocity.end(), {mesh.nodes.u[p], mesh.nodes.v[p], 0.0});
    node_body.push_back(mesh.nodes.body[p]);
  }
  std::vector<std::int32_t> connectivity, offsets, body;
  std::vector<std::uint8_t> types, damaged, criterion;
  std::vector<double> density, pressure, energy, sound_speed, von_mises, plastic_strain, damage_time, damage, time_step;
  std::array<std::vector<double>, 4> deviator;
  for (Index z : zones) {
    for (Index n : mesh.zones.corners[z]) connectivity.push_back(n);
    offsets.push_back(static_cast<std::int32_t>(connectivity.size()));
    types.push_back(9);  // VTK_QUAD
    body.push_back(mesh.zones.body[z]);
    density.push_back(mesh.zones.density[z]);
    pressure.push_back(mesh.zones.pressure[z]);
    energy.push_back(mesh.zones.specific_energy[z]);
    sound_speed.push_back(mesh.zones.sound_speed[z]);
    const double sxx = mesh.zones.deviator_xx[z], syy = mesh.zones.deviator_yy[z], sxy = mesh.zones.deviator_xy[z],
                 szz = mesh.zones.deviator_zz[z];
    deviator[0].push_back(sxx);
    deviator[1].push_back(syy);
    deviator[2].push_back(sxy);
    deviator[3].push_back(szz);
    // sigma_vm = sqrt(3 J2), J2 = s:s / 2 with the shear component counted twice.
    von_mises.push_back(std::sqrt(1.5 * (sxx * sxx + syy * syy + szz * szz + 2.0 * sxy * sxy)));
    plastic_strain.push_back(mesh.zones.plastic_strain[z]);
    damaged.push_back(mesh.zones.damaged[z]);
    damage_time.push_back(mesh.zones.damage_time[z]);
    criterion.push_back(mesh.zones.damage_criterion[z]);
    damage.push_back(mesh.zones.damage[z]);
    time_step.push_back(mesh.zones.stable_time_step[z]);
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
  vtk.array("velocity", 3, velocity);
  vtk.array("body", 1, node_body);
  vtk.xml() << "      </PointData>\n      <CellData Scalars=\"density\">\n";
  vtk.array("body", 1, body);
  vtk.array("density", 1, density);
  vtk.array("pressure", 1, pressure);
  vtk.array("specific_internal_energy", 1, energy);
  vtk.array("sound_speed", 1, sound_speed);
  const auto names = deviator_names(simulation.geometry());
  for (int k = 0; k < 4; ++k) vtk.array(names[static_cast<std::size_t>(k)].c_str(), 1, deviator[static_cast<std::size_t>(k)]);
  vtk.array("von_mises_stress", 1, von_mises);
  vtk.array("equivalent_plastic_strain", 1, plastic_strain);
  vtk.array("damaged", 1, damaged);
  vtk.array("damage_onset_time", 1, damage_time);
  vtk.array("damage_criterion", 1, criterion);
  vtk.array("damage", 1, damage);
  vtk.array("stable_time_step", 1, time_step);
  write_text_atomically(file, vtk.finish("      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n"));
}

void write_vtp(const Simulation& simulation, const std::filesystem::path& file, VtkEncoding encoding) {
  const Particles& particles = simulation.particles();
  std::vector<double> points, velocity;
  std::vector<std::int32_t> connectivity, offsets, body;
  for (Index i = 0; i < particles.size(); ++i) {
    points.insert(points.end(), {particles.x[i], particles.y[i], 0.0});
    velocity.insert(velocity.end(), {particles.u[i], particles.v[i], 0.0});
    connectivity.push_back(i);
    offsets.push_back(i + 1);
    body.push_back(particles.body[i]);
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
  vtk.array("velocity", 3, velocity);
  vtk.array("radius", 1, particles.radius);
  vtk.array("mass", 1, particles.mass);
  vtk.array("body", 1, body);
  vtk.array("birth_time", 1, particles.birth_time);
  write_text_atomically(file, vtk.finish("      </PointData>\n    </Piece>\n  </PolyData>\n"));
}

}  // namespace krug::io
