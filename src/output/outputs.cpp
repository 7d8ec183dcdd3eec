#include "krug/output/outputs.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "krug/core/error.hpp"
#include "krug/output/checkpoint.hpp"
#include "krug/solver/history_columns.hpp"

namespace krug::output {

using run::PenetrationReport;

using Json = nlohmann::ordered_json;  // keeps the contract's field order

namespace {

Json pair(Vec2 v) { return Json::array({v.x, v.y}); }

// JSON has no NaN or infinity: such a value is written as null (and the run has failed anyway).
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

const char* time_step_limit_name(std::int32_t limit) {
  switch (static_cast<TimeStepLimit>(limit)) {
    case TimeStepLimit::zone: return "zone";
    case TimeStepLimit::growth: return "growth_limit";
    case TimeStepLimit::particle_travel: return "particle_travel";
    case TimeStepLimit::maximum: return "max_time_step";
    case TimeStepLimit::end_time: return "end_time";
  }
  return "zone";
}

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
  s["warnings"] = result.warnings;
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
                           {"rezone", number(whole * e.rezone)},
                           {"contact", number(whole * e.contact)},
                           {"contact_overlap", number(whole * e.overlap)},
                           {"converted", number(whole * e.converted)},
                           {"boundary", number(whole * e.boundary)},
                           {"total", number(whole * e.total())},
                           {"initial_total", number(whole * ledger.initial_total_energy)},
                           {"relative_drift", number(ledger.relative_energy_drift())},
                           {"drift_limit", energy_drift_limit},
                           {"closed", ledger.energy_closed()}};
  Json bodies = Json::object();
  for (const Body& body : simulation.bodies()) {
    const BodySummary b = simulation.summarise(body);
    // Momentum and kinetic energy of the whole body from its nodes (per m of thickness in planar
    // geometry); in axisymmetric geometry only the axial momentum exists (a ring's radial momentum is 0).
    const NodeFields& nodes = simulation.mesh().nodes;
    double kinetic = 0.0;
    Vec2 momentum;
    for (Index n = body.node_begin; n < body.node_end; ++n) {
      kinetic += 0.5 * nodes.mass[n] * dot(nodes.velocity(n), nodes.velocity(n));
      momentum += nodes.mass[n] * nodes.velocity(n);
    }
    const bool axisymmetric = simulation.geometry() == GeometryKind::axisymmetric;
    bodies[body.name] = {{"mass", b.mass},
                         {"momentum", {number(whole * momentum.x), axisymmetric ? Json() : Json(number(whole * momentum.y))}},
                         {"kinetic_energy", number(whole * kinetic)},
                         {"velocity", pair(b.velocity)},
                         {"centroid", pair(b.centroid)},
                         {"bbox", {{"min", pair(b.bbox_min)}, {"max", pair(b.bbox_max)}}},
                         {"zones", b.zones}};
    const Index index = static_cast<Index>(&body - simulation.bodies().data());
    bodies[body.name]["energy"] = {{"internal", number(whole * simulation.internal_energy(index))},
                                   {"converted", number(whole * simulation.converted_energy(index))},
                                   {"plastic", number(whole * simulation.plastic_work(index))},
                                   {"viscous", number(whole * simulation.viscous_work(index))},
                                   {"hourglass", number(whole * simulation.hourglass_work(index))}};
    if (simulation.fracture_enabled()) {
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
  const TimeStepRecord& steps = result.time_steps;
  Json set_by = Json::object();
  for (std::size_t b = 0; b < steps.zone_cycles.size() && b < simulation.bodies().size(); ++b) {
    set_by[simulation.bodies()[b].name] = steps.zone_cycles[b];
  }
  set_by["growth_limit"] = steps.growth_cycles;
  set_by["particle_travel"] = steps.particle_cycles;
  set_by["viscous_damping"] = steps.damping_cycles;
  set_by["other"] = steps.other_cycles;
  Json smallest = {{"dt", steps.smallest}, {"time", steps.smallest_time}, {"set_by", time_step_limit_name(steps.smallest_limit)}};
  if (steps.smallest_body >= 0) {
    smallest["body"] = simulation.bodies()[static_cast<std::size_t>(steps.smallest_body)].name;
    smallest["zone"] = steps.smallest_zone;
  }
  s["time_step"] = {{"cycles_set_by", set_by}, {"smallest", smallest}};
  if (simulation.has_contact()) {
    const run::ContactRecord& c = result.contact;
    s["contact"] = {{"active_cycles", c.active_cycles},
                    {"unconverged_cycles", c.unconverged_cycles},
                    {"solved_together_cycles", c.solved_together_cycles},
                    {"most_sweeps", c.most_sweeps}};
  }
  if (result.penetration) {
    const PenetrationReport& p = *result.penetration;
    s["penetration"] = {{"projectile", p.projectile},
                        {"final", p.final},
                        {"perforated", p.perforated},
                        {"perforation_time", p.perforated ? Json(p.perforation_time) : Json(nullptr)},
                        {"depth", p.depth},
                        {"residual_velocity", p.residual_velocity},
                        {"residual_velocity_vector", pair(p.residual_velocity_vector)},
                        {"residual_mass", p.residual_mass},
                        {"initial_mass", p.initial_mass},
                        {"mass_lost", p.mass_lost},
                        {"eroded_mass", p.eroded_mass},
                        {"residual_kinetic_energy", p.projectile_kinetic_energy},
                        {"initial_speed", p.initial_speed},
                        {"piece_velocity_loss", p.piece_velocity_loss},
                        {"whole", {{"mass", p.whole_mass},
                                   {"velocity", p.whole_velocity},
                                   {"velocity_loss", p.whole_velocity_loss},
                                   {"free_element_mass", p.free_element_mass},
                                   {"free_element_velocity", p.free_element_velocity},
                                   {"backward_mass", p.backward_mass},
                                   {"backward_velocity", p.backward_velocity}}},
                        {"plug", p.plug_body.empty() ? Json(nullptr)
                                                     : Json{{"body", p.plug_body}, {"mass", p.plug_mass}, {"velocity", p.plug_velocity}}},
                        {"target_plastic_work", p.target_plastic_work},
                        {"target_kinetic_energy", p.target_kinetic_energy},
                        {"target_energy_absorbed", p.target_energy_absorbed}};
  }
  return s.dump(2) + "\n";
}

std::vector<std::string> penetration_lines(const RunResult& result) {
  std::vector<std::string> lines;
  if (!result.penetration) return lines;
  const PenetrationReport& p = *result.penetration;
  if (p.perforated) {
    lines.push_back(fmt::format("{} perforated at {:.2f} us: residual velocity {:.1f} m/s, residual mass {:.4g} g "
                                "({:.1f} % lost, {:.1f} % eroded)",
                                p.projectile, 1e6 * p.perforation_time, p.residual_velocity, 1e3 * p.residual_mass,
                                100.0 * p.mass_lost / p.initial_mass, 100.0 * p.eroded_mass / p.initial_mass));
  } else {
    lines.push_back(fmt::format("{} did not perforate: depth {:.3f} mm, velocity {:.1f} m/s, mass {:.4g} g", p.projectile,
                                1e3 * p.depth, p.residual_velocity, 1e3 * p.residual_mass));
  }
  if (p.initial_speed > 0.0) {
    lines.push_back(fmt::format("velocity loss dU/U0 {:.3f} of the largest piece, {:.3f} of the whole projectile "
                                "({:.1f} m/s over {:.4g} g; free elements {:.4g} g at {:.1f} m/s; {:.4g} g moving backwards)",
                                p.piece_velocity_loss, p.whole_velocity_loss, p.whole_velocity, 1e3 * p.whole_mass,
                                1e3 * p.free_element_mass, p.free_element_velocity, 1e3 * p.backward_mass));
  }
  lines.push_back(p.plug_body.empty() ? std::string("no plug")
                                      : fmt::format("plug from {}: {:.4g} g at {:.1f} m/s", p.plug_body, 1e3 * p.plug_mass,
                                                    p.plug_velocity));
  lines.push_back(fmt::format("energy absorbed by the targets {:.4g} J (plastic work {:.4g} J, kinetic {:.4g} J)",
                              p.target_energy_absorbed, p.target_plastic_work, p.target_kinetic_energy));
  if (!p.final) lines.push_back("not final: the run ended before the projectile cleared its targets or stopped");
  return lines;
}

LineFile::~LineFile() {
  try {
    flush();
  } catch (const InputError&) {
    // a destructor may not throw; the lines already written stay whole
  }
  if (descriptor_ >= 0) ::close(descriptor_);
}

void LineFile::open(const std::filesystem::path& file, bool append) {
  if (descriptor_ >= 0) ::close(descriptor_);
  file_ = file;
  pending_.clear();
  descriptor_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (append ? O_APPEND : O_TRUNC), 0644);
  if (descriptor_ < 0) throw InputError(fmt::format("{}: cannot write: {}", file.string(), std::strerror(errno)));
}

void LineFile::append(std::string_view lines) {
  pending_.append(lines);
  const auto now = std::chrono::steady_clock::now();
  if (pending_.size() >= (64u << 10) || now - last_write_ >= std::chrono::seconds(1)) flush();
}

void LineFile::flush() {
  std::size_t done = 0;
  while (descriptor_ >= 0 && done < pending_.size()) {
    const ssize_t written = ::write(descriptor_, pending_.data() + done, pending_.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) throw InputError(fmt::format("{}: cannot write: {}", file_.string(), std::strerror(errno)));
    done += static_cast<std::size_t>(written);
  }
  pending_.clear();
  last_write_ = std::chrono::steady_clock::now();
}

RunRecorder::RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory,
                         PictureHook picture_hook)
    : directory_(std::move(directory)),
      settings_(scenario.output),
      scenario_hash_(fnv1a(scenario.resolved_json)),
      picture_(std::move(picture_hook)) {
  open(scenario, true);
  history_.open(directory_ / "history.csv", false);
  append_history(history_header(simulation));
  write_history_row(simulation);
  write_snapshot(simulation);
  if (!settings_.pictures.every_snapshot) picture(simulation, "initial");
  next_history_time_ = settings_.history_interval;
  next_snapshot_time_ = settings_.snapshot_interval > 0.0 ? settings_.snapshot_interval
                                                          : std::numeric_limits<double>::infinity();
  if (!scenario.gauges.empty()) {
    gauges_.emplace(scenario.gauges, simulation);
    gauge_interval_ = scenario.gauges.interval;
    gauge_file_.open(directory_ / "gauges.csv", false);
    const std::string header = gauge_header();
    gauge_file_.append(header);
    gauge_bytes_ = header.size();
    write_gauge_row(simulation);
    next_gauge_time_ = gauge_interval_;
  }
}

RunRecorder::RunRecorder(const Scenario& scenario, const Simulation& simulation, std::filesystem::path directory,
                         PictureHook picture_hook, const RunProgress& resume,
                         const std::filesystem::path& previous_directory)
    : directory_(std::move(directory)),
      settings_(scenario.output),
      scenario_hash_(fnv1a(scenario.resolved_json)),
      picture_(std::move(picture_hook)) {
  open(scenario, false);
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
  history_.open(history, true);
  snapshots_ = resume.snapshots;
  particle_snapshots_ = resume.particle_snapshots;
  time_steps_ = resume.time_steps;
  contact_ = resume.contact;
  next_history_time_ = resume.next_history_time;
  next_snapshot_time_ = resume.next_snapshot_time;
  if (!scenario.gauges.empty()) {
    // As history.csv: cut back to (or copied up to) its length at the checkpoint; the impulses go on.
    gauges_.emplace(scenario.gauges, simulation);
    gauge_interval_ = scenario.gauges.interval;
    const std::filesystem::path file = directory_ / "gauges.csv";
    const std::string header = gauge_header();
    const bool carried = resume.gauge_bytes >= header.size();  // the checkpoint's run wrote gauges
    if (carried) gauges_->restore_impulses(resume.gauge_impulses);
    if (carried && !same) {
      std::ifstream in(previous_directory / "gauges.csv", std::ios::binary);
      std::string rows(static_cast<std::size_t>(resume.gauge_bytes), '\0');
      if (!in || !in.read(rows.data(), static_cast<std::streamsize>(rows.size()))) rows = header;
      write_text_atomically(file, rows);
    } else if (carried && std::filesystem::exists(file) && std::filesystem::file_size(file) >= resume.gauge_bytes) {
      std::filesystem::resize_file(file, resume.gauge_bytes);  // rows written after the checkpoint
    } else {
      write_text_atomically(file, header);  // a checkpoint taken without gauges: they start here
    }
    gauge_bytes_ = std::filesystem::file_size(file);
    gauge_file_.open(file, true);
    next_gauge_time_ = carried ? resume.next_gauge_time : simulation.time();
  }
}

void RunRecorder::open(const Scenario& scenario, bool fresh) {
  std::error_code error;
  std::filesystem::create_directories(directory_ / "snapshots", error);
  if (error) throw InputError(fmt::format("{}: cannot create the output directory: {}", directory_.string(), error.message()));
  const std::filesystem::path lock = directory_ / ".krug-lock";
  lock_descriptor_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_descriptor_ < 0) {
    throw InputError(fmt::format("{}: cannot write in the output directory: {}", directory_.string(), std::strerror(errno)));
  }
  if (::flock(lock_descriptor_, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock_descriptor_);
    lock_descriptor_ = -1;
    throw InputError(fmt::format("{}: another krug run is writing its outputs here; give this run another --out",
                                 directory_.string()));
  }
  if (fresh) {
    // What an earlier run into this directory wrote, by name; other files are left alone.
    auto remove_matching = [&](const std::filesystem::path& folder, const std::vector<std::string>& prefixes,
                               const std::vector<std::string>& extensions) {
      for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
        const std::string name = entry.path().filename().string();
        const bool prefix = std::any_of(prefixes.begin(), prefixes.end(), [&](const std::string& p) { return name.rfind(p, 0) == 0; });
        const bool extension = std::find(extensions.begin(), extensions.end(), entry.path().extension().string()) != extensions.end();
        if (entry.is_regular_file() && prefix && extension) std::filesystem::remove(entry.path(), error);
      }
    };
    remove_matching(directory_ / "snapshots", {"state_", "particles_"}, {".vtu", ".vtp"});
    remove_matching(directory_ / "pictures", {""}, {".png"});
    remove_matching(directory_ / "plots", {""}, {".png"});
    for (const char* name : {"summary.json", "final.vtu", "final_particles.vtp", "run.pvd", "checkpoint.bin", "gauges.csv"}) {
      std::filesystem::remove(directory_ / name, error);
    }
  }
  write_text_atomically(directory_ / "scenario.resolved.json", scenario.resolved_json + "\n");
}

void RunRecorder::add_progress(RunProgress& p) {
  history_.flush();
  p.next_history_time = next_history_time_;
  p.next_snapshot_time = next_snapshot_time_;
  p.snapshots = snapshots_;
  p.particle_snapshots = particle_snapshots_;
  p.history_bytes = history_bytes_;
  p.time_steps = time_steps_;
  p.contact = contact_;
  if (gauges_) {
    gauge_file_.flush();
    p.next_gauge_time = next_gauge_time_;
    p.gauge_bytes = gauge_bytes_;
    p.gauge_impulses = gauges_->impulses();
  }
}

std::filesystem::path RunRecorder::checkpoint(const Simulation& simulation, RunProgress& progress) {
  add_progress(progress);
  std::filesystem::path file = directory_ / "checkpoint.bin";
  write_checkpoint(file, simulation.state(), progress, scenario_hash_);
  return file;
}

std::string RunRecorder::gauge_header() const {
  std::string header = "time,cycle";
  for (const std::string& column : gauges_->columns()) header += "," + column;
  return header + "\n";
}

void RunRecorder::write_gauge_row(const Simulation& simulation) {
  gauges_->sample(simulation, gauge_values_);
  std::string row = fmt::format("{:.12e},{}", simulation.time(), simulation.cycle());
  for (const double v : gauge_values_) row += fmt::format(",{:.12e}", v);
  row += '\n';
  gauge_file_.append(row);
  gauge_bytes_ += row.size();
}

std::string RunRecorder::history_header(const Simulation& simulation) {
  std::string header;
  for (const std::string& name : history_names(simulation)) header += (header.empty() ? "" : ",") + name;
  return header + "\n";
}

void RunRecorder::append_history(const std::string& text) {
  history_.append(text);
  history_bytes_ += text.size();
}

void RunRecorder::picture(const Simulation& simulation, const std::string& name) {
  if (picture_ && settings_.pictures.enabled) picture_(simulation, directory_, name);
}

RunRecorder::~RunRecorder() {
  if (lock_descriptor_ >= 0) ::close(lock_descriptor_);  // releases the directory's lock
}

void RunRecorder::write_history_row(const Simulation& simulation) {
  // A count as an integer, any other value in scientific notation with the column's significant digits.
  std::string row;
  for (const HistoryCell& cell : history_cells(simulation)) {
    if (!row.empty()) row += ',';
    if (cell.column->digits == 0) {
      row += fmt::format("{}", static_cast<long long>(cell.value));
    } else {
      row += fmt::format("{:.{}e}", cell.value, cell.column->digits - 1);
    }
  }
  row += '\n';
  append_history(row);
}

void RunRecorder::write_snapshot(const Simulation& simulation) {
  const std::string name = fmt::format("snapshots/state_{:05d}.vtu", snapshots_.size());
  write_vtu(simulation, directory_ / name, settings_.vtk_format);
  if (settings_.pictures.every_snapshot) picture(simulation, fmt::format("state_{:05d}", snapshots_.size()));
  snapshots_.emplace_back(simulation.time(), name);
  if (simulation.fracture_enabled()) {
    const std::string particles = fmt::format("snapshots/particles_{:05d}.vtp", particle_snapshots_.size());
    write_vtp(simulation, directory_ / particles, settings_.vtk_format);
    particle_snapshots_.emplace_back(simulation.time(), particles);
  }
}

void RunRecorder::count_time_step(const Simulation& simulation) {
  TimeStepRecord& r = time_steps_;
  if (r.zone_cycles.size() != simulation.bodies().size()) r.zone_cycles.assign(simulation.bodies().size(), 0);
  const TimeStepLimit limit = simulation.time_step_limit();
  const Index body = limit == TimeStepLimit::zone ? simulation.body_of_zone(simulation.controlling_zone()) : -1;
  // Each cycle counts what chose the next step. The step just taken, if the damping bound cut it after
  // its forces, was set by the damping instead of the choice the last cycle counted for it.
  const auto counter = [&r](std::int32_t counted) -> std::int64_t* {
    if (counted >= 0) return &r.zone_cycles[static_cast<std::size_t>(counted)];
    if (counted == -2) return &r.growth_cycles;
    if (counted == -3) return &r.particle_cycles;
    if (counted == -4) return &r.other_cycles;
    return nullptr;
  };
  if (simulation.step_cut_by_damping()) {
    if (std::int64_t* chosen = counter(r.last_counted)) --*chosen;
    ++r.damping_cycles;
  }
  switch (limit) {
    case TimeStepLimit::zone: r.last_counted = body >= 0 ? static_cast<std::int32_t>(body) : -4; break;
    case TimeStepLimit::growth: r.last_counted = -2; break;
    case TimeStepLimit::particle_travel: r.last_counted = -3; break;
    default: r.last_counted = -4; break;
  }
  ++*counter(r.last_counted);
  const double dt = simulation.next_time_step();
  if (limit != TimeStepLimit::end_time && !simulation.finished() && (r.smallest == 0.0 || dt < r.smallest)) {
    r.smallest = dt;
    r.smallest_time = simulation.time();
    r.smallest_limit = static_cast<std::int32_t>(limit);
    r.smallest_body = body;
    r.smallest_zone = body >= 0 ? simulation.controlling_zone() - simulation.bodies()[static_cast<std::size_t>(body)].zone_begin : -1;
  }
}

void RunRecorder::cycle(const Simulation& simulation) {
  count_time_step(simulation);
  const contact::ContactStatistics& solve = simulation.last_contact();
  if (solve.active > 0) ++contact_.active_cycles;
  if (!solve.converged) ++contact_.unconverged_cycles;
  if (solve.together > 0) ++contact_.solved_together_cycles;
  contact_.most_sweeps = std::max(contact_.most_sweeps, static_cast<std::int32_t>(solve.sweeps));
  if (gauges_) {
    if (gauges_->needs_every_step()) gauges_->accumulate(simulation);
    if (simulation.time() >= next_gauge_time_ * (1.0 - 1e-12) && !simulation.finished()) {
      write_gauge_row(simulation);
      // The next multiple of the interval after this time (by multiplication: an interval far below the
      // time step must not take a loop of additions, nor one that 1e-300 leaves where it was).
      const double t = simulation.time() * (1.0 + 1e-12);
      next_gauge_time_ = std::max(gauge_interval_ * (std::floor(t / gauge_interval_) + 1.0),
                                  std::nextafter(t, std::numeric_limits<double>::infinity()));
    }
  }
  if (simulation.time() >= next_history_time_ * (1.0 - 1e-12)) {
    write_history_row(simulation);
    if (settings_.history_interval > 0.0) {
      while (next_history_time_ <= simulation.time()) next_history_time_ += settings_.history_interval;
    } else {
      next_history_time_ = simulation.time();  // 0: a row every cycle
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
  if (gauges_) {
    write_gauge_row(simulation);  // the last state, whatever the interval
    gauge_file_.flush();
  }
  write_vtu(simulation, directory_ / "final.vtu", settings_.vtk_format);
  if (simulation.fracture_enabled()) write_vtp(simulation, directory_ / "final_particles.vtp", settings_.vtk_format);
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
  RunResult full = result;
  full.time_steps = time_steps_;
  full.contact = contact_;
  write_text_atomically(directory_ / "summary.json", summary_json(simulation, full));
}

}  // namespace krug::output
