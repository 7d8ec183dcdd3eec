#pragma once
// The step's calls into the hydro kernels, one body at a time (docs/theory.md §2 steps 1 and 5): the
// kernels' compile-time variant (geometry and viscosity model; equation of state and strength model)
// is chosen once per body, outside the zone loops; the body's blocks of zones share the threads and
// their results are taken in block order (parallel.hpp), so the bits do not depend on the threads.
// Each function reads what its const arguments name and writes what the others name, nothing else.
#include <algorithm>
#include <cmath>
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/hydro/zone_forces.hpp"
#include "krug/hydro/zone_update.hpp"
#include "krug/material/material.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/solver/body.hpp"
#include "krug/solver/controls.hpp"

namespace krug {

// A zone's pressure and stress-wave speed (bulk, plus 4 mu / 3 rho with a shear modulus mu) from the
// EOS at its density and specific energy. Reads zones.density and specific_energy of zone z; writes its
// hydro.pressure and sound_speed.
template <class Eos>
void evaluate_eos(const Eos& eos, double mu, const ZoneFields& zones, HydroZoneFields& hydro, Index z) {
  const double rho = zones.density[z], e = zones.specific_energy[z];
  hydro.pressure[z] = eos.pressure(rho, e);
  hydro.sound_speed[z] = std::sqrt(std::max(eos.sound_speed_squared(rho, e, hydro.pressure[z]) + 4.0 * mu / (3.0 * rho), 0.0));
}

// The CFL number of a body of this material: controls.cfl_fluid without strength, controls.cfl with it.
double cfl_number(const Material& material, const Controls& controls);

// Whether some body of `bodies` takes this viscosity model (body_viscosity).
bool some_body_takes(ViscosityModel model, const std::vector<Body>& bodies, const std::vector<Material>& materials,
                     const Controls& controls, GeometryKind geometry);

// The force kernel's parameters for a body of this material, its viscosity model and corner-collapse
// pressure resolved (body_viscosity) for a body of this geometry; `previous_time_step` is dt^{n-1/2}.
ZoneForceParams zone_force_params(const Material& material, const Controls& controls, GeometryKind geometry,
                                  double previous_time_step);

// Step 1 on the body's zones (compute_corner_forces): reads the mesh's positions, velocities at
// t^{n-1/2} and zones, and the zones' pressure, sound speed, stress and damage; writes their corner
// forces and viscous speeds (`state.hydro`) and hourglass state (`state.hourglass`), the limiters of
// `limiters`, the work corrections of `area_weighted` and, with the tensor viscosity, the damping rows
// (4 per zone, where `damping.rows` is not null). Returns the artificial powers, the blocks' added in
// block order.
ArtificialPower body_corner_forces(const Mesh& mesh, ZoneState& state, const Body& body, GeometryKind geometry,
                                   const ZoneForceParams& params, int threads, AreaWeightedArrays area_weighted,
                                   SharedEdgeLimiters limiters, DampingRows damping);

// Step 5 on the body's zones (update_zones with the material's EOS and strength model): reads the
// positions at t^{n+1}, the velocities, the corner forces and `work_correction` (8 per zone, the
// area-weighted RZ form only, else null); writes the zones' geometry, density and energy, `state.hydro`
// and `state.strength` (update_zones). One result per block, in block order.
std::vector<ZoneUpdateResult> body_zone_update(Mesh& mesh, ZoneState& state, const Body& body, GeometryKind geometry,
                                               const Material& material, const ZoneUpdateParams& params, int threads,
                                               const double* work_correction);

// The area-weighted RZ form's per-node arrays at the current positions: `scale` s_p = M_p / M^A_p, with
// Wilkins' area mass M^A_p = sum over the node's active zones of rho_z A_z / 4, and `booking`, the
// weight of the node's viscous and hourglass work (s_p; 0 on the axis). Reads the mesh; writes both.
void area_weighted_scale(const Mesh& mesh, const std::vector<Body>& bodies, std::vector<double>& scale,
                         std::vector<double>& booking);

}  // namespace krug
