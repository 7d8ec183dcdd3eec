#include "scenario_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "expression.hpp"
#include "krug/core/error.hpp"
#include "krug/mesh/nosed_cylinder.hpp"
#include "krug/mesh/quality.hpp"

namespace krug::io::detail {

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

// Nodes of a side and which DOF a slip/symmetry condition holds there (the side's normal).
struct SideGeometry {
  bool along_first = false;   // all nodes share the first coordinate: the normal is the first axis
  bool along_second = false;  // all nodes share the second coordinate
};

SideGeometry side_geometry(const Mesh& mesh, const std::vector<Index>& nodes) {
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  for (Index n : nodes) {
    min_x = std::min(min_x, mesh.nodes.x[n]);
    max_x = std::max(max_x, mesh.nodes.x[n]);
    min_y = std::min(min_y, mesh.nodes.y[n]);
    max_y = std::max(max_y, mesh.nodes.y[n]);
  }
  const double extent = std::max({max_x - min_x, max_y - min_y, 1e-300});
  return {max_x - min_x <= 1e-9 * extent, max_y - min_y <= 1e-9 * extent};
}

}  // namespace

MeshedBody read_mesh(JsonObject spec, Mesh& mesh, Index body, GeometryKind geometry) {
  const AxisNames names = axis_names(geometry);
  const std::string type = spec.choice("type", {"rectangle", "sector", "nosed_cylinder"});
  generate::PositionMap map;
  if (spec.has("map")) {
    auto fields = read_field_pair(spec, "map", names, "an array of two expressions [new first, new second]");
    map = [fields](Vec2 p) { return Vec2{fields[0].at(p.x, p.y), fields[1].at(p.x, p.y)}; };
  } else {
    spec.optional_raw("map");
  }
  MeshedBody result;
  if (type == "rectangle") {
    const auto first = read_axis(spec.object(names.first));
    const auto second = read_axis(spec.object(names.second));
    const long zones = static_cast<long>(first.size() - 1) * static_cast<long>(second.size() - 1);
    if (zones > max_zones) spec.fail_here(fmt::format("{} zones is more than the {} this machine can hold", zones, max_zones));
    result.patch = generate::rectangle(mesh, first, second, body, map);
    result.side_names = {{names.first + "_min", "i_min"}, {names.first + "_max", "i_max"},
                         {names.second + "_min", "j_min"}, {names.second + "_max", "j_max"}};
  } else if (type == "nosed_cylinder") {
    // A projectile or rod along the axis: flat, hemispherical or tangent-ogive nose, O-grid at the nose.
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
    {
      // An upper bound of the generator's zone count: every column of the O-grid and shank.
      const long across = static_cast<long>(p.radial_zones) + p.core_zones + p.nose_zones;
      const long zones = across * (across + p.shank_zones);
      if (zones > max_zones) {
        spec.fail_here(fmt::format("up to {} zones is more than the {} this machine can hold", zones, max_zones));
      }
    }
    try {
      result.patch = generate::nosed_cylinder(mesh, p, body);
    } catch (const InputError& e) {
      spec.fail_here(e.what());  // the generator's reason, with the JSON path
    }
    for (const char* side : {"axis", "nose", "side", "rear"}) result.side_names[side] = side;
  } else {
    const auto radii = read_axis(spec.object("radius"));
    const auto angles = read_axis(spec.object("angle"), std::numbers::pi / 180.0);
    if (radii.front() < 0.0) spec.fail_here("radius.from must be >= 0");
    const long zones = static_cast<long>(radii.size() - 1) * static_cast<long>(angles.size() - 1);
    if (zones > max_zones) spec.fail_here(fmt::format("{} zones is more than the {} this machine can hold", zones, max_zones));
    result.patch = generate::sector(mesh, radii, angles, body, map);
    result.side_names = {{"inner", "i_min"}, {"outer", "i_max"}, {"start", "j_min"}, {"end", "j_max"}};
    if (radii.front() == 0.0) result.side_names.erase("inner");
  }
  spec.finish();
  return result;
}

void read_boundary(JsonObject spec, const MeshedBody& meshed, const std::string& body_name, GeometryKind geometry,
                   Mesh& mesh, std::map<Index, NodeConstraint>& constraints) {
  std::vector<std::string> valid;
  for (const auto& [user, _] : meshed.side_names) valid.push_back(user);
  for (const std::string& side : spec.keys()) {
    const auto found = meshed.side_names.find(side);
    if (found == meshed.side_names.end()) {
      continue;  // reported by finish() with a suggestion
    }
    const std::vector<Index>& nodes = meshed.patch.sides.at(found->second);
    const std::string path = spec.path_of(side);
    std::string type;
    std::optional<JsonObject> detail;
    if (spec.raw(side).is_string()) {
      type = spec.choice(side, {"free", "symmetry", "slip", "fixed"});
    } else {
      detail.emplace(spec.object(side));
      type = detail->choice("type", {"free", "symmetry", "slip", "fixed", "velocity"});
    }
    auto constrain = [&](Index n, bool fx, bool fy) {
      NodeConstraint& c = constraints[n];
      c.node = n;
      c.fix_x = c.fix_x || fx;
      c.fix_y = c.fix_y || fy;
    };
    if (type == "symmetry" || type == "slip") {
      const SideGeometry g = side_geometry(mesh, nodes);
      if (!g.along_first && !g.along_second) {
        throw InputError(fmt::format("{}: side \"{}\" of body \"{}\" is not a straight line along an axis; a {} "
                                     "condition needs a side of constant {} or constant {}",
                                     path, side, body_name, type, axis_name(geometry, 0), axis_name(geometry, 1)));
      }
      for (Index n : nodes) {
        constrain(n, g.along_first, g.along_second);
        if (g.along_first) mesh.nodes.u[n] = 0.0;
        if (g.along_second) mesh.nodes.v[n] = 0.0;
      }
    } else if (type == "fixed") {
      for (Index n : nodes) {
        constrain(n, true, true);
        mesh.nodes.u[n] = mesh.nodes.v[n] = 0.0;
      }
    } else if (type == "velocity") {
      const Json& v = detail->raw("velocity");
      const std::string expected = "[first, second] with numbers (m/s), or null for a free component";
      if (!v.is_array() || v.size() != 2) detail->fail("velocity", expected);
      for (int k = 0; k < 2; ++k) {
        if (!v[k].is_null() && !v[k].is_number()) detail->fail("velocity", expected);
      }
      detail->resolve("velocity", v);
      for (Index n : nodes) {
        constrain(n, v[0].is_number(), v[1].is_number());
        if (v[0].is_number()) mesh.nodes.u[n] = v[0].get<double>();
        if (v[1].is_number()) mesh.nodes.v[n] = v[1].get<double>();
      }
    }
    if (detail) detail->finish();
  }
  spec.finish(valid);
}

void read_initial(JsonObject spec, const Body& body, GeometryKind geometry, Mesh& mesh) {
  const AxisNames names = axis_names(geometry);
  if (spec.has("velocity")) {
    auto velocity = read_field_pair(spec, "velocity", names, "an array [first, second] of numbers or expressions (m/s)");
    for (Index n = body.node_begin; n < body.node_end; ++n) {
      mesh.nodes.u[n] = velocity[0].at(mesh.nodes.x[n], mesh.nodes.y[n]);
      mesh.nodes.v[n] = velocity[1].at(mesh.nodes.x[n], mesh.nodes.y[n]);
    }
  } else {
    spec.optional_raw("velocity");
  }
  auto zone_field = [&](std::string_view key, std::vector<double>& field, double fallback, bool positive) {
    const Json* v = spec.optional_raw(key);
    const ScalarField f = v ? ScalarField::from_json(*v, spec.path_of(key), names.first, names.second)
                            : ScalarField(fallback);
    spec.resolve(key, v ? *v : Json(fallback));
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      const Vec2 c = quad::centre(mesh.corner_positions(z));
      const double value = f.at(c.x, c.y);
      if (positive && !(value > 0.0)) {
        throw InputError(fmt::format("{}: gives {} at ({}, {}); expected a positive density", spec.path_of(key),
                                     value, c.x, c.y));
      }
      field[z] = value;
    }
  };
  if (spec.has("density")) {
    zone_field("density", mesh.zones.density, 0.0, true);
  } else {
    spec.optional_raw("density");  // the material's reference density, already set
  }
  zone_field("specific_internal_energy", mesh.zones.specific_energy, 0.0, false);
  if (auto deposit = spec.optional_object("energy_deposit")) {
    // Energy E (J; per unit thickness in planar geometry, whole body in axisymmetric) put into the
    // zones around the node nearest to `point`, in proportion to their mass.
    const double energy = deposit->number("energy", Range::positive());
    const Json& point = deposit->raw("point");
    if (!point.is_array() || point.size() != 2 || !point[0].is_number() || !point[1].is_number()) {
      deposit->fail("point", "an array [first, second] of coordinates (m)");
    }
    deposit->resolve("point", point);
    deposit->finish();
    const Vec2 target{point[0].get<double>(), point[1].get<double>()};
    Index closest = body.node_begin;
    for (Index n = body.node_begin; n < body.node_end; ++n) {
      if (norm(mesh.nodes.position(n) - target) < norm(mesh.nodes.position(closest) - target)) closest = n;
    }
    std::vector<Index> zones;
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      const ZoneCorners& c = mesh.zones.corners[z];
      if (std::find(c.begin(), c.end(), closest) != c.end()) zones.push_back(z);
    }
    // Masses are not known yet (the Simulation derives them): use density x volume here.
    double mass = 0.0;
    std::vector<double> zone_mass;
    for (Index z : zones) {
      const quad::Corners x = mesh.corner_positions(z);
      const double volume = geometry == GeometryKind::axisymmetric ? quad::axisymmetric_volume(x) : quad::area(x);
      zone_mass.push_back(mesh.zones.density[z] * volume);
      mass += zone_mass.back();
    }
    const double per_model = energy / whole_body_factor(geometry);
    for (std::size_t i = 0; i < zones.size(); ++i) {
      mesh.zones.specific_energy[zones[i]] += per_model / mass;  // same specific energy in each zone
    }
  }
  spec.finish();
}

}  // namespace krug::io::detail
