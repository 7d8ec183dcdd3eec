// VTK XML UnstructuredGrid (.vtu) of the active zones of every body, readable by ParaView.
// Cell fields are per zone, point fields per node; coordinates (x, y, 0) or (z, r, 0).
#include <fmt/format.h>

#include <sstream>

#include "krug/io/outputs.hpp"

namespace krug::io {

namespace {

template <class Value>
void data_array(std::ostringstream& out, const char* type, const char* name, int components,
                const std::vector<Value>& values) {
  out << fmt::format(R"(        <DataArray type="{}" Name="{}" NumberOfComponents="{}" format="ascii">)", type, name,
                     components)
      << '\n';
  for (std::size_t i = 0; i < values.size(); ++i) {
    out << (i % 6 == 0 ? "          " : " ") << fmt::format("{}", values[i]) << (i % 6 == 5 ? "\n" : "");
  }
  out << "\n        </DataArray>\n";
}

}  // namespace

void write_vtu(const Simulation& simulation, const std::filesystem::path& file) {
  const Mesh& mesh = simulation.mesh();
  std::vector<Index> zones;
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    if (mesh.zones.active[z]) zones.push_back(z);
  }
  std::vector<double> points, velocity;
  std::vector<Index> node_body;
  for (Index p = 0; p < mesh.nodes.size(); ++p) {
    points.insert(points.end(), {mesh.nodes.x[p], mesh.nodes.y[p], 0.0});
    velocity.insert(velocity.end(), {mesh.nodes.u[p], mesh.nodes.v[p], 0.0});
    node_body.push_back(mesh.nodes.body[p]);
  }
  std::vector<Index> connectivity, offsets, body;
  std::vector<int> types;
  std::vector<double> density, pressure, energy, sound_speed, deviator, plastic_strain, damage_time;
  std::vector<int> damaged, criterion;
  for (Index z : zones) {
    for (Index n : mesh.zones.corners[z]) connectivity.push_back(n);
    offsets.push_back(static_cast<Index>(connectivity.size()));
    types.push_back(9);  // VTK_QUAD
    body.push_back(mesh.zones.body[z]);
    density.push_back(mesh.zones.density[z]);
    pressure.push_back(mesh.zones.pressure[z]);
    energy.push_back(mesh.zones.specific_energy[z]);
    sound_speed.push_back(mesh.zones.sound_speed[z]);
    deviator.insert(deviator.end(), {mesh.zones.deviator_xx[z], mesh.zones.deviator_yy[z],
                                     mesh.zones.deviator_xy[z], mesh.zones.deviator_zz[z]});
    plastic_strain.push_back(mesh.zones.plastic_strain[z]);
    damaged.push_back(mesh.zones.damaged[z]);
    damage_time.push_back(mesh.zones.damage_time[z]);
    criterion.push_back(mesh.zones.damage_criterion[z]);
  }
  std::ostringstream out;
  out.precision(10);
  out << R"(<?xml version="1.0"?>)" << '\n'
      << R"(<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">)" << '\n'
      << "  <UnstructuredGrid>\n"
      << fmt::format(R"(    <Piece NumberOfPoints="{}" NumberOfCells="{}">)", mesh.nodes.size(), zones.size()) << '\n'
      << "      <Points>\n";
  data_array(out, "Float64", "coordinates", 3, points);
  out << "      </Points>\n      <Cells>\n";
  data_array(out, "Int32", "connectivity", 1, connectivity);
  data_array(out, "Int32", "offsets", 1, offsets);
  data_array(out, "UInt8", "types", 1, types);
  out << "      </Cells>\n      <PointData Vectors=\"velocity\">\n";
  data_array(out, "Float64", "velocity", 3, velocity);
  data_array(out, "Int32", "body", 1, node_body);
  out << "      </PointData>\n      <CellData Scalars=\"density\">\n";
  data_array(out, "Int32", "body", 1, body);
  data_array(out, "Float64", "density", 1, density);
  data_array(out, "Float64", "pressure", 1, pressure);
  data_array(out, "Float64", "specific_internal_energy", 1, energy);
  data_array(out, "Float64", "sound_speed", 1, sound_speed);
  data_array(out, "Float64", "deviatoric_stress_xx_yy_xy_zz", 4, deviator);
  data_array(out, "Float64", "equivalent_plastic_strain", 1, plastic_strain);
  data_array(out, "UInt8", "damaged", 1, damaged);
  data_array(out, "Float64", "damage_onset_time", 1, damage_time);
  data_array(out, "UInt8", "damage_criterion", 1, criterion);
  out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  write_text_atomically(file, out.str());
}

void write_vtp(const Simulation& simulation, const std::filesystem::path& file) {
  const Particles& particles = simulation.particles();
  std::vector<double> points, velocity;
  std::vector<Index> connectivity, offsets;
  for (Index i = 0; i < particles.size(); ++i) {
    points.insert(points.end(), {particles.x[i], particles.y[i], 0.0});
    velocity.insert(velocity.end(), {particles.u[i], particles.v[i], 0.0});
    connectivity.push_back(i);
    offsets.push_back(i + 1);
  }
  std::ostringstream out;
  out.precision(10);
  out << R"(<?xml version="1.0"?>)" << '\n'
      << R"(<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">)" << '\n'
      << "  <PolyData>\n"
      << fmt::format(R"(    <Piece NumberOfPoints="{}" NumberOfVerts="{}" NumberOfLines="0" NumberOfStrips="0" NumberOfPolys="0">)",
                     particles.size(), particles.size())
      << "\n      <Points>\n";
  data_array(out, "Float64", "coordinates", 3, points);
  out << "      </Points>\n      <Verts>\n";
  data_array(out, "Int32", "connectivity", 1, connectivity);
  data_array(out, "Int32", "offsets", 1, offsets);
  out << "      </Verts>\n      <PointData Scalars=\"radius\" Vectors=\"velocity\">\n";
  data_array(out, "Float64", "velocity", 3, velocity);
  data_array(out, "Float64", "radius", 1, particles.radius);
  data_array(out, "Float64", "mass", 1, particles.mass);
  data_array(out, "Int32", "body", 1, particles.body);
  data_array(out, "Float64", "birth_time", 1, particles.birth_time);
  out << "      </PointData>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  write_text_atomically(file, out.str());
}

}  // namespace krug::io
