// The fracture driver's root-free stretch test (fracture::stretches_below, krug/fracture/damage.hpp)
// against the exact principal stretches (fracture::zone_stretches): wherever the test says "below",
// every exact stretch is below the limit and none is negative, on random deformations of one zone
// with limits just above, at and just below its largest stretch; and an undeformed zone passes.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "krug/fracture/damage.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/quad.hpp"

using namespace krug;

namespace {

Mesh one_zone(double y_offset) {
  Mesh mesh;
  generate::rectangle(mesh, {0.0, 1e-4}, {y_offset, y_offset + 1e-4}, 0);
  mesh.nodes.x0 = mesh.nodes.x;
  mesh.nodes.y0 = mesh.nodes.y;
  return mesh;
}

void measure(Mesh& mesh) {
  const quad::Corners x = mesh.corner_positions(0);
  mesh.zones.area[0] = quad::area(x);
  mesh.zones.volume[0] = quad::axisymmetric_volume(x);
}

}  // namespace

TEST_CASE("stretches_below: an undeformed zone is below 1.4, planar and RZ", "[kernels][fracture_criteria]") {
  for (const double offset : {0.0, 1e-3}) {
    Mesh mesh = one_zone(offset);
    measure(mesh);
    CHECK(fracture::stretches_below(mesh, 0, false, 1.4));
    CHECK(fracture::stretches_below(mesh, 0, true, 1.4));
    CHECK_FALSE(fracture::stretches_below(mesh, 0, false, 1.0));  // the identity is not below 1
  }
}

TEST_CASE("stretches_below never passes a zone whose exact stretches reach the limit", "[kernels][fracture_criteria]") {
  std::mt19937_64 random(2024);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  long passed = 0, checked = 0;
  for (const bool axisymmetric : {false, true}) {
    for (int trial = 0; trial < 20000; ++trial) {
      Mesh mesh = one_zone(axisymmetric ? 2e-4 : 0.0);
      // An affine map near the identity (stretch, shear, rotation) plus a small hourglass-like jitter.
      const double a = 1.0 + 0.5 * unit(random), b = 0.5 * unit(random), c = 0.5 * unit(random),
                   d = 1.0 + 0.5 * unit(random);
      for (Index n = 0; n < mesh.nodes.size(); ++n) {
        const double x = mesh.nodes.x0[n], y = mesh.nodes.y0[n] - (axisymmetric ? 2e-4 : 0.0);
        mesh.nodes.x[n] = a * x + b * y + 1e-6 * unit(random);
        mesh.nodes.y[n] = c * x + d * y + (axisymmetric ? 2e-4 * (1.0 + 0.3 * unit(random)) : 0.0);
      }
      measure(mesh);
      const fracture::Stretches exact = fracture::zone_stretches(mesh, 0, axisymmetric);
      // Limits straddling the largest stretch, down to a relative distance of 1e-12.
      const double scale = std::pow(10.0, -12.0 + 11.0 * (0.5 + 0.5 * unit(random)));
      for (const double limit : {exact.largest() * (1.0 + scale), exact.largest(), exact.largest() * (1.0 - scale),
                                 exact.largest() * 1.1}) {
        ++checked;
        // With the zone's initial shape computed once (as the Simulation keeps it): the same answer.
        const bool below = fracture::stretches_below(mesh, 0, axisymmetric, limit);
        CHECK(fracture::stretches_below(mesh, 0, axisymmetric, limit, fracture::initial_shapes(mesh).front()) == below);
        if (!below) continue;
        ++passed;
        INFO("limit " << limit << " largest " << exact.largest() << " smallest " << exact.smallest());
        CHECK(exact.largest() < limit);
        CHECK(exact.smallest() >= 0.0);
      }
    }
  }
  CHECK(passed > checked / 5);  // the test is not vacuous: it passes the zones well below their limit
}
