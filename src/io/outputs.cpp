#include "krug/io/outputs.hpp"

#include <cmath>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "krug/core/error.hpp"

namespace krug::io {

using Json = nlohmann::ordered_json;  // keeps the contract's field order

void write_text_atomically(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path temporary = file.string() + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(fmt::format("{}: cannot write", temporary.string()));
    out << text;
    out.flush();
    if (!out) throw InputError(fmt::format("{}: write failed (disk full?)", temporary.string()));
  }
  std::filesystem::rename(temporary, file);
}

namespace {

Json pair(Vec2 v) { return Json::array({v.x, v.y}); }

// JSON has no NaN or infinity: such a value is written as null (and the run has failed anyway).
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace

std::string summary_json(const Simulation& simulation, const RunResult& result) {
  const double whole = simulation.whole_body_factor();
  const Ledger& ledger = simulation.ledger();
  const EnergyLedger& e = ledger.energy;
  const GeometryKind g = simulation.geometry();
  Json s;
  s["status"] = result.status == RunStatus::completed ? "completed" : "failed";
  s["message"] = result.message;
  s["geometry"] = g == GeometryKind::axisymmetric ? "axisymmetric" : "planar";
  s["axes"] = Json::array({std::string(axis_name(g, 0)), std::string(axis_name(g, 1))});
  s["units"] = "SI (m, kg, s, Pa, J); masses, momenta and energies for whole bodies";
  s["stopped_by"] = result.stopped_by;
  s["time"] = simulation.time();
  s["cycles"] = simulation.cycle();
  s["zone_cycles"] = simulation.zone_cycles();
  s["wall_seconds"] = result.wall_seconds;
  s["ledger"]["mass"] = {{"initial", whole * ledger.initial_mass},
                         {"final", whole * ledger.mass},
                         {"relative_error", number(ledger.relative_mass_error())}};
  s["ledger"]["axial_momentum"] = {{"initial", number(whole * ledger.initial_axial_momentum)},
                                   {"final", number(whole * ledger.axial_momentum)},
                                   {"boundary_impulse", number(whole * ledger.axial_boundary_impulse)}};
  s["ledger"]["energy"] = {{"kinetic", number(whole * e.kinetic)},
                           {"internal", number(whole * e.internal)},
                           {"plastic", number(whole * e.plastic)},
                           {"viscous", number(whole * e.viscous)},
                           {"hourglass", number(whole * e.hourglass)},
                           {"contact", number(whole * e.contact)},
                           {"contact_overlap", number(whole * e.overlap)},
                           {"converted", number(whole * e.converted)},
                           {"boundary", number(whole * e.boundary)},
                           {"total", number(whole * e.total())},
                           {"initial_total", number(whole * ledger.initial_total_energy)},
                           {"relative_drift", number(ledger.relative_energy_drift())}};
  Json bodies = Json::object();
  for (const Body& body : simulation.bodies()) {
    const BodySummary b = simulation.summarise(body);
    bodies[body.name] = {{"mass", b.mass},
                         {"velocity", pair(b.velocity)},
                         {"centroid", pair(b.centroid)},
                         {"bbox", {{"min", pair(b.bbox_min)}, {"max", pair(b.bbox_max)}}},
                         {"zones", b.zones}};
    if (simulation.fracture_enabled()) {
      const Index index = static_cast<Index>(&body - simulation.bodies().data());
      const FractureCounts& counts = simulation.fracture_counts(index);
      Json pieces = Json::array();
      for (const Fragment& f : simulation.fragments(body)) {
        pieces.push_back({{"mass", f.mass}, {"velocity", pair(f.velocity)}, {"centroid", pair(f.centroid)}, {"zones", f.zones}});
      }
      bodies[body.name]["fracture"] = {{"damaged_zones", counts.damaged},
                                       {"converted_zones", counts.converted},
                                       {"interior_conversions", counts.interior_conversions},
                                       {"converted_mass", whole * counts.converted_mass},
                                       {"eroded_zones", counts.eroded},
                                       {"eroded_mass", whole * counts.eroded_mass},
                                       {"fragments", pieces}};
    }
  }
  s["bodies"] = bodies;
  const Particles& particles = simulation.particles();
  double particle_mass = 0.0;
  Vec2 particle_momentum;
  for (Index i = 0; i < particles.size(); ++i) {
    particle_mass += particles.mass[i];
    particle_momentum += particles.mass[i] * particles.velocity(i);
  }
  s["particles"] = {{"count", particles.size()},
                    {"mass", whole * particle_mass},
                    {"momentum", pair(whole * particle_momentum)}};
  return s.dump(2) + "\n";
}

RunRecorder::RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory,
                         PictureHook picture_hook)
    : directory_(std::move(directory)), settings_(scenario.output), picture_(std::move(picture_hook)) {
  open(scenario);
  history_.open(directory_ / "history.csv", std::ios::trunc);
  if (!history_) throw InputError(fmt::format("{}: cannot write history.csv", directory_.string()));
  append_history(history_header(simulation));
  write_history_row(simulation);
  write_snapshot(simulation);
  if (!settings_.pictures.every_snapshot) picture(simulation, "initial");
  next_history_time_ = settings_.history_interval;
  next_snapshot_time_ = settings_.snapshot_interval > 0.0 ? settings_.snapshot_interval
                                                          : std::numeric_limits<double>::infinity();
}

RunRecorder::RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory,
                         PictureHook picture_hook, const RunProgress& resume,
                         const std::filesystem::path& previous_directory)
    : directory_(std::move(directory)), settings_(scenario.output), picture_(std::move(picture_hook)) {
  open(scenario);
  std::error_code error;
  const bool same = std::filesystem::equivalent(directory_, previous_directory, error);
  const std::filesystem::path history = directory_ / "history.csv";
  if (!same) {
    // A new directory: bring the history and the snapshots so far, so the outputs are whole.
    const std::filesystem::path old_history = previous_directory / "history.csv";
    std::ifstream in(old_history, std::ios::binary);
    std::string rows(static_cast<std::size_t>(resume.history_bytes), '\0');
    if (!in || !in.read(rows.data(), static_cast<std::streamsize>(rows.size()))) {
      rows = history_header(simulation);  // the earlier rows are lost; the columns stay the same
    }
    write_text_atomically(history, rows);
    history_bytes_ = rows.size();
    for (const auto* list : {&resume.snapshots, &resume.particle_snapshots}) {
      for (const auto& [time, name] : *list) {
        std::filesystem::copy_file(previous_directory / name, directory_ / name,
                                   std::filesystem::copy_options::overwrite_existing, error);
      }
    }
  } else if (std::filesystem::exists(history) && std::filesystem::file_size(history) >= resume.history_bytes) {
    std::filesystem::resize_file(history, resume.history_bytes);  // rows written after the checkpoint
    history_bytes_ = resume.history_bytes;
  } else {
    write_text_atomically(history, history_header(simulation));
    history_bytes_ = std::filesystem::file_size(history);
  }
  history_.open(history, std::ios::app);
  if (!history_) throw InputError(fmt::format("{}: cannot write history.csv", directory_.string()));
  snapshots_ = resume.snapshots;
  particle_snapshots_ = resume.particle_snapshots;
  next_history_time_ = resume.next_history_time;
  next_snapshot_time_ = resume.next_snapshot_time;
}

void RunRecorder::open(const Scenario& scenario) {
  std::error_code error;
  std::filesystem::create_directories(directory_ / "snapshots", error);
  if (error) throw InputError(fmt::format("{}: cannot create the output directory: {}", directory_.string(), error.message()));
  write_text_atomically(directory_ / "scenario.resolved.json", scenario.resolved_json + "\n");
}

RunProgress RunRecorder::progress() {
  history_.flush();
  RunProgress p;
  p.next_history_time = next_history_time_;
  p.next_snapshot_time = next_snapshot_time_;
  p.snapshots = snapshots_;
  p.particle_snapshots = particle_snapshots_;
  p.history_bytes = history_bytes_;
  return p;
}

std::string RunRecorder::history_header(const Simulation& simulation) {
  const GeometryKind g = simulation.geometry();
  const std::string a0(axis_name(g, 0)), a1(axis_name(g, 1));
  std::string header = "time,cycle,dt";
  for (const Body& body : simulation.bodies()) {
    header += fmt::format(",{0}_v{1},{0}_v{2},{0}_{1},{0}_{2}", body.name, a0, a1);
  }
  return header + ",kinetic,internal,plastic,viscous,hourglass,contact,contact_overlap,converted,boundary,total,relative_drift,"
                  "particles\n";
}

void RunRecorder::append_history(const std::string& text) {
  history_ << text;
  history_bytes_ += text.size();
}

void RunRecorder::picture(const Simulation& simulation, const std::string& name) {
  if (picture_ && settings_.pictures.enabled) picture_(simulation, directory_, name);
}

RunRecorder::~RunRecorder() = default;

void RunRecorder::write_history_row(const Simulation& simulation) {
  const double whole = simulation.whole_body_factor();
  const EnergyLedger& e = simulation.ledger().energy;
  std::string row = fmt::format("{:.9e},{},{:.6e}", simulation.time(), simulation.cycle(), simulation.last_time_step());
  for (const Body& body : simulation.bodies()) {
    const BodySummary b = simulation.summarise(body);
    row += fmt::format(",{:.9e},{:.9e},{:.9e},{:.9e}", b.velocity.x, b.velocity.y, b.centroid.x, b.centroid.y);
  }
  row += fmt::format(",{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.12e},{:.3e},{}\n",
                     whole * e.kinetic, whole * e.internal, whole * e.plastic, whole * e.viscous,
                     whole * e.hourglass, whole * e.contact, whole * e.overlap, whole * e.converted, whole * e.boundary,
                     whole * e.total(), simulation.ledger().relative_energy_drift(), simulation.particles().size());
  append_history(row);
}

void RunRecorder::write_snapshot(const Simulation& simulation) {
  const std::string name = fmt::format("snapshots/state_{:05d}.vtu", snapshots_.size());
  write_vtu(simulation, directory_ / name);
  if (settings_.pictures.every_snapshot) picture(simulation, fmt::format("state_{:05d}", snapshots_.size()));
  snapshots_.emplace_back(simulation.time(), name);
  if (simulation.fracture_enabled()) {
    const std::string particles = fmt::format("snapshots/particles_{:05d}.vtp", particle_snapshots_.size());
    write_vtp(simulation, directory_ / particles);
    particle_snapshots_.emplace_back(simulation.time(), particles);
  }
}

void RunRecorder::observe(const Simulation& simulation) {
  if (simulation.time() >= next_history_time_ * (1.0 - 1e-12)) {
    write_history_row(simulation);
    while (next_history_time_ <= simulation.time()) {
      next_history_time_ += settings_.history_interval > 0.0 ? settings_.history_interval : simulation.time();
      if (settings_.history_interval <= 0.0) break;
    }
  }
  if (simulation.time() >= next_snapshot_time_ * (1.0 - 1e-12) && !simulation.finished()) {
    write_snapshot(simulation);
    while (next_snapshot_time_ <= simulation.time() * (1.0 + 1e-12)) next_snapshot_time_ += settings_.snapshot_interval;
  }
}

void RunRecorder::finish(const Simulation& simulation, const RunResult& result) {
  if (snapshots_.empty() || snapshots_.back().first < simulation.time()) write_snapshot(simulation);
  write_history_row(simulation);
  history_.flush();
  write_vtu(simulation, directory_ / "final.vtu");
  if (simulation.fracture_enabled()) write_vtp(simulation, directory_ / "final_particles.vtp");
  std::string pvd = "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n";
  for (const auto& [time, file] : snapshots_) {
    pvd += fmt::format("    <DataSet timestep=\"{:.9e}\" part=\"0\" file=\"{}\"/>\n", time, file);
  }
  for (const auto& [time, file] : particle_snapshots_) {
    pvd += fmt::format("    <DataSet timestep=\"{:.9e}\" part=\"1\" file=\"{}\"/>\n", time, file);
  }
  pvd += "  </Collection>\n</VTKFile>\n";
  write_text_atomically(directory_ / "run.pvd", pvd);
  picture(simulation, "final");
  write_text_atomically(directory_ / "summary.json", summary_json(simulation, result));
}

}  // namespace krug::io
