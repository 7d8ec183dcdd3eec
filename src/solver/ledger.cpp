#include "krug/solver/ledger.hpp"

#include "krug/boundary/boundary.hpp"
#include "krug/contact/contact.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/particles/particles.hpp"

namespace krug {

void measure_ledger(const Mesh& mesh, const Particles& particles, Ledger& ledger) {
  const NodeFields& nodes = mesh.nodes;
  double kinetic = 0.0, momentum = 0.0;
  for (Index p = 0; p < nodes.size(); ++p) {
    kinetic += nodes.mass[p] * (nodes.u[p] * nodes.u[p] + nodes.v[p] * nodes.v[p]);
    momentum += nodes.mass[p] * nodes.u[p];
  }
  double mass = 0.0;
  for (Index i = 0; i < particles.size(); ++i) {
    kinetic += particles.mass[i] * (particles.u[i] * particles.u[i] + particles.v[i] * particles.v[i]);
    momentum += particles.mass[i] * particles.u[i];
    mass += particles.mass[i];
  }
  ledger.energy.kinetic = 0.5 * kinetic;
  ledger.axial_momentum = momentum;
  ledger.max_kinetic = std::max(ledger.max_kinetic, ledger.energy.kinetic);
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    if (mesh.zones.active[z]) mass += mesh.zones.mass[z];
  }
  ledger.mass = mass;
}

void book_contact_work(const contact::ContactSolver& contact, const NodeFields& nodes, const Particles& particles,
                       const boundary::Boundary& boundary, double dt_mid, Ledger& ledger) {
  // The overlap line is the part done by the contacts that carry a pre-existing overlap (docs/theory.md
  // §3): the rest, the work of contacts that started the step apart, is dissipative.
  const boundary::Books books{ledger.energy.boundary, ledger.axial_boundary_impulse};
  for (const contact::ContactPoint point : contact.touched_points()) {
    const Vec2 r = contact.reaction_force(point);
    if (point.is_particle()) {
      const Index i = point.index;
      const Vec2 ubar{0.5 * (particles.u_old[i] + particles.u[i]), 0.5 * (particles.v_old[i] + particles.v[i])};
      ledger.energy.contact += dt_mid * dot(r, ubar);
      ledger.energy.overlap += dt_mid * dot(contact.overlap_reaction_force(point), ubar);
      continue;
    }
    const Index p = point.index;
    const double ubar = 0.5 * (nodes.u_old[p] + nodes.u[p]);
    const double vbar = 0.5 * (nodes.v_old[p] + nodes.v[p]);
    ledger.energy.contact += dt_mid * (r.x * ubar + r.y * vbar);
    const Vec2 overlap = contact.overlap_reaction_force(point);
    ledger.energy.overlap += dt_mid * (overlap.x * ubar + overlap.y * vbar);
    boundary.book_reaction(nodes, p, r, dt_mid, books);
  }
}

}  // namespace krug
