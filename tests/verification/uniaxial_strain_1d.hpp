#pragma once
// An independent reference for plate impact and spall: a one-dimensional Lagrangian code in uniaxial
// strain, written for the test suite and sharing nothing with Krug's kernels (no Krug header is
// included). It solves the same model as a Krug strip between slip walls, by a different scheme:
//   * von Neumann-Richtmyer staggered leapfrog: node velocities at half steps, zone states at whole
//     steps; a zone's axial stress sigma = s - p - q acts on its two nodes;
//   * artificial viscosity of von Neumann-Richtmyer and Landshoff, q = rho (c2 du^2 + c1 c |du|) in
//     compression only (du the zone's velocity jump) - not Krug's edge viscosity;
//     (c2 = 1.5, c1 = 0.3: with c1 = 0.1 the shock rings at the free surface of a Y = 0 target, which
//     the pull-back measure mistakes for the release; the Y = 300 MPa results move by < 2 % between them);
//   * the Mie-Grueneisen equation of state in its common Hugoniot-referenced form (linear Us-up
//     Hugoniot, rho Gamma = rho0 Gamma0; e.g. Meyers, Dynamic Behavior of Materials, 1994, ch. 4):
//       p = rho0 c0^2 mu (1 + (1 - Gamma0/2) mu) / (1 - (s - 1) mu)^2 + rho0 Gamma0 e   (mu > 0)
//       p = rho0 c0^2 mu + rho0 Gamma0 e                                                 (mu <= 0)
//     with mu = rho/rho0 - 1; or a linear bulk modulus (p = K mu);
//   * Prandtl-Reuss elastic-perfectly plastic deviator in uniaxial strain: s_xx' = 4/3 G D,
//     s_yy = s_zz = -s_xx/2, von Mises yield 3/2 |s_xx| <= Y (radial return);
//   * the energy equation m de = -(p + q) dV + s_xx D V dt, with p at the new time solved in closed
//     form (p is linear in e), so that the scheme is the usual time-centred one;
//   * an instantaneous tensile criterion: a zone whose largest principal stress, max(s_xx, -s_xx/2) - p
//     (no q), exceeds sigma_* is damaged for good and keeps only compressive pressure (s = 0,
//     p = max(p, 0)), as in Krug's damage model;
//   * flyer and target as two bodies whose facing nodes stick while they press and part when they
//     pull (a perfectly inelastic node collision: momentum exact).
// Units SI, per unit area.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace krug::verification::reference1d {

struct Material {
  double density = 0.0;            // rho0 (kg/m^3)
  double bulk_sound_speed = 0.0;   // c0 (m/s)
  double hugoniot_slope = 0.0;     // s; 0 with gruneisen 0: linear bulk modulus rho0 c0^2
  double gruneisen = 0.0;          // Gamma0
  double shear_modulus = 0.0;      // G (Pa)
  double yield_stress = 0.0;       // Y (Pa); 0: no deviator at all
  double tensile_stress = std::numeric_limits<double>::infinity();  // sigma_* (Pa)

  // p(rho, e) and the isentropic (dp/drho)_s.
  double pressure(double rho, double e) const {
    const double mu = rho / density - 1.0;
    const double k = density * bulk_sound_speed * bulk_sound_speed;
    double reference = k * mu;
    if (mu > 0.0 && hugoniot_slope > 0.0) {
      const double d = 1.0 - (hugoniot_slope - 1.0) * mu;
      reference = k * mu * (1.0 + (1.0 - 0.5 * gruneisen) * mu) / (d * d);
    }
    return reference + density * gruneisen * e;
  }
  double sound_speed_squared(double rho, double e) const {
    const double h = 1e-7 * density;  // central difference of the reference curve along the isentrope
    const double p = pressure(rho, e);
    const double dp_drho_e = (pressure(rho + h, e) - pressure(rho - h, e)) / (2.0 * h);
    const double dp_de = density * gruneisen;
    return std::max(dp_drho_e + dp_de * p / (rho * rho), 0.0);
  }
};

struct Layer {
  Material material;
  double from = 0.0, to = 0.0;  // initial extent (m)
  int zones = 0;
  std::function<double(double)> velocity;  // initial velocity as a function of the initial position
};

struct Result {
  std::vector<std::pair<double, double>> free_surface;  // (t, velocity of the target's far face)
  double first_damage_time = -1.0;
  double first_damage_position = 0.0;  // initial position of the first damaged zone's centre (m)
  long damaged = 0;
  double initial_momentum = 0.0, final_momentum = 0.0;
};

// Runs flyer (first layer, on the left) onto target (second layer) to end_time.
inline Result run(const Layer& flyer, const Layer& target, double end_time, double cfl = 0.4,
                  double quadratic_q = 1.5, double linear_q = 0.3) {
  // Nodes 0..nf of the flyer, then nf+1..nf+1+nt of the target: two node arrays in one.
  struct Zone {
    const Material* material;
    double mass, x0_centre, rho, e, p, s, q, c2;
    bool damaged;
  };
  std::vector<double> x, u, mass;
  std::vector<Zone> zones;
  std::vector<int> left;  // left node of each zone
  Result result;
  auto add_layer = [&](const Layer& layer) {
    const int first = static_cast<int>(x.size());
    const double h = (layer.to - layer.from) / layer.zones;
    for (int i = 0; i <= layer.zones; ++i) {
      const double xi = layer.from + i * h;
      x.push_back(xi);
      u.push_back(layer.velocity ? layer.velocity(xi) : 0.0);
      mass.push_back(0.0);
    }
    for (int i = 0; i < layer.zones; ++i) {
      const double m = layer.material.density * h;
      Zone z{&layer.material, m, layer.from + (i + 0.5) * h, layer.material.density, 0.0, 0.0, 0.0, 0.0, 0.0, false};
      z.c2 = layer.material.sound_speed_squared(z.rho, 0.0);
      zones.push_back(z);
      left.push_back(first + i);
      mass[first + i] += 0.5 * m;
      mass[first + i + 1] += 0.5 * m;
    }
  };
  add_layer(flyer);
  add_layer(target);
  const int flyer_face = flyer.zones, target_face = flyer.zones + 1, far_face = static_cast<int>(x.size()) - 1;
  for (std::size_t i = 0; i < x.size(); ++i) result.initial_momentum += mass[i] * u[i];

  // Velocities start at t = 0 and are advanced to t = dt/2 with the initial (zero) stresses: the
  // leapfrog's first half step.
  std::vector<double> force(x.size());
  double t = 0.0, dt_previous = 0.0;
  while (t < end_time) {
    // Stable step: longitudinal wave and viscous speeds across each zone.
    double dt = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < zones.size(); ++k) {
      const Zone& z = zones[k];
      const double width = x[left[k] + 1] - x[left[k]];
      const double longitudinal = z.c2 + (z.material->yield_stress > 0.0 ? 4.0 * z.material->shear_modulus / (3.0 * z.rho) : 0.0);
      const double viscous = z.q > 0.0 ? 2.0 * std::sqrt(z.q / z.rho) : 0.0;
      dt = std::min(dt, cfl * width / (std::sqrt(longitudinal) + viscous));
    }
    if (dt_previous > 0.0) dt = std::min(dt, 1.2 * dt_previous);
    dt = std::min(dt, end_time - t);
    // Forces from the zones' stresses at time t.
    std::fill(force.begin(), force.end(), 0.0);
    for (std::size_t k = 0; k < zones.size(); ++k) {
      const double sigma = zones[k].s - zones[k].p - zones[k].q;
      force[left[k]] += sigma;  // M du/dt = sigma(right zone) - sigma(left zone)
      force[left[k] + 1] -= sigma;
    }
    // Velocities to t + dt/2 (from t - dt_previous/2; the first step from t = 0 takes a half step).
    const double step = dt_previous > 0.0 ? 0.5 * (dt + dt_previous) : 0.5 * dt;
    for (std::size_t i = 0; i < x.size(); ++i) u[i] += step * force[i] / mass[i];
    // The flyer's and the target's facing nodes: stuck while pressing (flyer face not slower than the
    // target face, no gap), a perfectly inelastic collision of the two nodes.
    if (x[flyer_face] >= x[target_face] - 1e-15 && u[flyer_face] > u[target_face]) {
      const double common = (mass[flyer_face] * u[flyer_face] + mass[target_face] * u[target_face]) /
                            (mass[flyer_face] + mass[target_face]);
      u[flyer_face] = u[target_face] = common;
    }
    std::vector<double> x_old = x;
    for (std::size_t i = 0; i < x.size(); ++i) x[i] += dt * u[i];
    if (x[flyer_face] > x[target_face]) {  // no overlap: the faces meet
      const double mean = 0.5 * (x[flyer_face] + x[target_face]);
      x[flyer_face] = x[target_face] = mean;
    }
    t += dt;
    // Zone states to t + dt.
    for (std::size_t k = 0; k < zones.size(); ++k) {
      Zone& z = zones[k];
      const Material& m = *z.material;
      const int a = left[k], b = a + 1;
      const double v_old = x_old[b] - x_old[a], v_new = x[b] - x[a];
      const double dv = v_new - v_old;
      const double v_mid = 0.5 * (v_old + v_new);
      const double rate = (u[b] - u[a]) / v_mid;  // D_xx at t + dt/2
      const double rho = z.mass / v_new;
      // Artificial viscosity at the half step, compression only.
      const double du = u[b] - u[a];
      const double rho_mid = z.mass / v_mid;
      z.q = du < 0.0 ? rho_mid * (quadratic_q * du * du + linear_q * std::sqrt(z.c2) * -du) : 0.0;
      // Deviator: elastic trial, then radial return to the yield surface.
      const double s_old = z.s;
      double s_new = 0.0;
      if (!z.damaged && m.yield_stress > 0.0) {
        s_new = s_old + dt * 4.0 / 3.0 * m.shear_modulus * rate;
        const double limit = 2.0 * m.yield_stress / 3.0;
        s_new = std::clamp(s_new, -limit, limit);
      }
      // Energy: m (e1 - e0) = -((p0 + p1)/2 + q) dV + (s0 + s1)/2 dV, with p1 = p(rho, e1) linear in e1.
      const double p0 = z.p;
      const double deviatoric = 0.5 * (s_old + s_new) * dv;
      const double a0 = m.pressure(rho, 0.0), a1 = m.density * m.gruneisen;  // p1 = a0 + a1 e1
      double e1 = (z.mass * z.e - (0.5 * (p0 + a0) + z.q) * dv + deviatoric) / (z.mass + 0.5 * a1 * dv);
      double p1 = a0 + a1 * e1;
      if (z.damaged && p1 < 0.0) {  // a damaged zone carries no tension: redo the energy with p1 = 0
        e1 = z.e + (-(0.5 * p0 + z.q) * dv + deviatoric) / z.mass;
        p1 = 0.0;
      }
      z.rho = rho;
      z.e = e1;
      z.p = p1;
      z.s = s_new;
      z.c2 = m.sound_speed_squared(rho, e1);
      // Fracture on the new stress, without q.
      if (!z.damaged && std::max(z.s, -0.5 * z.s) - z.p > m.tensile_stress) {
        z.damaged = true;
        z.s = 0.0;
        z.p = std::max(z.p, 0.0);
        ++result.damaged;
        if (result.first_damage_time < 0.0) {
          result.first_damage_time = t;
          result.first_damage_position = z.x0_centre;
        }
      }
    }
    result.free_surface.emplace_back(t - 0.5 * dt, u[far_face]);  // velocities live at half steps
    dt_previous = dt;
  }
  for (std::size_t i = 0; i < x.size(); ++i) result.final_momentum += mass[i] * u[i];
  return result;
}

}  // namespace krug::verification::reference1d
