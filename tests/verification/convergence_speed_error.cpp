// Speed against error (docs/performance.md, "Speed against error"): the L1 density error against the
// CPU time of the run for Sod, the cylindrical and spherical Sedov and Noh problems on their
// verification meshes at four resolutions, each against its exact profile (tests/data/exact), and
// the elastic-plastic Taylor bar's length and impact-face radius against their converged values. With
// KRUG_VERIFICATION_REPORT set every run prints a row: problem, zones, cycles, seconds, L1 error;
// scripts/speed_error.py runs this study at full scale and writes the table.
//
// KRUG_CONVERGENCE_SCALE scales the resolutions (CI runs 0.25). What is asserted is convergence: the
// error falls with every refinement whose coarser run has at least 20 zones along the flow.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "test_solid_measures.hpp"
#include "verification_support.hpp"

using namespace krug;
using namespace krug::verification;

namespace {

// L1 norm of (density - exact) along each row (a ray of a polar mesh, or the strip's rows), in the
// coordinate of the problem, averaged over the rows.
double l1_error(const Simulation& simulation, const Body& body, const ExactProfile& exact, Coordinate coordinate) {
  const Mesh& mesh = simulation.mesh();
  const PatchShape shape = patch_shape(mesh, body);
  double sum = 0.0;
  for (int j = 0; j < shape.zones_j; ++j) {
    for (const ZoneSample& s : row_profile(simulation, body, j, coordinate)) {
      sum += std::abs(s.density - exact.mean(exact.density, s.low, s.high)) * s.width();
    }
  }
  return sum / shape.zones_j;
}

// Time-step control and viscosity model under study (scripts/speed_error.py --cfl, --growth,
// --viscosity); default: the scenario's.
void apply_study_controls(scenario::Scenario& scenario) {
  if (const char* model = std::getenv("KRUG_STUDY_VISCOSITY"); model != nullptr && *model != '\0') {
    const std::string m = model;
    ViscosityParams& v = scenario.setup.controls.viscosity;
    if (m == "edge") v.model = ViscosityModel::edge;
    else if (m == "tensor") v.model = ViscosityModel::tensor;
    else if (m == "scalar") v.model = ViscosityModel::scalar;
    else if (m == "auto") v.model = ViscosityModel::automatic;
    else FAIL("KRUG_STUDY_VISCOSITY: edge, tensor, scalar or auto, not " << m);
  }
  if (const char* cfl = std::getenv("KRUG_STUDY_CFL"); cfl != nullptr && *cfl != '\0') {
    scenario.setup.controls.cfl = scenario.setup.controls.cfl_fluid = std::stod(cfl);
  }
  if (const char* growth = std::getenv("KRUG_STUDY_GROWTH"); growth != nullptr && *growth != '\0') {
    scenario.setup.controls.time_step_growth = std::stod(growth);
  }
}

struct Problem {
  std::string name, file, exact;
  Coordinate coordinate;
  int along, across;  // the example's zones along the flow and across (rows or angular zones)
  std::vector<double> refinements;
};

void study(const Problem& p) {
  std::vector<double> errors;
  std::vector<int> alongs;
  for (const double refinement : p.refinements) {
    const int along = std::max(4, static_cast<int>(std::lround(p.along * refinement * convergence_scale())));
    const int across = p.coordinate == Coordinate::first_axis
                           ? p.across
                           : std::max(2, static_cast<int>(std::lround(p.across * refinement * convergence_scale())));
    // Through placeholders, so that a new count never meets the other old one.
    const std::vector<Substitution> substitutions{{zones(p.along, -1).from, "\"zones\": -1"},
                                                  {zones(p.across, -2).from, "\"zones\": -2"},
                                                  {"\"zones\": -1", zones(0, along).to},
                                                  {"\"zones\": -2", zones(0, across).to}};
    scenario::Scenario scenario = load_example(p.file, substitutions);
    apply_study_controls(scenario);
    const Run run = run_to_end(scenario);
    INFO(p.name << " at " << along << " x " << across << ": " << run.failure);
    REQUIRE(run.completed());
    const double error = l1_error(run.simulation, run.simulation.bodies().front(), read_exact(p.exact), p.coordinate);
    report("speed-error " + p.name, format_number("L1 density error, %.0f cycles", static_cast<double>(run.simulation.cycle())),
           "0", error, format_number("%.0f zones along, ", along) + format_number("%.4g s", run.seconds),
           run.simulation.mesh().zones.size(), run.seconds);
    errors.push_back(error);
    alongs.push_back(along);
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    if (alongs[k - 1] < 20) continue;
    INFO(p.name << ": " << alongs[k - 1] << " -> " << alongs[k] << " zones, L1 " << errors[k - 1] << " -> " << errors[k]);
    CHECK(errors[k] < errors[k - 1]);
  }
}

}  // namespace

TEST_CASE("Speed against error: Sod, Sedov and Noh at four resolutions", "[convergence][speed_error]") {
  const std::vector<Problem> problems{
      {"Sod (planar strip)", "sod.json", "sod_t0.25.csv", Coordinate::first_axis, 200, 4, {0.5, 1.0, 2.0, 4.0}},
      {"Sedov cylindrical (XY polar)", "sedov_cylindrical.json", "sedov_cylindrical_t1.csv", Coordinate::radius, 40, 20,
       {0.5, 1.0, 2.0, 3.0}},
      {"Sedov spherical (RZ polar)", "sedov_spherical.json", "sedov_spherical_t1.csv", Coordinate::radius, 60, 30,
       {0.5, 1.0, 1.5, 2.0}},
      {"Noh cylindrical (XY polar)", "noh_cylindrical.json", "noh_cylindrical_t0.6.csv", Coordinate::radius, 50, 20,
       {0.5, 1.0, 1.5, 2.0}},
      {"Noh spherical (RZ polar)", "noh_spherical.json", "noh_spherical_t0.6.csv", Coordinate::radius, 100, 40,
       {0.25, 0.5, 0.75, 1.0}}};
  for (const Problem& p : problems) study(p);
}

TEST_CASE("Speed against error: the Taylor bar's length and face radius at four resolutions", "[convergence][speed_error]") {
  // Uniform meshes of k = 4, 8, 16, 32 zones across the radius (7.5 k along the bar) in the full
  // study, 2, 4, 8, 16 in CI. Error: the relative distance of the length and of the impact-face
  // radius from the converged values of verification.md E6 (21.43 mm, 7.23 mm), reported as their
  // mean. Asserted: both fall with every refinement from k = 4 (at k = 2 the bar is two zones wide).
  const double reference_length = 21.43e-3, reference_radius = 7.23e-3;
  const int base = std::max(2, static_cast<int>(std::lround(4 * convergence_scale())));
  std::vector<solid::TaylorLevel> levels;
  for (const int factor : {1, 2, 4, 8}) {
    const solid::TaylorLevel level = solid::taylor_level(base * factor, apply_study_controls);
    const double length_error = std::abs(level.measures.length / reference_length - 1.0);
    const double radius_error = std::abs(level.measures.face_radius / reference_radius - 1.0);
    const long zones = static_cast<long>(level.axial) * level.radial;
    report("speed-error Taylor bar (RZ, elastic-plastic)",
           format_number("mean relative error of length and face radius, %.0f cycles", static_cast<double>(level.cycles)),
           "0", 0.5 * (length_error + radius_error),
           format_number("length %+.4f, ", level.measures.length / reference_length - 1.0) +
               format_number("radius %+.4f, ", level.measures.face_radius / reference_radius - 1.0) +
               format_number("%.4g s", level.seconds),
           zones, level.seconds);
    if (!levels.empty() && levels.back().radial >= 4) {
      const solid::TaylorLevel& coarser = levels.back();
      INFO("k = " << coarser.radial << " -> " << level.radial);
      CHECK(length_error < std::abs(coarser.measures.length / reference_length - 1.0));
      CHECK(radius_error < std::abs(coarser.measures.face_radius / reference_radius - 1.0));
    }
    levels.push_back(level);
  }
}
