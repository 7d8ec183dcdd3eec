#include "krug/boundary/boundary.hpp"

namespace krug::boundary {

Boundary::Boundary(std::vector<NodeConstraint> constraints, std::vector<DrivenComponent> driven,
                   std::vector<FaceLoad> loads, std::vector<HeldSide> held_sides)
    : constraints_(std::move(constraints)),
      driven_(std::move(driven)),
      loads_(std::move(loads)),
      held_sides_(std::move(held_sides)) {}

void Boundary::initialise(NodeFields& nodes, GeometryKind geometry) {
  const auto size = static_cast<std::size_t>(nodes.size());
  if (geometry == GeometryKind::axisymmetric) {
    for (Index p = 0; p < nodes.size(); ++p) {
      if (nodes.y[p] == 0.0) {
        nodes.v[p] = 0.0;
        constraints_.push_back({p, false, true});
      }
    }
  }
  held_x_.assign(size, 0);
  held_y_.assign(size, 0);
  for (const NodeConstraint& c : constraints_) {
    if (c.fix_x) held_x_[static_cast<std::size_t>(c.node)] = 1;
    if (c.fix_y) held_y_[static_cast<std::size_t>(c.node)] = 1;
  }
  // A driven component is held: one that no constraint lists yet (a scene built in C++ may give it
  // alone) gets its constraint here.
  for (const DrivenComponent& d : driven_) {
    for (const Index n : d.nodes) {
      const auto p = static_cast<std::size_t>(n);
      if (!(d.component == 0 ? held_x_[p] : held_y_[p])) constraints_.push_back({n, d.component == 0, d.component == 1});
      (d.component == 0 ? held_x_ : held_y_)[p] = 1;
    }
  }
  for (const NodeConstraint& c : constraints_) {
    if (c.fix_x) { nodes.inv_mass_x[c.node] = 0.0; held_x_[static_cast<std::size_t>(c.node)] = 1; }
    if (c.fix_y) { nodes.inv_mass_y[c.node] = 0.0; held_y_[static_cast<std::size_t>(c.node)] = 1; }
  }
  driven_x_.assign(size, 0);
  driven_y_.assign(size, 0);
  for (const DrivenComponent& d : driven_) {
    for (const Index n : d.nodes) (d.component == 0 ? driven_x_ : driven_y_)[static_cast<std::size_t>(n)] = 1;
  }
}

void Boundary::apply_loads(NodeFields& nodes, const ZoneFields& zones, GeometryKind geometry, double time) {
  applied_.clear();
  for (const FaceLoad& load : loads_) {
    const double pressure = load.pressure ? load.pressure(time) : 0.0;
    const double traction = load.traction ? load.traction(time) : 0.0;
    for (const BoundarySegment& s : load.segments) {
      if (!zones.active[s.zone]) continue;  // the face left with its zone
      const std::array<Vec2, 2> f = segment_load(nodes.position(s.a), nodes.position(s.b), pressure, traction, geometry);
      applied_.push_back({s.a, f[0]});
      applied_.push_back({s.b, f[1]});
    }
  }
  // Summed in the order of the loads and segments (the same bits on any number of threads).
  for (const NodeLoad& l : applied_) {
    nodes.force_x[l.node] += l.force.x;
    nodes.force_y[l.node] += l.force.y;
  }
}

void Boundary::hold(NodeFields& nodes, double t_mid, double dt_mid, Books books) const {
  for (const DrivenComponent& d : driven_) {
    const double value = d.value(t_mid);  // once per step and side
    std::vector<double>& u = d.component == 0 ? nodes.u : nodes.v;
    for (const Index n : d.nodes) u[n] = value;
  }
  // A held component: the boundary supplies F_b = M (u^{n+1/2} - u^{n-1/2}) / dt^n - F, whose work is
  // F_b ubar dt^n; for a constant value (u^{n+1/2} = u^{n-1/2}) that is -F u dt^n.
  auto driven_work = [&](double mass, double force, double u_old, double u_new) {
    const double ubar = 0.5 * (u_old + u_new);
    return mass * ubar * (u_new - u_old) - dt_mid * force * ubar;
  };
  for (const NodeConstraint& c : constraints_) {
    const auto p = static_cast<std::size_t>(c.node);
    if (c.fix_x) {
      if (driven_x_[p]) {
        books.work += driven_work(nodes.mass[c.node], nodes.force_x[c.node], nodes.u_old[c.node], nodes.u[c.node]);
        books.axial_impulse += nodes.mass[c.node] * (nodes.u[c.node] - nodes.u_old[c.node]) - dt_mid * nodes.force_x[c.node];
      } else {
        books.work -= dt_mid * nodes.force_x[c.node] * nodes.u[c.node];
        books.axial_impulse -= dt_mid * nodes.force_x[c.node];
      }
    }
    if (c.fix_y) {
      if (driven_y_[p]) {
        books.work += driven_work(nodes.mass[c.node], nodes.force_y[c.node], nodes.v_old[c.node], nodes.v[c.node]);
      } else {
        books.work -= dt_mid * nodes.force_y[c.node] * nodes.v[c.node];
      }
    }
  }
}

void Boundary::book_reaction(const NodeFields& nodes, Index p, Vec2 r, double dt_mid, Books books) const {
  // ubar is u itself on a component held at a constant value.
  if (held_x_[static_cast<std::size_t>(p)]) {
    books.work -= dt_mid * r.x * (0.5 * (nodes.u_old[p] + nodes.u[p]));
    books.axial_impulse -= dt_mid * r.x;
  }
  if (held_y_[static_cast<std::size_t>(p)]) books.work -= dt_mid * r.y * (0.5 * (nodes.v_old[p] + nodes.v[p]));
}

void Boundary::book_loads(const NodeFields& nodes, double dt_mid, Books books) const {
  for (const NodeLoad& l : applied_) {
    const double ubar = 0.5 * (nodes.u_old[l.node] + nodes.u[l.node]);
    const double vbar = 0.5 * (nodes.v_old[l.node] + nodes.v[l.node]);
    books.work += dt_mid * (l.force.x * ubar + l.force.y * vbar);
    books.axial_impulse += dt_mid * l.force.x;
  }
}

}  // namespace krug::boundary
