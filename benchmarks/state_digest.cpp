// Digest of the state after a fixed number of cycles, to check that a change to the time step leaves
// results bitwise identical (docs/performance.md). Not a benchmark: prints, per problem, a 64-bit
// FNV-1a hash of every node, zone and particle field and of the ledger after the cycles, and with
// `--dump DIR` writes the same values as raw doubles to DIR/<problem>.bin for a comparison of two
// builds (scripts/compare_state_dumps.py).
//
//   build-bench/benchmarks/state_digest EXAMPLES_DIR [--dump DIR]
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "krug/scenario/scenario.hpp"
#include "krug/solver/simulation.hpp"
#include "problems.hpp"

namespace {

using krug::Simulation;
using krug::SimulationSetup;

struct Problem {
  std::string name;
  std::function<SimulationSetup()> setup;
  long cycles;
};

void append(std::vector<double>& out, const std::vector<double>& field) {
  out.insert(out.end(), field.begin(), field.end());
}

template <class Integer>
void append_integers(std::vector<double>& out, const std::vector<Integer>& field) {
  for (const Integer v : field) out.push_back(static_cast<double>(v));
}

std::vector<double> state_values(const Simulation& sim) {
  std::vector<double> out;
  const krug::NodeFields& n = sim.mesh().nodes;
  const krug::ZoneFields& z = sim.mesh().zones;
  const krug::HydroZoneFields& h = sim.zone_state().hydro;
  const krug::StrengthZoneFields& s = sim.zone_state().strength;
  const krug::HourglassZoneFields& q = sim.zone_state().hourglass;
  for (const auto* f : {&n.x, &n.y, &n.u, &n.v, &n.mass}) append(out, *f);
  for (const auto* f : {&z.density, &z.specific_energy, &h.pressure, &h.sound_speed, &z.volume, &s.deviator_xx,
                        &s.deviator_yy, &s.deviator_xy, &s.deviator_zz, &s.plastic_strain, &q.hourglass_x,
                        &q.hourglass_y, &h.corner_force, &h.viscous_speed}) {
    append(out, *f);
  }
  append_integers(out, z.active);
  append_integers(out, sim.zone_state().fracture.damaged);
  const krug::Particles& p = sim.particles();
  for (const auto* f : {&p.x, &p.y, &p.u, &p.v, &p.mass}) append(out, *f);
  const krug::EnergyLedger& e = sim.ledger().energy;
  for (double v : {e.kinetic, e.internal, e.plastic, e.viscous, e.hourglass, e.contact, e.overlap, e.converted,
                   e.boundary, sim.ledger().axial_momentum, sim.ledger().mass, sim.time()}) {
    out.push_back(v);
  }
  out.push_back(static_cast<double>(sim.cycle()));
  return out;
}

std::uint64_t fnv1a(const std::vector<double>& values) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const double v : values) {
    unsigned char bytes[sizeof(double)];
    std::memcpy(bytes, &v, sizeof v);
    for (const unsigned char b : bytes) hash = (hash ^ b) * 1099511628211ull;
  }
  return hash;
}

SimulationSetup from_file(const std::string& file) { return krug::scenario::load_scenario(file).setup; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: state_digest EXAMPLES_DIR [--dump DIR]\n");
    return 2;
  }
  const std::string examples = argv[1];
  const std::string dump = argc >= 4 && std::string(argv[2]) == "--dump" ? argv[3] : "";
  namespace problems = krug::problems;
  const std::vector<Problem> list = {
      {"sod_planar_100x25", [] { return problems::sod_strip(100, 25); }, 300},
      {"sedov_planar_50x50", [] { return problems::sedov_planar(50); }, 300},
      {"sedov_rz_50x50", [] { return problems::sedov_axisymmetric(50); }, 300},
      {"copper_rz_50x50", [] { return problems::copper_cylinder_rz(50); }, 300},
      {"taylor_bar", [&] { return from_file(examples + "/verification/taylor_bar.json"); }, 600},
      {"striker_dishing", [&] { return from_file(examples + "/contact/striker_dishing.json"); }, 600},
      {"bullet_rigid_wall", [&] { return from_file(examples + "/contact/bullet_rigid_wall.json"); }, 600},
      {"fracture_high_velocity", [&] { return from_file(examples + "/fracture/high_velocity.json"); }, 4000},
      // Boundary conditions: a velocity piston with slip walls, a skewed piston with symmetry sides, an
      // RZ sector with a symmetry side and the axis, and fixed rims with contact.
      {"piston_velocity", [&] { return from_file(examples + "/verification/piston.json"); }, 400},
      {"saltzman", [&] { return from_file(examples + "/verification/saltzman.json"); }, 400},
      {"noh_spherical", [&] { return from_file(examples + "/verification/noh_spherical.json"); }, 300},
      {"paper_spaced_fixed_rims", [&] { return from_file(examples + "/paper/coarse/spaced_3x1mm_2.6g_z5.json"); }, 600},
  };
  int status = 0;
  for (const Problem& problem : list) {
    try {
      Simulation sim(problem.setup());
      for (long k = 0; k < problem.cycles && !sim.finished(); ++k) sim.step();
      const std::vector<double> values = state_values(sim);
      long damaged = 0;
      for (const std::uint8_t d : sim.zone_state().fracture.damaged) damaged += d;
      std::printf("%-24s cycle %6ld  damaged zones %5ld  particles %5ld  %016llx\n", problem.name.c_str(),
                  sim.cycle(), damaged, static_cast<long>(sim.particles().size()),
                  static_cast<unsigned long long>(fnv1a(values)));
      if (!dump.empty()) {
        std::ofstream out(dump + "/" + problem.name + ".bin", std::ios::binary);
        out.write(reinterpret_cast<const char*>(values.data()),
                  static_cast<std::streamsize>(values.size() * sizeof(double)));
      }
    } catch (const std::exception& e) {
      std::printf("%-24s failed: %s\n", problem.name.c_str(), e.what());
      status = 1;
    }
  }
  return status;
}
