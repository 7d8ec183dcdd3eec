#pragma once
// Penetration results of a projectile run: does the projectile perforate its targets, with what
// residual velocity and mass, what plug leaves, how much energy the targets absorb.
//
// Definitions (docs/outputs.md, "Penetration"):
//   * impact axis: the first axis (z in axisymmetric geometry); in planar geometry the axis along which
//     the projectile's initial velocity is largest. `direction` is +1 or -1, the sense of that velocity.
//     Positions below are measured along the impact axis, in that sense.
//   * the projectile's piece: the heaviest connected piece of the projectile's zones; its nose is its
//     most advanced point, its tail its least advanced one;
//   * each target's main piece: the heaviest connected piece of that target body's zones;
//   * perforated: the nose of the projectile's piece has passed every point of every target's main
//     piece; cleared: its tail has;
//   * stopped: the projectile's piece no longer advances faster than a given speed;
//   * depth: how far the nose has passed the targets' initial front face (largest over the run);
//   * plug: the heaviest piece of a target body other than its main piece;
//   * energy absorbed by the targets: their plastic work plus the kinetic energy of their nodes and of
//     the particles made from their zones (the targets' elastic energy is not counted).
#include <optional>
#include <string>
#include <vector>

#include "krug/scenario/scenario.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::run {

// Which body is the projectile and which are its targets: read from the scenario's "penetration" block.
using scenario::PenetrationSetup;

// The geometry of a moment: where the projectile's piece and the targets' main pieces are.
struct PenetrationMoment {
  double nose = 0.0;         // most advanced coordinate of the projectile's piece (m, along the impact direction)
  double tail = 0.0;         // least advanced one
  double target_rear = 0.0;  // most advanced coordinate of any target's main piece
  bool perforated() const { return nose > target_rear; }
  bool cleared() const { return tail > target_rear; }
};

// The fixed geometry of a run and the record of its moments, kept by the run loop (and checkpointed).
struct PenetrationRecord {
  int axis = 0;              // 0: first coordinate, 1: second
  double direction = 1.0;    // +1 or -1
  double front = 0.0;        // the targets' initial front face (least advanced target point at t = 0)
  double rear = 0.0;         // the targets' initial rear face (most advanced target point at t = 0)
  double deepest = -1e300;   // largest nose position seen (m, along the impact direction)
  double perforation_time = -1.0;  // s; -1: not perforated yet
  double initial_speed = 0.0;  // m/s: the projectile's mass-weighted speed along the impact direction at t = 0
};

struct PenetrationReport {
  std::string projectile;
  // True when the run ended because the projectile had cleared its targets or stopped (the stop rule
  // with clear_of_targets): the figures are final, not bounds of a run cut short.
  bool final = false;
  bool perforated = false;
  double perforation_time = -1.0;      // s, -1 when not perforated
  double depth = 0.0;                  // m past the targets' initial front face (largest over the run)
  double residual_velocity = 0.0;      // m/s of the projectile's piece along the impact direction
  Vec2 residual_velocity_vector;       // both components
  double residual_mass = 0.0;          // kg, the projectile's piece
  double initial_mass = 0.0;           // kg, the projectile at t = 0
  double mass_lost = 0.0;              // kg: initial mass - residual mass (eroded, converted and broken-off)
  double eroded_mass = 0.0;            // kg, of which eroded
  std::string plug_body;               // empty when no target has a piece besides its main one
  double plug_mass = 0.0;              // kg
  double plug_velocity = 0.0;          // m/s along the impact direction
  double target_plastic_work = 0.0;    // J
  double target_kinetic_energy = 0.0;  // J: nodes and particles of the targets
  double target_energy_absorbed = 0.0; // J: the sum of the two
  double projectile_kinetic_energy = 0.0;  // J of the projectile's piece (nodes; half-step velocities)
  // The whole projectile: every node and every free element made from the projectile's zones
  // (largest piece, broken-off pieces, eroded and converted particles), mass-weighted momentum.
  double initial_speed = 0.0;          // m/s along the impact direction at t = 0
  double whole_velocity = 0.0;         // m/s: whole momentum along the impact direction / whole mass
  double whole_mass = 0.0;             // kg (equals initial_mass: the bookkeeping check of the figure)
  double piece_velocity_loss = 0.0;    // (initial_speed - residual_velocity) / initial_speed, the largest piece
  double whole_velocity_loss = 0.0;    // (initial_speed - whole_velocity) / initial_speed
  double free_element_mass = 0.0;      // kg of free elements made from the projectile (eroded or converted zones)
  double free_element_velocity = 0.0;  // m/s: their mass-weighted velocity along the impact direction
  double backward_mass = 0.0;          // kg of the projectile (nodal masses and free elements) moving against
                                       // the impact direction
  double backward_velocity = 0.0;      // m/s: its mass-weighted velocity along the impact direction (<= 0)
};

// The record's fixed geometry from the initial state (throws InputError when the projectile does not move).
PenetrationRecord start_penetration(const Simulation& simulation, const PenetrationSetup& setup);
// Where the pieces are now (computes the connected pieces of the projectile and the targets).
PenetrationMoment measure_penetration(const Simulation& simulation, const PenetrationSetup& setup,
                                      const PenetrationRecord& record);
// Adds the current moment to the record (deepest nose, perforation time). Cheap while the projectile's
// nose has not passed the targets' initial rear face; after that it computes the pieces every fourth
// cycle until the perforation (so the perforation time is known to within four steps).
// `projectile`: the projectile's summarise() of this moment (the run loop shares it with the stop rule).
void observe_penetration(const Simulation& simulation, const PenetrationSetup& setup, const BodySummary& projectile,
                         PenetrationRecord& record);
PenetrationReport report_penetration(const Simulation& simulation, const PenetrationSetup& setup,
                                     const PenetrationRecord& record);

}  // namespace krug::run
