// The stalled sweeps' pushing contacts solved together (ContactSolver::solve_pushing_together,
// contact.solve_stalled; docs/verification.md, Contact, C2).
#include "krug/contact/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace krug::contact {

bool ContactSolver::solve_pushing_together(double dt_mid, double dt_next) {
  std::vector<Index>& set = together_;
  set.clear();
  for (Index k : working_) {
    const Candidate& c = candidates_[static_cast<std::size_t>(k)];
    if (c.friction > 0.0 && c.normal > 0.0) return false;  // Coulomb's bound is not linear: left to the sweeps
    if (c.normal > 0.0 && c.kind != Kind::wall) set.push_back(k);
  }
  if (set.empty()) return false;
  const std::size_t n = set.size();
  const std::size_t nodes = reaction_x_.size();  // one per mesh node
  together_point_.assign(nodes + static_cast<std::size_t>(particles_.size), Vec2{});
  const auto slot = [&](ContactPoint p) {
    return p.is_particle() ? nodes + static_cast<std::size_t>(p.index) : static_cast<std::size_t>(p.index);
  };
  std::vector<Geometry> geometry(n);
  together_rhs_.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
    geometry[i] = contact_geometry(c, dt_next);
    if (!geometry[i].valid) return false;
    together_rhs_[i] = -(geometry[i].gap - overlap_target(geometry[i].start_gap, dt_next)) / (dt_mid * dt_next);
  }
  // q = W v: the forces v along the normals, to the points, through the inverse masses, back along the normals.
  const auto apply_w = [&](const std::vector<double>& v, std::vector<double>& q) {
    for (std::size_t i = 0; i < n; ++i) {
      const Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
      const Vec2 f = v[i] * geometry[i].normal;
      together_point_[slot(c.node)] += f;
      if (c.a.exists()) together_point_[slot(c.a)] -= (1.0 - geometry[i].xi) * f;
      if (c.b.exists()) together_point_[slot(c.b)] -= geometry[i].xi * f;
    }
    const auto velocity_change = [&](ContactPoint p) {
      const InverseMass w = inverse_mass(p);
      const Vec2 f = together_point_[slot(p)];
      return Vec2{w.x * f.x, w.y * f.y};
    };
    for (std::size_t i = 0; i < n; ++i) {
      const Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
      Vec2 du = velocity_change(c.node);
      if (c.a.exists()) du -= (1.0 - geometry[i].xi) * velocity_change(c.a);
      if (c.b.exists()) du -= geometry[i].xi * velocity_change(c.b);
      q[i] = dot(geometry[i].normal, du);
    }
    for (std::size_t i = 0; i < n; ++i) {  // clear the points touched
      const Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
      together_point_[slot(c.node)] = {};
      if (c.a.exists()) together_point_[slot(c.a)] = {};
      if (c.b.exists()) together_point_[slot(c.b)] = {};
    }
  };
  // The largest violation, relative to the contact's length, of gaps missing their targets by
  // `residual` (in the units of the right-hand side) where reactions push; of penetrations elsewhere.
  const auto worst_of = [&](const std::vector<double>& residual, const std::vector<double>& totals) {
    double worst = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double length = std::max(candidates_[static_cast<std::size_t>(set[i])].length, 1e-300);
      const double miss = residual[i] * dt_mid * dt_next / length;  // target - gap, relative
      worst = std::max(worst, totals[i] > 0.0 ? std::abs(miss) : miss);
    }
    return worst;
  };
  // Conjugate gradients from dR = 0 until the residual is 1e-13 of the first (far below the gap
  // tolerance: a loose stop here is the tolerance's residue in every later step), W sees no more of
  // the search direction, or the residual grows (a right-hand side W cannot meet: contacts that ask
  // for gaps no reactions give); the iterate with the smallest violation is kept.
  std::vector<double>&x = together_x_, &r = together_r_, &p = together_p_, &q = together_q_;
  x.assign(n, 0.0);
  r = together_rhs_;
  p = r;
  q.assign(n, 0.0);
  std::vector<double> best(n, 0.0), ones(n, 1.0);
  double best_worst = worst_of(r, ones);
  double rr = 0.0;
  for (double v : r) rr += v * v;
  const double stop = 1e-26 * rr;
  const int limit = static_cast<int>(std::min<std::size_t>(4 * n + 10, 2000));
  for (int iteration = 0; iteration < limit && rr > stop; ++iteration) {
    apply_w(p, q);
    double pq = 0.0;
    for (std::size_t i = 0; i < n; ++i) pq += p[i] * q[i];
    if (!(pq > 0.0)) break;
    const double alpha = rr / pq;
    double next = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      next += r[i] * r[i];
    }
    const double worst = worst_of(r, ones);
    if (worst < best_worst) {
      best_worst = worst;
      best = x;
    } else if (worst > 100.0 * best_worst) {
      break;
    }
    const double beta = next / rr;
    rr = next;
    for (std::size_t i = 0; i < n; ++i) p[i] = r[i] + beta * p[i];
  }
  // The changes, clamped where a total would pull, and kept only if the linear model says they at
  // least halve the largest violation of these contacts.
  std::vector<double> change(n), totals(n), current(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double normal = candidates_[static_cast<std::size_t>(set[i])].normal;
    totals[i] = std::max(0.0, normal + best[i]);
    change[i] = totals[i] - normal;
    current[i] = normal;
  }
  apply_w(change, q);
  for (std::size_t i = 0; i < n; ++i) r[i] = together_rhs_[i] - q[i];
  if (!(worst_of(r, totals) < 0.5 * worst_of(together_rhs_, current))) return false;
  // The new totals, applied as a sweep applies them (frictionless: the tangential reaction stays 0).
  for (std::size_t i = 0; i < n; ++i) {
    Candidate& c = candidates_[static_cast<std::size_t>(set[i])];
    replace_reaction(c, geometry[i], totals[i], c.tangent, dt_mid);
  }
  return true;
}

}  // namespace krug::contact
