#include "krug/solver/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/hydro/heat_conduction.hpp"
#include "krug/solver/hydro_step.hpp"
#include "krug/solver/initial_state.hpp"
#include "krug/solver/parallel.hpp"

namespace krug {

Simulation::Simulation(SimulationSetup setup)
    : geometry_(setup.geometry),
      materials_(std::move(setup.materials)),
      bodies_(std::move(setup.bodies)),
      boundary_(std::move(setup.constraints), std::move(setup.driven), std::move(setup.loads),
                std::move(setup.held_sides)),
      controls_(setup.controls) {
  state_.mesh = std::move(setup.mesh);
  state_.zone_state = std::move(setup.zone_state);
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

  derive_masses(state_.mesh, bodies_, materials_, geometry_);
  nodes.x0 = nodes.x;
  nodes.y0 = nodes.y;
  if (fracture_enabled_) {
    state_.zones_per_node = count_zones_per_node(state_.mesh);
    initial_shapes_ = fracture::initial_shapes(state_.mesh);
  }
  boundary_.initialise(nodes, geometry_);  // zero inverse masses where a condition holds (the axis in RZ among them)

  initialise_zone_state(state_.zone_state, zones, bodies_, materials_);
  build_edge_continuations(state_.mesh);
  node_corners_ = node_corners(state_.mesh);
  share_edge_limiters();
  if (some_body_takes(ViscosityModel::tensor, bodies_, materials_, controls_, geometry_)) {
    damping_rows_.assign(4 * static_cast<std::size_t>(zones.size()), 0.0);  // present: the step reads its bound
    damping_scale_.assign(nodes.size(), 0.0);
  }
  if (axisymmetric && controls_.axisymmetric_form == AxisymmetricForm::area_weighted) {
    area_weighted_work_.assign(state_.zone_state.hydro.corner_force.size(), 0.0);  // present: the form's per-step arrays
  }

  // First step: u given at t^0 is u^{-1/2} with dt^{-1/2} = 0, so dt^0 = dt^{1/2} / 2.
  const StableStep stable = first_stable_time_step(state_.mesh, state_.zone_state.hydro, bodies_, materials_, controls_);
  state_.controlling_zone = stable.zone;
  state_.stable_time_step = stable.time_step;
  double first = controls_.initial_time_step > 0.0 ? controls_.initial_time_step : stable.time_step;
  if (!std::isfinite(first)) first = 1e-6 * controls_.end_time;
  first = std::min({first, stable.time_step, controls_.max_time_step, controls_.end_time});
  state_.time_step_previous = 0.0;
  state_.time_step_next = first;
  state_.time_step_floor = controls_.time_step_floor > 0.0 ? controls_.time_step_floor : 1e-9 * first;

  measure_ledger(state_.mesh, state_.particles, state_.ledger);
  state_.ledger.energy.internal = krug::internal_energy(zones, 0, zones.size());
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
    limit_step_by_damping();
    // 2 and 3. The step was chosen from the particles' velocities before this solve (step 8), and the
    // solve can speed a particle up: one pinched between two others is driven out sideways, many times
    // faster, and may pass through another that is not among its candidates. When the solve moves a
    // particle beyond the reach they were searched over, the predictor and the solve are repeated with
    // half the step that would have kept it within reach (at most `most_repeats` times); F^n stays.
    constexpr int most_repeats = 8;
    const Ledger before_predictor = state_.ledger;  // the predictor books the held components' work
    const double deepest_gap = state_.deepest_contact_gap;
    for (int repeat = 0;; ++repeat) {
      predict_velocities();
      solve_contact_reactions();
      const double escape = contact_.empty() ? 0.0 : contact::particle_escape(state_.particles, state_.time_step_next);
      if (!(escape > 1.0) || repeat == most_repeats) break;
      repeat_shorter(0.5 * state_.time_step_next / escape, before_predictor, deepest_gap);
    }
    book_artificial_work();
    correct_and_move();
    update_zones();
    conduct_heat();
    rezone();
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

SimulationState Simulation::state() const { return state_; }

void Simulation::restore(SimulationState s) {
  if (s.mesh.nodes.size() != state_.mesh.nodes.size() || s.mesh.zones.size() != state_.mesh.zones.size() ||
      s.zone_state.size() != state_.mesh.zones.size() ||
      s.fracture_counts.size() != bodies_.size() || s.body_plastic_work.size() != bodies_.size() ||
      s.body_viscous_work.size() != bodies_.size() || s.body_hourglass_work.size() != bodies_.size() ||
      s.body_converted_energy.size() != bodies_.size()) {
    throw InputError("restart: the checkpoint does not belong to this scenario (mesh sizes or body counts differ)");
  }
  state_ = std::move(s);
  topology_changed_ = true;  // contact boundaries are rebuilt from the restored connectivity
  if (fracture_enabled_) initial_shapes_ = fracture::initial_shapes(state_.mesh);  // from the restored x0
  share_edge_limiters();
}

void Simulation::share_edge_limiters() {
  const bool edge_limiters = some_body_takes(ViscosityModel::edge, bodies_, materials_, controls_, geometry_) ||
                             some_body_takes(ViscosityModel::tensor, bodies_, materials_, controls_, geometry_);
  if (!edge_limiters || !controls_.viscosity.limiter) return;
  mirrored_edges_ = mirrored_edge_slots(state_.mesh);
  edge_limiters_.assign(mirrored_edges_.size(), 0.0);
}

void Simulation::cap_next_time_step(double dt) {
  state_.time_step_next = std::min(state_.time_step_next, dt);
}

void Simulation::compute_forces() {
  if (!area_weighted_work_.empty()) area_weighted_scale(state_.mesh, bodies_, area_weighted_scale_, area_weighted_booking_);
  const AreaWeightedArrays area_weighted{area_weighted_scale_.data(), area_weighted_booking_.data(),
                                         area_weighted_work_.data()};
  DampingRows damping;
  if (!damping_rows_.empty()) {
    const double* mass_scale = area_weighted_work_.empty() ? nullptr : area_weighted_scale_.data();
    for_each_block(0, state_.mesh.nodes.size(), controls_.threads, [&](Index, Index first, Index last) {
      damping_node_scale(state_.mesh.nodes, first, last, damping_scale_.data(), mass_scale);
    });
    damping = {damping_scale_.data(), damping_rows_.data()};
  }
  artificial_power_.resize(bodies_.size());
  for (const Body& body : bodies_) {
    const Material& material = materials_[static_cast<std::size_t>(body.material)];
    const ZoneForceParams params = zone_force_params(material, controls_, geometry_, state_.time_step_previous);
    const SharedEdgeLimiters limiters{mirrored_edges_.empty() ? nullptr : mirrored_edges_.data(),
                                      edge_limiters_.empty() ? nullptr : edge_limiters_.data()};
    artificial_power_[static_cast<std::size_t>(&body - bodies_.data())] =
        body_corner_forces(state_.mesh, state_.zone_state, body, geometry_, params, controls_.threads, area_weighted,
                           limiters, damping);
  }
  for_each_block(0, state_.mesh.nodes.size(), controls_.threads, [&](Index, Index first, Index last) {
    sum_corner_forces(state_.mesh.nodes, state_.zone_state.hydro, node_corners_, first, last);
  });
  if (boundary_.has_loads()) boundary_.apply_loads(state_.mesh.nodes, state_.mesh.zones, geometry_, state_.time);
}

void Simulation::limit_step_by_damping() {
  step_cut_by_damping_ = false;
  if (damping_rows_.empty()) return;
  DampingBound damping;
  for (const DampingBound& b :
       block_results<DampingBound>(0, state_.mesh.nodes.size(), controls_.threads, [&](Index first, Index last) {
         return damping_bound(state_.mesh.nodes, damping_rows_.data(), damping_scale_.data(), node_corners_, first, last,
                              area_weighted_work_.empty() ? nullptr : area_weighted_scale_.data());
       })) {
    damping.merge(b);
  }
  const double bound = damping.step;
  // The velocity update uses dt^n = (dt^{n-1/2} + dt^{n+1/2}) / 2: dt^{n+1/2} <= bound, and dt^n too
  // where that leaves dt^{n+1/2} at least bound / 2 (the bound fell by less than 1.5 times in a step).
  const double dt = std::min(bound, std::max(2.0 * bound - state_.time_step_previous, 0.5 * bound));
  if (!(dt < state_.time_step_next)) return;
  if (dt < state_.time_step_floor) {
    // Named by the first zone of the node the bound is set at.
    const Index node = damping.node;
    const Index zone = node_corners_.slot[static_cast<std::size_t>(node_corners_.offset[static_cast<std::size_t>(node)])] / 4;
    fail(fmt::format("time step {:.3e} s fell below its floor {:.3e} s (the tensor viscosity's damping, at a node of "
                     "this zone)",
                     dt, state_.time_step_floor),
         zone);
  }
  state_.time_step_next = dt;
  step_cut_by_damping_ = true;
  last_step_mid_ = 0.5 * (state_.time_step_previous + state_.time_step_next);
}

void Simulation::repeat_shorter(double dt, const Ledger& before_predictor, double deepest_gap) {
  NodeFields& nodes = state_.mesh.nodes;
  nodes.u.swap(nodes.u_old);  // back to u^{n-1/2}
  nodes.v.swap(nodes.v_old);
  state_.particles.u = state_.particles.u_old;
  state_.particles.v = state_.particles.v_old;
  state_.ledger = before_predictor;
  state_.deepest_contact_gap = deepest_gap;
  if (dt < state_.time_step_floor) {
    const std::string why = "(a particle driven beyond its contact search reach)";
    fail(fmt::format("time step {:.3e} s fell below its floor {:.3e} s {}", dt, state_.time_step_floor, why),
         state_.controlling_zone);
  }
  state_.time_step_next = dt;
  time_step_limit_ = TimeStepLimit::particle_travel;
  last_step_mid_ = 0.5 * (state_.time_step_previous + state_.time_step_next);
}

void Simulation::book_artificial_work() {
  const double dt_mid = 0.5 * (state_.time_step_previous + state_.time_step_next);
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    state_.ledger.energy.viscous += dt_mid * artificial_power_[b].viscous;
    state_.ledger.energy.hourglass += dt_mid * artificial_power_[b].hourglass;
    state_.body_viscous_work[b] += dt_mid * artificial_power_[b].viscous;
    state_.body_hourglass_work[b] += dt_mid * artificial_power_[b].hourglass;
  }
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
  last_contact_ = contact_.solve(contact::nodes_view(state_.mesh.nodes), contact::particles_view(state_.particles), dt_mid,
                                 state_.time_step_next, controls_.threads);
  state_.deepest_contact_gap = std::min(state_.deepest_contact_gap, last_contact_.deepest_gap);
}

void Simulation::correct_and_move() {
  NodeFields& nodes = state_.mesh.nodes;
  const double dt = state_.time_step_next;
  if (!contact_.empty()) {
    book_contact_work(contact_, nodes, state_.particles, boundary_, 0.5 * (state_.time_step_previous + state_.time_step_next),
                      state_.ledger);
  }
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
    params.cfl = cfl_number(material, controls_);
    const double* work_correction = area_weighted_work_.empty() ? nullptr : area_weighted_work_.data();
    const std::vector<ZoneUpdateResult> results = body_zone_update(
        state_.mesh, state_.zone_state, body, geometry_, material, params, controls_.threads, work_correction);
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
  measure_ledger(state_.mesh, state_.particles, state_.ledger);
}

void Simulation::conduct_heat() {
  const double coefficient = controls_.viscosity.heat_conduction;
  if (!(coefficient > 0.0)) return;
  ZoneFields& zones = state_.mesh.zones;
  heat_change_.assign(static_cast<std::size_t>(zones.size()), 0.0);
  for (const Body& body : bodies_) {
    const Material& material = materials_.at(static_cast<std::size_t>(body.material));
    if (material.shear_modulus() != 0.0) continue;  // bodies without strength only
    exchange_heat(state_.mesh, state_.zone_state.hydro, body.zone_begin, body.zone_end, coefficient,
                  state_.time_step_next, geometry_, heat_change_);
    std::visit([&](const auto& eos) {
      for (Index z = body.zone_begin; z < body.zone_end; ++z) {
        const double change = heat_change_[static_cast<std::size_t>(z)];
        if (change == 0.0) continue;
        zones.specific_energy[z] += change / zones.mass[z];
        evaluate_eos(eos, 0.0, zones, state_.zone_state.hydro, z);
      }
    }, material.eos);
  }
}

void Simulation::rezone() {
  RezoneParams params{.time_step = state_.time_step_next, .max_volume_change = controls_.max_volume_change};
  bool moved = false;
  for (const Body& body : bodies_) {
    if (!(body.rezone_ratio > 0.0)) continue;
    const Material& material = materials_[static_cast<std::size_t>(body.material)];
    params.cfl = cfl_number(material, controls_);
    params.relaxation = body.rezone_relaxation;
    const RezoneResult result = rezone_body(state_.mesh, state_.zone_state, body, material, geometry_, node_corners_, params,
                                            rezone_scratch_);
    state_.ledger.energy.rezone += result.kinetic_to_internal;
    moved = moved || result.moved_nodes > 0;
  }
  if (!moved) return;
  state_.ledger.energy.internal = krug::internal_energy(state_.mesh.zones, 0, state_.mesh.zones.size());
  measure_ledger(state_.mesh, state_.particles, state_.ledger);
  const StableStep stable = smallest_stable_step(state_.mesh.zones, state_.zone_state.hydro);
  state_.stable_time_step = stable.time_step;
  if (stable.zone >= 0) state_.controlling_zone = stable.zone;
}

void Simulation::choose_time_step() {
  state_.time += state_.time_step_next;
  ++state_.cycle;
  state_.time_step_previous = state_.time_step_next;
  const double remaining = controls_.end_time - state_.time;
  const TimeStepChoice choice = limit_time_step(state_.stable_time_step, state_.time_step_previous, controls_, state_.particles);
  const double dt = choice.time_step;
  time_step_limit_ = choice.limit;
  if (remaining > 0.0 && dt < state_.time_step_floor) {
    fail(fmt::format("time step {:.3e} s fell below its floor {:.3e} s", dt, state_.time_step_floor), state_.controlling_zone);
  }
  if (remaining < dt) time_step_limit_ = TimeStepLimit::end_time;
  state_.time_step_next = std::min(dt, std::max(remaining, 0.0));
  if (state_.time_step_next <= 0.0) state_.time_step_next = dt;  // finished(); keeps a meaningful value
}

void Simulation::fail(const std::string& what, Index zone) const {
  const Index b = body_of_zone(zone);
  const std::string body_name = b >= 0 ? bodies_[static_cast<std::size_t>(b)].name : "?";
  const long local = b >= 0 ? zone - bodies_[static_cast<std::size_t>(b)].zone_begin : zone;
  throw NumericalFailure(fmt::format("body '{}', zone {}, t = {:.6e} s (cycle {}): {}", body_name, local, state_.time,
                                     state_.cycle, what),
                         body_name, local, state_.time);
}

void Simulation::evaluate_fracture() {
  // The state just computed is at t^{n+1}; the plastic strain grew over dt^{n+1/2}.
  evaluate_failure_laws(state_.mesh, state_.zone_state, bodies_, materials_, failure_laws_, geometry_,
                        state_.time + state_.time_step_next, state_.time_step_next, state_.fracture_counts, controls_.threads,
                        initial_shapes_);
}

void Simulation::convert_fractured_zones() {
  const std::vector<Conversion> chosen = choose_conversions(state_.mesh, state_.zone_state, bodies_, materials_,
                                                            failure_laws_, controls_.fracture, boundary_.held_x(),
                                                            boundary_.held_y(), controls_.threads);
  if (chosen.empty()) return;
  convert_zones(chosen, state_.mesh, state_.particles, controls_.fracture.particles_per_zone,
                state_.time + state_.time_step_next, state_.zones_per_node, boundary_.held_x(), boundary_.held_y(),
                {state_.ledger, state_.body_converted_energy, state_.fracture_counts});
  topology_changed_ = true;
  // The step limit now comes from the zones that remain.
  const StableStep remaining = smallest_stable_step(state_.mesh.zones, state_.zone_state.hydro);
  state_.stable_time_step = remaining.time_step;
  if (remaining.zone >= 0) state_.controlling_zone = remaining.zone;
  measure_ledger(state_.mesh, state_.particles, state_.ledger);
}

}  // namespace krug
