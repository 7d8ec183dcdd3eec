#pragma once
// The history column registry: every column of the run's history (history.csv), once, with its name,
// whether it is repeated per body, the significant digits its value carries and the function that
// reads the value from the simulation. It knows no file format: the history writer
// (RunRecorder::history_header and write_history_row, src/output/outputs.cpp) walks it in this order, so a
// new history column is one entry here plus its row in docs/outputs.md (docs/architecture.md,
// "Adding an output field").
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "krug/core/geometry_kind.hpp"

namespace krug {

class Simulation;
struct Body;
struct BodySummary;

// What a column's value is read from: the simulation and, for a per-body column, the body and its
// summary (taken once per body and row).
struct HistorySample {
  const Simulation& simulation;
  const Body* body = nullptr;
  const BodySummary* summary = nullptr;
};

struct HistoryColumn {
  // The column's name; in a per-body column "{body}" stands for the body's name and "{a}", "{b}" for
  // the scenario's axis names (x, y or z, r).
  std::string_view name;
  bool per_body;  // one column per body, in the bodies' order; consecutive per-body entries repeat as a group
  int digits;     // significant digits of the value; 0: the value is a count (an integer)
  double (*value)(const HistorySample& sample);

  std::string name_in(GeometryKind geometry, std::string_view body_name) const;
};

// Every history column, in the file's order.
std::span<const HistoryColumn> history_columns();

// One cell of a row: its column's registry entry and its value.
struct HistoryCell {
  const HistoryColumn* column;
  double value;
};

// The columns' names for this simulation, in the file's order (per-body groups expanded per body).
std::vector<std::string> history_names(const Simulation& simulation);

// The columns' values now, in the same order as history_names.
std::vector<HistoryCell> history_cells(const Simulation& simulation);

}  // namespace krug
