#pragma once
#include <numbers>
#include <string_view>

namespace krug {

// Planar: the plane (x, y), extensive quantities per unit thickness.
// Axisymmetric: the meridian half-plane (z, r), r >= 0, extensive quantities per radian; reports
// multiply by 2 pi to give whole bodies.
enum class GeometryKind { planar, axisymmetric };

constexpr double whole_body_factor(GeometryKind g) {
  return g == GeometryKind::axisymmetric ? 2.0 * std::numbers::pi : 1.0;
}

constexpr std::string_view axis_name(GeometryKind g, int axis) {
  if (g == GeometryKind::axisymmetric) return axis == 0 ? "z" : "r";
  return axis == 0 ? "x" : "y";
}

}  // namespace krug
