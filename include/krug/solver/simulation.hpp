#pragma once
// The simulation: bodies on one Lagrangian mesh, their materials, boundary conditions, controls,
// the clock and the ledgers. step() is the recipe of docs/theory.md §2.
#include <string>
#include <vector>

#include "krug/boundary/boundary.hpp"
#include "krug/contact/contact.hpp"
#include "krug/core/geometry_kind.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/hydro/zone_forces.hpp"
#include "krug/particles/particles.hpp"
#include "krug/material/material.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/pieces.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/solver/body.hpp"
#include "krug/solver/controls.hpp"
#include "krug/solver/fracture_step.hpp"
#include "krug/solver/ledger.hpp"
#include "krug/solver/rezone.hpp"
#include "krug/solver/time_step.hpp"

namespace krug {

// Everything a run starts from. Zone density and specific energy and node velocity are set in
// `mesh`; masses, volumes and pressures are derived by the Simulation. `zone_state` is empty (zones
// start intact and unstressed) or sized to the mesh's zones (ZoneState::resize) to start some zones
// damaged or stressed; its pressures and wave speeds are derived.
struct SimulationSetup {
  GeometryKind geometry = GeometryKind::planar;
  Mesh mesh;
  ZoneState zone_state;
  std::vector<Material> materials;
  std::vector<Body> bodies;
  std::vector<NodeConstraint> constraints;               // held components (the axis in RZ is added by the Simulation)
  std::vector<boundary::DrivenComponent> driven;         // held components that follow a function of time
  std::vector<boundary::FaceLoad> loads;                 // pressure and traction on faces
  std::vector<boundary::HeldSide> held_sides;            // the constraints by the side that holds them (reports)
  contact::ContactSetup contact;
  std::vector<fracture::FailureLaw> fracture;  // per material; empty or not enabled (fracture::enabled): no fracture
  Controls controls;
};


// Everything that changes during a run: with the setup it came from, it restarts a run exactly.
// The mesh holds the topology and geometry (with each zone's mass, density and specific energy), the
// zone state the packages' per-zone fields (hydro, strength, hourglass, fracture; zone_state.hpp).
struct SimulationState {
  Mesh mesh;
  ZoneState zone_state;
  Particles particles;
  Ledger ledger;
  std::vector<FractureCounts> fracture_counts;
  std::vector<double> body_plastic_work;
  std::vector<double> body_viscous_work;     // per body, as the ledger's viscous line (per radian or per m)
  std::vector<double> body_hourglass_work;   // per body, as the ledger's hourglass line
  std::vector<double> body_converted_energy; // per body, as the ledger's converted line
  std::vector<Index> zones_per_node;
  double time = 0.0;
  long cycle = 0;
  long zone_cycles = 0;
  double time_step_previous = 0.0;
  double time_step_next = 0.0;
  double time_step_floor = 0.0;
  double stable_time_step = 0.0;
  Index controlling_zone = -1;
  double deepest_contact_gap = 0.0;
};

class Simulation {
 public:
  explicit Simulation(SimulationSetup setup);

  // One cycle: t^n -> t^{n+1}. Throws NumericalFailure: the fields are left as they were at the
  // failure, the ledger as it was at t^n (so that it closes).
  void step();
  bool finished() const;

  GeometryKind geometry() const { return geometry_; }
  const Mesh& mesh() const { return state_.mesh; }
  Mesh& mesh() { return state_.mesh; }
  // The zones' physics state by package (hydro, strength, hourglass, fracture), indexed like the mesh's zones.
  const ZoneState& zone_state() const { return state_.zone_state; }
  ZoneState& zone_state() { return state_.zone_state; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<Material>& materials() const { return materials_; }
  const Controls& controls() const { return controls_; }
  Controls& controls() { return controls_; }
  const Ledger& ledger() const { return state_.ledger; }

  double time() const { return state_.time; }
  long cycle() const { return state_.cycle; }
  long zone_cycles() const { return state_.zone_cycles; }
  double next_time_step() const { return state_.time_step_next; }
  double last_time_step() const { return state_.time_step_previous; }
  Index controlling_zone() const { return state_.controlling_zone; }
  // What set dt^{n+1/2} (with zone: the controlling zone), and the body owning a zone (-1 for none).
  TimeStepLimit time_step_limit() const { return time_step_limit_; }
  Index body_of_zone(Index zone) const { return krug::body_of_zone(bodies_, zone); }
  // The CFL-stable step of the current state (s; +infinity where no zone sets a wave speed).
  double stable_time_step() const { return state_.stable_time_step; }
  const contact::ContactStatistics& last_contact() const { return last_contact_; }
  bool has_contact() const { return !contact_.empty(); }  // any contact pair, wall or free particles
  // For gauges: the held velocity components, the contact solver (its last solve's reactions) and the
  // step dt^n = (dt^{n-1/2} + dt^{n+1/2}) / 2 of the last cycle, over which F^n and R acted (s).
  const std::vector<NodeConstraint>& constraints() const { return boundary_.constraints(); }
  const std::vector<boundary::HeldSide>& held_sides() const { return boundary_.held_sides(); }
  const contact::ContactSolver& contact() const { return contact_; }
  double last_step_mid() const { return last_step_mid_; }
  // Whether the tensor viscosity's damping bound cut the last step after its forces (step 1b).
  bool step_cut_by_damping() const { return step_cut_by_damping_; }
  // Deepest predicted gap left by contact over the run so far (m, <= 0).
  double deepest_contact_gap() const { return state_.deepest_contact_gap; }

  // Checkpoint and restart: state() after any step; restore() on a Simulation built from the same
  // setup continues the run exactly as if it had not stopped.
  SimulationState state() const;
  void restore(SimulationState state);

  // For tests of the time integration: cap the next step (the CFL and growth limits still apply).
  void cap_next_time_step(double dt);

  BodySummary summarise(const Body& body) const { return summarise_body(state_.mesh, body, geometry_); }
  // Connected pieces of a body's remaining zones (by shared edges; connected_pieces), heaviest first,
  // masses for the whole body (x 2 pi in RZ).
  std::vector<Fragment> fragments(const Body& body) const { return body_fragments(state_.mesh, body, geometry_); }
  const Particles& particles() const { return state_.particles; }
  const FractureCounts& fracture_counts(Index body) const { return state_.fracture_counts[static_cast<std::size_t>(body)]; }
  // Plastic work done in one body's zones so far (J per radian or per m; the ledger's plastic line is their sum).
  double plastic_work(Index body) const { return state_.body_plastic_work[static_cast<std::size_t>(body)]; }
  double viscous_work(Index body) const { return state_.body_viscous_work[static_cast<std::size_t>(body)]; }
  double hourglass_work(Index body) const { return state_.body_hourglass_work[static_cast<std::size_t>(body)]; }
  double converted_energy(Index body) const { return state_.body_converted_energy[static_cast<std::size_t>(body)]; }
  // Sum m e over the body's active zones (per radian or per m).
  double internal_energy(Index body) const {
    const Body& b = bodies_[static_cast<std::size_t>(body)];
    return krug::internal_energy(state_.mesh.zones, b.zone_begin, b.zone_end);
  }
  bool fracture_enabled() const { return fracture_enabled_; }
  double whole_body_factor() const { return krug::whole_body_factor(geometry_); }

 private:
  // The recipe, in order.
  void compute_forces();          // 1. F^n: corner forces of every zone, and the boundary loads
  void limit_step_by_damping();   // 1b. dt^{n+1/2} within the tensor viscosity's damping bound (that model only)
  void predict_velocities();      // 2. u* = u^{n-1/2} + dt^n F / M  (per-DOF inverse masses)
  void solve_contact_reactions(); // 3. R from the predicted gaps; the contact solver applies it as it goes:
                                  //    u^{n+1/2} = u* + dt^n R / M (nothing without contact)
  // 2-3 again with the shorter step dt: the velocities, ledger and deepest gap as before the predictor.
  void repeat_shorter(double dt, const Ledger& before_predictor, double deepest_gap);
  void book_artificial_work();    // the viscous and hourglass work of step 1 over the final dt^n
  void correct_and_move();        // 4. the contact and boundary work of R; x^{n+1} = x^n + dt^{n+1/2} u^{n+1/2}
  void update_zones();            // 5. geometry, density, energy, EOS, stable step
  void conduct_heat();            // 5b. artificial heat conduction between zones (if on)
  void rezone();                  // 5c. relax and remap where a body's mesh degrades (bodies that ask)
  void evaluate_fracture();       // 6. failure laws on intact zones; damage is permanent
  void convert_fractured_zones(); // 7. fully fractured surface zones -> particles (one layer per step)
  void choose_time_step();        // 8. dt^{n+3/2}

  void initialise();
  void share_edge_limiters();  // the edge-viscosity limiter computed once per edge (from the connectivity)
  boundary::Books boundary_books() { return {state_.ledger.energy.boundary, state_.ledger.axial_boundary_impulse}; }
  [[noreturn]] void fail(const std::string& what, Index zone) const;

  GeometryKind geometry_;
  // The run state, the one record that checkpoints and restarts carry (its fields above: the mesh, the
  // zone state, particles, ledger, per-body records, the clock).
  SimulationState state_;
  std::vector<Material> materials_;
  std::vector<Body> bodies_;
  boundary::Boundary boundary_;  // kinematic conditions and loads: their slots in the step, their books
  contact::ContactSolver contact_;
  std::vector<fracture::FailureLaw> failure_laws_;  // per body
  std::vector<fracture::InitialShape> initial_shapes_;  // per zone, from x0 (with fracture on; again at a restore)
  bool fracture_enabled_ = false;
  bool topology_changed_ = false;
  contact::ContactStatistics last_contact_;
  Controls controls_;
  std::vector<double> area_weighted_scale_;  // s_p = M_p / M^A_p, renewed every step (area-weighted RZ form only)
  std::vector<double> heat_change_;          // per zone, the artificial heat conduction of the step (scratch)
  std::vector<double> area_weighted_booking_;  // its viscous/hourglass work weight: s_p, 0 on the axis
  std::vector<Index> mirrored_edges_;        // mirrored_edge_slots() (edge or tensor viscosity with limiter only)
  NodeCorners node_corners_;                 // each node's zone corners, in zone order (the force sums)
  std::vector<double> area_weighted_work_;   // 8 per zone: work correction of the area-weighted RZ form (empty otherwise)
  std::vector<double> edge_limiters_;        // psi per zone edge, written and read by compute_forces
  std::vector<double> damping_rows_;         // 4 per zone: the tensor viscosity's damping rows (that model only)
  std::vector<double> damping_scale_;        // per node: the rows' 1 / sqrt(m_p), renewed every step (that model only)
  std::vector<ArtificialPower> artificial_power_;  // per body, of step 1 (booked once dt^n is final)
  RezoneScratch rezone_scratch_;                   // the rezone's work arrays (bodies that ask for it)

  TimeStepLimit time_step_limit_ = TimeStepLimit::zone;
  double last_step_mid_ = 0.0;  // dt^n of the last step (last_step_mid)
  bool step_cut_by_damping_ = false;
};

}  // namespace krug
