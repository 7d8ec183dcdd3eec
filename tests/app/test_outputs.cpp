// Output files are written atomically (docs/outputs.md): each goes to NAME.partial and is renamed
// over NAME once complete, so a reader (ParaView, a script polling a long run) sees the old file or
// the new one, never half of one; a write that cannot be made leaves the old file as it was.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "krug/core/error.hpp"
#include "krug/output/outputs.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/output/run_files.hpp"
#include "krug/solver/history_columns.hpp"
#include "krug/solver/output_fields.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

// Every file left below `dir` whose name ends in ".partial".
std::size_t partial_files(const fs::path& dir) {
  std::size_t count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 8 && name.compare(name.size() - 8, 8, ".partial") == 0) ++count;
  }
  return count;
}

}  // namespace

TEST_CASE("a file is replaced whole or not at all", "[app][outputs]") {
  const fs::path dir = krug::test::scratch("atomic");
  const fs::path file = dir / "summary.json";
  krug::output::write_text_atomically(file, "old\n");
  krug::output::write_text_atomically(file, std::string(1 << 20, 'x'));  // 1 MiB, replaces the old text
  CHECK(krug::test::read_text(file).size() == (1u << 20));
  CHECK(partial_files(dir) == 0);
  // A write that cannot be made (its temporary's directory is missing): an InputError naming the
  // file, and the old file untouched.
  CHECK_THROWS_AS(krug::output::write_text_atomically(dir / "missing" / "summary.json", "new\n"), krug::InputError);
  CHECK(krug::test::read_text(file).size() == (1u << 20));
}

TEST_CASE("completed and failed runs leave no partial files behind", "[app][outputs]") {
  const fs::path scenario_file = fs::path(KRUG_EXAMPLES_DIR) / "verification" / "slab_impact.json";
  for (const bool fail : {false, true}) {
    krug::test::Json document = krug::test::read_json(scenario_file);
    document["output"]["snapshot_interval"] = 1e-6;
    // A floor above the stable step (1.9e-8 s) fails the run at its first cycle.
    if (fail) document["controls"]["time_step_floor"] = 1e-6;
    const fs::path dir = krug::test::scratch(fail ? "atomic_failed" : "atomic_completed");
    krug::output::RunOptions options;
    options.output_directory = dir;
    const krug::run::RunResult result =
        krug::output::run_scenario(krug::scenario::parse_scenario(document.dump(), scenario_file.string()), options);
    CHECK((result.status == krug::run::RunStatus::failed) == fail);
    CHECK(partial_files(dir) == 0);
    // Complete files: the summary parses, the VTK files are closed.
    CHECK(krug::test::read_json(dir / "summary.json")["status"] == (fail ? "failed" : "completed"));
    CHECK_THAT(krug::test::read_text(dir / "final.vtu"), Catch::EndsWith("</VTKFile>\n"));
    CHECK_THAT(krug::test::read_text(dir / "run.pvd"), Catch::EndsWith("</VTKFile>\n"));
  }
}

namespace {

// The names of the DataArrays inside `section` (CellData, PointData) of a VTK XML file.
std::vector<std::string> array_names(const std::string& text, const std::string& section) {
  std::vector<std::string> names;
  const auto begin = text.find("<" + section);
  const auto end = text.find("</" + section + ">");
  if (begin == std::string::npos || end == std::string::npos) return names;
  for (auto at = text.find("Name=\"", begin); at != std::string::npos && at < end; at = text.find("Name=\"", at + 1)) {
    const auto close = text.find('"', at + 6);
    names.push_back(text.substr(at + 6, close - at - 6));
  }
  return names;
}

// The field names of docs/outputs.md's table between <!-- MARK --> and <!-- /MARK -->: the back-quoted
// names of the first column, `_yy`-style suffixes completed from the name before them, for rows whose
// note names `geometry` or no geometry.
std::vector<std::string> documented_fields(const std::string& mark, const std::string& geometry) {
  const std::string doc = krug::test::read_text(fs::path(KRUG_SCHEMA_FILE).parent_path() / "outputs.md");
  const auto begin = doc.find("<!-- " + mark + " -->");
  const auto end = doc.find("<!-- /" + mark + " -->");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  std::vector<std::string> names;
  std::size_t line_start = doc.find('\n', begin) + 1;
  while (line_start < end) {
    const std::size_t line_end = doc.find('\n', line_start);
    const std::string line = doc.substr(line_start, line_end - line_start);
    line_start = line_end + 1;
    if (line.rfind("| `", 0) != 0) continue;
    const std::string first = line.substr(2, line.find(" | ", 2) - 2);
    const bool planar_row = first.find("(planar)") != std::string::npos;
    const bool axisymmetric_row = first.find("(axisymmetric)") != std::string::npos;
    if ((planar_row && geometry != "planar") || (axisymmetric_row && geometry != "axisymmetric")) continue;
    std::string stem;
    for (auto at = first.find('`'); at != std::string::npos; at = first.find('`', first.find('`', at + 1) + 1)) {
      const std::string name = first.substr(at + 1, first.find('`', at + 1) - at - 1);
      if (name[0] == '_') {
        names.push_back(stem + name);
      } else {
        names.push_back(name);
        stem = name.substr(0, name.rfind('_'));
      }
    }
  }
  return names;
}

}  // namespace

TEST_CASE("docs/outputs.md lists exactly the VTK fields written, for both geometries", "[app][outputs]") {
  const fs::path dir = krug::test::scratch("vtk_fields");
  for (const char* example : {"verification/sod.json", "fracture/high_velocity.json"}) {
    const krug::scenario::Scenario scenario = krug::scenario::load_scenario(fs::path(KRUG_EXAMPLES_DIR) / example);
    const krug::Simulation simulation(scenario.setup);
    const std::string geometry = scenario.setup.geometry == krug::GeometryKind::planar ? "planar" : "axisymmetric";
    INFO(example << " (" << geometry << ")");
    krug::output::write_vtu(simulation, dir / "state.vtu");
    krug::output::write_vtp(simulation, dir / "particles.vtp");
    const std::string vtu = krug::test::read_text(dir / "state.vtu");
    const std::string vtp = krug::test::read_text(dir / "particles.vtp");
    CHECK(array_names(vtu, "CellData") == documented_fields("vtu-cell-fields", geometry));
    CHECK(array_names(vtu, "PointData") == std::vector<std::string>{"velocity", "body"});
    CHECK(array_names(vtp, "PointData") == documented_fields("vtp-point-fields", geometry));
  }
}

namespace {

// The DataArrays inside `section` (CellData, PointData) of an ASCII VTK XML file: name, components
// and the number of values written.
struct WrittenArray {
  std::string name;
  int components = 0;
  std::size_t values = 0;
};
std::vector<WrittenArray> written_arrays(const std::string& text, const std::string& section) {
  std::vector<WrittenArray> arrays;
  const auto begin = text.find("<" + section);
  const auto end = text.find("</" + section + ">");
  REQUIRE(begin != std::string::npos);
  REQUIRE(end != std::string::npos);
  auto attribute = [&](std::size_t element, const std::string& key) {
    const auto at = text.find(key + "=\"", element) + key.size() + 2;
    return text.substr(at, text.find('"', at) - at);
  };
  for (auto at = text.find("<DataArray", begin); at != std::string::npos && at < end; at = text.find("<DataArray", at + 1)) {
    WrittenArray array{attribute(at, "Name"), std::stoi(attribute(at, "NumberOfComponents")), 0};
    const auto body = text.find('>', at) + 1;
    std::istringstream values(text.substr(body, text.find("</DataArray>", body) - body));
    for (std::string value; values >> value;) ++array.values;
    arrays.push_back(array);
  }
  return arrays;
}

// The registry's fields of one location, in its order.
std::vector<const krug::OutputField*> registry_fields(krug::OutputLocation location) {
  std::vector<const krug::OutputField*> fields;
  for (const krug::OutputField& field : krug::output_fields()) {
    if (field.location == location) fields.push_back(&field);
  }
  return fields;
}

}  // namespace

TEST_CASE("the output field registry: unique names, and the VTK files write its fields as it describes them",
          "[app][outputs]") {
  using krug::OutputLocation;
  for (const auto geometry : {krug::GeometryKind::planar, krug::GeometryKind::axisymmetric}) {
    for (const auto location : {OutputLocation::node, OutputLocation::zone, OutputLocation::particle}) {
      std::vector<std::string_view> names;
      for (const krug::OutputField* field : registry_fields(location)) {
        CHECK(field->components >= 1);
        CHECK(field->fill != nullptr);
        names.push_back(field->name_in(geometry));
      }
      std::sort(names.begin(), names.end());
      CHECK(std::adjacent_find(names.begin(), names.end()) == names.end());
    }
  }
  // A planar scene and an axisymmetric one, the latter with two free particles, written in ASCII so
  // that the values can be counted.
  const fs::path dir = krug::test::scratch("output_registry");
  for (const char* example : {"verification/sod.json", "fracture/high_velocity.json"}) {
    INFO(example);
    const krug::scenario::Scenario scenario = krug::scenario::load_scenario(fs::path(KRUG_EXAMPLES_DIR) / example);
    krug::Simulation simulation(scenario.setup);
    krug::SimulationState state = simulation.state();
    state.particles.add({0.01, 0.001}, {-100.0, 5.0}, 1e-6, 1e-4, 1, 0.0);
    state.particles.add({0.02, 0.002}, {-50.0, 0.0}, 2e-6, 2e-4, 1, 0.0);
    simulation.restore(state);
    krug::output::write_vtu(simulation, dir / "state.vtu", krug::scenario::VtkEncoding::ascii);
    krug::output::write_vtp(simulation, dir / "particles.vtp", krug::scenario::VtkEncoding::ascii);
    const std::string vtu = krug::test::read_text(dir / "state.vtu");
    const std::string vtp = krug::test::read_text(dir / "particles.vtp");
    const krug::GeometryKind geometry = scenario.setup.geometry;
    auto count = [&](const std::string& text, const std::string& key) {
      const auto at = text.find(key + "=\"") + key.size() + 2;
      return static_cast<std::size_t>(std::stoul(text.substr(at, text.find('"', at) - at)));
    };
    struct Part {
      std::string text, section, count_key;
      OutputLocation location;
    };
    const std::vector<Part> parts = {{vtu, "PointData", "NumberOfPoints", OutputLocation::node},
                                     {vtu, "CellData", "NumberOfCells", OutputLocation::zone},
                                     {vtp, "PointData", "NumberOfPoints", OutputLocation::particle}};
    CHECK(count(vtp, "NumberOfPoints") == 2);
    for (const Part& part : parts) {
      INFO(part.section << " of " << (part.location == OutputLocation::particle ? "particles.vtp" : "state.vtu"));
      const std::vector<WrittenArray> arrays = written_arrays(part.text, part.section);
      const std::vector<const krug::OutputField*> fields = registry_fields(part.location);
      REQUIRE(arrays.size() == fields.size());
      for (std::size_t k = 0; k < arrays.size(); ++k) {
        INFO(arrays[k].name);
        CHECK(arrays[k].name == fields[k]->name_in(geometry));
        CHECK(arrays[k].components == fields[k]->components);
        CHECK(arrays[k].values == count(part.text, part.count_key) * static_cast<std::size_t>(fields[k]->components));
      }
    }
  }
}

TEST_CASE("summary.json: each body's momentum and kinetic energy add up to the ledger's", "[app][outputs]") {
  // E1: two elastic slabs, planar, no particles. The ledger's kinetic energy is 1/2 sum M |u|^2 over all
  // nodes at the half step; the bodies' figures are the same sums split by body.
  for (const char* example : {"verification/slab_impact.json", "verification/taylor_bar.json"}) {
    INFO(example);
    const fs::path dir = krug::test::scratch(std::string("summary_bodies_") + (example[13] == 's' ? "slab" : "bar"));
    const krug::scenario::Scenario scenario = krug::scenario::load_scenario(fs::path(KRUG_EXAMPLES_DIR) / example);
    krug::output::RunOptions options;
    options.output_directory = dir;
    REQUIRE(krug::output::run_scenario(scenario, options).status == krug::run::RunStatus::completed);
    const auto summary = krug::test::read_json(dir / "summary.json");
    double kinetic = 0.0;
    for (const auto& [name, body] : summary["bodies"].items()) {
      kinetic += body["kinetic_energy"].get<double>();
      const double mass = body["mass"].get<double>();
      CHECK(body["momentum"][0].get<double>() / mass == Approx(body["velocity"][0].get<double>()).epsilon(1e-12));
      if (summary["geometry"] == "axisymmetric") CHECK(body["momentum"][1].is_null());
    }
    CHECK(kinetic == Approx(summary["ledger"]["energy"]["kinetic"].get<double>()).epsilon(1e-12));
  }
}

TEST_CASE("docs/outputs.md lists exactly the history.csv columns written", "[app][outputs]") {
  const fs::path dir = krug::test::scratch("history_columns");
  const krug::scenario::Scenario scenario = krug::scenario::load_scenario(fs::path(KRUG_EXAMPLES_DIR) / "fracture" / "high_velocity.json");
  krug::output::RunOptions options;
  options.output_directory = dir;
  krug::scenario::Scenario short_run = scenario;
  short_run.setup.controls.end_time = 1e-7;
  REQUIRE(krug::output::run_scenario(short_run, options).status == krug::run::RunStatus::completed);
  const std::string history = krug::test::read_text(dir / "history.csv");
  const std::string header = history.substr(0, history.find('\n'));
  std::vector<std::string> written;
  for (std::size_t at = 0;;) {
    const std::size_t comma = header.find(',', at);
    written.push_back(header.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  // The documented list, with <body>, <a>, <b> filled in for this scenario (bodies striker and plate, axes z, r).
  std::vector<std::string> documented;
  for (const std::string& name : documented_fields("history-columns", "axisymmetric")) {
    if (name.find("<body>") == std::string::npos) {
      documented.push_back(name);
      continue;
    }
    for (const char* body : {"striker", "plate"}) {
      std::string filled = name;
      filled.replace(filled.find("<body>"), 6, body);
      for (const auto& [key, axis] : {std::pair{"<a>", "z"}, std::pair{"<b>", "r"}}) {
        if (const auto k = filled.find(key); k != std::string::npos) filled.replace(k, 3, axis);
      }
      documented.push_back(filled);
    }
  }
  // Per body, the documented order is velocity pair then centroid pair; the file groups them by body.
  std::vector<std::string> sorted_written = written, sorted_documented = documented;
  std::sort(sorted_written.begin(), sorted_written.end());
  std::sort(sorted_documented.begin(), sorted_documented.end());
  CHECK(sorted_written == sorted_documented);
  CHECK(written.front() == "time");
  CHECK(written.back() == "particles");
}

TEST_CASE("the history column registry: unique names, and history.csv has a cell per column in every row",
          "[app][outputs]") {
  for (const krug::HistoryColumn& column : krug::history_columns()) {
    CHECK(column.value != nullptr);
    CHECK(column.digits >= 0);
    // A per-body column names its body, so that the bodies' columns differ.
    CHECK(column.per_body == (column.name.find("{body}") != std::string_view::npos));
  }
  // A planar scene with one body and an axisymmetric one with two.
  for (const char* example : {"verification/sod.json", "fracture/high_velocity.json"}) {
    INFO(example);
    krug::scenario::Scenario scenario = krug::scenario::load_scenario(fs::path(KRUG_EXAMPLES_DIR) / example);
    scenario.setup.controls.end_time = 1e-7;
    const krug::Simulation simulation(scenario.setup);
    const std::vector<std::string> names = krug::history_names(simulation);
    std::size_t expected = 0;
    for (const krug::HistoryColumn& column : krug::history_columns()) {
      expected += column.per_body ? simulation.bodies().size() : 1;
    }
    CHECK(names.size() == expected);
    CHECK(krug::history_cells(simulation).size() == names.size());
    std::vector<std::string> sorted = names;
    std::sort(sorted.begin(), sorted.end());
    CHECK(std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end());

    const fs::path dir = krug::test::scratch(std::string("history_registry_") + (example[0] == 'v' ? "sod" : "fracture"));
    krug::output::RunOptions options;
    options.output_directory = dir;
    REQUIRE(krug::output::run_scenario(scenario, options).status == krug::run::RunStatus::completed);
    std::istringstream history(krug::test::read_text(dir / "history.csv"));
    std::string line;
    REQUIRE(std::getline(history, line));
    std::string header;
    for (const std::string& name : names) header += (header.empty() ? "" : ",") + name;
    CHECK(line == header);
    std::size_t rows = 0;
    while (std::getline(history, line)) {
      ++rows;
      CHECK(static_cast<std::size_t>(std::count(line.begin(), line.end(), ',')) + 1 == names.size());
    }
    CHECK(rows >= 2);
  }
}

TEST_CASE("summary.json: cycles_set_by counts each step the damping bound cut as the damping's", "[app][outputs][tensor]") {
  // The spherical Noh on the polar verification mesh with the tensor viscosity and subzonal pressures at
  // shocks (docs/verification.md F7), whose damping bound cuts steps near the centre from the first
  // cycles. Counted here independently, step by step: a step the bound cut after its forces was set by
  // the damping, any other by the limit that chose it at the end of the cycle before. The summary counts
  // each cycle's choice of the next step, so it leaves out the first step's choice and has the choice
  // after the last cycle instead; every other count must agree.
  krug::scenario::Scenario scenario =
      krug::scenario::load_scenario(fs::path(KRUG_EXAMPLES_DIR) / "verification" / "noh_spherical.json");
  scenario.setup.controls.viscosity.model = krug::ViscosityModel::tensor;
  scenario.setup.controls.hourglass.subzonal_pressure = 2.0;
  scenario.setup.controls.hourglass.subzonal_at_shocks = true;
  scenario.setup.controls.end_time = 0.03;
  const fs::path dir = krug::test::scratch("summary_damping_cycles");
  const auto name = [](krug::TimeStepLimit limit) {
    switch (limit) {
      case krug::TimeStepLimit::zone: return std::string("gas");
      case krug::TimeStepLimit::growth: return std::string("growth_limit");
      case krug::TimeStepLimit::particle_travel: return std::string("particle_travel");
      default: return std::string("other");
    }
  };
  std::map<std::string, long> taken;
  std::string chosen, first_choice;
  krug::output::RunOptions options;
  options.output_directory = dir;
  options.on_start = [&](const krug::Simulation& s) { chosen = first_choice = name(s.time_step_limit()); };
  options.on_cycle = [&](const krug::Simulation& s, double) {
    ++taken[s.step_cut_by_damping() ? std::string("viscous_damping") : chosen];
    chosen = name(s.time_step_limit());
    return true;
  };
  REQUIRE(krug::output::run_scenario(scenario, options).status == krug::run::RunStatus::completed);
  const auto summary = krug::test::read_json(dir / "summary.json");
  long cycles = 0;
  for (const auto& [key, count] : taken) cycles += count;
  REQUIRE(summary["cycles"].get<long>() == cycles);
  REQUIRE(taken["viscous_damping"] > 0);
  for (const std::string key : {"gas", "growth_limit", "particle_travel", "viscous_damping", "other"}) {
    INFO(key);
    const long expected = taken[key] - (key == first_choice ? 1 : 0) + (key == chosen ? 1 : 0);
    CHECK(summary["time_step"]["cycles_set_by"][key].get<long>() == expected);
  }
}
