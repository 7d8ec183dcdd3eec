// The files of a parameter sweep: each variant's scenario, and the table of their results.
#include "krug/output/sweep_files.hpp"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "krug/core/error.hpp"
#include "krug/output/text_file.hpp"

namespace krug::output {

namespace {

using Json = nlohmann::json;

std::string csv_number(const Json& value) {
  if (value.is_number_integer()) return value.dump();
  if (value.is_number()) return fmt::format("{:.9g}", value.get<double>());
  if (value.is_null()) return "";
  return csv_field(value.is_string() ? value.get<std::string>() : value.dump());
}

}  // namespace

std::vector<scenario::SweepVariant> prepare_sweep(const std::filesystem::path& scenario_file,
                                                  const std::vector<scenario::SweepParameter>& parameters,
                                                  const std::filesystem::path& directory) {
  scenario::SweepPlan plan = scenario::plan_sweep(scenario_file, parameters, directory);
  for (std::size_t v = 0; v < plan.variants.size(); ++v) {
    std::error_code error;
    std::filesystem::create_directories(plan.variants[v].directory, error);
    if (error) throw InputError(fmt::format("{}: cannot create: {}", plan.variants[v].directory.string(), error.message()));
    write_text_atomically(plan.variants[v].scenario, plan.texts[v]);
  }
  return std::move(plan.variants);
}

void write_sweep_table(const std::filesystem::path& directory, const std::vector<scenario::SweepParameter>& parameters,
                       const std::vector<scenario::SweepVariant>& variants) {
  std::vector<Json> summaries;
  bool penetration = false;
  std::vector<std::string> bodies;  // in order of first appearance
  std::vector<std::string> axes = {"x", "y"};
  for (const scenario::SweepVariant& variant : variants) {
    Json summary;
    std::ifstream in(variant.directory / "summary.json");
    if (in) {
      try {
        in >> summary;
      } catch (const nlohmann::json::exception&) {
        summary = Json();
      }
    }
    if (summary.is_object()) {
      if (summary.contains("axes") && summary["axes"].is_array() && summary["axes"].size() == 2) {
        axes = {summary["axes"][0].get<std::string>(), summary["axes"][1].get<std::string>()};
      }
      if (summary.contains("bodies") && summary["bodies"].is_object()) {
        for (const auto& [name, _] : summary["bodies"].items()) {
          if (std::find(bodies.begin(), bodies.end(), name) == bodies.end()) bodies.push_back(name);
        }
      }
    }
    summaries.push_back(summary);
    penetration = penetration || (summary.is_object() && summary.contains("penetration"));
  }
  // Penetration columns: the summaries' "penetration" block (docs/outputs.md), when any variant has one.
  const std::vector<std::vector<const char*>> penetration_columns = {
      {"perforated"}, {"perforation_time"}, {"residual_velocity"}, {"residual_mass"}, {"mass_lost"},
      {"eroded_mass"}, {"plug", "mass"}, {"plug", "velocity"}, {"target_energy_absorbed"}, {"final"},
      {"piece_velocity_loss"}, {"whole", "velocity"}, {"whole", "velocity_loss"}, {"whole", "free_element_mass"},
      {"whole", "backward_mass"}};
  std::vector<std::string> header = {"variant"};
  auto column_name = [](const std::vector<const char*>& path) {
    std::string name = "penetration";
    for (const char* key : path) name += std::string("_") + key;
    return name;
  };
  for (const scenario::SweepParameter& p : parameters) header.push_back(p.path);
  for (const char* column : {"status", "stopped_by", "time", "cycles", "wall_seconds", "energy_drift", "mass_error",
                             "particles"}) {
    header.emplace_back(column);
  }
  for (const std::string& b : bodies) {
    for (const std::string& column : {"v" + axes[0], "v" + axes[1], std::string("mass"), std::string("zones")}) {
      header.push_back(fmt::format("{}_{}", b, column));
    }
  }
  if (penetration) {
    for (const auto& path : penetration_columns) header.push_back(column_name(path));
  }
  header.emplace_back("message");
  std::string table;
  auto add_row = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (c > 0) table.push_back(',');
      table.append(cells[c]);
    }
    table.push_back('\n');
  };
  std::vector<std::string> header_cells;
  for (const std::string& h : header) header_cells.push_back(csv_field(h));
  add_row(header_cells);
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const Json& s = summaries[v];
    std::vector<std::string> cells = {csv_field(variants[v].name)};
    for (const std::string& value : variants[v].values) {
      const Json parsed = Json::parse(value);
      cells.push_back(parsed.is_string() ? csv_field(parsed.get<std::string>()) : csv_field(value));
    }
    auto get = [&](std::initializer_list<const char*> path) -> Json {
      const Json* at = &s;
      for (const char* key : path) {
        if (!at->is_object() || !at->contains(key)) return Json();
        at = &(*at)[key];
      }
      return *at;
    };
    cells.push_back(s.is_object() ? csv_number(get({"status"})) : std::string("not run"));
    cells.push_back(csv_number(get({"stopped_by"})));
    cells.push_back(csv_number(get({"time"})));
    cells.push_back(csv_number(get({"cycles"})));
    cells.push_back(csv_number(get({"wall_seconds"})));
    cells.push_back(csv_number(get({"ledger", "energy", "relative_drift"})));
    cells.push_back(csv_number(get({"ledger", "mass", "relative_error"})));
    cells.push_back(csv_number(get({"particles", "count"})));
    for (const std::string& b : bodies) {
      const Json body = get({"bodies", b.c_str()});
      const Json velocity = body.is_object() && body.contains("velocity") ? body["velocity"] : Json::array({nullptr, nullptr});
      cells.push_back(csv_number(velocity[0]));
      cells.push_back(csv_number(velocity[1]));
      cells.push_back(csv_number(body.is_object() && body.contains("mass") ? body["mass"] : Json()));
      cells.push_back(csv_number(body.is_object() && body.contains("zones") ? body["zones"] : Json()));
    }
    if (penetration) {
      for (const auto& path : penetration_columns) {
        const Json* at = s.is_object() && s.contains("penetration") ? &s["penetration"] : nullptr;
        for (const char* key : path) at = at && at->is_object() && at->contains(key) ? &(*at)[key] : nullptr;
        cells.push_back(at ? csv_number(*at) : std::string());
      }
    }
    cells.push_back(csv_number(get({"message"})));
    add_row(cells);
  }
  write_text_atomically(directory / "sweep.csv", table);
}

}  // namespace krug::output
