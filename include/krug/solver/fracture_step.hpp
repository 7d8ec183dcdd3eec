#pragma once
// Steps 6 and 7 of the time step (docs/theory.md §2): the failure laws on intact zones, the choice of
// the zones that leave the grid (fully fractured surface zones, the deviations of the interior rules,
// erosion on distortion), and their conversion into free elements with its books. Free functions that
// name what they read (const) and write; the Simulation calls them in its recipe.
#include <cstdint>
#include <vector>

#include "krug/core/geometry_kind.hpp"
#include "krug/fracture/damage.hpp"
#include "krug/fracture/failure_law.hpp"
#include "krug/material/material.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/particles/particles.hpp"
#include "krug/solver/body.hpp"
#include "krug/solver/controls.hpp"
#include "krug/solver/ledger.hpp"

namespace krug {

// Fracture counters of one body.
struct FractureCounts {
  long damaged = 0;               // zones damaged so far
  long converted = 0;             // zones converted to particles
  long interior_conversions = 0;  // of which converted away from the surface (f_i, inverted corner, dt floor)
  double converted_mass = 0.0;    // per radian or per m
  long eroded = 0;                // intact zones removed by erosion on distortion
  double eroded_mass = 0.0;       // per radian or per m
};

// Step 6: each body's failure law (laws[b], none where not fracture::enabled) on its intact zones at
// t^{n+1} = `now`, the plastic strain having grown over `dt`; adds the newly damaged zones to
// counts[b].damaged. Reads the mesh, the hydro and strength state; writes the fracture state (and,
// for a zone that becomes damaged, fracture::damage_zone's stress, pressure and hourglass state).
// Zone by zone, so in blocks on up to `threads` threads (solver/parallel.hpp) with the same result.
// `shapes`: every zone's fracture::initial_shape, computed once (empty: computed as needed).
void evaluate_failure_laws(const Mesh& mesh, ZoneState& state, const std::vector<Body>& bodies,
                           const std::vector<Material>& materials, const std::vector<fracture::FailureLaw>& laws,
                           GeometryKind geometry, double now, double dt, std::vector<FractureCounts>& counts,
                           int threads = 1, const std::vector<fracture::InitialShape>& shapes = {});

// Why a zone leaves the grid: fully fractured on a free surface (the paper's rule), damaged in the
// interior (a documented deviation: f_i, an inverted corner, the time-step floor), or eroded.
enum class ConversionRule : std::uint8_t { surface, interior, erosion };
struct Conversion {
  Index zone = -1;
  ConversionRule rule = ConversionRule::surface;
};

// Step 7's choice, the whole layer before any zone converts (one boundary layer a step): eroded
// zones of bodies that ask for erosion, then the damaged zones of bodies with a failure law, in zone
// order. held_x/held_y (per node) tell a free face from the axis, a symmetry plane or a held rim.
// Reads the mesh and the zones' damage, plastic strain and stable steps. The zone loops run in blocks
// on up to `threads` threads, their choices joined in block order: the same list on any number.
std::vector<Conversion> choose_conversions(const Mesh& mesh, const ZoneState& state, const std::vector<Body>& bodies,
                                           const std::vector<Material>& materials,
                                           const std::vector<fracture::FailureLaw>& laws,
                                           const FractureControls& controls, const std::vector<std::uint8_t>& held_x,
                                           const std::vector<std::uint8_t>& held_y, int threads = 1);

// Where a conversion books: the ledger's converted and internal lines, per body the converted energy
// and the counters.
struct ConversionBooks {
  Ledger& ledger;
  std::vector<double>& body_converted_energy;
  std::vector<FractureCounts>& counts;
};

// Step 7's conversion: each chosen zone into free elements at `time` (convert_zone_to_particles), in
// the order chosen, booked; zones_per_node (active zones touching each node) is kept up to date.
void convert_zones(const std::vector<Conversion>& chosen, Mesh& mesh, Particles& particles, int particles_per_zone,
                   double time, std::vector<Index>& zones_per_node, const std::vector<std::uint8_t>& held_x,
                   const std::vector<std::uint8_t>& held_y, ConversionBooks books);

}  // namespace krug
