#pragma once
// The driver of the fracture criteria over a mesh (step 6 of the time step): every intact active zone
// of a range is tested against criteria (1) (criteria.hpp) with its principal stretches from the
// initial shape (the hoop stretch r/R in axisymmetric geometry) and its principal stresses; a zone
// that fails becomes damaged for good: it keeps only compressive pressure (s = 0, p = max(p, 0)) and
// loses its hourglass stiffness, and its damage time and criterion are recorded.
#include "krug/core/geometry_kind.hpp"
#include "krug/fracture/criteria.hpp"
#include "krug/mesh/mesh.hpp"

namespace krug::fracture {

// Damages the zones of [zone_begin, zone_end) that exceed `limits` at time `now`; returns how many.
long damage_zones(Mesh& mesh, Index zone_begin, Index zone_end, const FractureLimits& limits, GeometryKind geometry,
                  double now);

}  // namespace krug::fracture
