#pragma once
// Numerical controls of a run, with defaults. Units SI.
#include <limits>

#include "krug/hydro/parameters.hpp"

namespace krug {

// Fracture and conversion to free elements (docs/theory.md §2 steps 6-7): numerical parameters.
struct FractureControls {
  double altitude_ratio = 0.25;            // f_h: fully fractured when the smallest altitude < f_h x initial
  double interior_altitude_ratio = 0.1;    // f_i: a damaged interior zone this thin converts too
  int particles_per_zone = 1;              // 1 (inscribed, radius min(sqrt(A), h)/2) or 4 (2x2, corner masses, node velocities)
  double time_step_floor_ratio = 0.2;      // damaged zones never drive dt below this x the median zone dt
  double particle_travel = 0.5;            // a particle moves at most this fraction of its radius per step
};

struct Controls {
  double end_time = 0.0;                 // s
  // Fraction of the zone's stable step: `cfl` in bodies with strength, `cfl_fluid` in bodies without
  // (docs/performance.md). A scenario that gives `cfl` alone sets both; code setting one sets one.
  double cfl = 0.5;
  double cfl_fluid = 0.6;
  double initial_time_step = 0.0;        // s; 0 = from the CFL condition (1e-6 end_time if that is unbounded)
  double max_time_step = std::numeric_limits<double>::infinity();  // s
  double time_step_growth = 1.1;         // largest ratio of one step to the previous
  double max_volume_change = 0.1;        // largest |dV/V| of a zone per step
  double time_step_floor = 0.0;          // s; 0 = 1e-9 of the first step. Below it the run stops.
  long max_cycles = 100'000'000;
  int threads = 1;                       // threads for the zone and node loops; the results do not depend on it
  ViscosityParams viscosity{.model = ViscosityModel::automatic};  // the model resolved per body (body_viscosity)
  HourglassParams hourglass;
  AxisymmetricForm axisymmetric_form = AxisymmetricForm::control_volume;
  FractureControls fracture;
};

}  // namespace krug
