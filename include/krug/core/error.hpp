#pragma once
#include <stdexcept>
#include <string>

namespace krug {

// Bad input: a scenario or a setup that cannot be run. The message says what and where.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run that went wrong numerically (NaN, a tangled zone, dt below its floor). Names the body,
// the zone and the time so that the state written alongside can be inspected.
class NumericalFailure : public std::runtime_error {
 public:
  NumericalFailure(std::string message, std::string body, long zone, double time)
      : std::runtime_error(std::move(message)), body_(std::move(body)), zone_(zone), time_(time) {}
  const std::string& body() const { return body_; }
  long zone() const { return zone_; }
  double time() const { return time_; }

 private:
  std::string body_;
  long zone_;
  double time_;
};

}  // namespace krug
