// The boundary package: the face load is the exact adjoint of the zone's volume (a pressure P on a
// zone's faces gives -P dV/dx_p at its corners, so a body at uniform pressure P under a load P is in
// equilibrium node by node), and the registry of condition kinds.
#include <catch2/catch.hpp>

#include <cmath>

#include "krug/boundary/conditions.hpp"
#include "krug/mesh/quad.hpp"

using namespace krug;

namespace {

// The nodal forces of a pressure on all four faces of a zone (corners counter-clockwise: the zone is
// on the left of each face c[p] -> c[p+1]).
std::array<Vec2, 4> zone_load(const quad::Corners& c, double pressure, double traction, GeometryKind geometry) {
  std::array<Vec2, 4> f{};
  for (int p = 0; p < 4; ++p) {
    const std::array<Vec2, 2> ends = boundary::segment_load(c[p], c[quad::next(p)], pressure, traction, geometry);
    f[p] += ends[0];
    f[quad::next(p)] += ends[1];
  }
  return f;
}

}  // namespace

TEST_CASE("a pressure on a zone's faces is -P dV/dx at its corners (planar and RZ)", "[boundary]") {
  const quad::Corners c{Vec2{0.10, 0.02}, Vec2{0.13, 0.025}, Vec2{0.125, 0.05}, Vec2{0.095, 0.045}};
  REQUIRE(quad::area(c) > 0.0);
  const double pressure = 3.0e8;
  const std::array<Vec2, 4> planar = zone_load(c, pressure, 0.0, GeometryKind::planar);
  const std::array<Vec2, 4> area_gradient = quad::area_gradient(c);
  const std::array<Vec2, 4> rz = zone_load(c, pressure, 0.0, GeometryKind::axisymmetric);
  const std::array<Vec2, 4> volume_gradient = quad::axisymmetric_volume_gradient(c);
  for (int p = 0; p < 4; ++p) {
    INFO("corner " << p);
    CHECK(planar[p].x == Approx(-pressure * area_gradient[p].x).epsilon(1e-14).margin(1e-6));
    CHECK(planar[p].y == Approx(-pressure * area_gradient[p].y).epsilon(1e-14).margin(1e-6));
    CHECK(rz[p].x == Approx(-pressure * volume_gradient[p].x).epsilon(1e-14).margin(1e-8));
    CHECK(rz[p].y == Approx(-pressure * volume_gradient[p].y).epsilon(1e-14).margin(1e-8));
  }
}

TEST_CASE("a traction along a closed zone boundary has no net force, and points along a -> b", "[boundary]") {
  const quad::Corners c{Vec2{0.0, 0.0}, Vec2{1.0, 0.0}, Vec2{1.0, 1.0}, Vec2{0.0, 1.0}};
  const std::array<Vec2, 4> f = zone_load(c, 0.0, 2.0, GeometryKind::planar);
  Vec2 sum;
  for (const Vec2& v : f) sum += v;
  CHECK(std::abs(sum.x) < 1e-15);
  CHECK(std::abs(sum.y) < 1e-15);
  // The face y = 0, traversed with the zone on the left, runs along +x: tau L / 2 to each end.
  const std::array<Vec2, 2> bottom = boundary::segment_load(c[0], c[1], 0.0, 2.0, GeometryKind::planar);
  CHECK(bottom[0].x == 1.0);
  CHECK(bottom[0].y == 0.0);
  // A pressure on it pushes in +y (into the body).
  const std::array<Vec2, 2> pushed = boundary::segment_load(c[0], c[1], 5.0, 0.0, GeometryKind::planar);
  CHECK(pushed[1].y == 2.5);
}

TEST_CASE("the condition registry: names, bare forms, kinds", "[boundary]") {
  CHECK(boundary::kind_names() ==
        std::vector<std::string>{"free", "symmetry", "slip", "fixed", "velocity", "pressure", "traction"});
  CHECK(boundary::kind_names(true) == std::vector<std::string>{"free", "symmetry", "slip", "fixed"});
  for (const boundary::ConditionKind& kind : boundary::condition_kinds()) {
    CHECK(boundary::find_kind(kind.name) == &kind);
    CHECK(&boundary::kind_of(kind.kind) == &kind);
    CHECK(!(kind.holds && kind.loads));
  }
  CHECK(boundary::find_kind("pressure")->loads);
  CHECK(boundary::find_kind("velocity")->holds);
  CHECK(boundary::find_kind("nonsense") == nullptr);
}
