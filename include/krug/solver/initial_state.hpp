#pragma once
// What a run derives from its setup before the first step (docs/theory.md §2): zone geometry and
// masses, nodal masses, the EOS state, and the first step's stable length. Free functions that read
// what their const arguments name and write the others.
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/material/material.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/solver/body.hpp"
#include "krug/solver/controls.hpp"
#include "krug/solver/time_step.hpp"

namespace krug {

// Zone area, volume and mass (a zone without a density takes its material's reference density), its
// initial smallest altitude, its corner and subzone masses, and the nodal masses from the corner
// volumes: median-mesh corner areas in planar geometry (Caramana et al. 1998), the consistent lumped
// masses integral N_p r dA in RZ, so that the corner forces dV/dx_p accelerate axis nodes correctly.
// Reads the positions and zones.density; writes zones.density (where <= 0), area, volume, mass,
// initial_altitude, corner_mass, subzone_mass, nodes.mass and the per-DOF inverse masses
// nodes.inv_mass_x/y (1/M, 0 for a node without mass). Throws InputError on a zone of
// non-positive area or volume, naming the body.
void derive_masses(Mesh& mesh, const std::vector<Body>& bodies, const std::vector<Material>& materials,
                   GeometryKind geometry);

// Per node, the number of active zones that have it as a corner (a triangle's repeated corner once).
std::vector<Index> count_zones_per_node(const Mesh& mesh);

// The zone state a run starts from: `state` as the setup gave it (zones damaged or stressed from the
// start), or, when empty, every group sized to the mesh's zones at its registry's fill values (intact,
// unstressed); then the pressure and wave speed from evaluate_initial_eos. Reads zones.density and
// specific_energy. Throws InputError when a given field does not have the mesh's zone count.
void initialise_zone_state(ZoneState& state, const ZoneFields& zones, const std::vector<Body>& bodies,
                           const std::vector<Material>& materials);
// Pressure and wave speed from each body's EOS at its zones' initial density and energy. Reads
// zones.density and specific_energy; writes pressure and sound_speed. Throws InputError on a
// non-finite state, naming the body.
void evaluate_initial_eos(const ZoneFields& zones, HydroZoneFields& hydro, const std::vector<Body>& bodies,
                          const std::vector<Material>& materials);

// The stable step of the first cycle: per active zone, the CFL number of its body times its stable
// length over its stress-wave speed plus twice the spread of its corner velocities (a zone must not
// invert in the first step even where the initial state sets no wave speed: a cold gas under a piston).
StableStep first_stable_time_step(const Mesh& mesh, const HydroZoneFields& hydro, const std::vector<Body>& bodies,
                                  const std::vector<Material>& materials, const Controls& controls);

}  // namespace krug
