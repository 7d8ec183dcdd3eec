#include "krug/run/events.hpp"

#include <algorithm>
#include <string>
#include <variant>

#include <fmt/format.h>

#include "krug/fracture/failure_law.hpp"

namespace krug::run {

EventWatch::EventWatch(const Simulation& simulation) {
  for (std::size_t b = 0; b < simulation.bodies().size(); ++b) {
    seen_.push_back(simulation.fracture_counts(static_cast<Index>(b)));  // a restart reports only what is new
  }
  contact_ = simulation.deepest_contact_gap() < 0.0;
}

std::vector<RunEvent> EventWatch::observe(const Simulation& simulation, const std::optional<PenetrationRecord>& penetration,
                                          const std::string& projectile) {
  std::vector<RunEvent> events;
  auto add = [&](std::string what) { events.push_back({simulation.time(), simulation.cycle(), std::move(what)}); };
  if (!contact_ && simulation.last_contact().active > 0) {
    contact_ = true;
    const long points = simulation.last_contact().active;
    add(fmt::format("first contact ({} point{} in contact)", points, points == 1 ? "" : "s"));
  }
  for (std::size_t b = 0; b < seen_.size(); ++b) {
    const FractureCounts& now = simulation.fracture_counts(static_cast<Index>(b));
    FractureCounts& seen = seen_[b];
    const std::string& name = simulation.bodies()[b].name;
    if (seen.damaged == 0 && now.damaged > 0) add(fmt::format("{}: first damaged zone", name));
    if (seen.converted == 0 && now.converted > 0) add(fmt::format("{}: first zone converted to free elements", name));
    if (seen.eroded == 0 && now.eroded > 0) add(fmt::format("{}: first zone eroded", name));
    seen = now;
  }
  if (!perforated_ && penetration && penetration->perforation_time >= 0.0) {
    perforated_ = true;
    add(fmt::format("{} perforated its targets", projectile));
  }
  return events;
}

std::string describe_zone(const Simulation& simulation, Index zone) {
  const Index body = zone >= 0 ? simulation.body_of_zone(zone) : -1;
  if (body < 0) return "no zone";
  const Body& b = simulation.bodies()[static_cast<std::size_t>(body)];
  return fmt::format("{} zone {}", b.name, zone - b.zone_begin);
}

std::vector<std::string> start_up_lines(const scenario::Scenario& scenario, const Simulation& simulation) {
  std::vector<std::string> lines;
  const GeometryKind g = simulation.geometry();
  lines.push_back(fmt::format("{} geometry ({}, {}), end time {:.4g} s{}",
                              g == GeometryKind::planar ? "planar" : "axisymmetric", axis_name(g, 0), axis_name(g, 1),
                              simulation.controls().end_time, scenario.stop ? ", or earlier by the stop rule" : ""));
  for (std::size_t i = 0; i < simulation.materials().size(); ++i) {
    const Material& m = simulation.materials()[i];
    const auto eos = std::visit([](const auto& model) { return model.name; }, m.eos);
    const auto strength = std::visit([](const auto& model) { return model.name; }, m.strength);
    // The failure law, when the material fractures (fracture/failure_law.hpp).
    std::string failure;
    if (i < scenario.scene.fracture.size() && fracture::enabled(scenario.scene.fracture[i])) {
      failure = fmt::format(", fracture {}",
                            std::visit([](const auto& law) { return law.name; }, scenario.scene.fracture[i]));
    }
    lines.push_back(fmt::format("material {}: {} kg/m^3, eos {}, strength {}{}", m.name, m.reference_density, eos,
                                strength, failure));
  }
  for (const Body& body : simulation.bodies()) {
    const BodySummary s = simulation.summarise(body);
    lines.push_back(fmt::format("body {}: {}, {} zones, {} nodes, {} {:.4g}..{:.4g} mm, {} {:.4g}..{:.4g} mm, mass {:.4g} kg{}",
                                body.name, simulation.materials()[static_cast<std::size_t>(body.material)].name,
                                body.zone_end - body.zone_begin, body.node_end - body.node_begin, axis_name(g, 0),
                                s.bbox_min.x * 1e3, s.bbox_max.x * 1e3, axis_name(g, 1), s.bbox_min.y * 1e3,
                                s.bbox_max.y * 1e3,
                                s.mass,  // whole body in RZ (summarise), per m of thickness in planar
                                g == GeometryKind::planar ? " per m of thickness" : ""));
  }
  lines.push_back(fmt::format("first time step {:.4g} s, set by {}", simulation.next_time_step(),
                              describe_zone(simulation, simulation.controlling_zone())));
  return lines;
}

}  // namespace krug::run
