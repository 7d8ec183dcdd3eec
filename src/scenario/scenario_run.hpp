#pragma once
// Reading a scenario's run settings (private to the io library): the output block, the stop rule and
// the penetration block, and the body names they and the contact block use. Every error names the
// JSON path.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "json_reader.hpp"
#include "krug/scenario/scenario.hpp"

namespace krug::scenario::detail {

// The index of the body a scenario names at `path` (`key` of `spec`); an unknown name lists the bodies
// and suggests the nearest.
Index body_index(JsonObject& spec, std::string_view key, const Json& name, const std::vector<Body>& bodies,
                 const std::string& path);

// `solids`: some material has a strength model (the pictures then show plastic strain by default).
OutputSettings read_output(JsonObject output, double end_time, GeometryKind geometry, bool solids);
// The stop rule; in a penetration scenario the body defaults to the projectile and the run waits for
// it to clear the targets.
StopRule read_stop_rule(JsonObject spec, const std::vector<Body>& bodies, const std::optional<PenetrationSetup>& penetration);
// {"projectile": name, "targets": [names]}; the targets default to every other body.
PenetrationSetup read_penetration(JsonObject spec, const std::vector<Body>& bodies);
// The gauges block (docs/scenario-format.md, "Gauges"); where the gauges lie is checked once the mesh is
// built (check_gauges).
GaugeSettings read_gauges(JsonObject spec, const std::vector<Body>& bodies, GeometryKind geometry);
// Each tracer inside a zone of the built initial mesh, a temperature asked only where a material has
// one; errors name gauges.tracers[i].
void check_gauges(const GaugeSettings& gauges, const SimulationSetup& setup);

}  // namespace krug::scenario::detail
