#include "krug/run/stop_rule.hpp"

#include <algorithm>
#include <cmath>

namespace krug::run {

namespace {

// Monotonic queue step: keeps the window's extreme (front) for one component. `better(a, b)` is
// true when a dominates b (a >= b for the maximum).
template <class Better>
void push(std::deque<StopMonitor::Sample>& queue, double time, double value, double window_start, Better better) {
  while (!queue.empty() && better(value, queue.back().second)) queue.pop_back();
  queue.emplace_back(time, value);
  while (queue.front().first < window_start) queue.pop_front();
}

}  // namespace

bool StopMonitor::observe(double time, Vec2 velocity, const std::function<bool()>& clear) {
  State& s = state_;
  if (!s.started) {
    s.started = true;
    s.initial_velocity = velocity;
    s.scale = norm(velocity);
  }
  s.scale = std::max(s.scale, norm(velocity));  // grows only for a body that starts slower than it gets
  const double tolerance = rule_.velocity_change * s.scale;
  const double window_start = time - rule_.no_contact_time;
  const auto greater = [](double a, double b) { return a >= b; };
  const auto less = [](double a, double b) { return a <= b; };
  push(s.max_x, time, velocity.x, window_start, greater);
  push(s.min_x, time, velocity.x, window_start, less);
  push(s.max_y, time, velocity.y, window_start, greater);
  push(s.min_y, time, velocity.y, window_start, less);
  if (!s.armed) {
    if (tolerance > 0.0 && norm(velocity - s.initial_velocity) > tolerance) {
      s.armed = true;
      s.armed_time = time;
    }
    return false;
  }
  if (time - s.armed_time < rule_.no_contact_time) return false;
  const double spread = std::max({s.max_x.front().second - velocity.x, velocity.x - s.min_x.front().second,
                                  s.max_y.front().second - velocity.y, velocity.y - s.min_y.front().second});
  return spread <= tolerance && clear();
}

}  // namespace krug::run
