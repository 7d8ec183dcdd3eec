// Steps 6 and 7 of the time step (krug/solver/fracture_step.hpp): failure laws on intact zones (the
// fracture module's driver, fracture/damage.hpp), and the conversion of fully fractured zones into free
// elements (Gulidov & Shabalin 1996).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <type_traits>
#include <variant>

#include "krug/fracture/damage.hpp"
#include "krug/particles/conversion.hpp"
#include "krug/solver/fracture_step.hpp"
#include "krug/solver/parallel.hpp"

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

// A face of a zone on the body's free surface: no zone across it, not collapsed, and not on the axis,
// a symmetry plane or a held rim (both ends held in the same direction).
bool face_is_free(const ZoneFields& zones, Index zone, int edge, const std::vector<std::uint8_t>& held_x,
                  const std::vector<std::uint8_t>& held_y) {
  const ZoneCorners& n = zones.corners[zone];
  const Index a = n[edge], b = n[quad::next(edge)];
  if (a == b || zones.neighbour[zone][edge] >= 0) return false;
  const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
  return !((held_x[ua] && held_x[ub]) || (held_y[ua] && held_y[ub]));
}

}  // namespace

void evaluate_failure_laws(const Mesh& mesh, ZoneState& state, const std::vector<Body>& bodies,
                           const std::vector<Material>& materials, const std::vector<fracture::FailureLaw>& laws,
                           GeometryKind geometry, double now, double dt, std::vector<FractureCounts>& counts,
                           int threads, const std::vector<fracture::InitialShape>& shapes) {
  const std::vector<double>& energy = mesh.zones.specific_energy;
  const fracture::InitialShape* shape = shapes.size() == static_cast<std::size_t>(mesh.zones.size()) ? shapes.data() : nullptr;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!fracture::enabled(laws[b])) continue;
    const Body& body = bodies[b];
    const Material& material = materials[static_cast<std::size_t>(body.material)];
    // One dispatch per body on the law and the strength model (which alone knows a temperature).
    const auto in_block = [&](Index first, Index last) {
      return std::visit(
          [&](const auto& law, const auto& strength) {
            using S = std::decay_t<decltype(strength)>;
            if constexpr (std::is_same_v<S, JohnsonCook>) {
              return fracture::damage_zones(mesh, state, first, last, law, geometry, now, dt,
                                            [&](Index z) { return strength.temperature_from_energy(energy[z]); }, shape);
            } else {
              return fracture::damage_zones(mesh, state, first, last, law, geometry, now, dt, fracture::NoTemperature{},
                                            shape);
            }
          },
          laws[b], material.strength);
    };
    const std::vector<long> damaged = block_results<long>(body.zone_begin, body.zone_end, threads, in_block);
    counts[b].damaged += std::accumulate(damaged.begin(), damaged.end(), 0L);
  }
}

std::vector<Conversion> choose_conversions(const Mesh& mesh, const ZoneState& state, const std::vector<Body>& bodies,
                                           const std::vector<Material>& materials,
                                           const std::vector<fracture::FailureLaw>& laws,
                                           const FractureControls& fc, const std::vector<std::uint8_t>& held_x,
                                           const std::vector<std::uint8_t>& held_y, int threads) {
  const ZoneFields& zones = mesh.zones;
  bool any_damaged = false;
  for (Index z = 0; z < zones.size() && !any_damaged; ++z) any_damaged = zones.active[z] && state.fracture.damaged[z];
  std::vector<Conversion> chosen;
  // The zones of [begin, end) that choose(z) picks, in zone order, found in blocks on the threads.
  const auto choose_in = [&](Index begin, Index end, auto choose) {
    const auto blocks = block_results<std::vector<Conversion>>(begin, end, threads, [&](Index first, Index last) {
      std::vector<Conversion> found;
      for (Index z = first; z < last; ++z) {
        if (const auto rule = choose(z)) found.push_back({z, *rule});
      }
      return found;
    });
    for (const std::vector<Conversion>& found : blocks) chosen.insert(chosen.end(), found.begin(), found.end());
  };
  // Erosion on distortion: intact zones of bodies that ask for it, collapsed below their ratio.
  for (const Body& body : bodies) {
    const fracture::ErosionLimits erosion = body.erosion();
    if (!erosion.any()) continue;
    choose_in(body.zone_begin, body.zone_end, [&](Index z) -> std::optional<ConversionRule> {
      if (!zones.active[z] || state.fracture.damaged[z]) return std::nullopt;
      const quad::Corners x = mesh.corner_positions(z);
      if (erosion.strained(state.strength.plastic_strain[z]) ||
          collapsed(erosion, x, zones.area[z], zones.initial_altitude[z]) ||
          has_inverted_corner(x, zones.corners[z])) {
        return ConversionRule::erosion;
      }
      return std::nullopt;
    });
  }
  if (!any_damaged) return chosen;
  // Damaged zones whose step is below time_step_floor_ratio x the median zone step (of the active
  // zones) convert instead of driving dt. The median is needed only if the smallest step of a damaged
  // zone can be below that floor: with r x v rounded (monotone in v), the floor r x median is at most
  // that smallest step when more than half of the active zones have r x step at most it, and then no
  // damaged zone is below it. Otherwise the median is taken as before.
  const double ratio = fc.time_step_floor_ratio;
  double median_step = 0.0;
  {
    double smallest_damaged = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (!fracture::enabled(laws[b])) continue;
      for (Index z = bodies[b].zone_begin; z < bodies[b].zone_end; ++z) {
        if (zones.active[z] && state.fracture.damaged[z]) {
          smallest_damaged = std::min(smallest_damaged, state.hydro.stable_time_step[z]);
        }
      }
    }
    Index active = 0, below = 0;
    for (Index z = 0; z < zones.size(); ++z) {
      if (!zones.active[z]) continue;
      ++active;
      below += ratio * state.hydro.stable_time_step[z] <= smallest_damaged ? 1 : 0;
    }
    if (below <= active / 2) {
      std::vector<double> steps;
      steps.reserve(static_cast<std::size_t>(active));
      for (Index z = 0; z < zones.size(); ++z) {
        if (zones.active[z]) steps.push_back(state.hydro.stable_time_step[z]);
      }
      std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
      median_step = steps[steps.size() / 2];
    }
  }

  // Choose the whole layer first, then convert: one boundary layer per step.
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!fracture::enabled(laws[b])) continue;
    const Body& body = bodies[b];
    const double reference_density = materials[static_cast<std::size_t>(body.material)].reference_density;
    const double loosening_limit = fracture::loosening_limit(laws[b]);
    choose_in(body.zone_begin, body.zone_end, [&](Index z) -> std::optional<ConversionRule> {
      if (!zones.active[z] || !state.fracture.damaged[z]) return std::nullopt;
      const quad::Corners x = mesh.corner_positions(z);
      const double altitude = quad::smallest_altitude(x, zones.area[z]);
      const double chi = fracture::loosening(zones.density[z], reference_density);
      const bool fully = fracture::fully_fractured(chi, loosening_limit, altitude,
                                                   zones.initial_altitude[z], fc.altitude_ratio);
      bool on_surface = false;
      for (int k = 0; k < 4 && !on_surface; ++k) on_surface = face_is_free(zones, z, k, held_x, held_y);
      if (fully && on_surface) return ConversionRule::surface;
      if (altitude < fc.interior_altitude_ratio * zones.initial_altitude[z] ||
          has_inverted_corner(x, zones.corners[z]) || state.hydro.stable_time_step[z] < ratio * median_step) {
        return ConversionRule::interior;  // a documented deviation from the paper, counted
      }
      return std::nullopt;
    });
  }
  return chosen;
}

void convert_zones(const std::vector<Conversion>& chosen, Mesh& mesh, Particles& particles, int particles_per_zone,
                   double time, std::vector<Index>& zones_per_node, const std::vector<std::uint8_t>& held_x,
                   const std::vector<std::uint8_t>& held_y, ConversionBooks books) {
  for (const auto& [z, rule] : chosen) {
    const double mass = mesh.zones.mass[z];
    const std::size_t b = static_cast<std::size_t>(mesh.zones.body[z]);
    const ConversionEnergy energy =
        convert_zone_to_particles(mesh, particles, z, particles_per_zone, time, zones_per_node, held_x, held_y);
    books.ledger.energy.converted += energy.converted();
    books.body_converted_energy[b] += energy.converted();
    books.ledger.energy.internal -= energy.internal;
    FractureCounts& counts = books.counts[b];
    if (rule == ConversionRule::erosion) {
      ++counts.eroded;
      counts.eroded_mass += mass;
      continue;
    }
    ++counts.converted;
    if (rule == ConversionRule::interior) ++counts.interior_conversions;
    counts.converted_mass += mass;
  }
}

}  // namespace krug
