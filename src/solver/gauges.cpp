#include "krug/solver/gauges.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "krug/core/error.hpp"

namespace krug {

namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// Bilinear shape functions at (xi, eta); corner p at ((-1,-1), (1,-1), (1,1), (-1,1))[p].
std::array<double, 4> shape(double xi, double eta) {
  return {0.25 * (1.0 - xi) * (1.0 - eta), 0.25 * (1.0 + xi) * (1.0 - eta), 0.25 * (1.0 + xi) * (1.0 + eta),
          0.25 * (1.0 - xi) * (1.0 + eta)};
}

Vec2 corner(const Mesh& mesh, Index node, bool current) {
  return current ? mesh.nodes.position(node) : Vec2{mesh.nodes.x0[node], mesh.nodes.y0[node]};
}

// The bilinear coordinates of `p` in the quad `c` by Newton's method; none when it does not converge.
std::optional<std::pair<double, double>> inverse_bilinear(const std::array<Vec2, 4>& c, Vec2 p) {
  double xi = 0.0, eta = 0.0;
  for (int iteration = 0; iteration < 30; ++iteration) {
    const std::array<double, 4> n = shape(xi, eta);
    Vec2 x{};
    for (int k = 0; k < 4; ++k) x += n[static_cast<std::size_t>(k)] * c[static_cast<std::size_t>(k)];
    const Vec2 r = x - p;
    // dx/dxi, dx/deta
    const Vec2 dxi = 0.25 * ((1.0 - eta) * (c[1] - c[0]) + (1.0 + eta) * (c[2] - c[3]));
    const Vec2 deta = 0.25 * ((1.0 - xi) * (c[3] - c[0]) + (1.0 + xi) * (c[2] - c[1]));
    const double det = dxi.x * deta.y - dxi.y * deta.x;
    if (!(std::abs(det) > 0.0)) return std::nullopt;
    const double dx = (r.x * deta.y - r.y * deta.x) / det;
    const double de = (dxi.x * r.y - dxi.y * r.x) / det;
    xi -= dx;
    eta -= de;
    if (std::abs(dx) + std::abs(de) < 1e-14) return std::pair{xi, eta};
    if (std::abs(xi) > 10.0 || std::abs(eta) > 10.0) return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

const std::vector<std::string>& tracer_quantity_names() {
  static const std::vector<std::string> names = {"position", "velocity", "pressure", "stress", "von_mises",
                                                 "plastic_strain", "density", "specific_energy", "temperature",
                                                 "damage"};
  return names;
}

std::optional<TracerLocation> locate_tracer(const Mesh& mesh, Vec2 position, bool current_positions) {
  constexpr double slack = 1e-9;  // a point on an edge belongs to the first zone holding it
  for (Index z = 0; z < mesh.zones.size(); ++z) {
    const ZoneCorners& k = mesh.zones.corners[z];
    std::array<Vec2, 4> c;
    Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    Vec2 hi = -1.0 * lo;
    for (std::size_t p = 0; p < 4; ++p) {
      c[p] = corner(mesh, k[p], current_positions);
      lo = {std::min(lo.x, c[p].x), std::min(lo.y, c[p].y)};
      hi = {std::max(hi.x, c[p].x), std::max(hi.y, c[p].y)};
    }
    const double margin = slack * std::max(hi.x - lo.x, hi.y - lo.y);
    if (position.x < lo.x - margin || position.x > hi.x + margin || position.y < lo.y - margin ||
        position.y > hi.y + margin) {
      continue;
    }
    const auto found = inverse_bilinear(c, position);
    if (!found) continue;
    const auto [xi, eta] = *found;
    if (std::abs(xi) <= 1.0 + slack && std::abs(eta) <= 1.0 + slack) {
      return TracerLocation{z, std::clamp(xi, -1.0, 1.0), std::clamp(eta, -1.0, 1.0)};
    }
  }
  return std::nullopt;
}

SurfaceLocation locate_surface_node(const Mesh& mesh, const Body& body, Vec2 position, bool current_positions) {
  // Boundary edges of the body's initial connectivity: those used by one zone only.
  std::map<std::pair<Index, Index>, int> uses;
  for (Index z = body.zone_begin; z < body.zone_end; ++z) {
    const ZoneCorners& c = mesh.zones.corners[z];
    for (int p = 0; p < 4; ++p) {
      const Index a = c[static_cast<std::size_t>(p)], b = c[static_cast<std::size_t>((p + 1) % 4)];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::map<Index, Vec2> normals;  // boundary node -> sum of its edges' outward normals
  for (Index z = body.zone_begin; z < body.zone_end; ++z) {
    const ZoneCorners& c = mesh.zones.corners[z];
    for (int p = 0; p < 4; ++p) {
      const Index a = c[static_cast<std::size_t>(p)], b = c[static_cast<std::size_t>((p + 1) % 4)];
      if (uses[{std::min(a, b), std::max(a, b)}] != 1) continue;
      // Counter-clockwise zone: the outward normal is to the right of a -> b.
      const Vec2 e = corner(mesh, b, current_positions) - corner(mesh, a, current_positions);
      const double length = norm(e);
      if (!(length > 0.0)) continue;
      const Vec2 n{e.y / length, -e.x / length};
      normals[a] += n;
      normals[b] += n;
    }
  }
  SurfaceLocation best;
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& [node, n] : normals) {
    const double d = norm(corner(mesh, node, current_positions) - position);
    if (d < nearest) {
      nearest = d;
      best.node = node;
      best.normal = norm(n) > 0.0 ? (1.0 / norm(n)) * n : Vec2{};
    }
  }
  return best;
}

bool has_temperature(const Simulation& simulation) {
  return std::any_of(simulation.materials().begin(), simulation.materials().end(),
                     [](const Material& m) { return std::holds_alternative<JohnsonCook>(m.strength); });
}

GaugeSampler::GaugeSampler(const GaugeSettings& settings, const Simulation& simulation) : settings_(settings) {
  const Mesh& mesh = simulation.mesh();
  const GeometryKind g = simulation.geometry();
  const std::string a0(axis_name(g, 0)), a1(axis_name(g, 1));
  const bool temperature = has_temperature(simulation);
  for (std::size_t i = 0; i < settings_.tracers.size(); ++i) {
    TracerGauge& t = settings_.tracers[i];
    const auto where = locate_tracer(mesh, t.position);
    if (!where) {
      throw InputError(fmt::format("gauges.tracers[{}].position: ({:.6g}, {:.6g}) lies in no zone of any body at t = 0",
                                   i, t.position.x, t.position.y));
    }
    tracers_.push_back(*where);
    if (t.quantities.empty()) {
      for (std::size_t q = 0; q < tracer_quantity_names().size(); ++q) {
        const auto quantity = static_cast<TracerQuantity>(q);
        if (quantity == TracerQuantity::temperature && !temperature) continue;
        t.quantities.push_back(quantity);
      }
    }
    for (const TracerQuantity q : t.quantities) {
      const std::string& n = t.name;
      switch (q) {
        case TracerQuantity::position:
          columns_.insert(columns_.end(), {n + "_" + a0, n + "_" + a1});
          break;
        case TracerQuantity::velocity:
          columns_.insert(columns_.end(), {n + "_v" + a0, n + "_v" + a1});
          break;
        case TracerQuantity::pressure: columns_.push_back(n + "_pressure"); break;
        case TracerQuantity::stress: {
          const std::string third = g == GeometryKind::axisymmetric ? "tt" : "zz";
          columns_.insert(columns_.end(), {n + "_sigma_" + a0 + a0, n + "_sigma_" + a1 + a1, n + "_sigma_" + a0 + a1,
                                           n + "_sigma_" + third});
          break;
        }
        case TracerQuantity::von_mises: columns_.push_back(n + "_von_mises"); break;
        case TracerQuantity::plastic_strain: columns_.push_back(n + "_plastic_strain"); break;
        case TracerQuantity::density: columns_.push_back(n + "_density"); break;
        case TracerQuantity::specific_energy: columns_.push_back(n + "_specific_energy"); break;
        case TracerQuantity::temperature:
          if (!temperature) {
            throw InputError(fmt::format("gauges.tracers[{}].quantities: \"temperature\": no material of this scenario "
                                         "carries a temperature (only the johnson_cook strength model does)", i));
          }
          columns_.push_back(n + "_temperature");
          break;
        case TracerQuantity::damage: columns_.push_back(n + "_damaged"); break;
      }
    }
  }
  for (std::size_t i = 0; i < settings_.surfaces.size(); ++i) {
    const SurfaceGauge& s = settings_.surfaces[i];
    const Body& body = simulation.bodies().at(static_cast<std::size_t>(s.body));
    SurfaceLocation where = locate_surface_node(mesh, body, s.position);
    if (where.node < 0) throw InputError(fmt::format("gauges.surfaces[{}].body: \"{}\" has no boundary", i, body.name));
    if (s.direction) where.normal = *s.direction;
    surfaces_.push_back(where);
    columns_.insert(columns_.end(), {s.name + "_" + a0, s.name + "_" + a1, s.name + "_v" + a0, s.name + "_v" + a1,
                                     s.name + "_velocity"});
  }
  if (settings_.forces) {
    const auto& bodies = simulation.bodies();
    const auto add = [&](Channel c, const std::string& name) {
      channels_.push_back(c);
      columns_.insert(columns_.end(), {name + "_F" + a0, name + "_F" + a1, name + "_I" + a0, name + "_I" + a1});
    };
    const contact::ContactSetup& contact = simulation.contact().setup();
    for (std::size_t k = 0; k < contact.pairs.size(); ++k) {
      const contact::BodyPair& p = contact.pairs[k];
      if (p.first == p.second) continue;  // self-contact: a body cannot push itself as a whole
      add({Channel::Kind::pair, static_cast<Index>(k)},
          fmt::format("pair_{}_{}", bodies[static_cast<std::size_t>(p.first)].name,
                      bodies[static_cast<std::size_t>(p.second)].name));
    }
    for (std::size_t w = 0; w < contact.walls.size(); ++w) {
      add({Channel::Kind::wall, static_cast<Index>(w)}, fmt::format("wall{}", w));
    }
    // Per body: one channel per side that holds components (held_<body>_<side>), then one for the
    // held components no side of the scenario holds (held_<body>: the axis in RZ, or a condition
    // given in code).
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      std::map<Index, std::array<bool, 2>> by_side;  // the body's components some side holds
      for (const boundary::HeldSide& side : simulation.held_sides()) {
        if (side.body != static_cast<Index>(b)) continue;
        for (const NodeConstraint& c : side.components) {
          by_side[c.node][0] = by_side[c.node][0] || c.fix_x;
          by_side[c.node][1] = by_side[c.node][1] || c.fix_y;
        }
        held_.push_back(side.components);
        add({Channel::Kind::held, static_cast<Index>(b)}, "held_" + bodies[b].name + "_" + side.side);
      }
      std::vector<NodeConstraint> rest;
      for (const NodeConstraint& c : simulation.constraints()) {
        if (c.node < bodies[b].node_begin || c.node >= bodies[b].node_end) continue;
        const auto found = by_side.find(c.node);
        const bool fx = c.fix_x && (found == by_side.end() || !found->second[0]);
        const bool fy = c.fix_y && (found == by_side.end() || !found->second[1]);
        if (fx || fy) rest.push_back({c.node, fx, fy});
      }
      if (rest.empty()) continue;
      held_.push_back(std::move(rest));
      add({Channel::Kind::held, static_cast<Index>(b)}, "held_" + bodies[b].name);
    }
    force_.assign(2 * channels_.size(), 0.0);
    impulse_.assign(2 * channels_.size(), 0.0);
  }
}

void GaugeSampler::restore_impulses(const std::vector<double>& impulses) {
  if (impulses.size() != impulse_.size()) {
    throw InputError(fmt::format("restart: the checkpoint carries {} gauge impulses, the scenario's gauges {}",
                                 impulses.size(), impulse_.size()));
  }
  impulse_ = impulses;
}

void GaugeSampler::accumulate(const Simulation& simulation) {
  if (channels_.empty()) return;
  const contact::ContactSolver& contact = simulation.contact();
  const bool any_contact = !contact.empty();
  if (any_contact) contact.source_forces(simulation.mesh(), scratch_);
  const NodeFields& nodes = simulation.mesh().nodes;
  std::size_t held = 0;
  for (std::size_t k = 0; k < channels_.size(); ++k) {
    const Channel& c = channels_[k];
    Vec2 f;
    switch (c.kind) {
      case Channel::Kind::pair: f = any_contact ? scratch_.pairs[static_cast<std::size_t>(c.index)] : Vec2{}; break;
      case Channel::Kind::wall: f = any_contact ? scratch_.walls[static_cast<std::size_t>(c.index)] : Vec2{}; break;
      case Channel::Kind::held:
        // The boundary keeps the held components: it supplies -(F + R) there (Simulation::predict_velocities,
        // book_contact_work).
        for (const NodeConstraint& h : held_[held]) {
          const Vec2 r = any_contact ? contact.reaction_force(contact::ContactPoint::node(h.node)) : Vec2{};
          if (h.fix_x) f.x -= nodes.force_x[h.node] + r.x;
          if (h.fix_y) f.y -= nodes.force_y[h.node] + r.y;
        }
        ++held;
        break;
    }
    force_[2 * k] = f.x;
    force_[2 * k + 1] = f.y;
    const double dt = simulation.last_step_mid();
    impulse_[2 * k] += dt * f.x;
    impulse_[2 * k + 1] += dt * f.y;
  }
}

void GaugeSampler::sample(const Simulation& simulation, std::vector<double>& values) const {
  values.clear();
  const Mesh& mesh = simulation.mesh();
  const NodeFields& nodes = mesh.nodes;
  const ZoneFields& zones = mesh.zones;
  const ZoneState& state = simulation.zone_state();
  for (std::size_t i = 0; i < tracers_.size(); ++i) {
    const TracerLocation& t = tracers_[i];
    const bool active = zones.active[t.zone] != 0;
    const ZoneCorners& c = zones.corners[t.zone];
    const std::array<double, 4> n = shape(t.xi, t.eta);
    Vec2 x, u;
    for (std::size_t p = 0; p < 4; ++p) {
      x += n[p] * nodes.position(c[p]);
      u += n[p] * nodes.velocity(c[p]);
    }
    const double nan = not_a_number;
    const double pressure = active ? state.hydro.pressure[t.zone] : nan;
    const double sxx = state.strength.deviator_xx[t.zone], syy = state.strength.deviator_yy[t.zone];
    const double sxy = state.strength.deviator_xy[t.zone], szz = state.strength.deviator_zz[t.zone];
    for (const TracerQuantity q : settings_.tracers[i].quantities) {
      switch (q) {
        case TracerQuantity::position: values.insert(values.end(), {active ? x.x : nan, active ? x.y : nan}); break;
        case TracerQuantity::velocity: values.insert(values.end(), {active ? u.x : nan, active ? u.y : nan}); break;
        case TracerQuantity::pressure: values.push_back(pressure); break;
        case TracerQuantity::stress:
          values.insert(values.end(), {sxx - pressure, syy - pressure, active ? sxy : nan, szz - pressure});
          break;
        case TracerQuantity::von_mises:
          values.push_back(active ? std::sqrt(1.5 * (sxx * sxx + syy * syy + szz * szz + 2.0 * sxy * sxy)) : nan);
          break;
        case TracerQuantity::plastic_strain: values.push_back(active ? state.strength.plastic_strain[t.zone] : nan); break;
        case TracerQuantity::density: values.push_back(active ? zones.density[t.zone] : nan); break;
        case TracerQuantity::specific_energy: values.push_back(active ? zones.specific_energy[t.zone] : nan); break;
        case TracerQuantity::temperature: {
          const Material& m = simulation.materials()[static_cast<std::size_t>(
              simulation.bodies()[static_cast<std::size_t>(zones.body[t.zone])].material)];
          const auto* jc = std::get_if<JohnsonCook>(&m.strength);
          values.push_back(active && jc ? jc->temperature_from_energy(zones.specific_energy[t.zone]) : nan);
          break;
        }
        case TracerQuantity::damage: values.push_back(active ? static_cast<double>(state.fracture.damaged[t.zone]) : nan); break;
      }
    }
  }
  for (const SurfaceLocation& s : surfaces_) {
    const Vec2 x = nodes.position(s.node), u = nodes.velocity(s.node);
    values.insert(values.end(), {x.x, x.y, u.x, u.y, dot(u, s.normal)});
  }
  const double whole = simulation.whole_body_factor();
  for (std::size_t k = 0; k < channels_.size(); ++k) {
    values.insert(values.end(), {whole * force_[2 * k], whole * force_[2 * k + 1], whole * impulse_[2 * k],
                                 whole * impulse_[2 * k + 1]});
  }
}

}  // namespace krug
