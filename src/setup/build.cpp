#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <variant>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/mesh/quality.hpp"
#include "krug/mesh/quad.hpp"
#include "krug/setup/scene.hpp"

namespace krug::setup {

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw InputError(fmt::format("{}: {}", where, message));
}

// `zones` more in a scene that has `before` already, against the scene's limit.
void check_zone_count(long zones, long before, long limit, const std::string& where, const char* qualifier = "") {
  if (zones + before > limit) {
    fail(where, fmt::format("{}{} zones ({} in the scene with the bodies before it, about {:.2g} GB of state) is more "
                            "than the {} allowed",
                            qualifier, zones, zones + before, static_cast<double>(zones + before) * bytes_per_zone / 1e9,
                            limit));
  }
}

// The mesh kinds (MeshShape in scene.hpp), one overload each: the kind's zone count checked against the
// scene's limit before anything is generated, then its generator. `before`: the zones already in the mesh.
generate::Patch generate_kind(const RectangleMesh& rectangle, const generate::PositionMap& map, Mesh& mesh, Index body,
                              long before, long zone_limit, const std::string& where) {
  check_zone_count(static_cast<long>(rectangle.first.size() - 1) * static_cast<long>(rectangle.second.size() - 1),
                   before, zone_limit, where);
  return generate::rectangle(mesh, rectangle.first, rectangle.second, body, map);
}

generate::Patch generate_kind(const SectorMesh& sector, const generate::PositionMap& map, Mesh& mesh, Index body,
                              long before, long zone_limit, const std::string& where) {
  if (sector.radii.front() < 0.0) fail(where, "radius.from must be >= 0");
  if (sector.angles.back() - sector.angles.front() > 2.0 * std::numbers::pi * (1.0 + 1e-12)) {
    fail(where, fmt::format("the sector spans {:g} radians; at most 2 pi", sector.angles.back() - sector.angles.front()));
  }
  check_zone_count(static_cast<long>(sector.radii.size() - 1) * static_cast<long>(sector.angles.size() - 1), before,
                   zone_limit, where);
  return generate::sector(mesh, sector.radii, sector.angles, body, map);
}

generate::Patch generate_kind(const NosedCylinderMesh& cylinder, const generate::PositionMap& map, Mesh& mesh,
                              Index body, long before, long zone_limit, const std::string& where) {
  const generate::NosedCylinderParams& p = cylinder.params;
  // An upper bound of the generator's zone count: every column of the O-grid and shank.
  const long across = static_cast<long>(p.radial_zones) + p.core_zones + p.nose_zones;
  check_zone_count(across * (across + p.shank_zones), before, zone_limit, where, "up to ");
  generate::Patch patch;
  try {
    patch = generate::nosed_cylinder(mesh, p, body);
  } catch (const InputError& e) {
    fail(where, e.what());  // the generator's reason, with the body's name
  }
  // The map moves every generated node, as the other kinds' generators apply it.
  if (map) {
    for (Index n = patch.node_begin; n < patch.node_end; ++n) {
      const Vec2 moved = map(mesh.nodes.position(n));
      mesh.nodes.x[n] = moved.x;
      mesh.nodes.y[n] = moved.y;
    }
  }
  return patch;
}

generate::Patch generate_mesh(const MeshDescription& description, Mesh& mesh, Index body, long zone_limit,
                              const std::string& where) {
  const long before = mesh.zones.size();
  return std::visit([&](const auto& kind) { return generate_kind(kind, description.map, mesh, body, before, zone_limit, where); },
                    description.shape);
}

// The side names of each mesh kind (user name -> generator side name).
std::map<std::string, std::string> kind_sides(const RectangleMesh&, GeometryKind geometry) {
  const std::string first(axis_name(geometry, 0)), second(axis_name(geometry, 1));
  return {{first + "_min", "i_min"}, {first + "_max", "i_max"}, {second + "_min", "j_min"}, {second + "_max", "j_max"}};
}

std::map<std::string, std::string> kind_sides(const SectorMesh& sector, GeometryKind) {
  std::map<std::string, std::string> sides = {{"outer", "i_max"}, {"start", "j_min"}, {"end", "j_max"}};
  if (sector.radii.empty() || sector.radii.front() != 0.0) sides["inner"] = "i_min";
  return sides;
}

std::map<std::string, std::string> kind_sides(const NosedCylinderMesh&, GeometryKind) {
  std::map<std::string, std::string> sides;
  for (const char* side : {"axis", "nose", "side", "rear"}) sides[side] = side;
  return sides;
}

void set_initial_fields(const InitialState& initial, const Body& body, GeometryKind geometry, Mesh& mesh,
                        const std::string& where) {
  if (initial.velocity) {
    const auto& velocity = *initial.velocity;
    for (Index n = body.node_begin; n < body.node_end; ++n) {
      mesh.nodes.u[n] = velocity[0](mesh.nodes.x[n], mesh.nodes.y[n]);
      mesh.nodes.v[n] = velocity[1](mesh.nodes.x[n], mesh.nodes.y[n]);
    }
  }
  auto zone_field = [&](const PointFunction& f, std::vector<double>& field, bool positive, const char* key) {
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      const Vec2 c = quad::centre(mesh.corner_positions(z));
      const double value = f ? f(c.x, c.y) : 0.0;
      if (positive && !(value > 0.0)) {
        fail(where + ".initial." + key, fmt::format("gives {} at ({}, {}); expected a positive density", value, c.x, c.y));
      }
      field[z] = value;
    }
  };
  if (initial.density) zone_field(initial.density, mesh.zones.density, true, "density");
  zone_field(initial.specific_internal_energy, mesh.zones.specific_energy, false, "specific_internal_energy");
  if (initial.energy_deposit) {
    const Vec2 target = initial.energy_deposit->point;
    Index closest = body.node_begin;
    for (Index n = body.node_begin; n < body.node_end; ++n) {
      if (norm(mesh.nodes.position(n) - target) < norm(mesh.nodes.position(closest) - target)) closest = n;
    }
    std::vector<Index> zones;
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      const ZoneCorners& c = mesh.zones.corners[z];
      if (std::find(c.begin(), c.end(), closest) != c.end()) zones.push_back(z);
    }
    // Masses are not known yet (the Simulation derives them): density x volume here.
    double mass = 0.0;
    std::vector<double> zone_mass;
    for (Index z : zones) {
      const quad::Corners x = mesh.corner_positions(z);
      const double volume = geometry == GeometryKind::axisymmetric ? quad::axisymmetric_volume(x) : quad::area(x);
      zone_mass.push_back(mesh.zones.density[z] * volume);
      mass += zone_mass.back();
    }
    const double per_model = initial.energy_deposit->energy / whole_body_factor(geometry);
    for (std::size_t i = 0; i < zones.size(); ++i) {
      mesh.zones.specific_energy[zones[i]] += per_model / mass;  // same specific energy in each zone
    }
  }
}

// Applies a body's side conditions through the boundary package's registry (boundary::condition_kinds()):
// held components go to `constraints` (a node on two sides takes both), with the condition that holds
// each in `held_by` and the side in `held_side`; driven components and loads to `target`. Functions of time are checked for finite
// values over the run.
void apply_boundary(const std::vector<SideBoundary>& boundary, const generate::Patch& patch, const Body& body,
                    const std::vector<std::pair<std::string, std::string>>& sides, GeometryKind geometry, Mesh& mesh,
                    double end_time, std::map<Index, NodeConstraint>& constraints,
                    std::map<Index, std::array<std::string, 2>>& held_by,
                    std::map<Index, std::array<std::string, 2>>& held_side, boundary::Target& target,
                    const std::string& where) {
  std::vector<BoundarySegment> body_segments;
  std::map<std::string, std::string> kinematic_sides;  // side -> the kind that holds it
  for (const SideBoundary& b : boundary) {
    if (boundary::kind_of(b.condition).holds) kinematic_sides[b.side] = boundary::kind_of(b.condition).name;
  }
  for (const SideBoundary& b : boundary) {
    const auto found = std::find_if(sides.begin(), sides.end(), [&](const auto& s) { return s.first == b.side; });
    if (found == sides.end()) {
      std::string valid;
      for (const auto& [user, _] : sides) valid += (valid.empty() ? "" : ", ") + user;
      fail(where + ".boundary." + b.side, fmt::format("body \"{}\" has no side of that name; its sides: {}", body.name, valid));
    }
    const boundary::ConditionKind& kind = boundary::kind_of(b.condition);
    boundary::Side side{b.side, body.name, where + ".boundary." + b.side, patch.sides.at(found->second), {}};
    if (kind.loads) {
      if (const auto held = kinematic_sides.find(b.side); held != kinematic_sides.end()) {
        fail(side.where, fmt::format("side \"{}\" of body \"{}\" is held by a {} condition and also given a {} load; a "
                                     "held face takes no load (the condition would absorb it)",
                                     b.side, body.name, held->second, kind.name));
      }
      if (body_segments.empty()) body_segments = boundary_segments(mesh, body.zone_begin, body.zone_end);
      const std::set<Index> on_side(side.nodes.begin(), side.nodes.end());
      for (const BoundarySegment& s : body_segments) {
        if (on_side.contains(s.a) && on_side.contains(s.b)) side.segments.push_back(s);
      }
    }
    // A function of time must give finite values over the run: sampled at 1001 times in [0, end_time].
    auto check_finite = [&](const boundary::TimeFunction& f, const std::string& key) {
      if (!f) return;
      for (int i = 0; i <= 1000; ++i) {
        const double t = end_time * i / 1000.0;
        const double value = f(t);
        if (!std::isfinite(value)) {
          fail(side.where + "." + key, fmt::format("gives {} at t = {:g} s; expected a finite value over the run", value, t));
        }
      }
    };
    check_finite(b.velocity_of_time[0], "velocity[0]");
    check_finite(b.velocity_of_time[1], "velocity[1]");
    check_finite(b.pressure, "pressure");
    check_finite(b.traction, "traction");
    const std::string label = fmt::format("{} ({})", side.where, kind.name);
    target.hold = [&](Index n, bool fx, bool fy) {
      NodeConstraint& c = constraints[n];
      c.node = n;
      c.fix_x = c.fix_x || fx;
      c.fix_y = c.fix_y || fy;
      if (fx) held_by[n][0] = label;
      if (fy) held_by[n][1] = label;
      if (fx) held_side[n][0] = b.side;
      if (fy) held_side[n][1] = b.side;
    };
    const boundary::Condition condition{b.condition, b.velocity, b.velocity_of_time, b.pressure, b.traction};
    kind.apply(condition, side, geometry, mesh.nodes, target);
    target.hold = nullptr;
  }
}

// Two bodies of a contact pair that touch, facing each other, where both hold the same velocity
// component at values that drive them into each other, cannot be kept apart: contact moves neither
// held node, so the bodies would pass through each other (or tangle the zones between). Such a
// scenario is refused, naming both conditions. Only nodes that coincide at the start are compared:
// held faces that meet later, across a gap, are not detected here.
void check_held_contact(const SimulationSetup& setup, const std::map<Index, NodeConstraint>& constraints,
                        const std::map<Index, std::array<std::string, 2>>& held_by, GeometryKind geometry) {
  const bool any_pair = std::any_of(setup.contact.pairs.begin(), setup.contact.pairs.end(),
                                    [](const contact::BodyPair& p) { return p.first != p.second; });
  if (!any_pair || constraints.empty()) return;
  const Mesh& mesh = setup.mesh;
  struct Held {
    Index node;
    NodeConstraint constraint;
    Vec2 outward;  // from the mean centre of the node's zones to the node
  };
  std::vector<std::vector<Held>> held(setup.bodies.size());
  std::map<Index, std::pair<Vec2, int>> centres;  // per held node: sum of its zones' centres, count
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    const ZoneCorners& n = mesh.zones.corners[z];
    const Vec2 centre = 0.25 * (mesh.nodes.position(n[0]) + mesh.nodes.position(n[1]) + mesh.nodes.position(n[2]) +
                                mesh.nodes.position(n[3]));
    for (int p = 0; p < 4; ++p) {
      if (std::find(n.begin(), n.begin() + p, n[p]) != n.begin() + p) continue;  // a repeated corner once
      if (!constraints.contains(n[p])) continue;
      auto& [sum, count] = centres[n[p]];
      sum += centre;
      ++count;
    }
  }
  for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
    const Body& body = setup.bodies[i];
    for (auto it = constraints.lower_bound(body.node_begin); it != constraints.end() && it->first < body.node_end; ++it) {
      const auto found = centres.find(it->first);
      if (found == centres.end()) continue;
      const auto& [sum, count] = found->second;
      held[i].push_back({it->first, it->second, mesh.nodes.position(it->first) - (1.0 / count) * sum});
    }
  }
  for (std::size_t k = 0; k < setup.contact.pairs.size(); ++k) {
    const contact::BodyPair& pair = setup.contact.pairs[k];
    if (pair.first == pair.second) continue;
    const std::size_t i = static_cast<std::size_t>(pair.first), j = static_cast<std::size_t>(pair.second);
    if (i >= held.size() || j >= held.size()) continue;  // the contact set-up names the bad pair itself
    for (const Held& a : held[i]) {
      const Vec2 pa = mesh.nodes.position(a.node);
      const double reach = 1e-6 * norm(a.outward);  // "touching": within a millionth of the zone's size
      for (const Held& b : held[j]) {
        if (norm(mesh.nodes.position(b.node) - pa) > reach) continue;
        for (int c = 0; c < 2; ++c) {
          if (!(c == 0 ? a.constraint.fix_x && b.constraint.fix_x : a.constraint.fix_y && b.constraint.fix_y)) continue;
          const double outward_a = c == 0 ? a.outward.x : a.outward.y, outward_b = c == 0 ? b.outward.x : b.outward.y;
          if (!(outward_a * outward_b < 0.0)) continue;  // not facing each other along this component
          const double va = c == 0 ? mesh.nodes.u[a.node] : mesh.nodes.v[a.node];
          const double vb = c == 0 ? mesh.nodes.u[b.node] : mesh.nodes.v[b.node];
          if (!((va - vb) * outward_a > 0.0)) continue;  // separating or moving together
          fail(fmt::format("contact.pairs[{}]", k),
               fmt::format("\"{}\" and \"{}\" touch at ({:.6g}, {:.6g}) m, where {} holds v_{} = {:g} m/s and {} "
                           "holds v_{} = {:g} m/s: the held nodes close at {:g} m/s and contact cannot move either, so "
                           "the bodies would pass through each other; free one of the two conditions",
                           setup.bodies[i].name, setup.bodies[j].name, pa.x, pa.y,
                           held_by.at(a.node)[static_cast<std::size_t>(c)], axis_name(geometry, c), va,
                           held_by.at(b.node)[static_cast<std::size_t>(c)], axis_name(geometry, c), vb, std::abs(va - vb)));
        }
      }
    }
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> side_names(const MeshDescription& mesh, GeometryKind geometry) {
  // sorted by the user's name
  const std::map<std::string, std::string> sides =
      std::visit([&](const auto& kind) { return kind_sides(kind, geometry); }, mesh.shape);
  return {sides.begin(), sides.end()};
}

SimulationSetup build_simulation(const SceneDescription& scene) {
  SimulationSetup setup;
  setup.geometry = scene.geometry;
  setup.materials = scene.materials;
  setup.fracture = scene.fracture;
  std::map<Index, NodeConstraint> constraints;
  std::map<Index, std::array<std::string, 2>> held_by;  // the boundary condition that holds each component
  std::map<Index, std::array<std::string, 2>> held_side;  // the side whose condition holds it (the last applied)
  boundary::Target target;  // driven components and loads of every body
  std::vector<std::string> where;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyDescription& description = scene.bodies[i];
    where.push_back(description.where.empty() ? fmt::format("bodies[{}]", i) : description.where);
    if (description.material < 0 || static_cast<std::size_t>(description.material) >= scene.materials.size()) {
      fail(where.back(), fmt::format("material index {} is not one of the scene's {} materials", description.material,
                                     scene.materials.size()));
    }
    if (scene.geometry == GeometryKind::axisymmetric &&
        scene.controls.axisymmetric_form == AxisymmetricForm::area_weighted &&
        !std::holds_alternative<NoStrength>(scene.materials[static_cast<std::size_t>(description.material)].strength)) {
      // Measured: a 6061 shell at rest, unloaded, grows hourglass energy by about e^5.5 per microsecond
      // in this form, and an elastic sphere rebounds faster than it struck (docs/verification.md).
      fail("controls.axisymmetric_form",
           fmt::format("\"area_weighted\" is for gases only, and body \"{}\" ({}) has material \"{}\" with strength: "
                       "the form is unstable with a stress deviator (its hourglass modes grow without load); use "
                       "\"control_volume\"",
                       description.name, where.back(),
                       scene.materials[static_cast<std::size_t>(description.material)].name));
    }
    Body body;
    body.name = description.name;
    body.material = description.material;
    body.set_erosion(description.erosion);
    body.rezone_ratio = description.rezone.altitude_ratio;
    body.rezone_relaxation = description.rezone.relaxation;
    const auto m = static_cast<std::size_t>(description.material);
    if (body.rezone_ratio > 0.0 && m < scene.fracture.size() && fracture::enabled(scene.fracture[m])) {
      fail(where.back() + ".rezone", "no rezone on a body whose material has a failure law (the remap does not "
                                     "carry damage)");
    }
    const generate::Patch patch =
        generate_mesh(description.mesh, setup.mesh, static_cast<Index>(i), scene.max_zones, where.back() + ".mesh");
    body.node_begin = patch.node_begin;
    body.node_end = patch.node_end;
    body.zone_begin = patch.zone_begin;
    body.zone_end = patch.zone_end;
    for (Index n = body.node_begin; n < body.node_end; ++n) {
      const double x = setup.mesh.nodes.x[n], y = setup.mesh.nodes.y[n];
      if (!(std::abs(x) <= max_coordinate && std::abs(y) <= max_coordinate)) {
        fail(where.back() + ".mesh", fmt::format("a node at ({:g}, {:g}) m lies beyond {:g} m of the origin; Krug's "
                                                 "scenarios are in SI units (m)",
                                                 x, y, max_coordinate));
      }
    }
    if (scene.geometry == GeometryKind::axisymmetric) {
      for (Index n = body.node_begin; n < body.node_end; ++n) {
        if (setup.mesh.nodes.y[n] < 0.0) {
          if (setup.mesh.nodes.y[n] > -1e-12) { setup.mesh.nodes.y[n] = 0.0; continue; }
          fail(where.back(), fmt::format("node at (z, r) = ({}, {}) lies below the axis; axisymmetric bodies need r >= 0",
                                         setup.mesh.nodes.x[n], setup.mesh.nodes.y[n]));
        }
      }
    }
    for (Index z = body.zone_begin; z < body.zone_end; ++z) {
      setup.mesh.zones.density[z] = scene.materials[static_cast<std::size_t>(body.material)].reference_density;
    }
    set_initial_fields(description.initial, body, scene.geometry, setup.mesh, where.back());
    apply_boundary(description.boundary, patch, body, side_names(description.mesh, scene.geometry), scene.geometry,
                   setup.mesh, scene.controls.end_time, constraints, held_by, held_side, target, where.back());
    // The body's held components by side, the sides in the scenario's order.
    for (const SideBoundary& b : description.boundary) {
      boundary::HeldSide group{static_cast<Index>(i), b.side, {}};
      if (std::any_of(setup.held_sides.begin(), setup.held_sides.end(), [&](const boundary::HeldSide& h) {
            return h.body == group.body && h.side == group.side;
          })) {
        continue;  // a side named twice
      }
      for (auto it = held_side.lower_bound(body.node_begin); it != held_side.end() && it->first < body.node_end; ++it) {
        const bool fx = it->second[0] == b.side, fy = it->second[1] == b.side;
        if (fx || fy) group.components.push_back({it->first, fx, fy});
      }
      if (!group.components.empty()) setup.held_sides.push_back(std::move(group));
    }
    setup.bodies.push_back(body);
  }
  // Bodies may touch but not overlap: a node or a zone centre of one inside a zone of another is an input error.
  build_edge_continuations(setup.mesh);
  for (std::size_t i = 0; i < setup.bodies.size(); ++i) {
    for (std::size_t j = 0; j < setup.bodies.size(); ++j) {
      if (i == j) continue;
      const Body& a = setup.bodies[i];
      const Body& b = setup.bodies[j];
      if (const auto overlap = find_node_inside_zones(setup.mesh, a.node_begin, a.node_end, b.zone_begin, b.zone_end)) {
        const Vec2 p = setup.mesh.nodes.position(overlap->node);
        throw InputError(fmt::format(
            "{} (\"{}\") overlaps {} (\"{}\"): its node at ({:.6g}, {:.6g}) lies {:.3g} m inside "
            "zone {} of \"{}\"; bodies may touch but not overlap (check the meshes' positions)",
            where[i], a.name, where[j], b.name, p.x, p.y, overlap->depth, overlap->zone - b.zone_begin, b.name));
      }
      if (const auto overlap = find_zone_centre_inside_zones(setup.mesh, a.zone_begin, a.zone_end, b.zone_begin, b.zone_end)) {
        Vec2 centre{0.0, 0.0};
        for (const Vec2& c : setup.mesh.corner_positions(overlap->node)) centre += 0.25 * c;
        throw InputError(fmt::format(
            "{} (\"{}\") overlaps {} (\"{}\"): the centre ({:.6g}, {:.6g}) of its zone {} lies {:.3g} m inside zone {} "
            "of \"{}\" (the two meshes share nodes or coincide); bodies may touch but not overlap (check the meshes' "
            "positions)",
            where[i], a.name, where[j], b.name, centre.x, centre.y, overlap->node - a.zone_begin, overlap->depth,
            overlap->zone - b.zone_begin, b.name));
      }
    }
  }
  for (const auto& [node, c] : constraints) setup.constraints.push_back(c);
  if (!target.loads.empty() && scene.geometry == GeometryKind::axisymmetric &&
      scene.controls.axisymmetric_form == AxisymmetricForm::area_weighted) {
    fail("controls.axisymmetric_form", "pressure and traction loads are weighted as the control-volume corner forces are; "
                                       "the \"area_weighted\" form does not take them");
  }
  setup.driven = std::move(target.driven);
  setup.loads = std::move(target.loads);
  setup.contact = scene.contact;
  check_held_contact(setup, constraints, held_by, scene.geometry);
  setup.controls = scene.controls;
  return setup;
}

}  // namespace krug::setup
