#pragma once
// The zones' physics state, grouped by the package that owns it: the hydro step (EOS, artificial
// viscosity, corner forces, stable step), material strength (deviatoric stress and plastic strain),
// hourglass control (the stiffness state) and fracture (damage). The mesh (mesh.hpp) holds what
// describes the zones themselves: connectivity, activity, mass, geometry, density and specific
// energy. Every group is indexed by zone like ZoneFields and has the mesh's zone count; a run keeps
// the groups in its state (ZoneState, held by the SimulationState beside the Mesh).
//
// Kernels take the groups they use, const for what they only read: a signature names what it reads
// and writes.
#include <cstdint>
#include <vector>

#include "krug/mesh/mesh.hpp"

namespace krug {

// The hydro step's per-zone results (docs/theory.md §2 steps 1, 5 and 8).
struct HydroZoneFields {
  std::vector<double> pressure;          // Pa, from the EOS (artificial viscosity not included)
  std::vector<double> sound_speed;       // m/s, stress-wave speed used by the time step
  std::vector<double> viscous_speed;     // m/s, the artificial-viscosity signal speed of the last step
  std::vector<double> volume_change;     // |dV/V| over the last step
  std::vector<double> corner_force;      // 8 per zone: force on corner p = (2p, 2p+1), at t^n
  std::vector<double> stable_time_step;  // the zone's own stable step from the last update (s)
};

// Material strength (Prandtl-Reuss): the deviatoric stress and the equivalent plastic strain.
struct StrengthZoneFields {
  std::vector<double> deviator_xx, deviator_yy;  // deviatoric stress (Pa)
  std::vector<double> deviator_xy, deviator_zz;  // zz: hoop (axisymmetric) or out-of-plane (planar)
  std::vector<double> plastic_strain;            // equivalent plastic strain
};

// Hourglass control: the Flanagan-Belytschko stiffness generalised forces.
struct HourglassZoneFields {
  std::vector<double> hourglass_x, hourglass_y;
};

// Fracture (docs/theory.md §2 step 6): permanent damage, when and why it started.
struct FractureZoneFields {
  std::vector<std::uint8_t> damaged;           // 0 intact, 1 damaged
  std::vector<double> damage_time;             // s; -1 while intact
  std::vector<std::uint8_t> damage_criterion;  // fracture::Criterion that fired
  std::vector<double> damage;                  // a damage law's D (Johnson-Cook: sum d eps_p / eps_f); 0 otherwise
  std::vector<double> damage_plastic_strain;   // the plastic strain already counted in `damage`
};

// The registries of the groups, as for_each_zone_field (mesh.hpp): every array, once, with its name,
// its entries per zone and the value a new entry takes. Resizing and checkpoints walk them (through
// for_each_zone_state_field), so a new field is its member above plus one line here.
template <class Hydro, class F>
void for_each_hydro_field(Hydro& h, F&& f) {
  f("pressure", h.pressure, 1, 0.0);
  f("sound_speed", h.sound_speed, 1, 0.0);
  f("viscous_speed", h.viscous_speed, 1, 0.0);
  f("volume_change", h.volume_change, 1, 0.0);
  f("corner_force", h.corner_force, 8, 0.0);
  f("stable_time_step", h.stable_time_step, 1, 0.0);
}

template <class Strength, class F>
void for_each_strength_field(Strength& s, F&& f) {
  f("deviator_xx", s.deviator_xx, 1, 0.0);
  f("deviator_yy", s.deviator_yy, 1, 0.0);
  f("deviator_xy", s.deviator_xy, 1, 0.0);
  f("deviator_zz", s.deviator_zz, 1, 0.0);
  f("plastic_strain", s.plastic_strain, 1, 0.0);
}

template <class Hourglass, class F>
void for_each_hourglass_field(Hourglass& h, F&& f) {
  f("hourglass_x", h.hourglass_x, 1, 0.0);
  f("hourglass_y", h.hourglass_y, 1, 0.0);
}

template <class Fracture, class F>
void for_each_fracture_field(Fracture& d, F&& f) {
  f("damaged", d.damaged, 1, std::uint8_t{0});
  f("damage_time", d.damage_time, 1, -1.0);
  f("damage_criterion", d.damage_criterion, 1, std::uint8_t{0});
  f("damage", d.damage, 1, 0.0);
  f("damage_plastic_strain", d.damage_plastic_strain, 1, 0.0);
}

// A field added to a group without its registry line changes these sizes: the build stops here
// (every member is a std::vector of 24 bytes).
static_assert(sizeof(std::vector<double>) != 24 || sizeof(HydroZoneFields) == 6 * 24,
              "HydroZoneFields changed: add the field to for_each_hydro_field");
static_assert(sizeof(std::vector<double>) != 24 || sizeof(StrengthZoneFields) == 5 * 24,
              "StrengthZoneFields changed: add the field to for_each_strength_field");
static_assert(sizeof(std::vector<double>) != 24 || sizeof(HourglassZoneFields) == 2 * 24,
              "HourglassZoneFields changed: add the field to for_each_hourglass_field");
static_assert(sizeof(std::vector<double>) != 24 || sizeof(FractureZoneFields) == 5 * 24,
              "FractureZoneFields changed: add the field to for_each_fracture_field");

// The physics state of every zone, by package.
struct ZoneState {
  HydroZoneFields hydro;
  StrengthZoneFields strength;
  HourglassZoneFields hourglass;
  FractureZoneFields fracture;

  Index size() const { return static_cast<Index>(hydro.pressure.size()); }
  // n zones; new entries take their registry's fill value.
  void resize(Index n);
};

// Every group's registry in turn (hydro, strength, hourglass, fracture): `f(name, array, per, fill)`.
template <class State, class F>
void for_each_zone_state_field(State& s, F&& f) {
  for_each_hydro_field(s.hydro, f);
  for_each_strength_field(s.strength, f);
  for_each_hourglass_field(s.hourglass, f);
  for_each_fracture_field(s.fracture, f);
}

static_assert(sizeof(ZoneState) == sizeof(HydroZoneFields) + sizeof(StrengthZoneFields) + sizeof(HourglassZoneFields) +
                                       sizeof(FractureZoneFields),
              "ZoneState changed: a new group needs its registry in for_each_zone_state_field");

}  // namespace krug
