#include "krug/solver/history_columns.hpp"

#include "krug/solver/simulation.hpp"

namespace krug {

namespace {

using S = const HistorySample&;

// A line of the energy ledger, whole body (x 2 pi in axisymmetric geometry).
double whole(S s, double EnergyLedger::*line) { return s.simulation.whole_body_factor() * s.simulation.ledger().energy.*line; }

const HistoryColumn columns[] = {
    // name, per body, significant digits (0: a count), value
    {"time", false, 10, [](S s) { return s.simulation.time(); }},
    {"cycle", false, 0, [](S s) { return static_cast<double>(s.simulation.cycle()); }},
    {"dt", false, 7, [](S s) { return s.simulation.last_time_step(); }},
    {"{body}_v{a}", true, 10, [](S s) { return s.summary->velocity.x; }},
    {"{body}_v{b}", true, 10, [](S s) { return s.summary->velocity.y; }},
    {"{body}_{a}", true, 10, [](S s) { return s.summary->centroid.x; }},
    {"{body}_{b}", true, 10, [](S s) { return s.summary->centroid.y; }},
    {"kinetic", false, 10, [](S s) { return whole(s, &EnergyLedger::kinetic); }},
    {"internal", false, 10, [](S s) { return whole(s, &EnergyLedger::internal); }},
    {"plastic", false, 10, [](S s) { return whole(s, &EnergyLedger::plastic); }},
    {"viscous", false, 10, [](S s) { return whole(s, &EnergyLedger::viscous); }},
    {"hourglass", false, 10, [](S s) { return whole(s, &EnergyLedger::hourglass); }},
    {"contact", false, 10, [](S s) { return whole(s, &EnergyLedger::contact); }},
    {"contact_overlap", false, 10, [](S s) { return whole(s, &EnergyLedger::overlap); }},
    {"converted", false, 10, [](S s) { return whole(s, &EnergyLedger::converted); }},
    {"boundary", false, 10, [](S s) { return whole(s, &EnergyLedger::boundary); }},
    {"total", false, 13, [](S s) { return s.simulation.whole_body_factor() * s.simulation.ledger().energy.total(); }},
    {"relative_drift", false, 4, [](S s) { return s.simulation.ledger().relative_energy_drift(); }},
    {"particles", false, 0, [](S s) { return static_cast<double>(s.simulation.particles().size()); }},
};

// Calls visit(column, body) for each column in the file's order: a run of consecutive per-body entries
// once per body (body null for the other columns).
template <class Visit>
void walk(const Simulation& simulation, Visit visit) {
  const std::span<const HistoryColumn> all = columns;
  for (std::size_t i = 0; i < all.size();) {
    if (!all[i].per_body) {
      visit(all[i], static_cast<const Body*>(nullptr));
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < all.size() && all[end].per_body) ++end;
    for (const Body& body : simulation.bodies()) {
      for (std::size_t k = i; k < end; ++k) visit(all[k], &body);
    }
    i = end;
  }
}

void replace_all(std::string& text, std::string_view key, std::string_view by) {
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + by.size())) {
    text.replace(at, key.size(), by);
  }
}

}  // namespace

std::string HistoryColumn::name_in(GeometryKind geometry, std::string_view body_name) const {
  std::string text(name);
  replace_all(text, "{body}", body_name);
  replace_all(text, "{a}", axis_name(geometry, 0));
  replace_all(text, "{b}", axis_name(geometry, 1));
  return text;
}

std::span<const HistoryColumn> history_columns() { return columns; }

std::vector<std::string> history_names(const Simulation& simulation) {
  std::vector<std::string> names;
  walk(simulation, [&](const HistoryColumn& column, const Body* body) {
    names.push_back(column.name_in(simulation.geometry(), body ? std::string_view(body->name) : std::string_view()));
  });
  return names;
}

std::vector<HistoryCell> history_cells(const Simulation& simulation) {
  std::vector<HistoryCell> cells;
  const Body* summarised = nullptr;
  BodySummary summary;
  walk(simulation, [&](const HistoryColumn& column, const Body* body) {
    if (body && body != summarised) {
      summary = simulation.summarise(*body);
      summarised = body;
    }
    cells.push_back({&column, column.value(HistorySample{simulation, body, body ? &summary : nullptr})});
  });
  return cells;
}

}  // namespace krug
