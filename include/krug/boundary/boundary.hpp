#pragma once
// The boundary package: every condition on a body's faces, as the step sees it (docs/theory.md §2,
// docs/architecture.md "The boundary package"). Kinematic conditions hold velocity components
// (symmetry, slip, fixed, a prescribed velocity, a velocity as a function of time, the axis in RZ);
// loads (pressure and tangential traction on a face) enter as nodal forces. The driver, Boundary,
// acts at the step's slots:
//
//   apply_loads(...)   after the corner forces: F^n += the loads at t^n on the faces at x^n
//   hold(...)          in the predictor: a held component keeps its value or takes v(t^{n+1/2}), and the
//                      boundary's work and axial impulse are booked
//   book_reaction(...) a contact reaction on a held component, cancelled by the boundary
//   book_loads(...)    once u^{n+1/2} is final: the loads' work F . ubar dt^n and impulse
//
// The package is stateless over a run (a restart needs nothing of it): what it holds is the setup.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/mesh/mesh.hpp"

namespace krug {

// A node whose velocity components are held at their initial values: zero for symmetry planes,
// slip planes, the axis and fixed rims; the prescribed value for a moving boundary (or, for a
// component driven by a function of time, that function's value: boundary::DrivenComponent).
struct NodeConstraint {
  Index node = 0;
  bool fix_x = false;
  bool fix_y = false;
};

namespace boundary {

// A value as a function of time t (s). An empty function stands for zero.
using TimeFunction = std::function<double(double)>;

// A velocity component of some nodes (a side's) prescribed as a function of time, evaluated once per
// step: u^{n+1/2} = value(t^{n+1/2}). The component is held (Boundary adds the NodeConstraint where
// none holds it).
struct DrivenComponent {
  std::vector<Index> nodes;
  int component = 0;  // 0: first coordinate, 1: second
  TimeFunction value;
};

// A load on boundary faces: a pressure p(t) (Pa, acting against the outward normal) and a tangential
// traction tau(t) (Pa, along a -> b of each segment: counter-clockwise about the body, the body on
// the left). The force follows the deformed face (its current length and normal); in axisymmetric
// geometry it is weighted by r exactly as the control-volume corner forces are (docs/theory.md §2).
struct FaceLoad {
  std::vector<BoundarySegment> segments;
  TimeFunction pressure, traction;
};

// The held components one side's condition holds (a component that two sides hold belongs to the one
// applied last), named for reports: the reaction gauges (gauges.csv, held_<body>_<side>).
struct HeldSide {
  Index body = 0;
  std::string side;
  std::vector<NodeConstraint> components;
};

// Where the boundary books its work and axial impulse (the ledger's lines, docs/theory.md §3).
struct Books {
  double& work;
  double& axial_impulse;
};

// The nodal force of a load on one segment a -> b, to each end (pressure p, traction tau; Pa).
// Planar: half of (-p n + tau t) L to each node (per unit thickness). Axisymmetric, per radian:
// the same times integral N r ds / L, that is (2 r_a + r_b) / 6 and (r_a + 2 r_b) / 6.
inline std::array<Vec2, 2> segment_load(Vec2 a, Vec2 b, double pressure, double traction, GeometryKind geometry) {
  const Vec2 d = b - a;
  const Vec2 normal_length{d.y, -d.x};  // n L, outward (the body is on the left of a -> b)
  const Vec2 force = (-pressure) * normal_length + traction * d;
  if (geometry == GeometryKind::axisymmetric) {
    return {((2.0 * a.y + b.y) / 6.0) * force, ((a.y + 2.0 * b.y) / 6.0) * force};
  }
  return {0.5 * force, 0.5 * force};
}

class Boundary {
 public:
  Boundary() = default;
  Boundary(std::vector<NodeConstraint> constraints, std::vector<DrivenComponent> driven, std::vector<FaceLoad> loads,
           std::vector<HeldSide> held_sides = {});

  // At t^0, with the nodal inverse masses set: in axisymmetric geometry every node on the axis holds
  // u_r = 0 (its velocity set so); every held component's inverse mass becomes 0.
  void initialise(NodeFields& nodes, GeometryKind geometry);

  // Adds the loads at time t (t^n) on the current faces of active zones to the nodal forces.
  void apply_loads(NodeFields& nodes, const ZoneFields& zones, GeometryKind geometry, double time);
  // The predictor slot, after u* = u^{n-1/2} + dt^n F / M: a component driven by a function takes its
  // value at t_mid = t^{n+1/2}; every held component's work and axial impulse are booked (the
  // boundary supplies what holds it: for a constant value -F u dt^n).
  void hold(NodeFields& nodes, double t_mid, double dt_mid, Books books) const;
  // A contact reaction r on node p: on a held component the boundary cancels it, doing -r ubar dt^n.
  void book_reaction(const NodeFields& nodes, Index p, Vec2 r, double dt_mid, Books books) const;
  // The loads' work dt^n F . ubar and impulse dt^n F_x, with ubar = (u^{n-1/2} + u^{n+1/2}) / 2.
  void book_loads(const NodeFields& nodes, double dt_mid, Books books) const;

  bool has_loads() const { return !loads_.empty(); }
  const std::vector<NodeConstraint>& constraints() const { return constraints_; }
  // The held components by the side that holds them (not the axis in RZ, added by initialise).
  const std::vector<HeldSide>& held_sides() const { return held_sides_; }
  const std::vector<std::uint8_t>& held_x() const { return held_x_; }  // per node: 1 where u_x is held
  const std::vector<std::uint8_t>& held_y() const { return held_y_; }

 private:
  std::vector<NodeConstraint> constraints_;
  std::vector<DrivenComponent> driven_;
  std::vector<FaceLoad> loads_;
  std::vector<HeldSide> held_sides_;
  std::vector<std::uint8_t> held_x_, held_y_;
  std::vector<std::uint8_t> driven_x_, driven_y_;  // per node: the held component follows a function of time
  struct NodeLoad {
    Index node;
    Vec2 force;
  };
  std::vector<NodeLoad> applied_;  // the loads of the current step, per segment end (for book_loads)
};

}  // namespace boundary
}  // namespace krug
