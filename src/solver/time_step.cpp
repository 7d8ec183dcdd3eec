#include "krug/solver/time_step.hpp"

#include <algorithm>
#include <limits>

namespace krug {

TimeStepChoice limit_time_step(double stable, double previous, const Controls& controls, const Particles& particles) {
  TimeStepChoice choice;
  double dt = std::min({stable, controls.time_step_growth * previous, controls.max_time_step});
  choice.limit = dt == stable ? TimeStepLimit::zone
                 : dt == controls.max_time_step ? TimeStepLimit::maximum : TimeStepLimit::growth;
  for (std::int32_t i = 0; i < particles.size(); ++i) {  // a particle moves at most a fraction of its radius
    const double speed = norm(particles.velocity(i));
    if (speed > 0.0 && controls.fracture.particle_travel * particles.radius[i] / speed < dt) {
      dt = controls.fracture.particle_travel * particles.radius[i] / speed;
      choice.limit = TimeStepLimit::particle_travel;
    }
  }
  choice.time_step = dt;
  return choice;
}

StableStep smallest_stable_step(const ZoneFields& zones, const HydroZoneFields& hydro) {
  StableStep smallest{std::numeric_limits<double>::infinity(), -1};
  for (Index z = 0; z < zones.size(); ++z) {
    if (zones.active[z] && hydro.stable_time_step[z] < smallest.time_step) {
      smallest.time_step = hydro.stable_time_step[z];
      smallest.zone = z;
    }
  }
  return smallest;
}

}  // namespace krug
