#pragma once
// A solid cylinder with a nose (projectiles, Taylor bars), meshed in the meridian half-plane (z, r),
// r >= 0, for axisymmetric runs; the same mesh is the half-body of a planar (x, y) run with y = 0 a
// symmetry plane. Nodes on the axis r = 0 are part of the body's boundary.
//
// Shape. Radius R, overall length L from the tip to the rear face, and a nose of length Ln:
//   flat           Ln = 0: the impact face is the plane z = tip (Taylor bar);
//   hemispherical  Ln = R: a quarter circle of radius R meeting the side tangentially;
//   ogive          a tangent ogive, a circular arc of radius rho = CRH * 2R (CRH: calibre radius head,
//                  >= 0.5) centred on the line r = R - rho and tangent to the side at the shoulder;
//                  Ln = sqrt(2 rho R - R^2), equivalently rho = (R^2 + Ln^2) / (2R). Give exactly
//                  one of nose_length (>= R) and ogive_calibers. CRH = 0.5 (Ln = R) is the
//                  hemisphere; secant ogives and blunted (meplat) tips are not provided.
// The tip is at z = tip_position on the axis; direction +1 points the nose to +z (the body lies in
// z <= tip_position), -1 to -z.
//
// Layout. Local axial coordinate s runs from the rear face (s = 0) to the tip (s = L); the shoulder,
// where the nose meets the side, is at s_sh = L - Ln. Radial grid lines in the shank are uniform,
// r_j = R j / n_r, so zones are square where their axial length is R / n_r; the shank's axial lines
// are graded (generate::graded_axis) from R / n_r-sized zones at the shoulder, growing by
// shank_ratio toward the rear.
//   * Flat nose: one structured block, n_z x n_r zones.
//   * Curved nose: an O-grid of two blocks sharing nodes (no repeated corner anywhere):
//
//                           side, r = R                   shoulder
//     rear   +-------------------------------------------+ - .
//     face   |  ring: n_ring zones thick, along the side  |      ' .       nose surface:
//            |  and round the nose down to the axis       |   ring   ' .   n_nose zones
//    r = a   +-------------------------------------------+- - - - K    .
//            |  core: n_z (shank) + n_cn (nose) columns   |  core  |ring :
//    r = 0   +-------------------------------------------+--------+-----+ tip
//          s = 0                                       s = s_sh   axis  s = L
//
//     The core block spans the whole length along the axis, r in [0, a] with a = R n_c / n_r; in
//     the nose its n_cn axial columns end at a front face (n_c zones) that meets the ring at the
//     valence-3 node K. The ring block (n_ring = n_r - n_c zones thick) runs from the rear face
//     along the side, round the nose and down to the axis ahead of the core; its outer edge is the
//     side plus the nose surface, whose n_nose = n_cn + n_c zones wrap the core's top (n_cn) and
//     front face (n_c). Nose surface nodes are at equal arc length on the exact profile.
//     Node positions in the shank are algebraic (straight grid lines). The nodes ahead of the
//     shoulder plane (s > s_sh) that are not on the nose surface are placed by the discrete
//     harmonic (Tutte) embedding of the graph of zone edges: each is the average of its edge
//     neighbours, from one sparse symmetric (graph Laplacian) solve per coordinate. Shank nodes
//     (the shoulder plane included) and nose surface nodes are held; nodes on the axis keep r = 0
//     exactly and slide along it. A convex-combination map of a planar mesh onto a convex boundary
//     does not fold (Tutte 1963; Floater 2003), and the nose region is convex; the O-grid keeps
//     corner angles away from 0 and 180 degrees at the tip, where a polar (sector) mesh would put
//     triangles. As a safety net every zone's area and corner sines are checked before anything is
//     appended, and an InputError names the zone if one is not positive.
//   Defaults (each 0 = automatic): n_c = round(0.6 n_r); n_cn = max(1, round(Ln n_r / R) - n_ring),
//   so the core's axial zones in the nose are about R / n_r long (for the hemisphere n_cn = n_c, a
//   symmetric O-grid); n_z the number of graded shank zones whose first is closest to R / n_r.
//   Measured with n_r = 10 (smallest corner sine / largest aspect ratio, see quality.hpp):
//   hemispherical 0.84 / 1.55; tangent ogive CRH 1: 0.78 / 1.97 (worst at the O-grid corner K);
//   CRH 3: 0.55 / 3.98, at the tip, against the bound sin(phi_tip) = 0.553 (the surface meets the
//   axis at phi_tip, so the tip zone has a smaller angle); flat: 1 / 1.0025. The values hardly
//   change with n_r (hemispherical, n_r = 40: 0.83 / 1.49).
//
// Named sides (Patch::sides), each listed in the order of one walk round the boundary
// axis -> nose -> side -> rear (counter-clockwise for direction +1, clockwise for -1); consecutive
// sides share their end node:
//   "axis"  nodes on r = 0 (r exactly 0), from the rear face to the tip;
//   "nose"  the nose surface from the tip to the shoulder (for a flat nose: the impact face from the
//           axis to the rim);
//   "side"  the cylindrical surface r = R (exactly), from the shoulder to the rear rim;
//   "rear"  the rear face, from the rim to the axis;
//   "tip"   the single node at the tip on the axis.
// Patch::zones_i = n_r (zones across the radius); Patch::zones_j = zones along the side and nose
// (n_z + n_nose; n_z for a flat nose). Nodes and zones are appended after those already in the mesh
// (the body's nodes and zones are contiguous ranges, every node unique), with `body` set on each;
// existing nodes and zones are untouched. Zones are counter-clockwise in the computational plane.
#include "krug/core/geometry_kind.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/mesh.hpp"

namespace krug::generate {

enum class NoseShape { flat, hemispherical, ogive };

struct NosedCylinderParams {
  // Shape.
  double radius = 0.0;          // R (m)
  double length = 0.0;          // L, along the axis from the tip to the rear face (m); L > nose length
  NoseShape nose = NoseShape::hemispherical;
  double nose_length = 0.0;     // ogive only: Ln (m), >= R; 0 = from ogive_calibers
  double ogive_calibers = 0.0;  // ogive only: ogive radius / (2R), >= 0.5; 0 = from nose_length
  double tip_position = 0.0;    // axial coordinate of the tip (m)
  int direction = 1;            // +1: the nose points to +z; -1: to -z
  // Mesh.
  int radial_zones = 10;        // n_r, zones across the radius (>= 2 for a curved nose)
  int core_zones = 0;           // curved nose: n_c, zones across the core block, 1..n_r-1; 0 = auto
  int nose_zones = 0;           // curved nose: n_nose, zones along the nose surface, > n_c; 0 = auto
  int shank_zones = 0;          // n_z, zones along the shank (the whole length if flat); 0 = auto
  double shank_ratio = 1.0;     // length ratio of successive shank zones from the nose to the rear
};

// Derived nose geometry (validates the shape parameters; throws InputError).
struct NoseGeometry {
  double length = 0.0;         // Ln (m): 0 flat, R hemispherical
  double profile_radius = 0.0; // radius of the nose arc (m): R hemispherical, rho ogive, 0 flat
  double tip_angle = 0.0;      // angle between the nose surface and the axis at the tip (rad): pi/2 unless ogive
  double arc_length = 0.0;     // length of the nose profile from the shoulder to the tip (m); R for flat
};
NoseGeometry nose_geometry(const NosedCylinderParams& params);

// Exact measure of the body: in axisymmetric geometry the whole-body volume (m^3, i.e. 2 pi times
// the sum of the zones' volumes per radian of an exact mesh); in planar geometry the area of the
// half-section r >= 0 (m^2 per unit thickness).
double nosed_cylinder_volume(const NosedCylinderParams& params, GeometryKind geometry);

// Appends the body to the mesh (see above). Throws InputError on bad parameters.
Patch nosed_cylinder(Mesh& mesh, const NosedCylinderParams& params, Index body);

}  // namespace krug::generate
