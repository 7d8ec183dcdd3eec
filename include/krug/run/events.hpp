#pragma once
// What a user watching a run wants to hear as it happens, and what the run starts from.
//
// EventWatch reports the first of each kind, with the time and cycle: the first contact reaction,
// each body's first damaged zone, first conversion to free elements and first eroded zone, and the
// projectile's perforation of its targets. start_up_lines() describes the set-up: geometry, the
// materials and their models, each body's zones, nodes and extent, and the first time step with the
// body and zone that set it. Both only read the state; the app prints them.
#include <optional>
#include <string>
#include <vector>

#include "krug/scenario/scenario.hpp"
#include "krug/run/penetration.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::run {

struct RunEvent {
  double time = 0.0;  // s
  long cycle = 0;
  std::string what;
};

class EventWatch {
 public:
  explicit EventWatch(const Simulation& simulation);
  // The events of the cycle just taken (none most cycles).
  std::vector<RunEvent> observe(const Simulation& simulation, const std::optional<PenetrationRecord>& penetration,
                                const std::string& projectile);

 private:
  bool contact_ = false;
  bool perforated_ = false;
  std::vector<FractureCounts> seen_;  // per body: the counts already reported as non-zero
};

std::vector<std::string> start_up_lines(const scenario::Scenario& scenario, const Simulation& simulation);

// "plate zone 123" for a zone of the mesh, or "no zone".
std::string describe_zone(const Simulation& simulation, Index zone);

}  // namespace krug::run
