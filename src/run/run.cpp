#include "krug/run/run.hpp"

#include <chrono>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/run/penetration.hpp"
#include "krug/run/stop_rule.hpp"

namespace krug::run {

using scenario::StopRule;

namespace {

// The share of the internal energy beyond which the hourglass work earns a warning.
constexpr double hourglass_warning_fraction = 0.05;

// Where a run stands between cycles, apart from the simulation and the observer.
struct LoopState {
  std::optional<StopMonitor> stop;
  std::optional<PenetrationRecord> penetration;
  double next_checkpoint_time = 0.0;
  double previous_wall_seconds = 0.0;  // wall time before a restart
};

std::optional<StopMonitor> stop_monitor(const Scenario& scenario) {
  if (!scenario.stop) return std::nullopt;
  return StopMonitor(*scenario.stop);
}

// Feeds the stop rule one sample: the body's velocity, and whether it is clear of the rule's plane
// (every node that carries mass beyond it, the way the body first moved along the first axis).
// With clear_of_targets, also whether the projectile has cleared its targets or stopped advancing.
// `known`: a summary of this moment already made for the rule's body (or none).
bool observe_stop(const Simulation& simulation, StopMonitor& monitor, const Scenario& scenario,
                  const std::optional<PenetrationRecord>& penetration, const std::optional<BodySummary>& known) {
  const StopRule& rule = monitor.rule();
  const BodySummary body =
      known ? *known : simulation.summarise(simulation.bodies()[static_cast<std::size_t>(rule.body_index)]);
  bool clear = true;
  if (rule.clear_of) {
    const bool moving_down = monitor.state().started ? monitor.state().initial_velocity.x < 0.0 : body.velocity.x < 0.0;
    clear = moving_down ? body.bbox_max.x < *rule.clear_of : body.bbox_min.x > *rule.clear_of;
  }
  return monitor.observe(simulation.time(), body.velocity, [&] {
    if (!clear) return false;
    if (!rule.clear_of_targets || !penetration) return true;
    const PenetrationRecord& r = *penetration;
    const double advance = r.direction * (r.axis == 0 ? body.velocity.x : body.velocity.y);
    if (advance <= rule.velocity_change * monitor.state().scale) return true;  // stopped, or turned back
    return measure_penetration(simulation, *scenario.penetration, r).cleared();
  });
}

// The loop after setup (fresh or restored): steps, outputs, stop rule, checkpoints, interruption.
RunResult run_loop(const Scenario& scenario, Simulation& simulation, RunObserver& observer, LoopState& loop,
                   const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return loop.previous_wall_seconds +
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const double interval = scenario.output.checkpoint_interval;
  RunResult result;
  auto checkpoint = [&] {
    RunProgress progress;
    progress.next_checkpoint_time = loop.next_checkpoint_time;
    progress.wall_seconds = elapsed();
    if (loop.stop) {
      progress.has_stop_state = true;
      progress.stop = loop.stop->state();
    }
    if (loop.penetration) {
      progress.has_penetration = true;
      progress.penetration = *loop.penetration;
    }
    result.checkpoint = observer.checkpoint(simulation, progress);
  };
  if (options.on_start) options.on_start(simulation);
  EventWatch events(simulation);
  const std::string projectile_name =
      scenario.penetration ? simulation.bodies()[static_cast<std::size_t>(scenario.penetration->projectile)].name : "";
  try {
    while (!simulation.finished()) {
      simulation.step();
      observer.cycle(simulation);
      // The projectile's summary, once per cycle, for the penetration record and the stop rule.
      std::optional<BodySummary> projectile;
      if (loop.penetration) {
        const Index p = scenario.penetration->projectile;
        projectile = simulation.summarise(simulation.bodies()[static_cast<std::size_t>(p)]);
        observe_penetration(simulation, *scenario.penetration, *projectile, *loop.penetration);
        if (loop.stop && loop.stop->rule().body_index != p) projectile.reset();
      }
      if (options.on_event) {
        for (const RunEvent& event : events.observe(simulation, loop.penetration, projectile_name)) options.on_event(event);
      }
      if (loop.stop && observe_stop(simulation, *loop.stop, scenario, loop.penetration, projectile)) {
        result.stopped_by = "stop rule";
        break;
      }
      if (interval > 0.0 && simulation.time() >= loop.next_checkpoint_time * (1.0 - 1e-12) && !simulation.finished()) {
        while (loop.next_checkpoint_time <= simulation.time() * (1.0 + 1e-12)) loop.next_checkpoint_time += interval;
        checkpoint();
      }
      if (options.interrupt && options.interrupt->load() && !simulation.finished()) {
        checkpoint();
        result.status = RunStatus::failed;
        result.message = "interrupted";
        result.stopped_by = "interrupted";
        break;
      }
      if (options.on_cycle && !options.on_cycle(simulation, elapsed())) {
        result.status = RunStatus::failed;
        result.message = "stopped on request before the end time";
        result.stopped_by = "request";
        break;
      }
    }
    if (result.status == RunStatus::completed && result.stopped_by == "end_time" &&
        simulation.cycle() >= simulation.controls().max_cycles && simulation.time() < simulation.controls().end_time) {
      result.status = RunStatus::failed;
      result.message = "reached max_cycles before the end time";
      result.stopped_by = "max_cycles";
    }
  } catch (const NumericalFailure& failure) {
    result.status = RunStatus::failed;
    result.message = failure.what();
    result.stopped_by = "failure";
  }
  result.wall_seconds = elapsed();
  if (options.on_finish) options.on_finish(simulation);
  if (loop.penetration) {
    result.penetration = report_penetration(simulation, *scenario.penetration, *loop.penetration);
    result.penetration->final = result.stopped_by == "stop rule" && loop.stop && loop.stop->rule().clear_of_targets;
    if (!result.penetration->final && result.status == RunStatus::completed) {
      result.warnings.push_back(fmt::format(
          "the run ended ({}) before the projectile had cleared its targets or stopped: the penetration figures are "
          "those of an unfinished perforation (raise end_time)", result.stopped_by));
    }
  }
  {
    // Hourglass work is numerical: a large share of the internal energy means the mesh's hourglass
    // modes carried a good part of the deformation, and the strains and stresses there are suspect.
    // The energy put into the zones: what they hold now plus what left the mesh with converted zones.
    // Judged body by body: a stiff target's small hourglass share must not hide a soft projectile's.
    for (Index b = 0; b < static_cast<Index>(simulation.bodies().size()); ++b) {
      const double into_zones = simulation.internal_energy(b) + simulation.converted_energy(b);
      const double hourglass = simulation.hourglass_work(b);
      if (into_zones > 0.0 && hourglass > hourglass_warning_fraction * into_zones) {
        result.warnings.push_back(fmt::format(
            "{}: hourglass work is {:.1f} % of the energy put into its zones ({:.4g} J of {:.4g} J, internal plus "
            "converted): the mesh's hourglass modes carried part of the deformation; refine the mesh where it "
            "deforms most, or check controls.hourglass",
            simulation.bodies()[static_cast<std::size_t>(b)].name, 100.0 * hourglass / into_zones,
            simulation.whole_body_factor() * hourglass, simulation.whole_body_factor() * into_zones));
      }
    }
  }
  if (!simulation.ledger().energy_closed()) {
    const bool approximate = simulation.geometry() == GeometryKind::axisymmetric &&
                             simulation.controls().axisymmetric_form == AxisymmetricForm::area_weighted;
    result.warnings.push_back(fmt::format(
        "the energy ledger did not close: relative drift {:.3g}, above {:.0e}{}; the figures of this run are suspect "
        "(summary.json ledger.energy.closed is false)",
        simulation.ledger().relative_energy_drift(), energy_drift_limit,
        approximate ? " (the area-weighted axisymmetric form is not conservative: its drift shrinks with the mesh)" : ""));
  }
  observer.finish(simulation, result);
  return result;
}

}  // namespace

void check_cycle_budget(const Simulation& simulation) {
  const double dt = simulation.stable_time_step();
  if (!(dt > 0.0) || !std::isfinite(dt)) return;  // no wave speed yet: nothing to estimate from
  const Controls& controls = simulation.controls();
  const double cycles = (controls.end_time - simulation.time()) / dt;
  if (cycles <= static_cast<double>(controls.max_cycles)) return;
  std::string where;
  const Index zone = simulation.controlling_zone();
  for (const Body& body : simulation.bodies()) {
    if (zone >= body.zone_begin && zone < body.zone_end) {
      where = fmt::format(" (set by zone {} of body \"{}\")", zone - body.zone_begin, body.name);
    }
  }
  throw InputError(fmt::format(
      "end_time: {:.4g} s needs at least {:.3g} cycles at the initial stable step {:.3g} s{}, more than "
      "controls.max_cycles = {}; check the end time's units, or raise controls.max_cycles",
      controls.end_time, cycles, dt, where, controls.max_cycles));
}

void validate_scenario(const Scenario& scenario) {
  const Simulation simulation(scenario.setup);
  check_cycle_budget(simulation);
}

RunResult run_simulation(const Scenario& scenario, Simulation& simulation, RunObserver& observer,
                         const RunOptions& options) {
  LoopState loop;
  if (scenario.penetration) loop.penetration = start_penetration(simulation, *scenario.penetration);
  loop.stop = stop_monitor(scenario);
  if (loop.stop) (void)observe_stop(simulation, *loop.stop, scenario, loop.penetration, std::nullopt);
  loop.next_checkpoint_time = scenario.output.checkpoint_interval;
  return run_loop(scenario, simulation, observer, loop, options);
}

RunResult resume_simulation(const Scenario& scenario, Simulation& simulation, const RunProgress& progress,
                            RunObserver& observer, const RunOptions& options) {
  LoopState loop;
  loop.stop = stop_monitor(scenario);
  if (loop.stop && progress.has_stop_state) loop.stop->restore(progress.stop);
  if (scenario.penetration) {
    loop.penetration =
        progress.has_penetration ? progress.penetration : start_penetration(simulation, *scenario.penetration);
  }
  loop.next_checkpoint_time = progress.next_checkpoint_time;
  if (scenario.output.checkpoint_interval > 0.0 && !(loop.next_checkpoint_time > simulation.time())) {
    loop.next_checkpoint_time = simulation.time() + scenario.output.checkpoint_interval;
  }
  loop.previous_wall_seconds = progress.wall_seconds;
  return run_loop(scenario, simulation, observer, loop, options);
}

}  // namespace krug::run
