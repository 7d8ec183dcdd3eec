#include "scenario_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "expression.hpp"
#include "krug/core/error.hpp"

namespace krug::scenario::detail {

namespace {

// One graded axis: {"from", "to", "zones", "ratio"} or {"from", "segments": [{"to", "zones", "ratio"}]}.
std::vector<double> read_axis(JsonObject spec, double scale = 1.0) {
  const double from = spec.number("from");
  std::vector<generate::AxisSegment> segments;
  auto read_segment = [&](JsonObject& s) {
    generate::AxisSegment seg;
    seg.to = s.number("to") * scale;
    seg.zones = static_cast<int>(s.integer("zones", 1, 1'000'000));
    seg.ratio = s.number("ratio", 1.0, Range{0.0, 100.0, true});
    s.finish();
    const double start = segments.empty() ? from * scale : segments.back().to;
    if (!(seg.to > start)) s.fail("to", fmt::format("a value greater than the segment's start {}", start / scale));
    segments.push_back(seg);
  };
  if (spec.has("segments")) {
    const Json& list = spec.raw("segments");
    if (!list.is_array() || list.empty()) spec.fail("segments", "a non-empty array of {to, zones, ratio}");
    Json resolved_list = Json::array();
    for (std::size_t i = 0; i < list.size(); ++i) {
      Json resolved_item = Json::object();
      JsonObject item(list[i], fmt::format("{}.segments[{}]", spec.path(), i), &resolved_item);
      read_segment(item);
      resolved_list.push_back(resolved_item);
    }
    spec.resolve("segments", resolved_list);
  } else {
    read_segment(spec);
    spec.finish({"segments"});
    return generate::graded_axis(from * scale, segments);
  }
  spec.finish();
  return generate::graded_axis(from * scale, segments);
}

std::vector<ScalarField> read_field_pair(JsonObject& spec, std::string_view key, const AxisNames& names,
                                         const std::string& expected) {
  const Json& v = spec.raw(key);
  if (!v.is_array() || v.size() != 2) spec.fail(key, expected);
  spec.resolve(key, v);
  return {ScalarField::from_json(v[0], spec.path_of(key) + "[0]", names.first, names.second),
          ScalarField::from_json(v[1], spec.path_of(key) + "[1]", names.first, names.second)};
}

}  // namespace

namespace {

// What a mesh kind's reader needs beside its keys.
struct MeshContext {
  GeometryKind geometry;
  bool allow_radian_angles;  // sector angles that look like radians are allowed ("allow_unusual")
};

// The mesh kinds' readers, one overload per alternative of setup::MeshShape: each reads its kind's keys
// from the mesh block (the generic read_mesh has read "type" and "map").
setup::RectangleMesh read_mesh_kind(std::type_identity<setup::RectangleMesh>, JsonObject& spec, const MeshContext& context) {
  const GeometryKind geometry = context.geometry;
  const AxisNames names = axis_names(geometry);
  // The other geometry's axis names are a likely slip: name the key that was written.
  const AxisNames other = axis_names(geometry == GeometryKind::planar ? GeometryKind::axisymmetric : GeometryKind::planar);
  for (const std::string& written : {other.first, other.second}) {
    if (spec.has(written) && written != names.first && written != names.second) {
      throw InputError(fmt::format("{}: {} rectangle names its axes \"{}\" and \"{}\"; found \"{}\" (an axis of {} "
                                   "geometry)",
                                   spec.path_of(written), geometry == GeometryKind::planar ? "a planar" : "an axisymmetric",
                                   names.first, names.second, written,
                                   geometry == GeometryKind::planar ? "axisymmetric" : "planar"));
    }
  }
  setup::RectangleMesh rectangle;
  rectangle.first = read_axis(spec.object(names.first));
  rectangle.second = read_axis(spec.object(names.second));
  return rectangle;
}

// A projectile or rod along the axis: flat, hemispherical or tangent-ogive nose, O-grid at the nose.
setup::NosedCylinderMesh read_mesh_kind(std::type_identity<setup::NosedCylinderMesh>, JsonObject& spec,
                                        const MeshContext& context) {
  const AxisNames names = axis_names(context.geometry);
  generate::NosedCylinderParams p;
  p.radius = spec.number("radius", Range::positive());
  p.length = spec.number("length", Range::positive());
  const std::string nose = spec.choice("nose", {"flat", "hemispherical", "ogive"}, "hemispherical");
  p.nose = nose == "flat" ? generate::NoseShape::flat
           : nose == "ogive" ? generate::NoseShape::ogive : generate::NoseShape::hemispherical;
  p.nose_length = spec.number("nose_length", 0.0, Range::non_negative());
  p.ogive_calibers = spec.number("ogive_calibers", 0.0, Range::non_negative());
  p.tip_position = spec.number("tip", 0.0);
  const std::string direction = spec.choice("points", {"+" + names.first, "-" + names.first}, "+" + names.first);
  p.direction = direction[0] == '+' ? 1 : -1;
  p.radial_zones = static_cast<int>(spec.integer("radial_zones", 10, 1, 100000));
  p.core_zones = static_cast<int>(spec.integer("core_zones", 0, 0, 100000));
  p.nose_zones = static_cast<int>(spec.integer("nose_zones", 0, 0, 100000));
  p.shank_zones = static_cast<int>(spec.integer("shank_zones", 0, 0, 1000000));
  p.shank_ratio = spec.number("shank_ratio", 1.0, Range{0.0, 100.0, true});
  return setup::NosedCylinderMesh{p};
}

setup::SectorMesh read_mesh_kind(std::type_identity<setup::SectorMesh>, JsonObject& spec, const MeshContext& context) {
  setup::SectorMesh sector;
  sector.radii = read_axis(spec.object("radius"));
  sector.angles = read_axis(spec.object("angle"), std::numbers::pi / 180.0);
  if (sector.radii.front() < 0.0) spec.fail_here("radius.from must be >= 0");
  const double from = sector.angles.front() * 180.0 / std::numbers::pi, to = sector.angles.back() * 180.0 / std::numbers::pi;
  for (const double degrees : {from, to}) {
    // pi/2, pi, 3 pi/2 or 2 pi written where degrees are expected: almost surely radians.
    const double quarters = degrees / (0.5 * std::numbers::pi);
    const bool looks_like_radians = degrees != 0.0 && std::abs(quarters - std::round(quarters)) < 1e-4 &&
                                    std::abs(quarters) <= 4.0 + 1e-9;
    if (looks_like_radians && !context.allow_radian_angles) {
      throw InputError(fmt::format("{}: {:g} looks like an angle in radians; angles are in degrees (90, 180, 360); if "
                                   "this is deliberate, add \"angle\" to the top-level \"allow_unusual\" list",
                                   spec.path_of("angle"), degrees));
    }
  }
  if (from < -360.0 || to > 360.0 || to - from > 360.0 * (1.0 + 1e-12)) {
    throw InputError(fmt::format("{}: the angles run from {:g} to {:g} degrees; expected a span of at most 360 degrees "
                                 "within [-360, 360] (angles are in degrees)",
                                 spec.path_of("angle"), from, to));
  }
  return sector;
}

}  // namespace

setup::MeshDescription read_mesh(JsonObject spec, GeometryKind geometry, bool allow_radian_angles) {
  const AxisNames names = axis_names(geometry);
  const std::string type = spec.choice("type", alternative_names<setup::MeshShape>());
  setup::MeshDescription result;
  if (spec.has("map")) {
    auto fields = read_field_pair(spec, "map", names, "an array of two expressions [new first, new second]");
    result.map = [fields](Vec2 p) { return Vec2{fields[0].at(p.x, p.y), fields[1].at(p.x, p.y)}; };
  } else {
    spec.optional_raw("map");
  }
  const MeshContext context{geometry, allow_radian_angles};
  result.shape = make_alternative<setup::MeshShape>(type, [&]<class Kind>(std::type_identity<Kind> kind) {
    return setup::MeshShape{read_mesh_kind(kind, spec, context)};
  });
  spec.finish();
  return result;
}

std::vector<setup::SideBoundary> read_boundary(JsonObject spec, const setup::MeshDescription& mesh, GeometryKind geometry) {
  std::vector<std::string> valid;
  for (const auto& [user, _] : setup::side_names(mesh, geometry)) valid.push_back(user);
  std::vector<setup::SideBoundary> result;
  for (const std::string& side : spec.keys()) {
    if (std::find(valid.begin(), valid.end(), side) == valid.end()) {
      continue;  // reported by finish() with a suggestion
    }
    setup::SideBoundary boundary;
    boundary.side = side;
    // The kinds are the boundary package's registry; a bare name only for those without parameters.
    const boundary::ConditionKind* kind = nullptr;
    std::optional<JsonObject> detail;
    if (spec.raw(side).is_string()) {
      kind = boundary::find_kind(spec.choice(side, boundary::kind_names(true)));
    } else {
      detail.emplace(spec.object(side));
      kind = boundary::find_kind(detail->choice("type", boundary::kind_names()));
    }
    boundary.condition = kind->kind;
    if (boundary.condition == setup::SideCondition::velocity) {
      // Each component: a number (m/s), an expression of t (a velocity in time) or null (free).
      const Json& v = detail->raw("velocity");
      const std::string expected =
          "[first, second] with numbers (m/s) or expressions of t such as \"-100 * min(t / 1e-6, 1)\", or null for a free component";
      if (!v.is_array() || v.size() != 2) detail->fail("velocity", expected);
      for (std::size_t k = 0; k < 2; ++k) {
        if (v[k].is_number()) {
          boundary.velocity[k] = v[k].get<double>();
        } else if (v[k].is_string()) {
          boundary.velocity_of_time[k] = time_function_from_json(v[k], fmt::format("{}[{}]", detail->path_of("velocity"), k));
        } else if (!v[k].is_null()) {
          detail->fail("velocity", expected);
        }
      }
      detail->resolve("velocity", v);
    }
    if (kind->loads) {
      // A pressure (against the outward normal) and a traction (along the side, counter-clockwise about
      // the body), each a number (Pa) or an expression of t; the kind's own key is required.
      for (const char* key : {"pressure", "traction"}) {
        const bool own = kind->name == key;
        const Json* value = own ? &detail->raw(key) : detail->optional_raw(key);
        if (!value) continue;
        (std::string_view(key) == "pressure" ? boundary.pressure : boundary.traction) =
            time_function_from_json(*value, detail->path_of(key));
        detail->resolve(key, *value);
      }
    }
    if (detail) detail->finish();
    result.push_back(std::move(boundary));
  }
  spec.finish(valid);
  return result;
}

setup::InitialState read_initial(JsonObject spec, GeometryKind geometry) {
  const AxisNames names = axis_names(geometry);
  setup::InitialState initial;
  auto function_of = [](ScalarField f) -> setup::PointFunction {
    return [f = std::move(f)](double first, double second) { return f.at(first, second); };
  };
  if (spec.has("velocity")) {
    auto velocity = read_field_pair(spec, "velocity", names, "an array [first, second] of numbers or expressions (m/s)");
    initial.velocity = std::array<setup::PointFunction, 2>{function_of(velocity[0]), function_of(velocity[1])};
  } else {
    spec.optional_raw("velocity");
  }
  auto zone_field = [&](std::string_view key, double fallback) -> setup::PointFunction {
    const Json* v = spec.optional_raw(key);
    spec.resolve(key, v ? *v : Json(fallback));
    if (!v) return {};
    return function_of(ScalarField::from_json(*v, spec.path_of(key), names.first, names.second));
  };
  if (spec.has("density")) {
    initial.density = zone_field("density", 0.0);
  } else {
    spec.optional_raw("density");  // the material's reference density
  }
  initial.specific_internal_energy = zone_field("specific_internal_energy", 0.0);
  if (auto deposit = spec.optional_object("energy_deposit")) {
    setup::EnergyDeposit d;
    d.energy = deposit->number("energy", Range::positive());
    const Json& point = deposit->raw("point");
    if (!point.is_array() || point.size() != 2 || !point[0].is_number() || !point[1].is_number()) {
      deposit->fail("point", "an array [first, second] of coordinates (m)");
    }
    deposit->resolve("point", point);
    deposit->finish();
    d.point = Vec2{point[0].get<double>(), point[1].get<double>()};
    initial.energy_deposit = d;
  }
  spec.finish();
  return initial;
}

}  // namespace krug::scenario::detail
