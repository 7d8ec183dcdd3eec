#pragma once
// Ballistic limit of a penetration scenario (`krug ballistic`, docs/outputs.md "Ballistic"): the
// projectile's impact speed is the variable. A search brackets the ballistic limit V_bl between the
// fastest run that stopped and the slowest that perforated and narrows the bracket by N-section
// (N runs per round) to a tolerance; then runs above V_bl feed a least-squares fit of the
// Lambert-Jonas curve
//
//     v_r = a (v_i^p - v_bl^p)^(1/p)   for v_i > v_bl   (0 below),
//
// with the standard uncertainties of a, p and v_bl from the covariance s^2 (J^T J)^-1. The
// Recht-Ipson curve (p = 2, a = m_p / (m_p + m_plug)) is fitted beside it as a reference, v_bl alone.
//
// The search knows nothing of how a run is made: it calls `BallisticEvaluate` with a batch of
// speeds and gets one outcome per speed (the app runs each as a `krug run` process, the tests a
// synthetic target; a batch is the unit a later parallel driver can spread over ranks). No physics.
#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace krug::run {

// What a run says about perforation. Only `stopped` and `perforated` count in the search:
// `unfinished` is a run that ended without a final answer (penetration.final false: end time reached,
// interrupted), `failed` one that failed or did not run.
enum class ImpactResult { stopped, perforated, unfinished, failed };
const char* to_string(ImpactResult result);

struct BallisticOutcome {
  double velocity = 0.0;           // m/s, the impact speed of the run
  ImpactResult result = ImpactResult::failed;
  double residual_velocity = 0.0;  // m/s, the projectile's largest piece along the impact direction
  double whole_velocity = 0.0;     // m/s, the whole projectile (penetration.whole.velocity)
  double residual_mass = 0.0;      // kg, the largest piece
  double initial_mass = 0.0;       // kg, the projectile at the start
  double plug_mass = 0.0;          // kg, 0 when there is no plug
  double eroded_mass = 0.0;        // kg
  double target_energy = 0.0;      // J, penetration.target_energy_absorbed
  long cycles = 0;
  double wall_seconds = 0.0;
  std::string status;              // the summary's status, or "not run"
  std::string stopped_by;
  std::string message;             // a failure's diagnostic
  std::string directory;           // where the run's outputs are (empty for a synthetic run)
};

// The outcome of a run from its summary.json text (docs/outputs.md). A text that is not a summary,
// or a summary without a penetration block, gives a failed outcome with a message.
BallisticOutcome outcome_from_summary(const std::string& summary_json, double velocity);

// ---- the fit ----

// The Lambert-Jonas residual velocity (0 at and below v_bl).
double lambert_jonas(double v_i, double a, double p, double v_bl);

struct CurveFitOptions {
  // Start (and, for a parameter that is not free, the fixed value). v_bl must lie below every v_i.
  double a = 1.0, p = 2.0, v_bl = 0.0;
  bool free_a = true, free_p = true, free_v_bl = true;
  int max_iterations = 200;
};

struct CurveFit {
  bool valid = false;       // converged with at least as many points as free parameters
  std::string note;         // why not, or what was fixed
  double a = 0.0, p = 0.0, v_bl = 0.0;
  // Standard uncertainties (sqrt of the covariance's diagonal, s^2 = RSS / (n - k)); 0 for a fixed
  // parameter, NaN when n == k (no degree of freedom left).
  double sigma_a = 0.0, sigma_p = 0.0, sigma_v_bl = 0.0;
  std::array<std::array<double, 3>, 3> covariance{};  // (a, p, v_bl), m/s units for v_bl
  int points = 0, free_parameters = 0, iterations = 0;
  double rms = 0.0;                // m/s, sqrt(RSS / n)
  std::vector<double> velocities;  // m/s, the points fitted
  std::vector<double> residuals;   // m/s, measured - fitted, per point
};

// Levenberg-Marquardt on the Lambert-Jonas curve through (v_i, v_r) (every v_i > 0). Steps that would
// leave v_bl >= min v_i, v_bl < 0, a <= 0 or p outside [0.5, 50] are refused.
CurveFit fit_lambert_jonas(const std::vector<double>& v_i, const std::vector<double>& v_r, const CurveFitOptions& options);

// ---- the search ----

struct BallisticOptions {
  double v_min = 0.0, v_max = 0.0;  // m/s, the range searched; 0 < v_min < v_max
  double tolerance = 10.0;          // m/s: the bracket is narrowed until no wider than this
  int points_above = 3;             // perforating runs wanted above the bracket (the fit's points)
  int batch = 1;                    // runs per round (the number of workers)
  int max_runs = 200;               // a bound on the whole study
  double velocity_quantum = 0.01;   // m/s: speeds are rounded to this (names of run directories)
};

// Evaluates every speed of the batch; returns one outcome per speed, in the same order.
using BallisticEvaluate = std::function<std::vector<BallisticOutcome>(const std::vector<double>&)>;

struct BallisticStudy {
  BallisticOptions options;
  std::vector<BallisticOutcome> runs;  // in the order evaluated
  std::vector<int> round;              // the round of each run (0: the coarse bracket)
  bool bracketed = false;              // a stop and a faster perforation were found
  bool converged = false;              // ... and the bracket is within the tolerance
  double bracket_low = 0.0;            // m/s, the fastest stop below the slowest perforation
  double bracket_high = 0.0;           // m/s, the slowest perforation
  double highest_stop = 0.0;           // m/s (may exceed bracket_high: a zone of mixed results)
  double lowest_perforation = 0.0;     // m/s
  double v50 = 0.0;                    // m/s, (highest stop + lowest perforation) / 2
  double v_bl = 0.0;                   // m/s, the bracket's midpoint
  std::vector<std::string> notes;      // failed and unfinished runs inside the bracket, mixed results, why it ended
  CurveFit fit;                        // Lambert-Jonas on the perforating runs
  CurveFit recht_ipson;                // p = 2, a = m_p / (m_p + mean plug mass), v_bl fitted
  double mean_plug_mass = 0.0;         // kg, over the perforating runs
  double projectile_mass = 0.0;        // kg
};

// The whole study: coarse bracket, N-section, points above, fit. `on_round` (optional) hears each
// round's outcomes as they come (for a progress display).
BallisticStudy ballistic_search(const BallisticOptions& options, const BallisticEvaluate& evaluate,
                                const std::function<void(const BallisticStudy&)>& on_round = {});

// The closing summary, one line per entry.
std::vector<std::string> ballistic_summary_lines(const BallisticStudy& study);

// ---- the scenario variants ----

// The projectile of a penetration scenario and its initial velocity as given (a vector of numbers).
struct BallisticProjectile {
  std::string name;
  std::size_t body = 0;                 // index in "bodies"
  std::array<double, 2> velocity{};     // m/s
  double speed = 0.0;                   // m/s, its length
  double end_time = 0.0;                // s, the scenario's end_time
};

// InputError when the scenario has no penetration block, the projectile is not a body, or its
// initial velocity is missing, zero, or given by expressions (which cannot be scaled safely).
BallisticProjectile ballistic_projectile(const std::string& scenario_text, const std::string& origin);

// The scenario with the projectile's initial velocity scaled to `speed` (direction kept), a title
// naming the speed, and, when `scale_end_time` and speed < the given speed, end_time stretched by
// given speed / speed (the same distance travelled; the end time is a bound for a run with a stop rule),
// then multiplied by `end_time_factor` (> 0; 1 leaves it).
std::string ballistic_variant(const std::string& scenario_text, const BallisticProjectile& projectile, double speed,
                              bool scale_end_time, const std::string& origin, double end_time_factor = 1.0);

// The run directory's name for a speed: "v0352.50".
std::string ballistic_run_name(double speed);

}  // namespace krug::run
