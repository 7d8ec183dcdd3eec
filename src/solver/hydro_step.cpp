#include "krug/solver/hydro_step.hpp"

#include <stdexcept>
#include <variant>

#include "krug/solver/parallel.hpp"

namespace krug {

double cfl_number(const Material& material, const Controls& controls) {
  return material.shear_modulus() == 0.0 ? controls.cfl_fluid : controls.cfl;
}

bool some_body_takes(ViscosityModel model, const std::vector<Body>& bodies, const std::vector<Material>& materials,
                     const Controls& controls, GeometryKind geometry) {
  return std::any_of(bodies.begin(), bodies.end(), [&](const Body& body) {
    return zone_force_params(materials[static_cast<std::size_t>(body.material)], controls, geometry, 0.0).viscosity.model ==
           model;
  });
}

ZoneForceParams zone_force_params(const Material& material, const Controls& controls, GeometryKind geometry,
                                  double previous_time_step) {
  ZoneForceParams params;
  params.shock_slope = material.shock_slope();
  params.shear_modulus = material.shear_modulus();
  params.flow_stress = material.initial_flow_stress();
  params.bending_modulus = material.bending_modulus();
  params.viscosity = controls.viscosity;
  params.hourglass = controls.hourglass;
  const BodyViscosity own = body_viscosity(controls.viscosity, controls.hourglass, material.shear_modulus() != 0.0, geometry);
  params.viscosity.model = own.model;
  params.hourglass.collapse_pressure = own.collapse_pressure;
  params.axisymmetric_form = controls.axisymmetric_form;
  params.previous_time_step = previous_time_step;
  return params;
}

ArtificialPower body_corner_forces(const Mesh& mesh, ZoneState& state, const Body& body, GeometryKind geometry,
                                   const ZoneForceParams& params, int threads, AreaWeightedArrays area_weighted,
                                   SharedEdgeLimiters limiters, DampingRows damping) {
  std::vector<ArtificialPower> block_power;
  auto run = [&]<GeometryKind G, ViscosityModel V>() {
    block_power = block_results<ArtificialPower>(body.zone_begin, body.zone_end, threads, [&](Index first, Index last) {
      return compute_corner_forces<G, V>(mesh, state.hydro, state.strength, state.hourglass, state.fracture, first, last,
                                         params, area_weighted, limiters, damping);
    });
  };
  auto run_geometry = [&]<GeometryKind G>() {
    switch (params.viscosity.model) {
      case ViscosityModel::edge: return run.template operator()<G, ViscosityModel::edge>();
      case ViscosityModel::scalar: return run.template operator()<G, ViscosityModel::scalar>();
      case ViscosityModel::tensor: return run.template operator()<G, ViscosityModel::tensor>();
      case ViscosityModel::off: break;
      case ViscosityModel::automatic:
        throw std::logic_error("body_corner_forces: viscosity model \"auto\" unresolved (take the parameters from "
                               "zone_force_params)");
    }
    return run.template operator()<G, ViscosityModel::off>();
  };
  if (geometry == GeometryKind::axisymmetric) {
    run_geometry.template operator()<GeometryKind::axisymmetric>();
  } else {
    run_geometry.template operator()<GeometryKind::planar>();
  }
  ArtificialPower power;
  for (const ArtificialPower& p : block_power) {
    power.viscous += p.viscous;
    power.hourglass += p.hourglass;
  }
  return power;
}

std::vector<ZoneUpdateResult> body_zone_update(Mesh& mesh, ZoneState& state, const Body& body, GeometryKind geometry,
                                               const Material& material, const ZoneUpdateParams& params, int threads,
                                               const double* work_correction) {
  HydroZoneFields& hydro = state.hydro;
  StrengthZoneFields& stress = state.strength;
  const FractureZoneFields& fracture = state.fracture;
  return std::visit([&](const auto& eos, const auto& strength) {
    return block_results<ZoneUpdateResult>(body.zone_begin, body.zone_end, threads, [&](Index first, Index last) {
      return geometry == GeometryKind::axisymmetric
                 ? update_zones<GeometryKind::axisymmetric>(mesh, hydro, stress, fracture, first, last, eos, strength,
                                                            params, work_correction)
                 : update_zones<GeometryKind::planar>(mesh, hydro, stress, fracture, first, last, eos, strength, params,
                                                      work_correction);
    });
  }, material.eos, material.strength);
}

void area_weighted_scale(const Mesh& mesh, const std::vector<Body>& bodies, std::vector<double>& scale,
                         std::vector<double>& booking) {
  // rho A = m / (V / A) changes as a zone moves off or towards the axis, so s_p is renewed every step
  // (held at its initial value, it let a converging sphere accelerate as if its area mass had not
  // grown: the spherical Noh stalled at a quarter of its density).
  const NodeFields& nodes = mesh.nodes;
  const ZoneFields& zones = mesh.zones;
  scale.assign(static_cast<std::size_t>(nodes.size()), 0.0);
  for (const Body& body : bodies) {
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      if (!zones.active[z]) continue;
      const quad::Corners x = mesh.corner_positions(z);
      const double area = quad::area(x);
      const double volume = quad::axisymmetric_volume(x);
      const double corner_area_mass = 0.25 * zones.mass[z] * area / volume;
      for (const Index n : zones.corners[z]) scale[static_cast<std::size_t>(n)] += corner_area_mass;
    }
  }
  // The booking weight: s_p stands for the node's radius (along every line of an equal-angle polar mesh
  // M_p / M^A_p grows like sin(theta_p)), except on the axis, where the consistent mass has no mirror
  // row and s_p = h/3 (h: the radius of the first line off the axis) while the radius is 0; booked with
  // s_p, the row next to the axis took 4/3 of the other rows' viscous heating per unit mass
  // (docs/verification.md, F4). 0 there.
  booking.resize(scale.size());
  for (std::size_t p = 0; p < scale.size(); ++p) {
    const double area_mass = scale[p];
    scale[p] = area_mass > 0.0 ? nodes.mass[static_cast<Index>(p)] / area_mass : 0.0;
    booking[p] = nodes.y[static_cast<Index>(p)] == 0.0 ? 0.0 : scale[p];
  }
}

}  // namespace krug
