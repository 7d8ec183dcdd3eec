// The step's parts that Simulation composes (include/krug/solver/), called alone on state built in
// code: the limits on the next time step (time_step.hpp) and the ledger's measured lines (ledger.hpp).
#include <catch2/catch.hpp>

#include "krug/mesh/mesh.hpp"
#include "krug/particles/particles.hpp"
#include "krug/solver/ledger.hpp"
#include "krug/solver/time_step.hpp"

using namespace krug;

// dt^{n+3/2} = min(stable, growth x dt^{n+1/2}, max, travel x radius / speed of every particle), and
// the limit that set it (docs/theory.md §2 step 8).
TEST_CASE("step parts: the next time step is the smallest limit, and names it", "[solver][time_step]") {
  Controls controls;  // growth 1.1, no maximum, particle travel 0.5
  Particles none;
  SECTION("a zone's stable step") {
    const TimeStepChoice choice = limit_time_step(1.0e-6, 1.0e-6, controls, none);
    CHECK(choice.time_step == 1.0e-6);
    CHECK(choice.limit == TimeStepLimit::zone);
  }
  SECTION("the growth limit: 1.1 x the previous step") {
    const TimeStepChoice choice = limit_time_step(5.0e-6, 1.0e-6, controls, none);
    CHECK(choice.time_step == 1.1 * 1.0e-6);
    CHECK(choice.limit == TimeStepLimit::growth);
  }
  SECTION("the largest step allowed") {
    controls.max_time_step = 2.0e-7;
    const TimeStepChoice choice = limit_time_step(5.0e-6, 1.0e-6, controls, none);
    CHECK(choice.time_step == 2.0e-7);
    CHECK(choice.limit == TimeStepLimit::maximum);
  }
  SECTION("a particle moves at most half its radius") {
    Particles particles;
    particles.add(Vec2{0.0, 0.0}, Vec2{300.0, 400.0}, 1.0e-3, 1.0e-3, 0, 0.0);  // 500 m/s, radius 1 mm
    const TimeStepChoice choice = limit_time_step(5.0e-6, 1.0e-5, controls, particles);
    CHECK(choice.time_step == Approx(0.5 * 1.0e-3 / 500.0).epsilon(1e-15));  // 1e-6 s
    CHECK(choice.limit == TimeStepLimit::particle_travel);
  }
}

// K = 1/2 sum M |u|^2 and the axial momentum over nodes and particles, the mass of the active zones
// and the particles, max K kept (docs/theory.md §3).
TEST_CASE("step parts: measure_ledger sums nodes, particles and active zones", "[solver][ledger]") {
  Mesh mesh;
  mesh.nodes.resize(2);
  mesh.nodes.mass = {2.0, 3.0};
  mesh.nodes.u = {1.0, -2.0};
  mesh.nodes.v = {0.5, 0.0};
  mesh.zones.resize(2);
  mesh.zones.mass = {4.0, 1.0};
  mesh.zones.active = {1, 0};  // the second zone has left the grid: its mass is the particle's
  Particles particles;
  particles.add(Vec2{0.0, 0.0}, Vec2{0.0, 4.0}, 1.0, 0.1, 0, 0.0);
  Ledger ledger;
  ledger.max_kinetic = 100.0;
  measure_ledger(mesh, particles, ledger);
  // K = (2 (1 + 0.25) + 3 x 4 + 1 x 16) / 2 = 15.25; momentum 2 x 1 + 3 x (-2) + 0 = -4; mass 4 + 1.
  CHECK(ledger.energy.kinetic == 15.25);
  CHECK(ledger.axial_momentum == -4.0);
  CHECK(ledger.mass == 5.0);
  CHECK(ledger.max_kinetic == 100.0);  // the largest so far is kept
  ledger.max_kinetic = 0.0;
  measure_ledger(mesh, particles, ledger);
  CHECK(ledger.max_kinetic == 15.25);
}
