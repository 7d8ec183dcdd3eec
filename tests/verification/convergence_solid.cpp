// Convergence studies of the solid-mechanics problems (ctest label `convergence`; verification.md
// E3, E5, E6): error against zones and against run time at three or more resolutions, with the
// observed order.
//   - E3 piston: L1 error of the velocity profile against the exact two-wave solution, and the front
//     positions;
//   - E5 beryllium plate: the period at three meshes and its Richardson limit, which must lie between
//     the Euler-Bernoulli (26.63 us) and Timoshenko (29.1 us) beam values;
//   - E6 Taylor bar: length and impact-face radius at three meshes, their Richardson limits against
//     the converged references 21.43 / 7.23 mm.
//
// KRUG_CONVERGENCE_SCALE (default 1: the full study) scales the resolutions; CI runs 0.25. With
// KRUG_VERIFICATION_REPORT set, each level prints a row of the docs/verification.md table.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "test_solid_measures.hpp"

using namespace krug;
using namespace krug::verification;
using namespace krug::verification::solid;

namespace {

int scaled(int zones, int smallest) {
  return std::max(smallest, static_cast<int>(std::lround(zones * convergence_scale())));
}

// ---- E3 piston -------------------------------------------------------------------------------------

struct PistonLevel {
  int zones = 0;
  double l1 = 0.0;            // integral of |u - u_exact| dx over the strip / (20 m/s x 1 m)
  double elastic_front = 0.0; // front position errors (m)
  double plastic_front = 0.0;
  double seconds = 0.0;
};

// Mean of the exact velocity over [a, b] at time t: 20 m/s behind the plastic front, the precursor's
// 4.7198 m/s between the fronts, rest ahead (verification.md E3).
double exact_piston_velocity(double a, double b, double t) {
  const double plastic = piston::plastic.front_speed * t, elastic = piston::elastic.front_speed * t;
  auto overlap = [&](double lo, double hi) { return std::max(0.0, std::min(b, hi) - std::max(a, lo)); };
  return (piston::plastic.velocity * overlap(a - 1.0, plastic) + piston::elastic.velocity * overlap(plastic, elastic)) /
         (b - a);
}

PistonLevel piston_level(int n) {
  // Square zones: the strip's height follows the zone length, so the time step is the CFL step of dx.
  const std::string from = R"("x": { "from": 0.0, "to": 1.0, "zones": 1000 }, "y": { "from": 0.0, "to": 0.001, "zones": 1 })";
  const std::string to = R"("x": { "from": 0.0, "to": 1.0, "zones": )" + std::to_string(n) +
                         R"( }, "y": { "from": 0.0, "to": )" + format_number("%.17g", 1.0 / n) + R"(, "zones": 1 })";
  const scenario::Scenario scenario = load_example("piston.json", {{from, to}});
  const Run run = run_to_end(scenario);
  INFO("piston at " << n << " zones: " << run.failure);
  REQUIRE(run.completed());
  const Simulation& sim = run.simulation;
  PistonLevel level;
  level.zones = n;
  level.seconds = run.seconds;
  for (const ZoneSample& z : row_profile(sim, sim.bodies()[0], 0, Coordinate::first_axis)) {
    level.l1 += std::abs(z.velocity - exact_piston_velocity(z.low, z.high, sim.time())) * z.width();
  }
  level.l1 /= piston::piston_speed * 1.0;
  const std::vector<StripZone> strip = strip_profile(sim, sim.bodies()[0]);
  level.elastic_front = velocity_front(strip, 0.5 * piston::elastic.velocity) - piston::elastic.front_speed * sim.time();
  level.plastic_front = velocity_front(strip, 0.5 * (piston::elastic.velocity + piston::plastic.velocity)) -
                        piston::plastic.front_speed * sim.time();
  return level;
}

}  // namespace

TEST_CASE("Convergence: E3 piston, L1 velocity error and front positions against zones and time",
          "[convergence][piston]") {
  // At least 250 zones: below that the precursor plateau (0.11 m wide at 150 us) spans fewer than 28
  // zones, the two fronts' captured structures (15-25 zones each) run into each other and the error
  // is not yet in its asymptotic range (measured order 0.59 from 125 to 250 zones).
  std::vector<PistonLevel> levels;
  for (const int n : {250, 500, 1000, 2000, 4000}) {
    const int zones = scaled(n, 250);
    if (levels.empty() || zones > levels.back().zones) levels.push_back(piston_level(zones));
  }
  REQUIRE(levels.size() >= 3);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const PistonLevel& l = levels[k];
    const double order = k == 0 ? 0.0 : std::log2(levels[k - 1].l1 / l.l1);
    report("E3 piston", "L1 velocity error / (20 m/s x 1 m) at " + std::to_string(l.zones) + " zones", "0", l.l1,
           k == 0 ? "-" : format_number("order %.2f", order), l.zones, l.seconds);
    report("E3 piston", "elastic / plastic front error (zones) at " + std::to_string(l.zones) + " zones", "0",
           l.elastic_front * l.zones, format_number("plastic %+.2f", l.plastic_front * l.zones), l.zones, l.seconds);
    // Fronts within 2 zones at every level (the E2 criterion; measured within 1 zone).
    CHECK(std::abs(l.elastic_front) * l.zones < 2.0);
    CHECK(std::abs(l.plastic_front) * l.zones < 2.0);
    if (k == 0) continue;
    INFO(levels[k - 1].zones << " -> " << l.zones << " zones: L1 " << levels[k - 1].l1 << " -> " << l.l1
                             << ", observed order " << order);
    // The plastic jump is a shock captured in a fixed number of zones: first order in L1. The elastic
    // precursor is a weak, nearly acoustic wave whose captured ramp also spreads with time (width
    // ~ sqrt(c t dx)), an L1 contribution of order 1/2. Measured 0.89, 0.98, 0.76, 0.96 from 250 to
    // 4000 zones; allow [0.6, 1.3].
    CHECK(order > 0.6);
    CHECK(order < 1.3);
  }
}

TEST_CASE("Convergence: E5 beryllium plate period, Richardson limit between the beam-theory values",
          "[convergence][plate]") {
  // Three meshes refined by 2 (30 x 5 to 120 x 20 in CI, 60 x 10 to 240 x 40 in the full study), at
  // 1/10 amplitude (the linear regime of the beam references) and at the full amplitude.
  const int base = convergence_scale() >= 1.0 ? 60 : 30;
  for (const double amplitude : {0.1, 1.0}) {
    std::vector<PlateVibration> levels;
    for (const int factor : {1, 2, 4}) levels.push_back(run_plate(base * factor, base * factor / 6, amplitude));
    for (const PlateVibration& l : levels) {
      INFO(l.failure);
      REQUIRE(l.failure.empty());
      report("E5 plate", format_number("period at %.1f amplitude (us), ", amplitude) + std::to_string(l.zones) + " zones",
             "26.63-29.1", 1e6 * l.period(), "-", l.zones, l.seconds);
    }
    const Richardson limit = richardson(levels[0].period(), levels[1].period(), levels[2].period());
    INFO("amplitude " << amplitude << ": periods " << levels[0].period() << ", " << levels[1].period() << ", "
                      << levels[2].period() << " s; observed order " << limit.order << ", limit " << limit.limit << " s");
    report("E5 plate", format_number("converged period at %.1f amplitude (us), Richardson", amplitude), "26.63-29.1",
           1e6 * limit.limit, format_number("order %.2f", limit.order), levels[2].zones, levels[2].seconds);
    // Second order for a smooth elastic vibration (measured 2.1 at 1/10 amplitude).
    CHECK(limit.order > 1.5);
    CHECK(limit.order < 3.0);
    if (amplitude < 0.5) {
      // verification.md E5: the converged 2D period lies between the Euler-Bernoulli and the
      // Timoshenko beam values (measured 28.91 us).
      CHECK(limit.limit > 26.63e-6);
      CHECK(limit.limit < 29.1e-6);
    } else {
      // Full amplitude (fibre strains of 12 %): a finding, not a reference. The period lengthens by
      // about 3.4 % over the small-amplitude one (quadratic in the amplitude; docs/verification.md).
      CHECK(limit.limit > 29.1e-6);
      CHECK(limit.limit < 31.0e-6);
    }
  }
}

TEST_CASE("Convergence: E6 Taylor bar length and face radius against zones and time, Richardson limits",
          "[convergence][taylor]") {
  // Uniform meshes k = 8, 16, 32 zones across the radius in the full study (4, 8, 16 in CI).
  const int base = scaled(8, 4);
  std::vector<TaylorLevel> levels;
  for (const int factor : {1, 2, 4}) levels.push_back(taylor_level(base * factor));
  const double reference_length = 21.43e-3, reference_radius = 7.23e-3;  // verification.md E6
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const TaylorLevel& l = levels[k];
    const long zones = static_cast<long>(l.axial) * l.radial;
    report("E6 Taylor bar", "length (mm), " + std::to_string(l.axial) + " x " + std::to_string(l.radial), "21.43",
           1e3 * l.measures.length, format_number("%+.3f mm", 1e3 * (l.measures.length - reference_length)), zones, l.seconds);
    report("E6 Taylor bar", "face radius (mm), " + std::to_string(l.axial) + " x " + std::to_string(l.radial), "7.23",
           1e3 * l.measures.face_radius, format_number("%+.3f mm", 1e3 * (l.measures.face_radius - reference_radius)),
           zones, l.seconds);
    if (k == 0) continue;
    // Each refinement brings both measures closer to the converged references (the bar shortens and
    // the face spreads with resolution: measured 22.30 / 6.08, 21.68 / 6.66, 21.50 / 6.97, 21.44 / 7.10 mm
    // at k = 4, 8, 16, 32).
    CHECK(std::abs(l.measures.length - reference_length) < std::abs(levels[k - 1].measures.length - reference_length));
    CHECK(std::abs(l.measures.face_radius - reference_radius) <
          std::abs(levels[k - 1].measures.face_radius - reference_radius));
  }
  const Richardson length = richardson(levels[0].measures.length, levels[1].measures.length, levels[2].measures.length);
  const Richardson radius =
      richardson(levels[0].measures.face_radius, levels[1].measures.face_radius, levels[2].measures.face_radius);
  INFO("Richardson: length " << length.limit << " m (order " << length.order << "), face radius " << radius.limit
                             << " m (order " << radius.order << ")");
  const long finest = static_cast<long>(levels[2].axial) * levels[2].radial;
  report("E6 Taylor bar", "length (mm), Richardson limit", "21.42-21.43", 1e3 * length.limit,
         format_number("order %.2f", length.order), finest, levels[2].seconds);
  report("E6 Taylor bar", "face radius (mm), Richardson limit", "7.22-7.23", 1e3 * radius.limit,
         format_number("order %.2f", radius.order), finest, levels[2].seconds);
  // The limits against the converged references. The estimate itself is uncertain by the change
  // between successive triples (measured: length 21.420 from k = 4-16 and 21.417 from 8-32; face
  // radius 7.326 and 7.213 mm): within 0.05 mm for the length and 0.15 mm for the face radius.
  CHECK(std::abs(length.limit - reference_length) < 0.05e-3);
  CHECK(std::abs(radius.limit - reference_radius) < 0.15e-3);
}
