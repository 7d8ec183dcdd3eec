#include "krug/solver/output_fields.hpp"

#include <cmath>

#include "krug/solver/simulation.hpp"

namespace krug {

namespace {

using Items = std::span<const Index>;

// One value per item: get(i) for each item, as T.
template <class T, class Get>
OutputValues each(Items items, Get get) {
  std::vector<T> values;
  values.reserve(items.size());
  for (Index i : items) values.push_back(static_cast<T>(get(i)));
  return values;
}

// The in-plane vector (a[i], b[i]) of each item as (a, b, 0), VTK's three components.
OutputValues vector3(Items items, const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> values;
  values.reserve(3 * items.size());
  for (Index i : items) values.insert(values.end(), {a[i], b[i], 0.0});
  return values;
}

const NodeFields& nodes(const Simulation& s) { return s.mesh().nodes; }
const ZoneFields& zones(const Simulation& s) { return s.mesh().zones; }
const HydroZoneFields& hydro(const Simulation& s) { return s.zone_state().hydro; }
const StrengthZoneFields& strength(const Simulation& s) { return s.zone_state().strength; }
const FractureZoneFields& fracture(const Simulation& s) { return s.zone_state().fracture; }

// sigma_vm = sqrt(3 J2), J2 = s:s / 2 with the shear component counted twice.
double von_mises(const StrengthZoneFields& z, Index i) {
  const double sxx = z.deviator_xx[i], syy = z.deviator_yy[i], sxy = z.deviator_xy[i], szz = z.deviator_zz[i];
  return std::sqrt(1.5 * (sxx * sxx + syy * syy + szz * szz + 2.0 * sxy * sxy));
}

// eta = -p / sigma_vm (p the equation of state's pressure, compression positive); 0 where sigma_vm = 0.
double triaxiality(const Simulation& s, Index i) {
  const double vm = von_mises(strength(s), i);
  return vm > 0.0 ? -hydro(s).pressure[i] / vm : 0.0;
}

using L = OutputLocation;
using S = const Simulation&;

// The deviator's components are named by the scenario's axes: (xx, yy, xy, zz) planar, with zz the
// out-of-plane component; (zz, rr, zr, tt) axisymmetric, with tt the hoop component.
const OutputField fields[] = {
    // name, axisymmetric name, components, location, values
    {"velocity", "", 3, L::node, [](S s, Items i) { return vector3(i, nodes(s).u, nodes(s).v); }},
    {"body", "", 1, L::node, [](S s, Items i) { return each<std::int32_t>(i, [&](Index p) { return nodes(s).body[p]; }); }},
    {"body", "", 1, L::zone, [](S s, Items i) { return each<std::int32_t>(i, [&](Index z) { return zones(s).body[z]; }); }},
    {"density", "", 1, L::zone, [](S s, Items i) { return each<double>(i, [&](Index z) { return zones(s).density[z]; }); }},
    {"pressure", "", 1, L::zone, [](S s, Items i) { return each<double>(i, [&](Index z) { return hydro(s).pressure[z]; }); }},
    {"specific_internal_energy", "", 1, L::zone,
     [](S s, Items i) { return each<double>(i, [&](Index z) { return zones(s).specific_energy[z]; }); }},
    {"sound_speed", "", 1, L::zone, [](S s, Items i) { return each<double>(i, [&](Index z) { return hydro(s).sound_speed[z]; }); }},
    {"deviatoric_stress_xx", "deviatoric_stress_zz", 1, L::zone,
     [](S s, Items i) { return each<double>(i, [&](Index z) { return strength(s).deviator_xx[z]; }); }},
    {"deviatoric_stress_yy", "deviatoric_stress_rr", 1, L::zone,
     [](S s, Items i) { return each<double>(i, [&](Index z) { return strength(s).deviator_yy[z]; }); }},
    {"deviatoric_stress_xy", "deviatoric_stress_zr", 1, L::zone,
     [](S s, Items i) { return each<double>(i, [&](Index z) { return strength(s).deviator_xy[z]; }); }},
    {"deviatoric_stress_zz", "deviatoric_stress_tt", 1, L::zone,
     [](S s, Items i) { return each<double>(i, [&](Index z) { return strength(s).deviator_zz[z]; }); }},
    {"von_mises_stress", "", 1, L::zone, [](S s, Items i) { return each<double>(i, [&](Index z) { return von_mises(strength(s), z); }); }},
    {"stress_triaxiality", "", 1, L::zone, [](S s, Items i) { return each<double>(i, [&](Index z) { return triaxiality(s, z); }); }},
    {"equivalent_plastic_strain", "", 1, L::zone,
     [](S s, Items i) { return each<double>(i, [&](Index z) { return strength(s).plastic_strain[z]; }); }},
    {"damaged", "", 1, L::zone, [](S s, Items i) { return each<std::uint8_t>(i, [&](Index z) { return fracture(s).damaged[z]; }); }},
    {"damage_onset_time", "", 1, L::zone, [](S s, Items i) { return each<double>(i, [&](Index z) { return fracture(s).damage_time[z]; }); }},
    {"damage_criterion", "", 1, L::zone,
     [](S s, Items i) { return each<std::uint8_t>(i, [&](Index z) { return fracture(s).damage_criterion[z]; }); }},
    {"damage", "", 1, L::zone, [](S s, Items i) { return each<double>(i, [&](Index z) { return fracture(s).damage[z]; }); }},
    {"stable_time_step", "", 1, L::zone,
     [](S s, Items i) { return each<double>(i, [&](Index z) { return hydro(s).stable_time_step[z]; }); }},
    {"velocity", "", 3, L::particle, [](S s, Items i) { return vector3(i, s.particles().u, s.particles().v); }},
    {"radius", "", 1, L::particle, [](S s, Items i) { return each<double>(i, [&](Index p) { return s.particles().radius[p]; }); }},
    {"mass", "", 1, L::particle, [](S s, Items i) { return each<double>(i, [&](Index p) { return s.particles().mass[p]; }); }},
    {"body", "", 1, L::particle, [](S s, Items i) { return each<std::int32_t>(i, [&](Index p) { return s.particles().body[p]; }); }},
    {"birth_time", "", 1, L::particle,
     [](S s, Items i) { return each<double>(i, [&](Index p) { return s.particles().birth_time[p]; }); }},
};

}  // namespace

std::span<const OutputField> output_fields() { return fields; }

}  // namespace krug
