#include "krug/solver/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/solver/parallel.hpp"
#include "krug/hydro/heat_conduction.hpp"
#include "krug/hydro/zone_forces.hpp"
#include "krug/hydro/zone_update.hpp"

namespace krug {

namespace {

// A zone's pressure and stress-wave speed (bulk, plus 4 mu / 3 rho with a shear modulus mu) from the
// EOS at its density and specific energy.
template <class Eos>
void evaluate_eos(const Eos& eos, double mu, ZoneFields& zones, Index z) {
  const double rho = zones.density[z], e = zones.specific_energy[z];
  zones.pressure[z] = eos.pressure(rho, e);
  zones.sound_speed[z] = std::sqrt(std::max(eos.sound_speed_squared(rho, e, zones.pressure[z]) + 4.0 * mu / (3.0 * rho), 0.0));
}

// Picks the compile-time variant of the force kernel once per body; its blocks of zones share the threads,
// and their artificial powers are added in block order.
ArtificialPower dispatch_zone_forces(GeometryKind geometry, ViscosityModel model, int threads, Mesh& mesh,
                                     const Body& body, const ZoneForceParams& params,
                                     AreaWeightedArrays area_weighted, SharedEdgeLimiters limiters) {
  std::vector<ArtificialPower> block_power;
  auto run = [&]<GeometryKind G, ViscosityModel V>() {
    block_power = block_results<ArtificialPower>(body.zone_begin, body.zone_end, threads, [&](Index first, Index last) {
      return compute_corner_forces<G, V>(mesh, first, last, params, area_weighted, limiters);
    });
  };
  auto run_geometry = [&]<GeometryKind G>() {
    switch (model) {
      case ViscosityModel::edge: return run.template operator()<G, ViscosityModel::edge>();
      case ViscosityModel::scalar: return run.template operator()<G, ViscosityModel::scalar>();
      case ViscosityModel::off: break;
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

}  // namespace

Simulation::Simulation(SimulationSetup setup)
    : geometry_(setup.geometry),
      materials_(std::move(setup.materials)),
      bodies_(std::move(setup.bodies)),
      boundary_(std::move(setup.constraints), std::move(setup.driven), std::move(setup.loads)),
      controls_(setup.controls) {
  state_.mesh = std::move(setup.mesh);
  state_.fracture_counts.assign(bodies_.size(), FractureCounts{});
  state_.body_plastic_work.assign(bodies_.size(), 0.0);
  state_.body_viscous_work.assign(bodies_.size(), 0.0);
  state_.body_hourglass_work.assign(bodies_.size(), 0.0);
  state_.body_converted_energy.assign(bodies_.size(), 0.0);
  for (const Body& body : bodies_) {
    const auto m = static_cast<std::size_t>(body.material);
    failure_laws_.push_back(m < setup.fracture.size() ? setup.fracture[m] : fracture::FailureLaw{});
    fracture_enabled_ = fracture_enabled_ || fracture::enabled(failure_laws_.back()) || body.erosion().any();
  }
  initialise();
  if (fracture_enabled_) {
    // Free elements collide with everything (docs/theory.md §2 step 7); in RZ the axis holds the rings.
    setup.contact.particles = true;
    setup.contact.axis_wall = geometry_ == GeometryKind::axisymmetric;
  }
  if (!setup.contact.empty()) {
    std::vector<std::pair<Index, Index>> ranges;
    for (const Body& body : bodies_) ranges.emplace_back(body.zone_begin, body.zone_end);
    contact_ = contact::ContactSolver(std::move(setup.contact), state_.mesh, ranges);
  }
}

void Simulation::initialise() {
  const bool axisymmetric = geometry_ == GeometryKind::axisymmetric;
  NodeFields& nodes = state_.mesh.nodes;
  ZoneFields& zones = state_.mesh.zones;
  if (!(controls_.end_time > 0.0)) throw InputError("end_time must be positive");

  // Zone geometry and mass; nodal mass from the r-weighted corner volumes of the median mesh.
  std::fill(nodes.mass.begin(), nodes.mass.end(), 0.0);
  for (const Body& body : bodies_) {
    const Material& material = materials_.at(static_cast<std::size_t>(body.material));
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      const quad::Corners x = state_.mesh.corner_positions(z);
      const double area = quad::area(x);
      const double volume = axisymmetric ? quad::axisymmetric_volume(x) : area;
      if (!(area > 0.0) || !(volume > 0.0)) {
        throw InputError(fmt::format("body '{}': zone {} has non-positive area {:.3e} m^2 (inverted corners "
                                     "or a node below the axis)", body.name, z - body.zone_begin, area));
      }
      if (zones.density[z] <= 0.0) zones.density[z] = material.reference_density;
      zones.area[z] = area;
      zones.volume[z] = volume;
      zones.mass[z] = zones.density[z] * volume;
      const ZoneCorners& n = zones.corners[z];
      zones.initial_altitude[z] = quad::smallest_altitude(x, area);
      // Planar: median-mesh corner areas (Caramana et al. 1998). Axisymmetric: consistent lumped masses
      // integral N_p r dA, so that the corner forces dV/dx_p accelerate axis nodes correctly.
      const std::array<double, 4> axisymmetric_corners =
          axisymmetric ? quad::axisymmetric_corner_volumes(x) : std::array<double, 4>{};
      for (int p = 0; p < 4; ++p) {
        const quad::Corners region = quad::corner_region(x, p);
        const double corner_volume = axisymmetric ? axisymmetric_corners[p] : quad::area(region);
        zones.corner_mass[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p)] = zones.density[z] * corner_volume;
        // The corner's region of the median mesh (its subzone), with the zone's volume measure.
        zones.subzone_mass[4 * static_cast<std::size_t>(z) + static_cast<std::size_t>(p)] =
            zones.density[z] * (axisymmetric ? quad::axisymmetric_volume(region) : quad::area(region));
        nodes.mass[n[p]] += zones.density[z] * corner_volume;
      }
    }
  }

  nodes.x0 = nodes.x;
  nodes.y0 = nodes.y;
  if (fracture_enabled_) {
    state_.zones_per_node.assign(static_cast<std::size_t>(nodes.size()), 0);
    for (Index z = 0; z < zones.size(); ++z) {
      if (!zones.active[z]) continue;
      const ZoneCorners& n = zones.corners[z];
      for (int p = 0; p < 4; ++p) {
        if (p > 0 && n[p] == n[p - 1]) continue;
        if (p == 3 && n[3] == n[0]) continue;
        ++state_.zones_per_node[static_cast<std::size_t>(n[p])];
      }
    }
  }
  // Per-DOF inverse masses, zero where a condition holds the component (the axis in RZ among them).
  for (Index p = 0; p < nodes.size(); ++p) {
    const double inverse = nodes.mass[p] > 0.0 ? 1.0 / nodes.mass[p] : 0.0;
    nodes.inv_mass_x[p] = inverse;
    nodes.inv_mass_y[p] = inverse;
  }
  boundary_.initialise(nodes, geometry_);

  // Pressure and wave speed from the EOS at the initial state.
  for (const Body& body : bodies_) {
    const Material& material = materials_.at(static_cast<std::size_t>(body.material));
    const double mu = material.shear_modulus();
    std::visit([&](const auto& eos) {
      for (Index z = body.zone_begin; z < body.zone_end; ++z) {
        evaluate_eos(eos, mu, zones, z);
        const double rho = zones.density[z], e = zones.specific_energy[z];
        if (!std::isfinite(e) || !std::isfinite(zones.pressure[z]) || !std::isfinite(zones.sound_speed[z])) {
          throw InputError(fmt::format("body '{}': zone {} starts with a non-finite state (rho {}, e {}, p {})",
                                       body.name, z - body.zone_begin, rho, e, zones.pressure[z]));
        }
      }
    }, material.eos);
  }
  build_edge_continuations(state_.mesh);
  node_corners_ = node_corners(state_.mesh);
  share_edge_limiters();
  if (axisymmetric && controls_.axisymmetric_form == AxisymmetricForm::area_weighted) {
    area_weighted_work_.assign(zones.corner_force.size(), 0.0);  // its presence selects the form's per-step arrays
  }

  // First step: u given at t^0 is u^{-1/2} with dt^{-1/2} = 0, so dt^0 = dt^{1/2} / 2.
  double stable = std::numeric_limits<double>::infinity();
  for (const Body& body : bodies_) {
    const double cfl = cfl_of(body);
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      if (!zones.active[z]) continue;
      // The stress-wave speed, plus the spread of corner velocities: a zone must not invert in the
      // first step even where the initial state sets no wave speed (a cold gas under a piston).
      const ZoneCorners& n = zones.corners[z];
      const Vec2 mean = 0.25 * (nodes.velocity(n[0]) + nodes.velocity(n[1]) + nodes.velocity(n[2]) + nodes.velocity(n[3]));
      double spread = 0.0;
      for (int p = 0; p < 4; ++p) spread = std::max(spread, norm(nodes.velocity(n[p]) - mean));
      const double speed = zones.sound_speed[z] + 2.0 * spread;
      if (speed <= 0.0) continue;
      const double dt = cfl * quad::stable_length(state_.mesh.corner_positions(z), zones.area[z]) / speed;
      if (dt < stable) { stable = dt; state_.controlling_zone = z; }
    }
  }
  state_.stable_time_step = stable;
  double first = controls_.initial_time_step > 0.0 ? controls_.initial_time_step : stable;
  if (!std::isfinite(first)) first = 1e-6 * controls_.end_time;
  first = std::min({first, stable, controls_.max_time_step, controls_.end_time});
  state_.time_step_previous = 0.0;
  state_.time_step_next = first;
  state_.time_step_floor = controls_.time_step_floor > 0.0 ? controls_.time_step_floor : 1e-9 * first;

  measure_ledger();
  state_.ledger.energy.internal = 0.0;
  for (Index z = 0; z < zones.size(); ++z) {
    if (zones.active[z]) state_.ledger.energy.internal += zones.mass[z] * zones.specific_energy[z];
  }
  state_.ledger.initial_total_energy = state_.ledger.energy.total();
  state_.ledger.initial_mass = state_.ledger.mass;
  state_.ledger.initial_axial_momentum = state_.ledger.axial_momentum;
}

void Simulation::step() {
  // A failure part-way through the step would leave the ledger holding some of this step's work and
  // none of its energies; it goes back to the last completed cycle's, which closes.
  const Ledger at_start = state_.ledger;
  last_step_mid_ = 0.5 * (state_.time_step_previous + state_.time_step_next);
  try {
    compute_forces();
    predict_velocities();
    solve_contact_reactions();
    correct_and_move();
    update_zones();
    conduct_heat();
    if (fracture_enabled_) {
      evaluate_fracture();
      convert_fractured_zones();
    }
  } catch (const NumericalFailure&) {
    state_.ledger = at_start;
    throw;
  }
  choose_time_step();
}

bool Simulation::finished() const {
  return state_.time >= controls_.end_time * (1.0 - 1e-12) || state_.cycle >= controls_.max_cycles;
}

double Simulation::internal_energy(Index body) const {
  const Body& b = bodies_[static_cast<std::size_t>(body)];
  const ZoneFields& zones = state_.mesh.zones;
  double sum = 0.0;
  for (Index z = b.zone_begin; z < b.zone_end; ++z) {
    if (zones.active[z]) sum += zones.mass[z] * zones.specific_energy[z];
  }
  return sum;
}

SimulationState Simulation::state() const { return state_; }

void Simulation::restore(SimulationState s) {
  if (s.mesh.nodes.size() != state_.mesh.nodes.size() || s.mesh.zones.size() != state_.mesh.zones.size() ||
      s.fracture_counts.size() != bodies_.size() || s.body_plastic_work.size() != bodies_.size() ||
      s.body_viscous_work.size() != bodies_.size() || s.body_hourglass_work.size() != bodies_.size() ||
      s.body_converted_energy.size() != bodies_.size()) {
    throw InputError("restart: the checkpoint does not belong to this scenario (mesh sizes or body counts differ)");
  }
  state_ = std::move(s);
  topology_changed_ = true;  // contact boundaries are rebuilt from the restored connectivity
  share_edge_limiters();
}

void Simulation::share_edge_limiters() {
  if (controls_.viscosity.model != ViscosityModel::edge || !controls_.viscosity.limiter) return;
  mirrored_edges_ = mirrored_edge_slots(state_.mesh);
  edge_limiters_.assign(mirrored_edges_.size(), 0.0);
}

void Simulation::cap_next_time_step(double dt) {
  state_.time_step_next = std::min(state_.time_step_next, dt);
}

void Simulation::update_area_weighted_scale() {
  // Wilkins' area mass of a node, M^A_p = sum over its zones of rho_z A_z / 4 at the current
  // positions: rho A = m / (V / A) changes as the zone moves off or towards the axis, so s_p = M_p / M^A_p
  // is renewed every step (held at its initial value, it let a converging sphere accelerate as if its
  // area mass had not grown: the spherical Noh stalled at a quarter of its density).
  const NodeFields& nodes = state_.mesh.nodes;
  const ZoneFields& zones = state_.mesh.zones;
  area_weighted_scale_.assign(static_cast<std::size_t>(nodes.size()), 0.0);
  for (const Body& body : bodies_) {
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      if (!zones.active[z]) continue;
      const quad::Corners x = state_.mesh.corner_positions(z);
      const double area = quad::area(x);
      const double volume = quad::axisymmetric_volume(x);
      const double corner_area_mass = 0.25 * zones.mass[z] * area / volume;
      for (const Index n : zones.corners[z]) area_weighted_scale_[static_cast<std::size_t>(n)] += corner_area_mass;
    }
  }
  // The booking weight of a node's viscous and hourglass work: s_p stands for the node's radius (along
  // every line of an equal-angle polar mesh M_p / M^A_p grows like sin(theta_p)), except on the axis,
  // where the consistent mass has no mirror row and s_p = h/3 (h: the radius of the first line off the
  // axis) while the radius is 0; booked with s_p, the row next to the axis took 4/3 of the other rows'
  // viscous heating per unit mass (docs/verification.md, F4). 0 there.
  area_weighted_booking_.resize(area_weighted_scale_.size());
  for (std::size_t p = 0; p < area_weighted_scale_.size(); ++p) {
    const double area_mass = area_weighted_scale_[p];
    area_weighted_scale_[p] = area_mass > 0.0 ? nodes.mass[static_cast<Index>(p)] / area_mass : 0.0;
    area_weighted_booking_[p] = nodes.y[static_cast<Index>(p)] == 0.0 ? 0.0 : area_weighted_scale_[p];
  }
}

void Simulation::compute_forces() {
  if (!area_weighted_work_.empty()) update_area_weighted_scale();
  const AreaWeightedArrays area_weighted{area_weighted_scale_.data(), area_weighted_booking_.data(),
                                         area_weighted_work_.data()};
  const double dt_mid = 0.5 * (state_.time_step_previous + state_.time_step_next);
  for (const Body& body : bodies_) {
    const Material& material = materials_[static_cast<std::size_t>(body.material)];
    ZoneForceParams params;
    params.shock_slope = material.shock_slope();
    params.shear_modulus = material.shear_modulus();
    params.viscosity = controls_.viscosity;
    params.hourglass = controls_.hourglass;
    params.axisymmetric_form = controls_.axisymmetric_form;
    params.previous_time_step = state_.time_step_previous;
    const SharedEdgeLimiters limiters{mirrored_edges_.empty() ? nullptr : mirrored_edges_.data(),
                                      edge_limiters_.empty() ? nullptr : edge_limiters_.data()};
    const ArtificialPower power =
        dispatch_zone_forces(geometry_, controls_.viscosity.model, controls_.threads, state_.mesh, body, params,
                             area_weighted, limiters);
    state_.ledger.energy.viscous += dt_mid * power.viscous;
    state_.ledger.energy.hourglass += dt_mid * power.hourglass;
    const std::size_t b = static_cast<std::size_t>(&body - bodies_.data());
    state_.body_viscous_work[b] += dt_mid * power.viscous;
    state_.body_hourglass_work[b] += dt_mid * power.hourglass;
  }
  for_each_block(0, state_.mesh.nodes.size(), controls_.threads, [&](Index, Index first, Index last) {
    sum_corner_forces(state_.mesh, node_corners_, first, last);
  });
  if (boundary_.has_loads()) boundary_.apply_loads(state_.mesh.nodes, state_.mesh.zones, geometry_, state_.time);
}

void Simulation::predict_velocities() {
  NodeFields& nodes = state_.mesh.nodes;
  const double dt_mid = 0.5 * (state_.time_step_previous + state_.time_step_next);
  // u^{n-1/2} becomes u_old by exchanging the arrays; every u is then written from it.
  nodes.u_old.swap(nodes.u);
  nodes.v_old.swap(nodes.v);
  state_.particles.u_old = state_.particles.u;  // particles feel no F: u* = u^{n-1/2}
  state_.particles.v_old = state_.particles.v;
  for_each_block(0, nodes.size(), controls_.threads, [&](Index, Index first, Index last) {
    for (Index p = first; p < last; ++p) {
      nodes.u[p] = nodes.u_old[p] + dt_mid * nodes.force_x[p] * nodes.inv_mass_x[p];
      nodes.v[p] = nodes.v_old[p] + dt_mid * nodes.force_y[p] * nodes.inv_mass_y[p];
    }
  });
  // Held components keep their value or take v(t^{n+1/2}); the boundary books what holds them.
  boundary_.hold(nodes, state_.time + 0.5 * state_.time_step_next, dt_mid, boundary_books());
}

void Simulation::solve_contact_reactions() {
  if (contact_.empty()) return;  // R = 0: a scene without contact pays nothing here
  const double dt_mid = 0.5 * (state_.time_step_previous + state_.time_step_next);
  if (topology_changed_) {
    contact_.rebuild_boundaries(state_.mesh);
    topology_changed_ = false;
  }
  last_contact_ = contact_.solve(state_.mesh, state_.particles, dt_mid, state_.time_step_next);
  state_.deepest_contact_gap = std::min(state_.deepest_contact_gap, last_contact_.deepest_gap);
}

void Simulation::book_contact_work(double dt_mid) {
  // W_contact = sum dt^n R . ubar over the nodes that received a reaction; on a held DOF the
  // boundary cancels R (boundary::Boundary::book_reaction). The overlap line is the part of
  // it done by the contacts that carry a pre-existing overlap (docs/theory.md §3): the rest, the work
  // of contacts that started the step apart, is dissipative.
  const NodeFields& nodes = state_.mesh.nodes;
  for (const contact::ContactPoint point : contact_.touched_points()) {
    const Vec2 r = contact_.reaction_force(point);
    if (point.is_particle()) {
      const Index i = point.index;
      const Vec2 ubar{0.5 * (state_.particles.u_old[i] + state_.particles.u[i]), 0.5 * (state_.particles.v_old[i] + state_.particles.v[i])};
      state_.ledger.energy.contact += dt_mid * dot(r, ubar);
      state_.ledger.energy.overlap += dt_mid * dot(contact_.overlap_reaction_force(point), ubar);
      continue;
    }
    const Index p = point.index;
    const double ubar = 0.5 * (nodes.u_old[p] + nodes.u[p]);
    const double vbar = 0.5 * (nodes.v_old[p] + nodes.v[p]);
    state_.ledger.energy.contact += dt_mid * (r.x * ubar + r.y * vbar);
    const Vec2 overlap = contact_.overlap_reaction_force(point);
    state_.ledger.energy.overlap += dt_mid * (overlap.x * ubar + overlap.y * vbar);
    boundary_.book_reaction(nodes, p, r, dt_mid, boundary_books());
  }
}

void Simulation::correct_and_move() {
  NodeFields& nodes = state_.mesh.nodes;
  const double dt = state_.time_step_next;
  if (!contact_.empty()) book_contact_work(0.5 * (state_.time_step_previous + state_.time_step_next));
  if (boundary_.has_loads()) boundary_.book_loads(nodes, 0.5 * (state_.time_step_previous + state_.time_step_next), boundary_books());
  for_each_block(0, nodes.size(), controls_.threads, [&](Index, Index first, Index last) {
    for (Index p = first; p < last; ++p) {
      nodes.x[p] += dt * nodes.u[p];
      nodes.y[p] += dt * nodes.v[p];
    }
  });
  for (Index i = 0; i < state_.particles.size(); ++i) {
    state_.particles.x[i] += dt * state_.particles.u[i];
    state_.particles.y[i] += dt * state_.particles.v[i];
  }
}

void Simulation::update_zones() {
  ZoneUpdateParams params;
  params.time_step_mid = 0.5 * (state_.time_step_previous + state_.time_step_next);
  params.time_step_next = state_.time_step_next;
  params.max_volume_change = controls_.max_volume_change;
  state_.stable_time_step = std::numeric_limits<double>::infinity();
  double internal = 0.0;
  for (const Body& body : bodies_) {
    const Material& material = materials_[static_cast<std::size_t>(body.material)];
    params.shear_modulus = material.shear_modulus();
    params.cfl = cfl_of(body);
    const double* work_correction = area_weighted_work_.empty() ? nullptr : area_weighted_work_.data();
    // One dispatch per body: the zone loop is compiled for this geometry, EOS and strength model; its
    // blocks share the threads, and their results are taken in block order.
    const std::vector<ZoneUpdateResult> results = std::visit([&](const auto& eos, const auto& strength) {
      return block_results<ZoneUpdateResult>(body.zone_begin, body.zone_end, controls_.threads, [&](Index first, Index last) {
        return geometry_ == GeometryKind::axisymmetric
                   ? krug::update_zones<GeometryKind::axisymmetric>(state_.mesh, first, last, eos, strength, params, work_correction)
                   : krug::update_zones<GeometryKind::planar>(state_.mesh, first, last, eos, strength, params, work_correction);
      });
    }, material.eos, material.strength);
    for (const ZoneUpdateResult& result : results) {
      state_.ledger.energy.plastic += result.plastic_work;
      state_.body_plastic_work[static_cast<std::size_t>(&body - bodies_.data())] += result.plastic_work;
      if (result.failed_zone >= 0) {
        fail("zone tangled (non-positive area) or its energy is not finite", result.failed_zone);
      }
      internal += result.internal_energy;
      if (result.stable_time_step < state_.stable_time_step) {
        state_.stable_time_step = result.stable_time_step;
        state_.controlling_zone = result.controlling_zone;
      }
    }
    state_.zone_cycles += body.zone_end - body.zone_begin;
  }
  state_.ledger.energy.internal = internal;
  measure_ledger();
}

void Simulation::conduct_heat() {
  const double coefficient = controls_.viscosity.heat_conduction;
  if (!(coefficient > 0.0)) return;
  ZoneFields& zones = state_.mesh.zones;
  heat_change_.assign(static_cast<std::size_t>(zones.size()), 0.0);
  for (const Body& body : bodies_) {
    const Material& material = materials_.at(static_cast<std::size_t>(body.material));
    if (material.shear_modulus() != 0.0) continue;  // bodies without strength only
    exchange_heat(state_.mesh, body.zone_begin, body.zone_end, coefficient, state_.time_step_next, geometry_,
                  heat_change_);
    std::visit([&](const auto& eos) {
      for (Index z = body.zone_begin; z < body.zone_end; ++z) {
        const double change = heat_change_[static_cast<std::size_t>(z)];
        if (change == 0.0) continue;
        zones.specific_energy[z] += change / zones.mass[z];
        evaluate_eos(eos, 0.0, zones, z);
      }
    }, material.eos);
  }
}

void Simulation::choose_time_step() {
  state_.time += state_.time_step_next;
  ++state_.cycle;
  state_.time_step_previous = state_.time_step_next;
  const double remaining = controls_.end_time - state_.time;
  double dt = std::min({state_.stable_time_step, controls_.time_step_growth * state_.time_step_previous, controls_.max_time_step});
  time_step_limit_ = dt == state_.stable_time_step ? TimeStepLimit::zone
                     : dt == controls_.max_time_step ? TimeStepLimit::maximum : TimeStepLimit::growth;
  for (Index i = 0; i < state_.particles.size(); ++i) {  // a particle moves at most a fraction of its radius
    const double speed = norm(state_.particles.velocity(i));
    if (speed > 0.0 && controls_.fracture.particle_travel * state_.particles.radius[i] / speed < dt) {
      dt = controls_.fracture.particle_travel * state_.particles.radius[i] / speed;
      time_step_limit_ = TimeStepLimit::particle_travel;
    }
  }
  if (remaining > 0.0 && dt < state_.time_step_floor) {
    fail(fmt::format("time step {:.3e} s fell below its floor {:.3e} s", dt, state_.time_step_floor), state_.controlling_zone);
  }
  if (remaining < dt) time_step_limit_ = TimeStepLimit::end_time;
  state_.time_step_next = std::min(dt, std::max(remaining, 0.0));
  if (state_.time_step_next <= 0.0) state_.time_step_next = dt;  // finished(); keeps a meaningful value
}

void Simulation::measure_ledger() {
  const NodeFields& nodes = state_.mesh.nodes;
  double kinetic = 0.0, momentum = 0.0;
  for (Index p = 0; p < nodes.size(); ++p) {
    kinetic += nodes.mass[p] * (nodes.u[p] * nodes.u[p] + nodes.v[p] * nodes.v[p]);
    momentum += nodes.mass[p] * nodes.u[p];
  }
  double mass = 0.0;
  for (Index i = 0; i < state_.particles.size(); ++i) {
    kinetic += state_.particles.mass[i] * (state_.particles.u[i] * state_.particles.u[i] + state_.particles.v[i] * state_.particles.v[i]);
    momentum += state_.particles.mass[i] * state_.particles.u[i];
    mass += state_.particles.mass[i];
  }
  state_.ledger.energy.kinetic = 0.5 * kinetic;
  state_.ledger.axial_momentum = momentum;
  state_.ledger.max_kinetic = std::max(state_.ledger.max_kinetic, state_.ledger.energy.kinetic);
  for (Index z = 0; z < state_.mesh.zones.size(); ++z) {
    if (state_.mesh.zones.active[z]) mass += state_.mesh.zones.mass[z];
  }
  state_.ledger.mass = mass;
}

void Simulation::fail(const std::string& what, Index zone) const {
  std::string body_name = "?";
  long local = zone;
  for (const Body& body : bodies_) {
    if (zone >= body.zone_begin && zone < body.zone_end) {
      body_name = body.name;
      local = zone - body.zone_begin;
    }
  }
  throw NumericalFailure(fmt::format("body '{}', zone {}, t = {:.6e} s (cycle {}): {}", body_name, local, state_.time,
                                     state_.cycle, what),
                         body_name, local, state_.time);
}

double Simulation::cfl_of(const Body& body) const {
  return materials_[static_cast<std::size_t>(body.material)].shear_modulus() == 0.0 ? controls_.cfl_fluid : controls_.cfl;
}

Index Simulation::body_of_zone(Index zone) const {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (zone >= bodies_[b].zone_begin && zone < bodies_[b].zone_end) return static_cast<Index>(b);
  }
  return -1;
}

BodySummary Simulation::summarise(const Body& body) const {
  const NodeFields& nodes = state_.mesh.nodes;
  BodySummary s;
  double mass = 0.0;
  Vec2 momentum, moment;
  s.bbox_min = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  s.bbox_max = -s.bbox_min;
  for (Index p = body.node_begin; p < body.node_end; ++p) {
    mass += nodes.mass[p];
    momentum += nodes.mass[p] * nodes.velocity(p);
    moment += nodes.mass[p] * nodes.position(p);
    if (nodes.mass[p] == 0.0) continue;  // a node whose zones have all left the grid: no longer the body's
    s.bbox_min = {std::min(s.bbox_min.x, nodes.x[p]), std::min(s.bbox_min.y, nodes.y[p])};
    s.bbox_max = {std::max(s.bbox_max.x, nodes.x[p]), std::max(s.bbox_max.y, nodes.y[p])};
  }
  for (Index z = body.zone_begin; z < body.zone_end; ++z) s.zones += state_.mesh.zones.active[z] ? 1 : 0;
  s.mass = whole_body_factor() * mass;
  if (mass > 0.0) {
    s.velocity = (1.0 / mass) * momentum;
    s.centroid = (1.0 / mass) * moment;
  }
  return s;
}

}  // namespace krug
