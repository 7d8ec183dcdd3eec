#include "krug/run/penetration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "krug/core/error.hpp"

namespace krug::run {

namespace {

double along(Vec2 v, int axis) { return axis == 0 ? v.x : v.y; }

const Body& body_of(const Simulation& simulation, Index b) { return simulation.bodies()[static_cast<std::size_t>(b)]; }

// The most and the least advanced coordinate, along the impact direction, of a box.
double advanced(Vec2 lo, Vec2 hi, const PenetrationRecord& r) {
  return r.direction > 0.0 ? along(hi, r.axis) : -along(lo, r.axis);
}
double retreated(Vec2 lo, Vec2 hi, const PenetrationRecord& r) {
  return r.direction > 0.0 ? along(lo, r.axis) : -along(hi, r.axis);
}

}  // namespace

PenetrationRecord start_penetration(const Simulation& simulation, const PenetrationSetup& setup) {
  const Body& projectile = body_of(simulation, setup.projectile);
  const BodySummary p = simulation.summarise(projectile);
  PenetrationRecord r;
  r.axis = simulation.geometry() == GeometryKind::axisymmetric || std::abs(p.velocity.x) >= std::abs(p.velocity.y) ? 0 : 1;
  const double speed = along(p.velocity, r.axis);
  if (!(std::abs(speed) > 0.0)) {
    throw InputError(fmt::format("penetration.projectile: body \"{}\" has no initial velocity along the {} axis",
                                 projectile.name, r.axis == 0 ? "first" : "second"));
  }
  r.direction = speed > 0.0 ? 1.0 : -1.0;
  r.front = std::numeric_limits<double>::infinity();
  r.rear = -std::numeric_limits<double>::infinity();
  for (const Index t : setup.targets) {
    const BodySummary s = simulation.summarise(body_of(simulation, t));
    r.front = std::min(r.front, retreated(s.bbox_min, s.bbox_max, r));
    r.rear = std::max(r.rear, advanced(s.bbox_min, s.bbox_max, r));
  }
  r.deepest = advanced(p.bbox_min, p.bbox_max, r);
  r.initial_speed = r.direction * speed;
  return r;
}

PenetrationMoment measure_penetration(const Simulation& simulation, const PenetrationSetup& setup,
                                      const PenetrationRecord& record) {
  PenetrationMoment m;
  const std::vector<Fragment> pieces = simulation.fragments(body_of(simulation, setup.projectile));
  if (pieces.empty()) {  // the whole projectile has left the grid
    m.nose = m.tail = -std::numeric_limits<double>::infinity();
  } else {
    m.nose = advanced(pieces.front().bbox_min, pieces.front().bbox_max, record);
    m.tail = retreated(pieces.front().bbox_min, pieces.front().bbox_max, record);
  }
  m.target_rear = -std::numeric_limits<double>::infinity();
  for (const Index t : setup.targets) {
    const std::vector<Fragment> target = simulation.fragments(body_of(simulation, t));
    if (target.empty()) continue;
    m.target_rear = std::max(m.target_rear, advanced(target.front().bbox_min, target.front().bbox_max, record));
  }
  return m;
}

void observe_penetration(const Simulation& simulation, const PenetrationSetup& setup, const BodySummary& p,
                         PenetrationRecord& record) {
  if (p.zones == 0) return;
  const double nose = advanced(p.bbox_min, p.bbox_max, record);
  record.deepest = std::max(record.deepest, nose);
  // The pieces are found every fourth cycle (the perforation time is known to 4 steps) once the nose
  // has passed the targets' initial rear face, until the perforation.
  if (record.perforation_time >= 0.0 || nose <= record.rear || simulation.cycle() % 4 != 0) return;
  if (measure_penetration(simulation, setup, record).perforated()) record.perforation_time = simulation.time();
}

PenetrationReport report_penetration(const Simulation& simulation, const PenetrationSetup& setup,
                                     const PenetrationRecord& record) {
  const double whole = simulation.whole_body_factor();
  const Body& projectile = body_of(simulation, setup.projectile);
  PenetrationReport r;
  r.projectile = projectile.name;
  r.perforation_time = record.perforation_time;
  r.perforated = record.perforation_time >= 0.0 || measure_penetration(simulation, setup, record).perforated();
  if (r.perforated && r.perforation_time < 0.0) r.perforation_time = simulation.time();
  r.depth = std::max(0.0, record.deepest - record.front);

  const NodeFields& nodes = simulation.mesh().nodes;
  const ZoneFields& zones = simulation.mesh().zones;
  double initial_mass = 0.0;
  for (Index z = projectile.zone_begin; z < projectile.zone_end; ++z) initial_mass += zones.mass[z];
  r.initial_mass = whole * initial_mass;
  const std::vector<Fragment> pieces = simulation.fragments(projectile);
  if (!pieces.empty()) {
    r.residual_mass = pieces.front().mass;
    r.residual_velocity_vector = pieces.front().velocity;
    r.residual_velocity = record.direction * along(pieces.front().velocity, record.axis);
    r.projectile_kinetic_energy = 0.5 * r.residual_mass * dot(r.residual_velocity_vector, r.residual_velocity_vector);
  }
  r.mass_lost = r.initial_mass - r.residual_mass;
  r.eroded_mass = whole * simulation.fracture_counts(setup.projectile).eroded_mass;

  // The whole projectile: its nodes (nodal masses carry every zone still on the grid) and the free
  // elements made from its zones.
  const Particles& particles = simulation.particles();
  double node_mass = 0.0, node_momentum = 0.0, back_mass = 0.0, back_momentum = 0.0;
  for (Index n = projectile.node_begin; n < projectile.node_end; ++n) {
    const double along_n = record.direction * along(Vec2{nodes.u[n], nodes.v[n]}, record.axis);
    node_mass += nodes.mass[n];
    node_momentum += nodes.mass[n] * along_n;
    if (along_n < 0.0) {
      back_mass += nodes.mass[n];
      back_momentum += nodes.mass[n] * along_n;
    }
  }
  double free_mass = 0.0, free_momentum = 0.0;
  for (Index i = 0; i < particles.size(); ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    if (particles.body[k] != setup.projectile) continue;
    const double along_p = record.direction * along(particles.velocity(i), record.axis);
    free_mass += particles.mass[k];
    free_momentum += particles.mass[k] * along_p;
    if (along_p < 0.0) {
      back_mass += particles.mass[k];
      back_momentum += particles.mass[k] * along_p;
    }
  }
  r.initial_speed = record.initial_speed;
  r.whole_mass = whole * (node_mass + free_mass);
  r.whole_velocity = node_mass + free_mass > 0.0 ? (node_momentum + free_momentum) / (node_mass + free_mass) : 0.0;
  r.free_element_mass = whole * free_mass;
  r.free_element_velocity = free_mass > 0.0 ? free_momentum / free_mass : 0.0;
  r.backward_mass = whole * back_mass;
  r.backward_velocity = back_mass > 0.0 ? back_momentum / back_mass : 0.0;
  if (r.initial_speed > 0.0) {
    r.piece_velocity_loss = (r.initial_speed - r.residual_velocity) / r.initial_speed;
    r.whole_velocity_loss = (r.initial_speed - r.whole_velocity) / r.initial_speed;
  }

  for (const Index t : setup.targets) {
    const Body& target = body_of(simulation, t);
    const std::vector<Fragment> target_pieces = simulation.fragments(target);
    if (target_pieces.size() > 1 && target_pieces[1].mass > r.plug_mass) {
      r.plug_body = target.name;
      r.plug_mass = target_pieces[1].mass;
      r.plug_velocity = record.direction * along(target_pieces[1].velocity, record.axis);
    }
    r.target_plastic_work += whole * simulation.plastic_work(t);
    double kinetic = 0.0;
    for (Index n = target.node_begin; n < target.node_end; ++n) {
      kinetic += nodes.mass[n] * (nodes.u[n] * nodes.u[n] + nodes.v[n] * nodes.v[n]);
    }
    for (Index i = 0; i < particles.size(); ++i) {
      if (particles.body[static_cast<std::size_t>(i)] != t) continue;
      kinetic += particles.mass[static_cast<std::size_t>(i)] * dot(particles.velocity(i), particles.velocity(i));
    }
    r.target_kinetic_energy += 0.5 * whole * kinetic;
  }
  r.target_energy_absorbed = r.target_plastic_work + r.target_kinetic_energy;
  return r;
}

}  // namespace krug::run
