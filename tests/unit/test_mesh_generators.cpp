// Mesh generators and zone quality: graded axes, rectangles, sectors and the nosed cylinder (flat,
// hemispherical and ogival noses). Invariants checked on every generated body: zones
// counter-clockwise with positive area, every node unique and used, the boundary one closed loop,
// named sides on the exact geometry; and the meshed volume against the exact solid.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <vector>

#include "krug/core/error.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/nosed_cylinder.hpp"
#include "krug/mesh/quality.hpp"

using namespace krug;
using namespace krug::generate;

namespace {

constexpr double pi = std::numbers::pi;

// The paper's bullet (docs/validation.md): radius 2.78 mm, a .22 LR-like 10.4 mm length with a
// hemispherical nose; and a Taylor bar (flat nose, radius 3.2 mm, length 32.4 mm).
NosedCylinderParams bullet() {
  NosedCylinderParams p;
  p.radius = 2.78e-3;
  p.length = 10.4e-3;
  p.nose = NoseShape::hemispherical;
  p.radial_zones = 10;
  return p;
}

NosedCylinderParams taylor_bar() {
  NosedCylinderParams p;
  p.radius = 3.2e-3;
  p.length = 32.4e-3;
  p.nose = NoseShape::flat;
  p.radial_zones = 10;
  return p;
}

NosedCylinderParams ogive_bullet(double calibers) {
  NosedCylinderParams p = bullet();
  p.nose = NoseShape::ogive;
  p.ogive_calibers = calibers;
  p.length = 20e-3;
  return p;
}

// 2 pi * sum of the zones' volumes per radian: the whole-body volume of the meshed polygon.
double meshed_volume(const Mesh& mesh, const Patch& patch) {
  double v = 0.0;
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) v += quad::axisymmetric_volume(mesh.corner_positions(z));
  return 2.0 * pi * v;
}

double meshed_area(const Mesh& mesh, const Patch& patch) {
  double a = 0.0;
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) a += quad::area(mesh.corner_positions(z));
  return a;
}

// Every zone of the patch counter-clockwise with positive area, using only the patch's own nodes.
void check_zones(const Mesh& mesh, const Patch& patch, Index body) {
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) {
    INFO("zone " << z);
    REQUIRE(quad::area(mesh.corner_positions(z)) > 0.0);
    REQUIRE(mesh.zones.body[z] == body);
    for (Index n : mesh.zones.corners[z]) {
      REQUIRE(n >= patch.node_begin);
      REQUIRE(n < patch.node_end);
    }
  }
  for (Index n = patch.node_begin; n < patch.node_end; ++n) REQUIRE(mesh.nodes.body[n] == body);
}

// The boundary of the zones in the patch is one closed loop: every boundary node starts exactly one
// segment and ends exactly one, and walking a -> b from any segment visits all of them.
// Returns the boundary nodes. (Connectivity is rebuilt first, as a simulation setup does.)
std::set<Index> check_single_closed_loop(Mesh& mesh, const Patch& patch) {
  build_edge_continuations(mesh);
  const std::vector<BoundarySegment> segments = boundary_segments(mesh, patch.zone_begin, patch.zone_end);
  REQUIRE(segments.size() >= 3);
  std::map<Index, int> starts, ends;
  std::map<Index, Index> successor;
  for (const BoundarySegment& s : segments) {
    ++starts[s.a];
    ++ends[s.b];
    successor[s.a] = s.b;
  }
  std::set<Index> nodes;
  for (const auto& [n, count] : starts) {
    INFO("boundary node " << n);
    REQUIRE(count == 1);
    REQUIRE(ends[n] == 1);
    nodes.insert(n);
  }
  REQUIRE(ends.size() == starts.size());
  std::size_t steps = 0;
  Index n = segments.front().a;
  do {
    n = successor.at(n);
    ++steps;
  } while (n != segments.front().a && steps <= segments.size());
  REQUIRE(steps == segments.size());
  return nodes;
}

// No two nodes of the patch coincide: none closer than `separation` (a sweep over nodes sorted by x).
void check_unique_nodes(const Mesh& mesh, const Patch& patch, double separation) {
  std::vector<Vec2> x;
  for (Index n = patch.node_begin; n < patch.node_end; ++n) x.push_back(mesh.nodes.position(n));
  std::sort(x.begin(), x.end(), [](Vec2 a, Vec2 b) { return a.x < b.x; });
  std::size_t close_pairs = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = i + 1; j < x.size() && x[j].x - x[i].x < separation; ++j) {
      if (norm(x[j] - x[i]) < separation) ++close_pairs;
    }
  }
  REQUIRE(close_pairs == 0);
  // ... and every node is a corner of some zone.
  std::vector<int> used(static_cast<std::size_t>(patch.node_end - patch.node_begin), 0);
  for (Index z = patch.zone_begin; z < patch.zone_end; ++z) {
    for (Index c : mesh.zones.corners[z]) used[static_cast<std::size_t>(c - patch.node_begin)] = 1;
  }
  REQUIRE(std::count(used.begin(), used.end(), 0) == 0);
}

// The named sides of a nosed cylinder cover the boundary exactly and join end to end in the order
// axis -> nose -> side -> rear -> axis; tip is the axis' last node.
void check_sides(const Mesh& mesh, const Patch& patch, const NosedCylinderParams& p, const std::set<Index>& boundary) {
  const auto& axis = patch.sides.at("axis");
  const auto& nose = patch.sides.at("nose");
  const auto& side = patch.sides.at("side");
  const auto& rear = patch.sides.at("rear");
  const auto& tip = patch.sides.at("tip");
  REQUIRE(tip.size() == 1);
  CHECK(axis.back() == tip[0]);
  CHECK(nose.front() == axis.back());
  CHECK(side.front() == nose.back());
  CHECK(rear.front() == side.back());
  CHECK(axis.front() == rear.back());
  std::set<Index> named;
  for (const auto* s : {&axis, &nose, &side, &rear}) named.insert(s->begin(), s->end());
  CHECK(named == boundary);
  const double rear_z = p.tip_position - p.direction * p.length;
  for (Index n : axis) CHECK(mesh.nodes.y[n] == 0.0);   // exactly on the axis
  for (Index n : side) CHECK(mesh.nodes.y[n] == p.radius);
  for (Index n : rear) CHECK(mesh.nodes.x[n] == Approx(rear_z).margin(1e-15));
  CHECK(mesh.nodes.x[tip[0]] == p.tip_position);
  CHECK(mesh.nodes.y[tip[0]] == 0.0);
}

}  // namespace

TEST_CASE("graded_axis lands on its breakpoints and grows by the ratio", "[mesh]") {
  const std::vector<AxisSegment> segments{{1.0, 5, 1.2}, {3.0, 4, 1.0}, {3.5, 3, 0.5}};
  const std::vector<double> lines = graded_axis(-0.5, segments);
  REQUIRE(lines.size() == 1 + 5 + 4 + 3);
  CHECK(lines[0] == -0.5);
  CHECK(lines[5] == 1.0);  // breakpoints exactly, not to round-off
  CHECK(lines[9] == 3.0);
  CHECK(lines[12] == 3.5);
  // Successive zone sizes within a segment: h_{k+1} / h_k = ratio (geometric series definition).
  auto check_ratio = [&](std::size_t first_line, int zones, double ratio) {
    for (int k = 0; k + 1 < zones; ++k) {
      const std::size_t i = first_line + static_cast<std::size_t>(k);
      const double h0 = lines[i + 1] - lines[i], h1 = lines[i + 2] - lines[i + 1];
      CHECK(h1 / h0 == Approx(ratio).margin(1e-12));
    }
  };
  check_ratio(0, 5, 1.2);
  check_ratio(5, 4, 1.0);
  check_ratio(9, 3, 0.5);
  // First zone of a graded segment: h = L (r - 1) / (r^n - 1).
  CHECK(lines[1] - lines[0] == Approx(1.5 * 0.2 / (std::pow(1.2, 5) - 1.0)).margin(1e-14));
  CHECK_THROWS_AS(graded_axis(0.0, {{1.0, 0, 1.0}}), InputError);
  CHECK_THROWS_AS(graded_axis(0.0, {{1.0, 2, 0.0}}), InputError);
}

TEST_CASE("rectangle: positive zones, one closed boundary loop, exact area", "[mesh]") {
  Mesh mesh;
  const Patch first = rectangle(mesh, graded_axis(0.0, {{2.0, 6, 1.1}}), graded_axis(0.0, {{1.0, 4, 1.0}}), 0);
  check_zones(mesh, first, 0);
  const std::set<Index> boundary = check_single_closed_loop(mesh, first);
  CHECK(boundary.size() == 2 * (6 + 4));  // perimeter nodes of a 6 x 4 grid
  check_unique_nodes(mesh, first, 0.1);
  CHECK(meshed_area(mesh, first) == Approx(2.0).margin(1e-14));
  const ZoneQuality q = zone_quality(mesh, first.zone_begin, first.zone_end);
  CHECK(q.min_corner_sine == Approx(1.0).margin(1e-14));  // rectangles
  CHECK(q.zones == 24);
}

TEST_CASE("sector: positive zones and one closed loop, with and without the centre", "[mesh]") {
  const std::vector<double> angles = graded_axis(0.0, {{0.5 * pi, 6, 1.0}});
  SECTION("annulus") {
    Mesh mesh;
    const Patch patch = sector(mesh, graded_axis(0.5, {{1.0, 4, 1.0}}), angles, 2);
    check_zones(mesh, patch, 2);
    check_single_closed_loop(mesh, patch);
    check_unique_nodes(mesh, patch, 0.05);
    // Polygon inscribed in the quarter annulus: 6 trapezoids per ring, (1/2)(r_o^2 - r_i^2) sin(dtheta) each.
    CHECK(meshed_area(mesh, patch) == Approx(6 * 0.5 * (1.0 - 0.25) * std::sin(pi / 12.0)).margin(1e-14));
    CHECK(zone_quality(mesh, patch.zone_begin, patch.zone_end).min_corner_sine > 0.0);
  }
  SECTION("with its centre: the inner zones are triangles (a repeated corner)") {
    Mesh mesh;
    const Patch patch = sector(mesh, graded_axis(0.0, {{1.0, 4, 1.0}}), angles, 0);
    check_zones(mesh, patch, 0);
    const std::set<Index> boundary = check_single_closed_loop(mesh, patch);
    CHECK(boundary.count(patch.sides.at("i_min").front()) == 1);  // the centre is a boundary node
    check_unique_nodes(mesh, patch, 0.05);
    // The degenerate zones are what the nosed cylinder avoids: their corner sine is 0.
    CHECK(zone_quality(mesh, patch.zone_begin, patch.zone_end).min_corner_sine == 0.0);
  }
}

TEST_CASE("zone_quality on hand-made quadrilaterals", "[mesh]") {
  auto single = [](quad::Corners c) {
    Mesh mesh;
    mesh.nodes.resize(4);
    for (Index p = 0; p < 4; ++p) { mesh.nodes.x[p] = c[p].x; mesh.nodes.y[p] = c[p].y; }
    mesh.zones.resize(1);
    mesh.zones.corners[0] = {0, 1, 2, 3};
    return zone_quality(mesh, 0, 1);
  };
  const ZoneQuality square = single({Vec2{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  CHECK(square.min_corner_sine == Approx(1.0).margin(1e-15));
  CHECK(square.max_aspect_ratio == Approx(1.0).margin(1e-15));
  CHECK(square.min_area == Approx(1.0).margin(1e-15));
  CHECK(square.min_corner_sine_zone == 0);
  // 3 x 1 rectangle: aspect = longest edge / smallest altitude = 3.
  CHECK(single({Vec2{0, 0}, {3, 0}, {3, 1}, {0, 1}}).max_aspect_ratio == Approx(3.0).margin(1e-14));
  // Rhombus with 30 degree corners: sine 1/2; aspect = 1 / sin 30 = 2 (unit sides, altitude 1/2).
  const double c30 = std::cos(pi / 6.0), s30 = 0.5;
  const ZoneQuality rhombus = single({Vec2{0, 0}, {1, 0}, {1 + c30, s30}, {c30, s30}});
  CHECK(rhombus.min_corner_sine == Approx(0.5).margin(1e-14));
  CHECK(rhombus.max_aspect_ratio == Approx(2.0).margin(1e-14));
  // Repeated corner (triangle): corner sine 0.
  CHECK(single({Vec2{0, 0}, {1, 0}, {0, 1}, {0, 1}}).min_corner_sine == 0.0);
  // Clockwise (inverted) square: negative sine, non-positive area, infinite aspect.
  const ZoneQuality inverted = single({Vec2{0, 0}, {0, 1}, {1, 1}, {1, 0}});
  CHECK(inverted.min_corner_sine == Approx(-1.0).margin(1e-15));
  CHECK(inverted.min_area < 0.0);
  CHECK(std::isinf(inverted.max_aspect_ratio));
}

TEST_CASE("nosed cylinder, flat nose (Taylor bar): exact volume, square zones at the face", "[mesh]") {
  const NosedCylinderParams p = taylor_bar();
  Mesh mesh;
  const Patch patch = nosed_cylinder(mesh, p, 0);
  check_zones(mesh, patch, 0);
  const std::set<Index> boundary = check_single_closed_loop(mesh, patch);
  check_sides(mesh, patch, p, boundary);
  check_unique_nodes(mesh, patch, 0.1 * p.radius / p.radial_zones);
  // Volume pi R^2 L to round-off (the mesh is exactly the cylinder's section).
  CHECK(meshed_volume(mesh, patch) == Approx(pi * p.radius * p.radius * p.length).epsilon(1e-13));
  CHECK(nosed_cylinder_volume(p, GeometryKind::axisymmetric) == Approx(pi * p.radius * p.radius * p.length).epsilon(1e-15));
  const ZoneQuality q = zone_quality(mesh, patch.zone_begin, patch.zone_end);
  CHECK(q.min_corner_sine == Approx(1.0).margin(1e-12));
  // Automatic shank zones: round(L / (R / n_r)) = round(101.25) = 101 uniform zones, aspect 1.0025.
  CHECK(patch.zones_j == 101);
  CHECK(q.max_aspect_ratio == Approx(32.4 / 101 / 0.32).margin(1e-9));
  // Graded: the face zone stays square (first zone = R / n_r), later zones grow by the ratio.
  NosedCylinderParams graded = p;
  graded.shank_ratio = 1.05;
  graded.shank_zones = 30;
  Mesh m2;
  const Patch g = nosed_cylinder(m2, graded, 0);
  const auto& axis = g.sides.at("axis");  // rear -> tip
  const std::size_t last = axis.size() - 1;
  const double h_face = m2.nodes.x[axis[last]] - m2.nodes.x[axis[last - 1]];
  const double h_next = m2.nodes.x[axis[last - 1]] - m2.nodes.x[axis[last - 2]];
  CHECK(h_next / h_face == Approx(1.05).margin(1e-9));
  CHECK(meshed_volume(m2, g) == Approx(pi * p.radius * p.radius * p.length).epsilon(1e-13));
}

TEST_CASE("nosed cylinder, hemispherical nose (bullet): valid O-grid without degenerate zones", "[mesh]") {
  for (const double length : {10.4e-3, 41e-3}) {  // the .22 LR-like and the 11 g readings of the paper
    NosedCylinderParams p = bullet();
    p.length = length;
    p.tip_position = 0.05;
    Mesh mesh;
    const Patch patch = nosed_cylinder(mesh, p, 0);
    INFO("length " << length);
    check_zones(mesh, patch, 0);
    const std::set<Index> boundary = check_single_closed_loop(mesh, patch);
    check_sides(mesh, patch, p, boundary);
    check_unique_nodes(mesh, patch, 0.1 * p.radius / p.radial_zones);
    for (Index n : patch.sides.at("nose")) {  // on the exact hemisphere centred at (tip - R, 0)
      const Vec2 d = mesh.nodes.position(n) - Vec2{p.tip_position - p.radius, 0.0};
      CHECK(norm(d) == Approx(p.radius).margin(1e-15));
    }
    // Quality: measured min corner sine 0.838 and max aspect 1.55 for n_r = 10 (see the header);
    // the bounds leave a margin for round-off and small layout changes, far from any sliver.
    const ZoneQuality q = zone_quality(mesh, patch.zone_begin, patch.zone_end);
    CHECK(q.min_corner_sine > 0.8);
    CHECK(q.max_aspect_ratio < 2.0);
    CHECK(q.min_area > 0.0);
  }
}

TEST_CASE("nosed cylinder, hemispherical nose: volume converges at second order", "[mesh]") {
  // The zones tile the polygon inscribed in the profile; the deficit is the chord segments of the
  // nose. For n equal-angle chords (dtheta = pi / 2n) each segment has area R^2 dtheta^3 / 12 at
  // distance R sin(theta) from the axis (Pappus), so the volume deficit is
  // pi R^3 dtheta^2 / 6 = pi^3 R^3 / (24 n^2) + O(n^-4).
  NosedCylinderParams p = bullet();
  const double exact = pi * p.radius * p.radius * (p.length - p.radius) + 2.0 / 3.0 * pi * std::pow(p.radius, 3);
  CHECK(nosed_cylinder_volume(p, GeometryKind::axisymmetric) == Approx(exact).epsilon(1e-14));
  std::vector<double> deficit;
  for (const int n_r : {10, 20}) {
    p.radial_zones = n_r;
    Mesh mesh;
    const Patch patch = nosed_cylinder(mesh, p, 0);
    const int n_nose = static_cast<int>(patch.sides.at("nose").size()) - 1;
    CHECK(n_nose == 12 * n_r / 10);  // defaults: n_c = 0.6 n_r, n_cn = n_c: the resolution doubles
    deficit.push_back(exact - meshed_volume(mesh, patch));
    const double leading = std::pow(pi, 3) * std::pow(p.radius, 3) / (24.0 * n_nose * n_nose);
    CHECK(deficit.back() == Approx(leading).epsilon(0.01));  // O(n^-2) relative correction: 0.14% at n = 12
  }
  CHECK(deficit[0] > 0.0);
  CHECK(deficit[0] / deficit[1] == Approx(4.0).margin(0.2));  // second order; measured 3.996
  // Planar: half-section area R (L - R) + pi R^2 / 4 within the chord segments, sum of
  // R^2 (dtheta - sin dtheta) / 2 over n chords (exact for equal angles).
  p.radial_zones = 10;
  Mesh mesh;
  const Patch patch = nosed_cylinder(mesh, p, 0);
  const double dtheta = pi / 2.0 / 12.0;
  const double planar_exact = nosed_cylinder_volume(p, GeometryKind::planar);
  CHECK(planar_exact == Approx(p.radius * (p.length - p.radius) + pi * p.radius * p.radius / 4.0).epsilon(1e-14));
  CHECK(planar_exact - meshed_area(mesh, patch) ==
        Approx(12 * 0.5 * p.radius * p.radius * (dtheta - std::sin(dtheta))).epsilon(1e-6));
}

TEST_CASE("nosed cylinder, tangent ogive: valid, quality near the tip-angle bound, volume converges", "[mesh]") {
  for (const double calibers : {1.0, 3.0}) {
    NosedCylinderParams p = ogive_bullet(calibers);
    INFO("CRH " << calibers);
    const NoseGeometry g = nose_geometry(p);
    // Tangent ogive: rho = 2R CRH, Ln = sqrt(2 rho R - R^2), sin(tip angle) = Ln / rho.
    CHECK(g.profile_radius == Approx(2.0 * p.radius * calibers).epsilon(1e-15));
    CHECK(g.length == Approx(p.radius * std::sqrt(4.0 * calibers - 1.0)).epsilon(1e-14));
    std::vector<double> deficit, nose_zones;
    const double exact = nosed_cylinder_volume(p, GeometryKind::axisymmetric);
    for (const int n_r : {10, 20}) {
      p.radial_zones = n_r;
      Mesh mesh;
      const Patch patch = nosed_cylinder(mesh, p, 0);
      check_zones(mesh, patch, 0);
      const std::set<Index> boundary = check_single_closed_loop(mesh, patch);
      check_sides(mesh, patch, p, boundary);
      check_unique_nodes(mesh, patch, 0.05 * p.radius / n_r);
      const Vec2 centre{p.tip_position - g.length, p.radius - g.profile_radius};
      for (Index n : patch.sides.at("nose")) {
        CHECK(norm(mesh.nodes.position(n) - centre) == Approx(g.profile_radius).margin(1e-14));
      }
      // The zone at the tip has the angle between the axis and the last chord, below the tip angle,
      // so sin(tip angle) bounds the quality from above. The worst zone is that one for sharp
      // ogives (measured 0.987 of the bound at CRH 3) and the O-grid corner for blunt ones
      // (measured 0.78 at CRH 1, 0.84 for the hemisphere): 10% below the smaller of the two.
      const ZoneQuality q = zone_quality(mesh, patch.zone_begin, patch.zone_end);
      CHECK(q.min_corner_sine > 0.9 * std::min(std::sin(g.tip_angle), 0.78));
      CHECK(q.min_corner_sine < std::sin(g.tip_angle));
      deficit.push_back(exact - meshed_volume(mesh, patch));
      nose_zones.push_back(static_cast<double>(patch.sides.at("nose").size() - 1));
    }
    CHECK(deficit[0] > 0.0);
    CHECK(deficit[0] / exact < 1e-3);
    // Second order in the nose resolution: deficit ratio = (n_nose fine / n_nose coarse)^2 (4.21 for
    // CRH 1, where rounding gives 19 and 39 nose zones; 4 for CRH 3, 35 and 70), within 5%.
    const double expected_ratio = std::pow(nose_zones[1] / nose_zones[0], 2);
    CHECK(deficit[0] / deficit[1] == Approx(expected_ratio).epsilon(0.05));
  }
  // The same ogive given by its length.
  NosedCylinderParams by_length = ogive_bullet(3.0);
  by_length.ogive_calibers = 0.0;
  by_length.nose_length = by_length.radius * std::sqrt(11.0);
  CHECK(nose_geometry(by_length).profile_radius == Approx(6.0 * by_length.radius).epsilon(1e-14));
}

TEST_CASE("nosed cylinder appends to a mesh and mirrors with direction", "[mesh]") {
  Mesh mesh;
  const Patch plate = rectangle(mesh, graded_axis(0.0, {{3e-3, 3, 1.0}}), graded_axis(0.0, {{20e-3, 10, 1.0}}), 0);
  const std::vector<double> plate_x = mesh.nodes.x, plate_y = mesh.nodes.y;
  const auto plate_corners = mesh.zones.corners;

  NosedCylinderParams p = bullet();
  p.tip_position = -1e-3;  // nose toward +z, 1 mm in front of the plate
  const Patch forward = nosed_cylinder(mesh, p, 1);
  p.direction = -1;
  p.tip_position = 4e-3;   // a second bullet behind the plate, nose toward -z
  const Patch backward = nosed_cylinder(mesh, p, 2);

  CHECK(forward.node_begin == plate.node_end);
  CHECK(forward.zone_begin == plate.zone_end);
  CHECK(backward.node_begin == forward.node_end);
  for (Index n = 0; n < plate.node_end; ++n) {  // the plate's nodes and zones are untouched
    CHECK(mesh.nodes.x[n] == plate_x[n]);
    CHECK(mesh.nodes.y[n] == plate_y[n]);
    CHECK(mesh.nodes.body[n] == 0);
  }
  for (Index z = 0; z < plate.zone_end; ++z) CHECK(mesh.zones.corners[z] == plate_corners[z]);
  check_zones(mesh, forward, 1);
  check_zones(mesh, backward, 2);
  for (const Patch* b : {&forward, &backward}) {
    const std::set<Index> boundary = check_single_closed_loop(mesh, *b);
    CHECK(boundary.size() == b->sides.at("axis").size() + b->sides.at("nose").size() +
                                 b->sides.at("side").size() + b->sides.at("rear").size() - 4);
  }
  check_sides(mesh, backward, p, check_single_closed_loop(mesh, backward));
  // Node for node, the backward bullet is the forward one reflected in the plane midway between tips.
  const double mid = 0.5 * (-1e-3 + 4e-3);
  for (Index k = 0; k < forward.node_end - forward.node_begin; ++k) {
    CHECK(mesh.nodes.x[backward.node_begin + k] == Approx(2.0 * mid - mesh.nodes.x[forward.node_begin + k]).margin(1e-15));
    CHECK(mesh.nodes.y[backward.node_begin + k] == mesh.nodes.y[forward.node_begin + k]);
  }
  CHECK(meshed_volume(mesh, backward) == Approx(meshed_volume(mesh, forward)).epsilon(1e-13));
}

TEST_CASE("nosed cylinder rejects inconsistent parameters", "[mesh]") {
  Mesh mesh;
  auto fails = [&](NosedCylinderParams p) { CHECK_THROWS_AS(nosed_cylinder(mesh, p, 0), InputError); };
  NosedCylinderParams p = ogive_bullet(3.0);
  p.nose_length = 10e-3;  // both nose_length and ogive_calibers
  fails(p);
  p = ogive_bullet(0.0);  // neither
  fails(p);
  p = ogive_bullet(0.4);  // CRH < 0.5 is not a tangent ogive
  fails(p);
  p = bullet();
  p.length = p.radius;  // no shank
  fails(p);
  p = bullet();
  p.core_zones = 6;
  p.nose_zones = 6;  // must exceed core_zones
  fails(p);
  p = bullet();
  p.core_zones = 10;  // must be below radial_zones
  fails(p);
  p = bullet();
  p.radial_zones = 1;
  fails(p);
  p = taylor_bar();
  p.nose_zones = 4;  // curved noses only
  fails(p);
  p = bullet();
  p.direction = 0;
  fails(p);
  CHECK(mesh.nodes.size() == 0);  // nothing appended by a failed call
}
