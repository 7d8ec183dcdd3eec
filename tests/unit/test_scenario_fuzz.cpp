// Fuzzing the scenario reader in-process (so it also runs under AddressSanitizer and
// UndefinedBehaviorSanitizer in scripts/test.sh). Every example scenario and every scenario of
// tests/app/data/ is mutated many times with a fixed seed: a key deleted or misspelt, a value of the
// wrong type, a number made negative, zero, tiny, huge or fractional, a string made empty or an
// expression broken, an array shortened or lengthened, the text truncated or a character changed,
// deep nesting. Each mutant must either be read or be refused with an InputError; nothing else may
// escape, and nothing may crash. A mutant the reader accepts must still satisfy the schema
// (docs/scenario.schema.json: the schema is never stricter than the reader) and must build a
// Simulation or be refused by it with an InputError.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include <nlohmann/json.hpp>

#include "../app/schema_validator.hpp"
#include "krug/core/error.hpp"
#include "krug/scenario/scenario.hpp"
#include "krug/solver/simulation.hpp"

namespace {

using Json = nlohmann::json;

// A small deterministic generator (splitmix64): the same mutants on every platform and run.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
  template <class T>
  const T& pick(const std::vector<T>& items) { return items[below(items.size())]; }

 private:
  std::uint64_t state_;
};

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::vector<std::filesystem::path> seed_files() {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path examples(KRUG_EXAMPLES_DIR);
  for (const auto& entry : std::filesystem::recursive_directory_iterator(examples)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  }
  const std::filesystem::path app_data = examples.parent_path() / "tests" / "app" / "data";
  if (std::filesystem::exists(app_data)) {
    for (const auto& entry : std::filesystem::directory_iterator(app_data)) {
      if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// JSON pointers to every value in the document (the root excluded).
void collect(const Json& v, const std::string& at, std::vector<std::string>& out) {
  if (!at.empty()) out.push_back(at);
  if (v.is_object()) {
    for (const auto& [key, child] : v.items()) collect(child, at + "/" + key, out);
  } else if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) collect(v[i], at + "/" + std::to_string(i), out);
  }
}

const std::vector<Json>& wrong_values() {
  static const std::vector<Json> values = {
      Json("text"), Json(""), Json(true), Json(false), Json(nullptr), Json::array(), Json::object(),
      Json::array({1, 2, 3}), Json::array({"a", "b"}), Json(42), Json(-1), Json(0), Json(0.5), Json(-0.0),
      Json(1e300), Json(-1e300), Json(1e-320), Json(2147483648.0), Json(9.3e18), Json(-9.3e18),
      Json(18446744073709551615ULL), Json(std::int64_t{-9223372036854775807LL - 1}), Json(1.5),
      Json::object({{"model", "linear"}}), Json::array({Json::object()}), Json("x/0"), Json("sqrt(-1)"),
      Json("("), Json("x +"), Json("1e400"), Json("nan"), Json("unknown_name"), Json(std::string(5000, 'x'))};
  return values;
}

// One mutant of `document` (whose text is `text`), described in `what`.
std::string mutate(const Json& document, const std::string& text, Random& random, std::string& what) {
  std::vector<std::string> pointers;
  collect(document, "", pointers);
  Json copy = document;
  const std::string at = pointers.empty() ? "" : random.pick(pointers);
  const Json::json_pointer where(at);
  switch (random.below(10)) {
    case 0: {  // delete a key or an array item
      what = "delete " + at;
      const Json::json_pointer parent = where.parent_pointer();
      Json& container = copy[parent];
      if (container.is_object()) container.erase(where.back());
      else if (container.is_array() && !container.empty()) container.erase(container.size() - 1);
      return copy.dump();
    }
    case 1:
    case 2: {  // a value of the wrong type or out of range
      const Json& value = random.pick(wrong_values());
      what = "set " + at + " = " + value.dump().substr(0, 60);
      copy[where] = value;
      return copy.dump();
    }
    case 3: {  // a number made negative, zero, huge, tiny or fractional
      const Json& old = copy[where];
      const double x = old.is_number() ? old.get<double>() : 1.0;
      const std::vector<double> options = {-x, 0.0, x * 1e300, x * 1e-300, x + 0.5, -1e-300, x * 1e6, -x * 1e6};
      const double value = random.pick(options);
      what = "set " + at + " = " + Json(value).dump();
      copy[where] = value;
      return copy.dump();
    }
    case 4: {  // a misspelt key
      const Json::json_pointer parent = where.parent_pointer();
      Json& container = copy[parent];
      if (!container.is_object()) return mutate(document, text, random, what);
      const std::string key = where.back();
      std::string typo = key.empty() ? "x" : key.substr(0, key.size() - 1) + "_";
      what = "rename " + at + " to " + typo;
      container[typo] = container[key];
      container.erase(key);
      return copy.dump();
    }
    case 5: {  // an array made longer, shorter or empty
      Json& value = copy[where];
      if (!value.is_array()) return mutate(document, text, random, what);
      const std::size_t choice = random.below(3);
      if (choice == 0 && !value.empty()) value.push_back(value.back());
      else if (choice == 1 && !value.empty()) value.erase(value.size() - 1);
      else value = Json::array();
      what = "resize array " + at;
      return copy.dump();
    }
    case 6: {  // truncated text
      const std::size_t cut = random.below(text.size());
      what = "truncate at " + std::to_string(cut);
      return text.substr(0, cut);
    }
    case 7: {  // one character changed
      std::string corrupted = text;
      const std::size_t position = random.below(corrupted.size());
      const std::string replacements = "{}[]\",:0-e.9 xN\\";
      corrupted[position] = replacements[random.below(replacements.size())];
      what = "character " + std::to_string(position) + " changed";
      return corrupted;
    }
    case 8: {  // a number token JSON cannot hold
      const std::vector<std::string> tokens = {"1e400", "-1e400", "NaN", "Infinity", "-Infinity", "0x10", "01", "1.", ".5"};
      const std::string token = random.pick(tokens);
      copy[where] = "@@TOKEN@@";
      std::string out = copy.dump();
      const auto p = out.find("\"@@TOKEN@@\"");
      out.replace(p, 11, token);
      what = "set " + at + " = " + token;
      return out;
    }
    default: {  // deep nesting in place of a value
      const std::size_t depth = 1 + random.below(3000);
      copy[where] = "@@DEEP@@";
      std::string out = copy.dump();
      const auto p = out.find("\"@@DEEP@@\"");
      out.replace(p, 10, std::string(depth, '[') + std::string(depth, ']'));
      what = "nest " + std::to_string(depth) + " arrays at " + at;
      return out;
    }
  }
}

}  // namespace

TEST_CASE("mutated scenarios are read or refused with an InputError, never anything else", "[scenario][fuzz]") {
  const krug::test::SchemaValidator schema(
      Json::parse(read_text(std::filesystem::path(KRUG_EXAMPLES_DIR).parent_path() / "docs" / "scenario.schema.json")));
  Random random(20240611);
  const auto files = seed_files();
  REQUIRE(files.size() >= 3);
  long refused = 0, accepted = 0, built = 0;
  for (const auto& file : files) {
    const std::string original = read_text(file);
    const Json document = Json::parse(original);
    // The resolved form carries every default, so its mutants reach keys the file leaves out.
    const std::string resolved_text = krug::scenario::parse_scenario(original, file.string()).resolved_json;
    const Json resolved = Json::parse(resolved_text);
    for (int i = 0; i < 40; ++i) {
      const bool use_resolved = i % 2 == 1;
      std::string what;
      const std::string mutant = mutate(use_resolved ? resolved : document, use_resolved ? resolved_text : original,
                                        random, what);
      INFO(file.filename().string() << (use_resolved ? " (resolved)" : "") << ": " << what);
      try {
        const krug::scenario::Scenario scenario = krug::scenario::parse_scenario(mutant, "mutant.json");
        ++accepted;
        const auto errors = schema.validate(Json::parse(mutant));
        INFO("schema: " << (errors.empty() ? std::string() : errors.front()));
        CHECK(errors.empty());
        if (scenario.setup.mesh.zones.size() <= 20000) {
          try {
            const krug::Simulation simulation(scenario.setup);
            ++built;
          } catch (const krug::InputError&) {
            ++refused;
          }
        }
      } catch (const krug::InputError& e) {
        ++refused;
        CHECK(std::string(e.what()).size() > 10);  // says something
      } catch (const std::exception& e) {
        FAIL("escaped as " << typeid(e).name() << ": " << e.what());
      }
    }
  }
  INFO("accepted " << accepted << ", refused " << refused << ", simulations built " << built);
  CHECK(accepted + refused >= 40L * static_cast<long>(files.size()));
  CHECK(refused > accepted);  // most mutants are errors
}
