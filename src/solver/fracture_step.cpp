// Steps 6 and 7 of the time step (docs/architecture.md): fracture criteria on intact zones (the
// fracture module's driver, fracture/damage.hpp), and the conversion of fully fractured zones into free
// elements (Gulidov & Shabalin 1996).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>
#include <variant>

#include "krug/fracture/damage.hpp"
#include "krug/particles/conversion.hpp"
#include "krug/solver/simulation.hpp"

namespace krug {

namespace {

bool has_inverted_corner(const quad::Corners& x, const ZoneCorners& n) {
  for (int p = 0; p < 4; ++p) {
    if (n[p] == n[quad::next(p)] || n[p] == n[quad::prev(p)]) continue;  // the repeated corner of a triangle
    if (cross(x[quad::next(p)] - x[p], x[quad::prev(p)] - x[p]) <= 0.0) return true;
  }
  return false;
}

// ErosionLimits::collapsed on quad::smallest_altitude, with a test first that needs neither the square
// root nor the division: area^2 > (ratio h0)^2 longest^2 (with a relative margin of 1e-9, far above the
// rounding) means the altitude is above its limit. Otherwise the altitude is computed as before.
bool collapsed(const fracture::ErosionLimits& erosion, const quad::Corners& x, double area, double initial_altitude) {
  const double limit = erosion.altitude_ratio * initial_altitude;
  double longest = 0.0;
  for (int p = 0; p < 4; ++p) {
    const Vec2 e = x[quad::next(p)] - x[p];
    longest = std::max(longest, dot(e, e));
  }
  if (area > 0.0 && area * area > (limit * limit) * longest * (1.0 + 1e-9)) return false;
  return erosion.collapsed(quad::smallest_altitude(x, area), initial_altitude);
}

}  // namespace

void Simulation::evaluate_fracture() {
  const double now = state_.time + state_.time_step_next;  // the state just computed is at t^{n+1}
  const double dt = state_.time_step_next;                  // the step over which the plastic strain grew
  const std::vector<double>& energy = state_.mesh.zones.specific_energy;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!fracture::enabled(failure_laws_[b])) continue;
    const Body& body = bodies_[b];
    const Material& material = materials_[static_cast<std::size_t>(body.material)];
    // One dispatch per body on the law and the strength model (which alone knows a temperature).
    state_.fracture_counts[b].damaged += std::visit(
        [&](const auto& law, const auto& strength) {
          using S = std::decay_t<decltype(strength)>;
          if constexpr (std::is_same_v<S, JohnsonCook>) {
            return fracture::damage_zones(state_.mesh, body.zone_begin, body.zone_end, law, geometry_, now, dt,
                                          [&](Index z) { return strength.temperature_from_energy(energy[z]); });
          } else {
            return fracture::damage_zones(state_.mesh, body.zone_begin, body.zone_end, law, geometry_, now, dt);
          }
        },
        failure_laws_[b], material.strength);
  }
}

bool Simulation::face_is_free(Index zone, int edge) const {
  const ZoneCorners& n = state_.mesh.zones.corners[zone];
  const Index a = n[edge], b = n[quad::next(edge)];
  if (a == b || state_.mesh.zones.neighbour[zone][edge] >= 0) return false;
  // Not on the axis, a symmetry plane or a fixed rim: both ends held in the same direction.
  const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
  return !((boundary_.held_x()[ua] && boundary_.held_x()[ub]) || (boundary_.held_y()[ua] && boundary_.held_y()[ub]));
}

void Simulation::convert_fractured_zones() {
  ZoneFields& zones = state_.mesh.zones;
  const FractureControls& fc = controls_.fracture;
  bool any_damaged = false;
  for (Index z = 0; z < zones.size() && !any_damaged; ++z) any_damaged = zones.active[z] && zones.damaged[z];
  std::vector<std::pair<Index, ConversionRule>> chosen;
  // Erosion on distortion: intact zones of bodies that ask for it, collapsed below their ratio.
  for (const Body& body : bodies_) {
    const fracture::ErosionLimits erosion = body.erosion();
    if (!erosion.any()) continue;
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      if (!zones.active[z] || zones.damaged[z]) continue;
      const quad::Corners x = state_.mesh.corner_positions(z);
      if (erosion.strained(zones.plastic_strain[z]) ||
          collapsed(erosion, x, zones.area[z], zones.initial_altitude[z]) ||
          has_inverted_corner(x, zones.corners[z])) {
        chosen.emplace_back(z, ConversionRule::erosion);
      }
    }
  }
  if (!any_damaged && chosen.empty()) return;
  // Damaged zones whose step is below time_step_floor_ratio x the median zone step (of the active
  // zones) convert instead of driving dt. The median is needed only if the smallest step of a damaged
  // zone can be below that floor: with r x v rounded (monotone in v), the floor r x median is at most
  // that smallest step when more than half of the active zones have r x step at most it, and then no
  // damaged zone is below it. Otherwise the median is taken as before.
  const double ratio = fc.time_step_floor_ratio;
  double median_step = 0.0;
  if (any_damaged) {
    double smallest_damaged = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      if (!fracture::enabled(failure_laws_[b])) continue;
      for (Index z = bodies_[b].zone_begin; z < bodies_[b].zone_end; ++z) {
        if (zones.active[z] && zones.damaged[z]) smallest_damaged = std::min(smallest_damaged, zones.stable_time_step[z]);
      }
    }
    Index active = 0, below = 0;
    for (Index z = 0; z < zones.size(); ++z) {
      if (!zones.active[z]) continue;
      ++active;
      below += ratio * zones.stable_time_step[z] <= smallest_damaged ? 1 : 0;
    }
    if (below <= active / 2) {
      std::vector<double> steps;
      steps.reserve(static_cast<std::size_t>(active));
      for (Index z = 0; z < zones.size(); ++z) {
        if (zones.active[z]) steps.push_back(zones.stable_time_step[z]);
      }
      std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
      median_step = steps[steps.size() / 2];
    }
  }

  // Choose the whole layer first, then convert: one boundary layer per step.
  for (std::size_t b = 0; b < bodies_.size() && any_damaged; ++b) {
    if (!fracture::enabled(failure_laws_[b])) continue;
    const Body& body = bodies_[b];
    const double reference_density = materials_[static_cast<std::size_t>(body.material)].reference_density;
    const double loosening_limit = fracture::loosening_limit(failure_laws_[b]);
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      if (!zones.active[z] || !zones.damaged[z]) continue;
      const quad::Corners x = state_.mesh.corner_positions(z);
      const double altitude = quad::smallest_altitude(x, zones.area[z]);
      const double chi = fracture::loosening(zones.density[z], reference_density);
      const bool fully = fracture::fully_fractured(chi, loosening_limit, altitude,
                                                   zones.initial_altitude[z], fc.altitude_ratio);
      bool on_surface = false;
      for (int k = 0; k < 4 && !on_surface; ++k) on_surface = face_is_free(z, k);
      if (fully && on_surface) {
        chosen.emplace_back(z, ConversionRule::surface);
      } else if (altitude < fc.interior_altitude_ratio * zones.initial_altitude[z] ||
                 has_inverted_corner(x, zones.corners[z]) ||
                 zones.stable_time_step[z] < ratio * median_step) {
        chosen.emplace_back(z, ConversionRule::interior);  // a documented deviation from the paper, counted
      }
    }
  }
  if (chosen.empty()) return;
  for (const auto& [z, rule] : chosen) convert_zone(z, rule);
  topology_changed_ = true;
  // The step limit now comes from the zones that remain.
  state_.stable_time_step = std::numeric_limits<double>::infinity();
  for (Index z = 0; z < zones.size(); ++z) {
    if (zones.active[z] && zones.stable_time_step[z] < state_.stable_time_step) {
      state_.stable_time_step = zones.stable_time_step[z];
      state_.controlling_zone = z;
    }
  }
  measure_ledger(state_.mesh, state_.particles, state_.ledger);
}

void Simulation::convert_zone(Index z, ConversionRule rule) {
  const double mass = state_.mesh.zones.mass[z];
  const std::size_t b = static_cast<std::size_t>(state_.mesh.zones.body[z]);
  const ConversionEnergy energy =
      convert_zone_to_particles(state_.mesh, state_.particles, z, controls_.fracture.particles_per_zone,
                                state_.time + state_.time_step_next, state_.zones_per_node, boundary_.held_x(), boundary_.held_y());
  state_.ledger.energy.converted += energy.converted();
  state_.body_converted_energy[b] += energy.converted();
  state_.ledger.energy.internal -= energy.internal;
  if (rule == ConversionRule::erosion) {
    ++state_.fracture_counts[b].eroded;
    state_.fracture_counts[b].eroded_mass += mass;
    return;
  }
  ++state_.fracture_counts[b].converted;
  if (rule == ConversionRule::interior) ++state_.fracture_counts[b].interior_conversions;
  state_.fracture_counts[b].converted_mass += mass;
}

std::vector<Fragment> Simulation::fragments(const Body& body) const {
  std::vector<Fragment> pieces = connected_pieces(state_.mesh, body.zone_begin, body.zone_end);
  for (Fragment& f : pieces) f.mass *= whole_body_factor();
  std::sort(pieces.begin(), pieces.end(), [](const Fragment& a, const Fragment& b) { return a.mass > b.mass; });
  return pieces;
}

}  // namespace krug
