#pragma once
// Free elements: rigid discrete particles made from fractured zones (Gulidov & Shabalin 1996). A
// particle carries mass and momentum; it has no stress and no rotation, and moves by contact
// reactions alone. In axisymmetric geometry a particle is a ring: a disc cross-section in the (z, r)
// plane with the mass (per radian) of the material it came from.
#include <cstdint>
#include <vector>

#include "krug/core/vec2.hpp"

namespace krug {

struct Particles {
  std::vector<double> x, y;                 // centre (m)
  std::vector<double> u, v;                 // velocity at half steps (m/s)
  std::vector<double> u_old, v_old;         // velocity at t^{n-1/2} during a step
  std::vector<double> mass;                 // kg per radian (axisymmetric) or per m (planar)
  std::vector<double> radius;               // m
  std::vector<std::int32_t> body;           // body whose zone it came from
  std::vector<double> birth_time;           // s

  std::int32_t size() const { return static_cast<std::int32_t>(x.size()); }
  Vec2 position(std::int32_t i) const { return {x[i], y[i]}; }
  Vec2 velocity(std::int32_t i) const { return {u[i], v[i]}; }

  void add(Vec2 centre, Vec2 velocity, double particle_mass, double particle_radius, std::int32_t origin,
           double time) {
    x.push_back(centre.x);
    y.push_back(centre.y);
    u.push_back(velocity.x);
    v.push_back(velocity.y);
    u_old.push_back(velocity.x);
    v_old.push_back(velocity.y);
    mass.push_back(particle_mass);
    radius.push_back(particle_radius);
    body.push_back(origin);
    birth_time.push_back(time);
  }
};

// The particles' field registry: each member with its name, in the order checkpoints write them.
// A new member is one line here (checkpoints and their checks walk it); the size check below stops
// the build when a member has none.
template <class ParticlesT, class F>
void for_each_particle_field(ParticlesT& p, F&& f) {
  f("x", p.x);
  f("y", p.y);
  f("u", p.u);
  f("v", p.v);
  f("u_old", p.u_old);
  f("v_old", p.v_old);
  f("mass", p.mass);
  f("radius", p.radius);
  f("body", p.body);
  f("birth_time", p.birth_time);
}
static_assert(sizeof(std::vector<double>) != 24 || sizeof(Particles) == 10 * 24,
              "Particles changed: add the field to for_each_particle_field");

}  // namespace krug
