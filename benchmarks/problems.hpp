#pragma once
// Standard gas-dynamics problems built through the public API, for the benchmarks (and for tests that
// want the same set-ups). Header-only, no test or benchmark framework. The problems are dimensionless
// (rho ~ 1, lengths ~ 1) as in the literature they come from.
//
//   sod_strip          Sod (1978) shock tube on a planar 2D strip [0, 1] x [0, width]: left state
//                      rho = 1, p = 1; right state rho = 0.125, p = 0.1; gamma = 1.4; interface at
//                      x = 0.5; rigid walls all round; end time 0.2.
//   sedov_planar       Cylindrical Sedov blast on the planar XY quarter [0, 1.2]^2: gamma = 1.4,
//                      rho = 1, E = 0.311357 per unit length (shock radius 1 at t = 1; Kamm & Timmes
//                      2007), E/4 deposited as internal energy in the zone at the origin corner;
//                      slip planes x = 0 and y = 0 (and the outer sides, which the shock does not
//                      reach by t = 1); end time 1.
//   sedov_axisymmetric Spherical Sedov blast on the RZ quarter [0, 1.2]^2 (z first, r second):
//                      E = 0.851072 (shock radius 1 at t = 1), the half space z >= 0 per radian gets
//                      E / (4 pi) in the zone at the origin; the axis r = 0 is held by the solver,
//                      slip plane z = 0 (and the outer sides); end time 1.
//   noh_axisymmetric   Spherical Noh (1987) implosion on the RZ quarter [0, 1]^2: gamma = 5/3, rho = 1,
//                      e = 0, every node moving at speed 1 towards the origin; the axis r = 0 is held by
//                      the solver, slip plane z = 0, the outer sides free (the benchmarks take early
//                      cycles, when every zone ahead of the shock is compressing); end time 0.6.
//   copper_cylinder_rz Elastic-plastic impact (SI units): a copper cylinder, length = radius = 10 mm,
//                      in RZ, Mie-Grueneisen EOS (c0 3940 m/s, s 1.49, Gamma0 2.0, rho0 8930) and
//                      Prandtl-Reuss plasticity with linear hardening (mu 43.3 GPa, Y0 400 MPa,
//                      H 100 MPa), moving at 300 m/s onto a slip plane at z = 0 (the impact face's
//                      nodes are held axially from t = 0); no contact; end time 20 us.
//
// Zones are square in every problem. The background specific energy of the Sedov problems is a tiny
// positive value (1e-12 of the blast zone's) instead of 0, so that every zone has a defined sound
// speed; it changes nothing at the scale of the solution.
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "krug/material/material.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::problems {

namespace detail {

inline void hold_side(SimulationSetup& setup, const generate::Patch& patch, const std::string& side, bool fix_x,
                      bool fix_y) {
  for (const Index node : patch.sides.at(side)) setup.constraints.push_back({node, fix_x, fix_y});
}

// One ideal-gas body covering a uniform rectangle of nx x ny square-ish zones.
inline generate::Patch gas_rectangle(SimulationSetup& setup, double length_x, int nx, double length_y, int ny,
                                     double gamma, double reference_density) {
  const generate::Patch patch = generate::rectangle(setup.mesh, generate::graded_axis(0.0, {{length_x, nx, 1.0}}),
                                                    generate::graded_axis(0.0, {{length_y, ny, 1.0}}), /*body*/ 0);
  setup.materials.push_back(Material{"gas", reference_density, IdealGas{gamma}});
  setup.bodies.push_back({"gas", 0, patch.node_begin, patch.node_end, patch.zone_begin, patch.zone_end});
  return patch;
}

inline double zone_centre_x(const Mesh& mesh, Index z) { return quad::centre(mesh.corner_positions(z)).x; }

}  // namespace detail

inline constexpr double sod_end_time = 0.2;
inline constexpr double sedov_end_time = 1.0;
inline constexpr double sedov_cylindrical_energy = 0.311357;  // per unit length, gamma = 1.4
inline constexpr double sedov_spherical_energy = 0.851072;    // whole sphere, gamma = 1.4

// Sod shock tube, nx zones along the tube and ny across it; the strip is ny/nx long across so that
// zones are square.
inline SimulationSetup sod_strip(int nx, int ny) {
  constexpr double gamma = 1.4;
  SimulationSetup setup;
  setup.geometry = GeometryKind::planar;
  const double width = static_cast<double>(ny) / static_cast<double>(nx);
  const generate::Patch patch = detail::gas_rectangle(setup, 1.0, nx, width, ny, gamma, 1.0);
  ZoneFields& zones = setup.mesh.zones;
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) {
    const bool left = detail::zone_centre_x(setup.mesh, z) < 0.5;
    const double rho = left ? 1.0 : 0.125;
    const double p = left ? 1.0 : 0.1;
    zones.density[z] = rho;
    zones.specific_energy[z] = p / ((gamma - 1.0) * rho);
  }
  detail::hold_side(setup, patch, "i_min", true, false);
  detail::hold_side(setup, patch, "i_max", true, false);
  detail::hold_side(setup, patch, "j_min", false, true);
  detail::hold_side(setup, patch, "j_max", false, true);
  setup.controls.end_time = sod_end_time;
  return setup;
}

// Cylindrical Sedov blast on the planar quarter [0, 1.2]^2 with n x n zones.
inline SimulationSetup sedov_planar(int n) {
  constexpr double gamma = 1.4, rho = 1.0, side = 1.2;
  SimulationSetup setup;
  setup.geometry = GeometryKind::planar;
  const generate::Patch patch = detail::gas_rectangle(setup, side, n, side, n, gamma, rho);
  ZoneFields& zones = setup.mesh.zones;
  const Index origin = patch.zone_begin;  // i = 0, j = 0
  const quad::Corners x = setup.mesh.corner_positions(origin);
  const double blast = 0.25 * sedov_cylindrical_energy / (rho * quad::area(x));
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) {
    zones.density[z] = rho;
    zones.specific_energy[z] = z == origin ? blast : 1e-12 * blast;
  }
  detail::hold_side(setup, patch, "i_min", true, false);
  detail::hold_side(setup, patch, "i_max", true, false);
  detail::hold_side(setup, patch, "j_min", false, true);
  detail::hold_side(setup, patch, "j_max", false, true);
  setup.controls.end_time = sedov_end_time;
  return setup;
}

// Spherical Sedov blast on the RZ quarter [0, 1.2]^2 (z, r) with n x n zones.
inline SimulationSetup sedov_axisymmetric(int n) {
  constexpr double gamma = 1.4, rho = 1.0, side = 1.2;
  SimulationSetup setup;
  setup.geometry = GeometryKind::axisymmetric;
  const generate::Patch patch = detail::gas_rectangle(setup, side, n, side, n, gamma, rho);
  ZoneFields& zones = setup.mesh.zones;
  const Index origin = patch.zone_begin;  // z in [0, dz], r in [0, dr]
  const quad::Corners x = setup.mesh.corner_positions(origin);
  const double mass_per_radian = rho * quad::axisymmetric_volume(x);
  const double blast = sedov_spherical_energy / (4.0 * std::numbers::pi) / mass_per_radian;
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) {
    zones.density[z] = rho;
    zones.specific_energy[z] = z == origin ? blast : 1e-12 * blast;
  }
  // The axis (j_min, r = 0) is held by the solver; z = 0 is a slip plane.
  detail::hold_side(setup, patch, "i_min", true, false);
  detail::hold_side(setup, patch, "i_max", true, false);
  detail::hold_side(setup, patch, "j_max", false, true);
  setup.controls.end_time = sedov_end_time;
  return setup;
}

// Spherical Noh implosion on the RZ quarter [0, 1]^2 (z, r) with n x n zones.
inline SimulationSetup noh_axisymmetric(int n) {
  constexpr double gamma = 5.0 / 3.0, rho = 1.0;
  SimulationSetup setup;
  setup.geometry = GeometryKind::axisymmetric;
  const generate::Patch patch = detail::gas_rectangle(setup, 1.0, n, 1.0, n, gamma, rho);
  ZoneFields& zones = setup.mesh.zones;
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) {
    zones.density[z] = rho;
    zones.specific_energy[z] = 0.0;
  }
  NodeFields& nodes = setup.mesh.nodes;
  for (Index p = patch.node_begin; p < patch.node_end; ++p) {
    const double radius = std::hypot(nodes.x[p], nodes.y[p]);
    nodes.u[p] = radius > 0.0 ? -nodes.x[p] / radius : 0.0;
    nodes.v[p] = radius > 0.0 ? -nodes.y[p] / radius : 0.0;
  }
  // The axis (j_min, r = 0) is held by the solver; z = 0 is a slip plane.
  detail::hold_side(setup, patch, "i_min", true, false);
  setup.controls.end_time = 0.6;
  return setup;
}

inline constexpr double copper_cylinder_end_time = 20e-6;

// Copper cylinder striking a slip plane (RZ), n x n square zones on z in [0, 10 mm], r in [0, 10 mm].
inline SimulationSetup copper_cylinder_rz(int n, double impact_speed = 300.0) {
  constexpr double side = 0.01, rho0 = 8930.0;
  SimulationSetup setup;
  setup.geometry = GeometryKind::axisymmetric;
  const generate::Patch patch = generate::rectangle(setup.mesh, generate::graded_axis(0.0, {{side, n, 1.0}}),
                                                    generate::graded_axis(0.0, {{side, n, 1.0}}), /*body*/ 0);
  MieGruneisen eos;
  eos.reference_density = rho0;
  eos.bulk_sound_speed = 3940.0;
  eos.hugoniot_slope = 1.49;
  eos.gruneisen = 2.0;
  LinearHardening strength;
  strength.shear_modulus = 43.3e9;
  strength.yield_stress = 400e6;
  strength.hardening_modulus = 100e6;
  setup.materials.push_back(Material{"copper", rho0, eos, strength});
  setup.bodies.push_back({"cylinder", 0, patch.node_begin, patch.node_end, patch.zone_begin, patch.zone_end});
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) setup.mesh.zones.density[z] = rho0;
  for (Index p = patch.node_begin; p < patch.node_end; ++p) setup.mesh.nodes.u[p] = -impact_speed;
  // The axis (j_min, r = 0) is held by the solver; the impact face z = 0 slides on the plane.
  detail::hold_side(setup, patch, "i_min", true, false);
  for (const Index node : patch.sides.at("i_min")) setup.mesh.nodes.u[node] = 0.0;
  setup.controls.end_time = copper_cylinder_end_time;
  return setup;
}

}  // namespace krug::problems
