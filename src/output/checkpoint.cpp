// Checkpoint files: a versioned binary image of SimulationState and of the run loop's progress.
#include "krug/output/checkpoint.hpp"

#include <cstring>
#include <fstream>
#include <sstream>
#include <type_traits>

#include <fmt/format.h>

#include "krug/core/error.hpp"
#include "krug/output/text_file.hpp"

namespace krug::output {

using run::PenetrationRecord;
using run::StopWindow;
using run::TimeStepRecord;

namespace {

constexpr char magic[8] = {'K', 'R', 'U', 'G', 'C', 'K', 'P', 'T'};
constexpr char end_magic[8] = {'K', 'R', 'U', 'G', 'E', 'N', 'D', '!'};
constexpr std::uint32_t byte_order_mark = 0x01020304;

// Every field of the state is written by name below. When a field is added to one of these
// structures, these sizes change and the build stops here: add the field to write_state() and
// read_state() (and raise checkpoint_version), or a restart would silently lose it.
// (NodeFields and ZoneFields are written through their registry, mesh.hpp, and the ZoneState's groups
// through theirs, zone_state.hpp.)
static_assert(sizeof(std::vector<double>) != 24 || sizeof(Particles) == 10 * 24,
              "Particles changed: update src/output/checkpoint.cpp");
static_assert(sizeof(EnergyLedger) == 10 * sizeof(double), "EnergyLedger changed: update src/output/checkpoint.cpp");
static_assert(sizeof(Ledger) == sizeof(EnergyLedger) + 7 * sizeof(double), "Ledger changed: update src/output/checkpoint.cpp");
static_assert(sizeof(FractureCounts) == 6 * 8, "FractureCounts changed: update src/output/checkpoint.cpp");
static_assert(sizeof(std::vector<double>) != 24 ||
                  sizeof(SimulationState) == sizeof(Mesh) + sizeof(ZoneState) + sizeof(Particles) + sizeof(Ledger) + 6 * 24 + 9 * 8,
              "SimulationState changed: update src/output/checkpoint.cpp");

class Writer {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class T>
  void vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    value(static_cast<std::uint64_t>(v.size()));
    if (!v.empty()) bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void text(const std::string& s) {
    value(static_cast<std::uint64_t>(s.size()));
    bytes_.append(s);
  }
  void raw(const char* data, std::size_t size) { bytes_.append(data, size); }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  Reader(const std::string& bytes, std::size_t end, std::string file) : bytes_(bytes), end_(end), file_(std::move(file)) {}

  template <class T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    return v;
  }
  template <class T>
  void vector(std::vector<T>& v) {
    const auto count = value<std::uint64_t>();
    if (count > (end_ - position_) / sizeof(T)) corrupt("a field longer than the file");
    v.resize(static_cast<std::size_t>(count));
    if (count > 0) std::memcpy(v.data(), bytes_.data() + position_, v.size() * sizeof(T));
    position_ += v.size() * sizeof(T);
  }
  std::string text() {
    const auto size = value<std::uint64_t>();
    if (size > end_ - position_) corrupt("a text longer than the file");
    std::string s = bytes_.substr(position_, static_cast<std::size_t>(size));
    position_ += s.size();
    return s;
  }
  void expect(const char* data, std::size_t size, const char* what) {
    need(size);
    if (std::memcmp(bytes_.data() + position_, data, size) != 0) corrupt(what);
    position_ += size;
  }
  std::size_t position() const { return position_; }
  [[noreturn]] void corrupt(const std::string& what) const {
    throw InputError(fmt::format("{}: not a usable Krug checkpoint: {}", file_, what));
  }

 private:
  void need(std::size_t size) const {
    if (size > end_ - position_) corrupt("the file ends early (truncated?)");
  }
  const std::string& bytes_;
  std::size_t position_ = 0;
  std::size_t end_;
  std::string file_;
};

// The same list of fields, in the same order, for writing and reading: `io` is a Writer or a
// Reader and `field` is applied to each vector, `scalar` to each value.
// The mesh's fields in the registry's order (mesh.hpp): `io` is a Writer or a Reader.
template <class Io, class MeshT>
void mesh_fields(Io& io, MeshT& mesh) {
  auto each = [&io](std::string_view, auto& field, std::size_t, auto) { io.vector(field); };
  for_each_node_field(mesh.nodes, each);
  for_each_zone_field(mesh.zones, each);
}

// The zone state's fields, group by group in the registries' order (zone_state.hpp).
template <class Io, class State>
void zone_state_fields(Io& io, State& state) {
  for_each_zone_state_field(state, [&io](std::string_view, auto& field, std::size_t, auto) { io.vector(field); });
}

template <class Io, class ParticlesT>
void particle_fields(Io& io, ParticlesT& p) {
  for_each_particle_field(p, [&](std::string_view, auto& field) { io.vector(field); });
}

struct TimedValue {
  double time, value;
};

std::vector<TimedValue> items_of(const std::deque<StopWindow::Sample>& queue) {
  std::vector<TimedValue> items;
  for (const auto& [time, value] : queue) items.push_back({time, value});
  return items;
}

}  // namespace

std::uint64_t fnv1a(const std::string& bytes, std::uint64_t hash) {
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

void write_checkpoint(const std::filesystem::path& file, const SimulationState& s, const RunProgress& progress,
                      std::uint64_t scenario_hash) {
  Writer w;
  w.raw(magic, sizeof magic);
  w.value(checkpoint_version);
  w.value(byte_order_mark);
  w.value(static_cast<std::uint32_t>(sizeof(double)));
  w.value(static_cast<std::uint32_t>(sizeof(Index)));
  w.value(scenario_hash);
  // State.
  mesh_fields(w, s.mesh);
  w.value(static_cast<std::uint8_t>(s.mesh.zones.neighbours_built));
  zone_state_fields(w, s.zone_state);
  particle_fields(w, s.particles);
  w.value(s.ledger);
  w.vector(s.fracture_counts);
  w.vector(s.body_plastic_work);
  w.vector(s.body_viscous_work);
  w.vector(s.body_hourglass_work);
  w.vector(s.body_converted_energy);
  w.vector(s.zones_per_node);
  w.value(s.time);
  w.value(static_cast<std::int64_t>(s.cycle));
  w.value(static_cast<std::int64_t>(s.zone_cycles));
  w.value(s.time_step_previous);
  w.value(s.time_step_next);
  w.value(s.time_step_floor);
  w.value(s.stable_time_step);
  w.value(s.controlling_zone);
  w.value(s.deepest_contact_gap);
  // Progress.
  w.value(progress.next_history_time);
  w.value(progress.next_snapshot_time);
  w.value(progress.next_checkpoint_time);
  for (const auto* list : {&progress.snapshots, &progress.particle_snapshots}) {
    w.value(static_cast<std::uint64_t>(list->size()));
    for (const auto& [time, name] : *list) {
      w.value(time);
      w.text(name);
    }
  }
  w.value(progress.history_bytes);
  w.value(progress.wall_seconds);
  w.value(static_cast<std::uint8_t>(progress.has_stop_state));
  const StopWindow& stop = progress.stop;
  w.value(static_cast<std::uint8_t>(stop.started));
  w.value(stop.initial_velocity);
  w.value(stop.scale);
  w.value(static_cast<std::uint8_t>(stop.armed));
  w.value(stop.armed_time);
  for (const auto* q : {&stop.max_x, &stop.min_x, &stop.max_y, &stop.min_y}) {
    w.vector(items_of(*q));
  }
  w.value(static_cast<std::uint8_t>(progress.has_penetration));
  w.value(progress.penetration);
  const TimeStepRecord& steps = progress.time_steps;
  w.vector(steps.zone_cycles);
  w.value(steps.growth_cycles);
  w.value(steps.particle_cycles);
  w.value(steps.other_cycles);
  w.value(steps.damping_cycles);
  w.value(steps.smallest);
  w.value(steps.smallest_time);
  w.value(steps.smallest_body);
  w.value(steps.smallest_zone);
  w.value(steps.smallest_limit);
  w.value(steps.last_counted);
  w.value(progress.contact.active_cycles);
  w.value(progress.contact.unconverged_cycles);
  w.value(progress.contact.solved_together_cycles);
  w.value(progress.contact.most_sweeps);
  w.value(progress.next_gauge_time);
  w.value(progress.gauge_bytes);
  w.vector(progress.gauge_impulses);
  w.value(fnv1a(w.bytes()));
  w.raw(end_magic, sizeof end_magic);
  write_text_atomically(file, w.bytes());
}

Checkpoint read_checkpoint(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the checkpoint", file.string()));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_checkpoint(buffer.str(), file.string());
}

Checkpoint parse_checkpoint(const std::string& bytes, const std::string& name) {
  constexpr std::size_t trailer = sizeof(std::uint64_t) + sizeof end_magic;
  if (bytes.size() < sizeof magic + trailer) Reader(bytes, bytes.size(), name).corrupt("the file is too short");
  const std::size_t body_end = bytes.size() - trailer;
  {
    Reader tail(bytes, bytes.size(), name);
    if (std::memcmp(bytes.data(), magic, sizeof magic) != 0) tail.corrupt("it does not start with KRUGCKPT");
    if (std::memcmp(bytes.data() + body_end + sizeof(std::uint64_t), end_magic, sizeof end_magic) != 0) {
      tail.corrupt("the end marker is missing (truncated?)");
    }
    std::uint64_t stored = 0;
    std::memcpy(&stored, bytes.data() + body_end, sizeof stored);
    if (stored != fnv1a(bytes.substr(0, body_end))) tail.corrupt("the checksum does not match (corrupted)");
  }
  Reader r(bytes, body_end, name);
  r.expect(magic, sizeof magic, "it does not start with KRUGCKPT");
  const auto version = r.value<std::uint32_t>();
  if (version != checkpoint_version) {
    r.corrupt(fmt::format("format version {}, this krug reads version {}", version, checkpoint_version));
  }
  if (r.value<std::uint32_t>() != byte_order_mark) r.corrupt("written on a machine of another byte order");
  if (r.value<std::uint32_t>() != sizeof(double) || r.value<std::uint32_t>() != sizeof(Index)) {
    r.corrupt("written with other number sizes");
  }
  Checkpoint c;
  c.scenario_hash = r.value<std::uint64_t>();
  SimulationState& s = c.state;
  mesh_fields(r, s.mesh);
  s.mesh.zones.neighbours_built = r.value<std::uint8_t>() != 0;
  zone_state_fields(r, s.zone_state);
  particle_fields(r, s.particles);
  s.ledger = r.value<Ledger>();
  r.vector(s.fracture_counts);
  r.vector(s.body_plastic_work);
  r.vector(s.body_viscous_work);
  r.vector(s.body_hourglass_work);
  r.vector(s.body_converted_energy);
  r.vector(s.zones_per_node);
  s.time = r.value<double>();
  s.cycle = static_cast<long>(r.value<std::int64_t>());
  s.zone_cycles = static_cast<long>(r.value<std::int64_t>());
  s.time_step_previous = r.value<double>();
  s.time_step_next = r.value<double>();
  s.time_step_floor = r.value<double>();
  s.stable_time_step = r.value<double>();
  s.controlling_zone = r.value<Index>();
  s.deepest_contact_gap = r.value<double>();
  RunProgress& p = c.progress;
  p.next_history_time = r.value<double>();
  p.next_snapshot_time = r.value<double>();
  p.next_checkpoint_time = r.value<double>();
  for (auto* list : {&p.snapshots, &p.particle_snapshots}) {
    const auto count = r.value<std::uint64_t>();
    if (count > body_end) r.corrupt("a snapshot list longer than the file");
    for (std::uint64_t i = 0; i < count; ++i) {
      const double time = r.value<double>();
      list->emplace_back(time, r.text());
    }
  }
  p.history_bytes = r.value<std::uint64_t>();
  p.wall_seconds = r.value<double>();
  p.has_stop_state = r.value<std::uint8_t>() != 0;
  StopWindow& stop = p.stop;
  stop.started = r.value<std::uint8_t>() != 0;
  stop.initial_velocity = r.value<Vec2>();
  stop.scale = r.value<double>();
  stop.armed = r.value<std::uint8_t>() != 0;
  stop.armed_time = r.value<double>();
  for (auto* q : {&stop.max_x, &stop.min_x, &stop.max_y, &stop.min_y}) {
    std::vector<TimedValue> items;
    r.vector(items);
    q->clear();
    for (const TimedValue& item : items) q->emplace_back(item.time, item.value);
  }
  p.has_penetration = r.value<std::uint8_t>() != 0;
  p.penetration = r.value<PenetrationRecord>();
  TimeStepRecord& steps = p.time_steps;
  r.vector(steps.zone_cycles);
  steps.growth_cycles = r.value<std::int64_t>();
  steps.particle_cycles = r.value<std::int64_t>();
  steps.other_cycles = r.value<std::int64_t>();
  steps.damping_cycles = r.value<std::int64_t>();
  steps.smallest = r.value<double>();
  steps.smallest_time = r.value<double>();
  steps.smallest_body = r.value<std::int32_t>();
  steps.smallest_zone = r.value<std::int32_t>();
  steps.smallest_limit = r.value<std::int32_t>();
  steps.last_counted = r.value<std::int32_t>();
  p.contact.active_cycles = r.value<std::int64_t>();
  p.contact.unconverged_cycles = r.value<std::int64_t>();
  p.contact.solved_together_cycles = r.value<std::int64_t>();
  p.contact.most_sweeps = r.value<std::int32_t>();
  p.next_gauge_time = r.value<double>();
  p.gauge_bytes = r.value<std::uint64_t>();
  r.vector(p.gauge_impulses);
  if (r.position() != body_end) r.corrupt("unexpected bytes after the last field");
  // Consistency of what was read (a checkpoint that passed its checksum but was written wrongly, or
  // resealed after an edit): every field of the registry has its entries per node or zone, every
  // particle field one entry per particle, and every index points inside its range.
  const auto nodes = s.mesh.nodes.x.size();
  const auto zones = s.mesh.zones.corners.size();
  for_each_node_field(s.mesh.nodes, [&](std::string_view field_name, const auto& field, std::size_t per, auto) {
    if (field.size() != nodes * per) r.corrupt(fmt::format("node field {} has {} entries for {} nodes", field_name, field.size(), nodes));
  });
  const auto zone_size = [&](std::string_view field_name, const auto& field, std::size_t per, auto) {
    if (field.size() != zones * per) r.corrupt(fmt::format("zone field {} has {} entries for {} zones", field_name, field.size(), zones));
  };
  for_each_zone_field(s.mesh.zones, zone_size);
  for_each_zone_state_field(s.zone_state, zone_size);
  if (!s.zones_per_node.empty() && s.zones_per_node.size() != nodes) {
    r.corrupt("the zone count per node has the wrong length");  // empty without fracture
  }
  const auto particles = s.particles.x.size();
  for_each_particle_field(s.particles, [&](std::string_view field_name, const auto& field) {
    if (field.size() != particles) r.corrupt(fmt::format("particle field {} has {} entries for {} particles", field_name, field.size(), particles));
  });
  const auto bodies = s.fracture_counts.size();
  auto in_range = [](Index i, std::size_t size) { return i >= 0 && static_cast<std::size_t>(i) < size; };
  for (const ZoneCorners& corners : s.mesh.zones.corners) {
    for (Index n : corners) {
      if (!in_range(n, nodes)) r.corrupt("a zone corner outside the node range");
    }
  }
  for (const auto* list : {&s.mesh.zones.edge_before, &s.mesh.zones.edge_after}) {
    for (const ZoneCorners& entry : *list) {
      for (Index n : entry) {
        if (n != -1 && !in_range(n, nodes)) r.corrupt("an edge continuation outside the node range");
      }
    }
  }
  for (const ZoneCorners& entry : s.mesh.zones.neighbour) {
    for (Index z : entry) {
      if (z != -1 && !in_range(z, zones)) r.corrupt("a zone neighbour outside the zone range");
    }
  }
  for (Index b : s.mesh.zones.body) {
    if (!in_range(b, bodies)) r.corrupt("a zone's body outside the body range");
  }
  for (Index b : s.mesh.nodes.body) {
    if (b != -1 && !in_range(b, bodies)) r.corrupt("a node's body outside the body range");
  }
  for (Index b : s.particles.body) {
    if (!in_range(b, bodies)) r.corrupt("a particle's body outside the body range");
  }
  return c;
}

}  // namespace krug::output
