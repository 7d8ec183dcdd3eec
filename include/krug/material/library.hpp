#pragma once
// The material library: named sets of published constants, each number with its source beside it.
// A scenario names a set (`"materials": {"plate": "al6061-t6"}`, or `{"base": "al6061-t6", ...}` with
// overrides); the scenario reader expands the set into the material block it already reads, so a set
// is exactly what a user could have written by hand (docs/materials.md, docs/scenario-format.md).
//
// The data are plain constants, not files read at run time. Each constant names the scenario block it
// belongs to ("" for the material's own keys such as `density`, "eos", "strength", "fracture") and the
// key the model's parameter list gives it (parameters.hpp), so the strict reader checks every key.
//
// The Johnson–Cook damage constants D1..D5 (Johnson & Cook 1985, fracture strain
// eps_f = [D1 + D2 exp(D3 sigma*)] [1 + D4 ln(rate*)] [1 + D5 T*], sigma* = mean stress / von Mises
// stress) are carried in the block "damage" for the sets where they are published. They enter a
// scenario only through a fracture block that asks for the Johnson-Cook failure law (the reader fills
// the block's missing d1..d5 from the set: src/scenario/scenario.cpp, expand_material), and are listed by
// `krug materials NAME`.
//
// Sources, abbreviated in the strings below (full references in docs/materials.md):
//   JC83   Johnson & Cook (1983), 7th Int. Symp. Ballistics, The Hague, 541-547, Table 1 (strength)
//   JC85   Johnson & Cook (1985), Eng. Fract. Mech. 21(1), 31-48, Table 1 (damage)
//   S96    Steinberg (1996), UCRL-MA-106439 Change 1, "Equation of state and strength properties of
//          selected materials" (Us-up fit c0, s; Gamma0; shear modulus G0; yield Y0)
//   L00    Lesuer (2000), DOT/FAA/AR-00/25 (Ti-6Al-4V and 2024-T3 Johnson-Cook strength)
//   L01    Lesuer, Kay & LeBlanc (2001), UCRL-JC-134118 (6061-T6 Johnson-Cook strength and damage)
//   K03    Kay (2003), DOT/FAA/AR-03/57 (Ti-6Al-4V Johnson-Cook damage)
//   B09    Brar, Joshi & Harris (2009), AIP Conf. Proc. 1195, 945 (7075-T6 strength and damage)
//   ASM    ASM Handbook vol. 1 (steels) and vol. 2 (aluminium, titanium): room-temperature elastic
//          constants and specific heats
//   KL     Kaye & Laby, Tables of Physical and Chemical Constants (elastic moduli of polycrystalline iron)
//   GS96   Gulidov & Shabalin (1996), the paper this code follows (its 6061-T6 and lead)
#include <array>
#include <span>
#include <string_view>

namespace krug::library {

// One constant of a set: its block in a scenario's material ("" for the material's own keys, "eos",
// "strength", "fracture"; "damage" for the Johnson–Cook damage constants, read by the Johnson-Cook
// failure law when a scenario asks for it), its key there,
// its value in SI, its unit (for listings) and its source.
struct Constant {
  std::string_view block;
  std::string_view key;
  double value = 0.0;
  std::string_view unit;
  std::string_view source;
};

struct MaterialSet {
  std::string_view name;            // what a scenario writes, e.g. "al6061-t6"
  std::string_view title;           // the material in words
  std::string_view eos_model;       // `eos.model`
  std::string_view strength_model;  // `strength.model`
  std::string_view source;          // one line: where the set comes from
  std::string_view notes;           // the choices made (which source, why)
  std::span<const Constant> constants;
};

namespace data {

// Room temperature of every Johnson–Cook set: the scenario's default (the sources quote 293-298 K).
inline constexpr double room = 293.0;
inline constexpr std::string_view room_source = "room temperature, the reader's default (JC83: ambient)";
inline constexpr std::string_view rate_source = "the reference strain rate of the fit (1/s, as in JC83)";

inline constexpr std::array al6061_t6{
    Constant{"", "density", 2703.0, "kg/m^3", "S96 (6061-T6)"},
    Constant{"eos", "bulk_sound_speed", 5240.0, "m/s", "S96 (6061-T6), c0"},
    Constant{"eos", "hugoniot_slope", 1.40, "-", "S96 (6061-T6), s"},
    Constant{"eos", "gruneisen", 1.97, "-", "S96 (6061-T6), Gamma0"},
    Constant{"strength", "shear_modulus", 27.6e9, "Pa", "S96 (6061-T6), G0"},
    Constant{"strength", "yield_stress", 324.0e6, "Pa", "L01, A"},
    Constant{"strength", "hardening_coefficient", 114.0e6, "Pa", "L01, B"},
    Constant{"strength", "hardening_exponent", 0.42, "-", "L01, n"},
    Constant{"strength", "strain_rate_coefficient", 0.002, "-", "L01, C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 1.34, "-", "L01, m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 925.0, "K", "L01, T_melt"},
    Constant{"strength", "specific_heat", 896.0, "J/(kg K)", "ASM vol. 2 (6061-T6)"},
    Constant{"damage", "d1", -0.77, "-", "L01, D1"},
    Constant{"damage", "d2", 1.45, "-", "L01, D2"},
    Constant{"damage", "d3", -0.47, "-", "L01, D3"},
    Constant{"damage", "d4", 0.0, "-", "L01, D4"},
    Constant{"damage", "d5", 1.60, "-", "L01, D5"},
};

inline constexpr std::array al2024_t3{
    Constant{"", "density", 2785.0, "kg/m^3", "S96 (2024)"},
    Constant{"eos", "bulk_sound_speed", 5328.0, "m/s", "S96 (2024), c0"},
    Constant{"eos", "hugoniot_slope", 1.338, "-", "S96 (2024), s"},
    Constant{"eos", "gruneisen", 2.00, "-", "S96 (2024), Gamma0"},
    Constant{"strength", "shear_modulus", 28.6e9, "Pa", "S96 (2024), G0"},
    Constant{"strength", "yield_stress", 369.0e6, "Pa", "L00 (2024-T3), A"},
    Constant{"strength", "hardening_coefficient", 684.0e6, "Pa", "L00 (2024-T3), B"},
    Constant{"strength", "hardening_exponent", 0.73, "-", "L00 (2024-T3), n"},
    Constant{"strength", "strain_rate_coefficient", 0.0083, "-", "L00 (2024-T3), C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 1.7, "-", "L00 (2024-T3), m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 775.0, "K", "JC83 (2024-T351), T_melt"},
    Constant{"strength", "specific_heat", 875.0, "J/(kg K)", "JC83 (2024-T351)"},
    Constant{"damage", "d1", 0.13, "-", "JC85 (2024-T351), D1"},
    Constant{"damage", "d2", 0.13, "-", "JC85 (2024-T351), D2"},
    Constant{"damage", "d3", -1.5, "-", "JC85 (2024-T351), D3"},
    Constant{"damage", "d4", 0.011, "-", "JC85 (2024-T351), D4"},
    Constant{"damage", "d5", 0.0, "-", "JC85 (2024-T351), D5"},
};

inline constexpr std::array al7075_t6{
    Constant{"", "density", 2810.0, "kg/m^3", "ASM vol. 2 (7075-T6)"},
    Constant{"eos", "bulk_modulus", 70.3e9, "Pa", "from E = 71.7 GPa, nu = 0.33 (ASM vol. 2, 7075-T6): K = E / (3 (1 - 2 nu))"},
    Constant{"strength", "shear_modulus", 26.9e9, "Pa", "ASM vol. 2 (7075-T6)"},
    Constant{"strength", "yield_stress", 546.0e6, "Pa", "B09 (7075-T6), A"},
    Constant{"strength", "hardening_coefficient", 674.0e6, "Pa", "B09 (7075-T6), B"},
    Constant{"strength", "hardening_exponent", 0.72, "-", "B09 (7075-T6), n"},
    Constant{"strength", "strain_rate_coefficient", 0.059, "-", "B09 (7075-T6), C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 1.56, "-", "B09 (7075-T6), m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 908.0, "K", "ASM vol. 2 (7075, liquidus 635 C)"},
    Constant{"strength", "specific_heat", 960.0, "J/(kg K)", "ASM vol. 2 (7075-T6)"},
    Constant{"damage", "d1", -0.068, "-", "B09 (7075-T6), D1"},
    Constant{"damage", "d2", 0.451, "-", "B09 (7075-T6), D2"},
    Constant{"damage", "d3", -0.952, "-", "B09 (7075-T6), D3"},
    Constant{"damage", "d4", 0.036, "-", "B09 (7075-T6), D4"},
    Constant{"damage", "d5", 0.697, "-", "B09 (7075-T6), D5"},
};

inline constexpr std::array lead{
    Constant{"", "density", 11350.0, "kg/m^3", "S96 (lead)"},
    Constant{"eos", "bulk_sound_speed", 2006.0, "m/s", "S96 (lead), c0"},
    Constant{"eos", "hugoniot_slope", 1.429, "-", "S96 (lead), s"},
    Constant{"eos", "gruneisen", 2.74, "-", "S96 (lead), Gamma0"},
    Constant{"strength", "shear_modulus", 8.6e9, "Pa", "S96 (lead), G0"},
    Constant{"strength", "yield_stress", 8.0e6, "Pa", "S96 (lead), Y0 (perfectly plastic: no Johnson-Cook fit in JC83)"},
};

inline constexpr std::array ofhc_copper{
    Constant{"", "density", 8930.0, "kg/m^3", "S96 (copper), the Hugoniot's reference density (JC83 lists 8960)"},
    Constant{"eos", "bulk_sound_speed", 3940.0, "m/s", "S96 (copper), c0"},
    Constant{"eos", "hugoniot_slope", 1.489, "-", "S96 (copper), s"},
    Constant{"eos", "gruneisen", 2.02, "-", "S96 (copper), Gamma0"},
    Constant{"strength", "shear_modulus", 47.7e9, "Pa", "S96 (copper), G0"},
    Constant{"strength", "yield_stress", 90.0e6, "Pa", "JC83 (OFHC copper), A"},
    Constant{"strength", "hardening_coefficient", 292.0e6, "Pa", "JC83 (OFHC copper), B"},
    Constant{"strength", "hardening_exponent", 0.31, "-", "JC83 (OFHC copper), n"},
    Constant{"strength", "strain_rate_coefficient", 0.025, "-", "JC83 (OFHC copper), C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 1.09, "-", "JC83 (OFHC copper), m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 1356.0, "K", "JC83 (OFHC copper), T_melt"},
    Constant{"strength", "specific_heat", 383.0, "J/(kg K)", "JC83 (OFHC copper)"},
    Constant{"damage", "d1", 0.54, "-", "JC85 (OFHC copper), D1"},
    Constant{"damage", "d2", 4.89, "-", "JC85 (OFHC copper), D2"},
    Constant{"damage", "d3", -3.03, "-", "JC85 (OFHC copper), D3"},
    Constant{"damage", "d4", 0.014, "-", "JC85 (OFHC copper), D4"},
    Constant{"damage", "d5", 1.12, "-", "JC85 (OFHC copper), D5"},
};

// Steels and iron: a linear bulk modulus from the elastic constants, not a Us-up fit: iron's
// alpha-epsilon transition at 13 GPa splits the shock, and a single linear fit through it gives a
// bulk sound speed far below the elastic one (docs/materials.md).
inline constexpr std::string_view steel_moduli = "from E = 205 GPa, nu = 0.29 (ASM vol. 1, 4340)";

inline constexpr std::array steel_4340{
    Constant{"", "density", 7830.0, "kg/m^3", "JC83 (4340 steel, Rc 30)"},
    Constant{"eos", "bulk_modulus", 162.7e9, "Pa", steel_moduli},
    Constant{"strength", "shear_modulus", 79.5e9, "Pa", steel_moduli},
    Constant{"strength", "yield_stress", 792.0e6, "Pa", "JC83 (4340 steel, Rc 30), A"},
    Constant{"strength", "hardening_coefficient", 510.0e6, "Pa", "JC83 (4340 steel, Rc 30), B"},
    Constant{"strength", "hardening_exponent", 0.26, "-", "JC83 (4340 steel, Rc 30), n"},
    Constant{"strength", "strain_rate_coefficient", 0.014, "-", "JC83 (4340 steel, Rc 30), C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 1.03, "-", "JC83 (4340 steel, Rc 30), m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 1793.0, "K", "JC83 (4340 steel, Rc 30), T_melt"},
    Constant{"strength", "specific_heat", 477.0, "J/(kg K)", "JC83 (4340 steel, Rc 30)"},
    Constant{"damage", "d1", 0.05, "-", "JC85 (4340 steel, Rc 30), D1"},
    Constant{"damage", "d2", 3.44, "-", "JC85 (4340 steel, Rc 30), D2"},
    Constant{"damage", "d3", -2.12, "-", "JC85 (4340 steel, Rc 30), D3"},
    Constant{"damage", "d4", 0.002, "-", "JC85 (4340 steel, Rc 30), D4"},
    Constant{"damage", "d5", 0.61, "-", "JC85 (4340 steel, Rc 30), D5"},
};

inline constexpr std::array armco_iron{
    Constant{"", "density", 7890.0, "kg/m^3", "JC83 (Armco iron)"},
    Constant{"eos", "bulk_modulus", 169.8e9, "Pa", "KL (iron, polycrystalline)"},
    Constant{"strength", "shear_modulus", 81.6e9, "Pa", "KL (iron, polycrystalline)"},
    Constant{"strength", "yield_stress", 175.0e6, "Pa", "JC83 (Armco iron), A"},
    Constant{"strength", "hardening_coefficient", 380.0e6, "Pa", "JC83 (Armco iron), B"},
    Constant{"strength", "hardening_exponent", 0.32, "-", "JC83 (Armco iron), n"},
    Constant{"strength", "strain_rate_coefficient", 0.060, "-", "JC83 (Armco iron), C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 0.55, "-", "JC83 (Armco iron), m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 1811.0, "K", "JC83 (Armco iron), T_melt"},
    Constant{"strength", "specific_heat", 452.0, "J/(kg K)", "JC83 (Armco iron)"},
    Constant{"damage", "d1", -2.20, "-", "JC85 (Armco iron), D1"},
    Constant{"damage", "d2", 5.43, "-", "JC85 (Armco iron), D2"},
    Constant{"damage", "d3", -0.47, "-", "JC85 (Armco iron), D3"},
    Constant{"damage", "d4", 0.016, "-", "JC85 (Armco iron), D4"},
    Constant{"damage", "d5", 0.63, "-", "JC85 (Armco iron), D5"},
};

// The tungsten alloy of JC83 (0.07 Ni, 0.03 Fe by weight: 90 W-7 Ni-3 Fe). Its elastic constants are
// not in JC83; E and nu are typical of 90 % tungsten heavy alloys (an estimate, docs/materials.md).
inline constexpr std::string_view wha_moduli =
    "estimate: E = 345 GPa, nu = 0.29, typical of 90 % W heavy alloys (not in JC83)";

inline constexpr std::array tungsten_alloy{
    Constant{"", "density", 17000.0, "kg/m^3", "JC83 (tungsten alloy, .07 Ni .03 Fe)"},
    Constant{"eos", "bulk_modulus", 273.8e9, "Pa", wha_moduli},
    Constant{"strength", "shear_modulus", 133.7e9, "Pa", wha_moduli},
    Constant{"strength", "yield_stress", 1506.0e6, "Pa", "JC83 (tungsten alloy), A"},
    Constant{"strength", "hardening_coefficient", 177.0e6, "Pa", "JC83 (tungsten alloy), B"},
    Constant{"strength", "hardening_exponent", 0.12, "-", "JC83 (tungsten alloy), n"},
    Constant{"strength", "strain_rate_coefficient", 0.016, "-", "JC83 (tungsten alloy), C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 1.00, "-", "JC83 (tungsten alloy), m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 1723.0, "K", "JC83 (tungsten alloy), T_melt"},
    Constant{"strength", "specific_heat", 134.0, "J/(kg K)", "JC83 (tungsten alloy)"},
};

inline constexpr std::array ti6al4v{
    Constant{"", "density", 4419.0, "kg/m^3", "S96 (Ti-6Al-4V)"},
    Constant{"eos", "bulk_sound_speed", 5130.0, "m/s", "S96 (Ti-6Al-4V), c0"},
    Constant{"eos", "hugoniot_slope", 1.028, "-", "S96 (Ti-6Al-4V), s"},
    Constant{"eos", "gruneisen", 1.23, "-", "S96 (Ti-6Al-4V), Gamma0"},
    Constant{"strength", "shear_modulus", 41.9e9, "Pa", "S96 (Ti-6Al-4V), G0"},
    Constant{"strength", "yield_stress", 1098.0e6, "Pa", "L00 (Ti-6Al-4V), A"},
    Constant{"strength", "hardening_coefficient", 1092.0e6, "Pa", "L00 (Ti-6Al-4V), B"},
    Constant{"strength", "hardening_exponent", 0.93, "-", "L00 (Ti-6Al-4V), n"},
    Constant{"strength", "strain_rate_coefficient", 0.014, "-", "L00 (Ti-6Al-4V), C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 1.1, "-", "L00 (Ti-6Al-4V), m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 1878.0, "K", "L00 (Ti-6Al-4V), T_melt"},
    Constant{"strength", "specific_heat", 526.0, "J/(kg K)", "ASM vol. 2 (Ti-6Al-4V)"},
    Constant{"damage", "d1", -0.09, "-", "K03 (Ti-6Al-4V), D1"},
    Constant{"damage", "d2", 0.25, "-", "K03 (Ti-6Al-4V), D2"},
    Constant{"damage", "d3", -0.5, "-", "K03 (Ti-6Al-4V), D3"},
    Constant{"damage", "d4", 0.014, "-", "K03 (Ti-6Al-4V), D4"},
    Constant{"damage", "d5", 3.87, "-", "K03 (Ti-6Al-4V), D5"},
};

// Rolled homogeneous armour (MIL-DTL-12560): no Johnson-Cook fit of RHA itself is in the sources above;
// 4340 steel at Rc 30 (JC83, JC85) stands in, inside RHA's hardness range (about Rc 23-41 by thickness).
inline constexpr std::array rha{
    Constant{"", "density", 7850.0, "kg/m^3", "ASM vol. 1 (carbon and low-alloy steels)"},
    Constant{"eos", "bulk_modulus", 162.7e9, "Pa", steel_moduli},
    Constant{"strength", "shear_modulus", 79.5e9, "Pa", steel_moduli},
    Constant{"strength", "yield_stress", 792.0e6, "Pa", "JC83 (4340 steel, Rc 30, standing in for RHA), A"},
    Constant{"strength", "hardening_coefficient", 510.0e6, "Pa", "JC83 (4340, Rc 30), B"},
    Constant{"strength", "hardening_exponent", 0.26, "-", "JC83 (4340, Rc 30), n"},
    Constant{"strength", "strain_rate_coefficient", 0.014, "-", "JC83 (4340, Rc 30), C"},
    Constant{"strength", "reference_strain_rate", 1.0, "1/s", rate_source},
    Constant{"strength", "thermal_softening_exponent", 1.03, "-", "JC83 (4340, Rc 30), m"},
    Constant{"strength", "room_temperature", room, "K", room_source},
    Constant{"strength", "melt_temperature", 1793.0, "K", "JC83 (4340, Rc 30), T_melt"},
    Constant{"strength", "specific_heat", 477.0, "J/(kg K)", "JC83 (4340, Rc 30)"},
    Constant{"damage", "d1", 0.05, "-", "JC85 (4340, Rc 30), D1"},
    Constant{"damage", "d2", 3.44, "-", "JC85 (4340, Rc 30), D2"},
    Constant{"damage", "d3", -2.12, "-", "JC85 (4340, Rc 30), D3"},
    Constant{"damage", "d4", 0.002, "-", "JC85 (4340, Rc 30), D4"},
    Constant{"damage", "d5", 0.61, "-", "JC85 (4340, Rc 30), D5"},
};

// The paper's own data (docs/validation.md): exactly the numbers its scenarios have always used.
inline constexpr std::array paper_al6061_t6{
    Constant{"", "density", 2700.0, "kg/m^3", "GS96 (6061-T6)"},
    Constant{"eos", "bulk_modulus", 7.3e10, "Pa", "GS96 (6061-T6), K"},
    Constant{"strength", "shear_modulus", 2.46e10, "Pa", "GS96 (6061-T6), mu"},
    Constant{"strength", "yield_stress", 2.8e8, "Pa", "GS96 (6061-T6), Y0"},
    Constant{"fracture", "elongation", 0.4, "-", "GS96 (6061-T6), criterion eps_*"},
    Constant{"fracture", "loosening", 0.03, "-", "GS96 (6061-T6), loosening chi_*"},
};

inline constexpr std::array paper_lead{
    Constant{"", "density", 11340.0, "kg/m^3", "GS96 (lead)"},
    Constant{"eos", "bulk_modulus", 5.0e10, "Pa", "GS96 (lead), K"},
    Constant{"strength", "shear_modulus", 5.7e9, "Pa", "GS96 (lead), mu"},
    Constant{"strength", "yield_stress", 3.0e7, "Pa", "GS96 (lead), Y0 (does not fracture)"},
};

}  // namespace data

// Every set, in the order `krug materials` lists them.
inline constexpr std::array<MaterialSet, 12> material_sets{{
    {"al6061-t6", "aluminium alloy 6061-T6", "mie_gruneisen", "johnson_cook",
     "Steinberg 1996 (EOS, G); Lesuer et al. 2001 (Johnson-Cook strength and damage)",
     "Johnson-Cook (L01) rather than Steinberg's perfectly plastic Y0 = 290 MPa: hardening, rate and heat.",
     data::al6061_t6},
    {"al2024-t3", "aluminium alloy 2024-T3", "mie_gruneisen", "johnson_cook",
     "Steinberg 1996 (EOS, G, 2024); Lesuer 2000 (Johnson-Cook, 2024-T3); Johnson & Cook 1985 (damage, 2024-T351)",
     "Lesuer's fit of 2024-T3 itself rather than JC83's 2024-T351 (A 265 MPa, B 426 MPa, n 0.34, C 0.015, m 1); "
     "damage from JC85's 2024-T351, the nearest published temper.",
     data::al2024_t3},
    {"al7075-t6", "aluminium alloy 7075-T6", "linear", "johnson_cook",
     "ASM (density, elastic constants); Brar, Joshi & Harris 2009 (Johnson-Cook strength and damage)",
     "Linear EOS: no Us-up fit of 7075 in the sources used. B09's abstract prints D1..D3 as 0.451, -0.952, "
     "-0.068, which gives a negative fracture strain; the order used is D1 -0.068, D2 0.451, D3 -0.952.",
     data::al7075_t6},
    {"lead", "pure lead", "mie_gruneisen", "perfectly_plastic",
     "Steinberg 1996 (EOS, G0, Y0)",
     "Perfectly plastic at Steinberg's Y0 = 8 MPa: JC83 has no lead. The paper's lead (paper-lead) is stiffer "
     "and stronger (K 50 GPa, Y 30 MPa).",
     data::lead},
    {"ofhc-copper", "OFHC copper (annealed)", "mie_gruneisen", "johnson_cook",
     "Steinberg 1996 (EOS, G0); Johnson & Cook 1983 (strength); Johnson & Cook 1985 (damage)",
     "Density 8930 kg/m^3, the reference of Steinberg's Hugoniot, rather than JC83's 8960 (0.3 % apart).",
     data::ofhc_copper},
    {"steel-4340", "AISI 4340 steel, Rc 30", "linear", "johnson_cook",
     "Johnson & Cook 1983 / 1985 (4340 at Rc 30); ASM (elastic constants)",
     "Linear EOS from E and nu (see the note on iron and steels in docs/materials.md).",
     data::steel_4340},
    {"armco-iron", "Armco iron", "linear", "johnson_cook",
     "Johnson & Cook 1983 / 1985 (Armco iron); Kaye & Laby (elastic moduli)",
     "Linear EOS: iron's alpha-epsilon transition at 13 GPa makes a single Us-up fit misleading.",
     data::armco_iron},
    {"tungsten-alloy", "tungsten heavy alloy 90W-7Ni-3Fe", "linear", "johnson_cook",
     "Johnson & Cook 1983 (tungsten alloy .07Ni .03Fe); elastic constants an estimate",
     "E and nu are an estimate typical of 90 % W alloys, not from JC83; no damage constants published there.",
     data::tungsten_alloy},
    {"ti-6al-4v", "titanium alloy Ti-6Al-4V", "mie_gruneisen", "johnson_cook",
     "Steinberg 1996 (EOS, G0); Lesuer 2000 (Johnson-Cook); Kay 2003 (damage)",
     "Lesuer's Johnson-Cook fit rather than Steinberg's Y0 = 1.33 GPa; specific heat from ASM.",
     data::ti6al4v},
    {"rha", "rolled homogeneous armour steel (4340 at Rc 30 standing in)", "linear", "johnson_cook",
     "Johnson & Cook 1983 / 1985 (4340 steel, Rc 30, standing in for RHA); ASM",
     "No RHA fit in the sources used: 4340 at Rc 30 lies inside RHA's hardness range; use steel-4340's numbers "
     "knowingly, or override them with a fit of the armour at hand.",
     data::rha},
    {"paper-al6061-t6", "6061-T6 as in Gulidov & Shabalin 1996", "linear", "perfectly_plastic",
     "Gulidov & Shabalin 1996 (the paper's case, docs/validation.md)",
     "The paper's numbers exactly, with its fracture criterion (elongation 0.4, loosening 0.03).",
     data::paper_al6061_t6},
    {"paper-lead", "lead as in Gulidov & Shabalin 1996", "linear", "perfectly_plastic",
     "Gulidov & Shabalin 1996 (the paper's case, docs/validation.md)",
     "The paper's numbers exactly; it does not fracture (erosion, a numerical deviation, is the scenario's).",
     data::paper_lead},
}};

// The set of that name, or null.
constexpr const MaterialSet* find_material_set(std::string_view name) {
  for (const MaterialSet& set : material_sets) {
    if (set.name == name) return &set;
  }
  return nullptr;
}

// The constant of a set at (block, key), or null.
constexpr const Constant* find_constant(const MaterialSet& set, std::string_view block, std::string_view key) {
  for (const Constant& c : set.constants) {
    if (c.block == block && c.key == key) return &c;
  }
  return nullptr;
}

}  // namespace krug::library
