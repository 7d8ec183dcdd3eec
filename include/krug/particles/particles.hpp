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

}  // namespace krug
