#pragma once
// A scene in C++ types, with no file format: each body's mesh (a generator and its parameters), its
// boundary conditions on named sides and its initial fields as functions of position; the materials,
// fracture limits, contact and numerical controls. build_simulation() turns a scene into a
// SimulationSetup: meshes generated and checked, fields initialised, bodies tested for overlap.
//
// The io module translates scenario JSON into this description (docs/scenario-format.md); a C++
// program may fill one in directly (docs/architecture.md, "Using the library"). Units SI.
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "krug/boundary/conditions.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/nosed_cylinder.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::setup {

// Zones a scene may ask for by default: about 10 GB of state at about 500 bytes a zone (node and
// zone fields); SceneDescription::max_zones sets another limit.
inline constexpr long max_zones = 20'000'000;
inline constexpr double bytes_per_zone = 500.0;
// Node coordinates a scene may have (m): an impact problem is metres across, not kilometres; a
// coordinate beyond this is a unit slip or a typing error (1e300).
inline constexpr double max_coordinate = 1e4;

// A field over a body: its value at a point (first, second coordinate in m).
using PointFunction = std::function<double(double first, double second)>;

// The mesh kinds, each a generator's parameters with its scenario `name` (`mesh.type`). The registry is
// the variant MeshShape: the scenario reader offers its names and reads the chosen kind's keys (an
// overload of read_mesh_kind in src/scenario/scenario_bodies.cpp), and build_simulation generates it and names
// its sides (overloads of generate_kind and kind_sides in src/setup/build.cpp). A kind without one of
// them stops the build. A new kind is its struct here, its line in MeshShape, those three overloads, its
// branch in docs/scenario.schema.json and its row in docs/scenario-format.md.

// A rectangle with grid lines at these coordinates (m), i along the first axis, j along the second.
// Sides: "<first>_min", "<first>_max", "<second>_min", "<second>_max" (x/y planar, z/r axisymmetric).
struct RectangleMesh {
  static constexpr std::string_view name = "rectangle";
  std::vector<double> first, second;
};

// An annular sector: radii (m, increasing; a first radius of 0 puts one node at the centre) and angles
// (radians, increasing). Sides: "inner" (absent when the first radius is 0), "outer", "start", "end".
struct SectorMesh {
  static constexpr std::string_view name = "sector";
  std::vector<double> radii, angles;
};

// A projectile or rod along the axis (generate::nosed_cylinder). Sides: "axis", "nose", "side", "rear".
struct NosedCylinderMesh {
  static constexpr std::string_view name = "nosed_cylinder";
  generate::NosedCylinderParams params;
};

// The mesh kinds a scene may use, in the order a scenario's error message lists them.
using MeshShape = std::variant<RectangleMesh, SectorMesh, NosedCylinderMesh>;

struct MeshDescription {
  MeshShape shape;
  generate::PositionMap map;  // optional, every kind: applied to every generated node
};

// The side names a boundary may use for this mesh, in the generator's terms (user name -> generator
// side name).
std::vector<std::pair<std::string, std::string>> side_names(const MeshDescription& mesh, GeometryKind geometry);

// The condition kinds are the boundary package's registry (boundary::condition_kinds()).
using SideCondition = boundary::Kind;

struct SideBoundary {
  std::string side;
  SideCondition condition = SideCondition::free;
  std::array<std::optional<double>, 2> velocity;         // m/s, for SideCondition::velocity
  std::array<boundary::TimeFunction, 2> velocity_of_time{};  // velocity: a component as a function of t (m/s), replacing velocity[k]
  boundary::TimeFunction pressure{}, traction{};             // Pa as functions of t, for SideCondition::pressure and ::traction
};

// Energy E (J; per unit thickness in planar geometry, whole body in axisymmetric) put into the zones
// around the node nearest to `point`, the same specific energy in each.
struct EnergyDeposit {
  double energy = 0.0;
  Vec2 point;
};

struct InitialState {
  std::optional<std::array<PointFunction, 2>> velocity;  // m/s at each node; empty: at rest
  PointFunction density;                                  // kg/m^3 at each zone centre; empty: the material's reference density
  PointFunction specific_internal_energy;                 // J/kg at each zone centre; empty: 0
  std::optional<EnergyDeposit> energy_deposit;
};

struct BodyDescription {
  std::string name;
  Index material = 0;  // index into SceneDescription::materials
  fracture::ErosionLimits erosion;
  struct Rezone {
    double altitude_ratio = 0.0;  // Body::rezone_ratio: 0, no rezoning
    double relaxation = 0.05;     // Body::rezone_relaxation
  } rezone;
  MeshDescription mesh;
  InitialState initial;
  std::vector<SideBoundary> boundary;  // applied in order; a node on two sides takes both constraints
  // How error messages name this body (a scenario's JSON path, "bodies[2]"); empty: "bodies[<index>]".
  std::string where;
};

struct SceneDescription {
  GeometryKind geometry = GeometryKind::planar;
  std::vector<Material> materials;
  std::vector<fracture::FailureLaw> fracture;  // per material; empty: no fracture
  std::vector<BodyDescription> bodies;
  contact::ContactSetup contact;
  Controls controls;
  long max_zones = setup::max_zones;  // a body asking for more zones is refused before it is built
};

// Generates every body's mesh in order, sets its initial fields and constraints, and checks what a
// mesh can only show once built: zone counts, nodes below the axis, positive densities, straight
// symmetry sides, bodies that overlap. Every error is an InputError naming the body's `where`.
SimulationSetup build_simulation(const SceneDescription& scene);

}  // namespace krug::setup
