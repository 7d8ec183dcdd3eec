// Consumer of an installed Krug: builds a planar gas strip of 4 x 1 zones through the public API,
// runs a few cycles and checks the two invariants every run must keep (docs/theory.md §3):
// total energy to round-off and mass exactly. Exit status 0 on success.
#include <cmath>
#include <cstdio>

#include <krug/material/material.hpp>
#include <krug/mesh/generators.hpp>
#include <krug/solver/simulation.hpp>

namespace {

// Kinetic plus internal energy straight from the mesh fields (per unit thickness), independent of the
// library's ledger: velocities and masses of the nodes, specific energies and masses of the zones.
double mesh_energy(const krug::Mesh& mesh) {
  double energy = 0.0;
  for (krug::Index p = 0; p < mesh.nodes.size(); ++p) {
    energy += 0.5 * mesh.nodes.mass[p] * (mesh.nodes.u[p] * mesh.nodes.u[p] + mesh.nodes.v[p] * mesh.nodes.v[p]);
  }
  for (krug::Index z = 0; z < mesh.zones.size(); ++z) energy += mesh.zones.mass[z] * mesh.zones.specific_energy[z];
  return energy;
}

}  // namespace

int main() {
  using namespace krug;
  constexpr double gamma = 1.4;

  SimulationSetup setup;
  setup.geometry = GeometryKind::planar;
  const generate::Patch patch = generate::rectangle(setup.mesh, generate::graded_axis(0.0, {{1.0, 4, 1.0}}),
                                                    generate::graded_axis(0.0, {{0.25, 1, 1.0}}), /*body*/ 0);
  setup.materials.push_back(Material{"gas", 1.0, IdealGas{gamma}});
  setup.bodies.push_back({"gas", 0, patch.node_begin, patch.node_end, patch.zone_begin, patch.zone_end});
  // A small shock tube: (rho, p) = (1, 1) in the left half, (0.125, 0.1) in the right half.
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) {
    const bool left = z - patch.zone_begin < 2;
    const double rho = left ? 1.0 : 0.125, p = left ? 1.0 : 0.1;
    setup.mesh.zones.density[z] = rho;
    setup.mesh.zones.specific_energy[z] = p / ((gamma - 1.0) * rho);
  }
  // Rigid walls all round: held velocity components stay zero, so no boundary work.
  for (const Index node : patch.sides.at("i_min")) setup.constraints.push_back({node, true, false});
  for (const Index node : patch.sides.at("i_max")) setup.constraints.push_back({node, true, false});
  for (const Index node : patch.sides.at("j_min")) setup.constraints.push_back({node, false, true});
  for (const Index node : patch.sides.at("j_max")) setup.constraints.push_back({node, false, true});
  setup.controls.end_time = 10.0;  // longer than the cycles run: dt ~ 0.1 on these 0.25 m zones

  Simulation sim(std::move(setup));
  const double initial_mass = sim.summarise(sim.bodies().front()).mass;
  const double initial_energy = mesh_energy(sim.mesh());
  const int cycles = 10;
  for (int k = 0; k < cycles && !sim.finished(); ++k) sim.step();

  // Rigid walls do no work, so K + IE itself is conserved (K at the half step, docs/theory.md §2).
  const double drift = sim.ledger().relative_energy_drift();
  const double mesh_drift = std::abs(mesh_energy(sim.mesh()) - initial_energy) / initial_energy;
  const double mass = sim.summarise(sim.bodies().front()).mass;
  double kinetic = 0.0;
  for (Index p = 0; p < sim.mesh().nodes.size(); ++p) kinetic += sim.mesh().nodes.u[p] * sim.mesh().nodes.u[p];
  std::printf("krug consumer: %ld cycles to t = %.4e, energy drift %.3e (ledger) %.3e (mesh), mass %.17g -> %.17g\n",
              sim.cycle(), sim.time(), drift, mesh_drift, initial_mass, mass);
  if (sim.cycle() < cycles || !(kinetic > 0.0)) {
    std::fprintf(stderr, "expected %d cycles of a moving gas\n", cycles);
    return 1;
  }
  if (!(drift <= 1e-12) || !(mesh_drift <= 1e-12)) {
    std::fprintf(stderr, "energy drift exceeds 1e-12\n");
    return 1;
  }
  if (mass != initial_mass || sim.ledger().relative_mass_error() != 0.0) {
    std::fprintf(stderr, "mass changed\n");
    return 1;
  }
  return 0;
}
