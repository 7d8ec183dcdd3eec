#pragma once
// Step 8 of the time step (docs/theory.md §2): the limits on dt^{n+3/2}.
#include <cstdint>

#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/particles/particles.hpp"
#include "krug/solver/controls.hpp"

namespace krug {

// What set the last time step.
enum class TimeStepLimit : std::uint8_t {
  zone,             // a zone's CFL-stable step (controlling_zone())
  growth,           // the growth limit on the previous step
  particle_travel,  // a particle may move only a fraction of its radius per step
  maximum,          // controls.max_time_step
  end_time          // the last step, cut to reach the end time
};

struct TimeStepChoice {
  double time_step = 0.0;  // s
  TimeStepLimit limit = TimeStepLimit::zone;
};

// The smallest of the zones' stable step `stable`, the growth limit on the previous step, the largest
// step allowed and the step over which a particle moves a fraction of its radius; the floor and the
// end time are the caller's. Reads the particles' radii and velocities.
// A stable step and the zone that sets it.
struct StableStep {
  double time_step;  // s; +infinity where no zone sets a speed
  Index zone = -1;   // the zone that sets it
};

// The smallest stable step of the active zones (hydro.stable_time_step) and the first zone with it;
// +infinity and -1 when no zone is active.
StableStep smallest_stable_step(const ZoneFields& zones, const HydroZoneFields& hydro);

TimeStepChoice limit_time_step(double stable, double previous, const Controls& controls, const Particles& particles);

}  // namespace krug
