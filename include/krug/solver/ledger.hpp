#pragma once
// The conservation ledgers every run keeps (docs/theory.md §3). Values are per radian
// (axisymmetric) or per unit thickness (planar); reports multiply by whole_body_factor().
//
//   E_total = K + IE + E_converted - W_contact - W_boundary
//
// W_contact is the work of contact and friction forces on the system, W_boundary the work done on
// the system by boundary conditions. Plastic, viscous and hourglass work are parts of IE. The overlap
// line is the part of W_contact done by contacts that carry a pre-existing overlap (pushed open by the
// overlap rule, so it may be positive); the rest, W_contact - overlap, is <= 0.
#include <algorithm>
#include <cmath>

namespace krug {

struct Mesh;
struct NodeFields;
struct Particles;
namespace contact { class ContactSolver; }
namespace boundary { class Boundary; }

struct EnergyLedger {
  double kinetic = 0.0;     // K at t^{n+1/2}: 1/2 sum M |u|^2 over nodes and particles
  double internal = 0.0;    // IE = sum m e
  double plastic = 0.0;     // plastic work (part of IE)
  double viscous = 0.0;     // artificial-viscosity work (part of IE)
  double hourglass = 0.0;   // hourglass work (part of IE)
  double rezone = 0.0;      // kinetic energy the rezone's remap turned into heat (part of IE)
  double contact = 0.0;     // W_contact: <= 0 apart from the overlap line
  double overlap = 0.0;     // the part of W_contact done by contacts with a pre-existing overlap (any sign)
  double converted = 0.0;   // energy removed with zones converted to particles
  double boundary = 0.0;    // W_boundary, work done on the system by boundary conditions

  double total() const { return kinetic + internal + converted - contact - boundary; }
};

// A relative energy drift above this is not round-off: the control-volume scheme closes its books to
// 1e-15..1e-12 over a run (docs/verification.md), so a run past it reports that its ledger did not close.
inline constexpr double energy_drift_limit = 1e-6;

struct Ledger {
  EnergyLedger energy;
  double initial_total_energy = 0.0;
  double max_kinetic = 0.0;
  double initial_mass = 0.0;
  double mass = 0.0;
  double initial_axial_momentum = 0.0;
  double axial_momentum = 0.0;
  double axial_boundary_impulse = 0.0;  // impulse of boundary conditions on the system, axial

  // max(E(0), max_t K, |W_boundary|): the energy the drift is relative to.
  double energy_scale() const {
    return std::max({std::abs(initial_total_energy), max_kinetic, std::abs(energy.boundary)});
  }
  // |E(t) - E(0)| / energy_scale(): defined also for runs that start at rest.
  double relative_energy_drift() const {
    const double scale = energy_scale();
    return scale > 0.0 ? std::abs(energy.total() - initial_total_energy) / scale : 0.0;
  }
  bool energy_closed() const { return relative_energy_drift() <= energy_drift_limit; }
  double relative_mass_error() const {
    return initial_mass > 0.0 ? std::abs(mass - initial_mass) / initial_mass : 0.0;
  }
};

// The measured lines at t^{n+1/2}: K = 1/2 sum M |u|^2 and the axial momentum of nodes and particles,
// the largest K so far, and the mass of the active zones and the particles. Reads the mesh and the
// particles; writes energy.kinetic, axial_momentum, max_kinetic and mass of `ledger`.
void measure_ledger(const Mesh& mesh, const Particles& particles, Ledger& ledger);

// The contact lines of step 4: W_contact += dt^n R . ubar over the nodes and particles the contact
// solver's last solve touched (ubar the mid velocity), the overlap line the part of it done by contacts
// that carry a pre-existing overlap; on a held component the boundary cancels R (Boundary::book_reaction,
// which books on the boundary lines). Reads the solver, nodes and particles; writes energy.contact,
// energy.overlap, energy.boundary and axial_boundary_impulse of `ledger`.
void book_contact_work(const contact::ContactSolver& contact, const NodeFields& nodes, const Particles& particles,
                       const boundary::Boundary& boundary, double dt_mid, Ledger& ledger);

}  // namespace krug
