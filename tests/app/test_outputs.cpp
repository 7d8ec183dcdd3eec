// Output files are written atomically (docs/outputs.md): each goes to NAME.partial and is renamed
// over NAME once complete, so a reader (ParaView, a script polling a long run) sees the old file or
// the new one, never half of one; a write that cannot be made leaves the old file as it was.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "krug/core/error.hpp"
#include "krug/io/outputs.hpp"
#include "krug/run/run.hpp"
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
  krug::io::write_text_atomically(file, "old\n");
  krug::io::write_text_atomically(file, std::string(1 << 20, 'x'));  // 1 MiB, replaces the old text
  CHECK(krug::test::read_text(file).size() == (1u << 20));
  CHECK(partial_files(dir) == 0);
  // A write that cannot be made (its temporary's directory is missing): an InputError naming the
  // file, and the old file untouched.
  CHECK_THROWS_AS(krug::io::write_text_atomically(dir / "missing" / "summary.json", "new\n"), krug::InputError);
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
    krug::run::RunOptions options;
    options.output_directory = dir;
    const krug::io::RunResult result =
        krug::run::run_scenario(krug::io::parse_scenario(document.dump(), scenario_file.string()), options);
    CHECK((result.status == krug::io::RunStatus::failed) == fail);
    CHECK(partial_files(dir) == 0);
    // Complete files: the summary parses, the VTK files are closed.
    CHECK(krug::test::read_json(dir / "summary.json")["status"] == (fail ? "failed" : "completed"));
    CHECK_THAT(krug::test::read_text(dir / "final.vtu"), Catch::EndsWith("</VTKFile>\n"));
    CHECK_THAT(krug::test::read_text(dir / "run.pvd"), Catch::EndsWith("</VTKFile>\n"));
  }
}
