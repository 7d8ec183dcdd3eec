#pragma once
// The stop rule of a projectile run (scenario key "stop"; docs/scenario-format.md, "Stop rule").
//
// V(t) is the body's mass-weighted mean velocity (its momentum over its mass), sampled at the end of
// every cycle. Internal waves do not change it; only external forces do (contact, boundary
// conditions) and, slightly, mass leaving with converted zones. With S the body's initial speed
// |V(0)| (or, for a body that starts at rest, the largest |V| seen so far) and f = velocity_change:
//   * the rule arms at the first sample with |V(t) - V(0)| > f S (the body has been hit);
//   * once armed, the run stops at the first sample t with t - t_armed >= no_contact_time at which
//     each component of V has stayed within f S of its current value over the window
//     [t - no_contact_time, t]: no contact impulse larger than f S times the body's mass.
// Each component's window extremes are kept in monotonic queues (O(1) per cycle).
// With `clear_of` or `clear_of_targets`, the run also waits until the caller reports the body clear
// (asked only when the velocity window would stop the run, since finding the pieces costs a pass
// over the mesh).
#include <deque>
#include <functional>
#include <utility>

#include "krug/core/vec2.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/run/state.hpp"

namespace krug::run {

using scenario::StopRule;

class StopMonitor {
 public:
  // The window's state (kept in checkpoints: StopWindow, state.hpp).
  using Sample = StopWindow::Sample;
  using State = StopWindow;

  explicit StopMonitor(StopRule rule) : rule_(std::move(rule)) {}

  // After every cycle (and once at the start): true when the run should stop. `clear`: the body has
  // passed the rule's clear_of plane (true when the rule has none).
  bool observe(double time, Vec2 velocity, const std::function<bool()>& clear);
  bool observe(double time, Vec2 velocity, bool clear = true) {
    return observe(time, velocity, [clear] { return clear; });
  }

  const StopRule& rule() const { return rule_; }
  const State& state() const { return state_; }
  void restore(State state) { state_ = std::move(state); }

 private:
  StopRule rule_;
  State state_;
};

}  // namespace krug::run
