#pragma once
// Strict reading of a JSON scenario (private to the io library). Every accessor names the JSON path
// of what it reads; a wrong type, a value out of range, a missing key or an unknown key is an
// InputError that says where, what was found and what was expected (an unknown key suggests the
// nearest valid one, an unknown model name lists the valid ones). What is read, defaults included,
// is copied into a "resolved" document so a run can be reproduced from its output directory.
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace krug::scenario {

using Json = nlohmann::json;

struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false}; }
  static Range between(double lo, double hi) { return {lo, hi, false}; }
  std::string describe() const;
  bool contains(double v) const;
};

// Edit distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b);
// The candidate nearest to `word`, if it is close enough to be a likely typo.
std::optional<std::string> nearest(std::string_view word, const std::vector<std::string>& candidates);
// A short rendering of a JSON value for error messages.
std::string describe_value(const Json& value);

// Limits on a scenario document, checked before anything is built from it.
inline constexpr int max_json_depth = 64;                       // nested arrays and objects
inline constexpr std::uintmax_t max_scenario_bytes = 64u << 20;  // 64 MiB

// The text of a regular file of at most `max_bytes`; anything else (missing, a directory, a FIFO or
// a device, which a reader would wait on forever, or too large) is an InputError naming the file.
std::string read_text_file(const std::filesystem::path& file, std::string_view what,
                           std::uintmax_t max_bytes = max_scenario_bytes);

// Parses JSON text after checking its shape: nesting no deeper than max_json_depth and no key twice
// in one object (the second would silently win). Errors are InputErrors naming `origin` and the
// JSON path. Works for both nlohmann::json and nlohmann::ordered_json.
template <class Document>
Document parse_document(const std::string& text, const std::string& origin);
// The shape check of parse_document alone (text that is not JSON passes: the parser reports it).
void check_document_shape(const std::string& text, const std::string& origin);

// A registry that is a std::variant of kinds, each with its `name` (equations of state, strength
// models, failure laws, mesh kinds): the names in the variant's order, for `JsonObject::choice`, and
// the alternative of a chosen name, built by `make(std::type_identity<Kind>{})`. A reader of such a
// registry is one generic function; a new kind is a line in its variant and the kind's own reading.
template <class Variant>
std::vector<std::string> alternative_names() {
  std::vector<std::string> names;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (names.emplace_back(std::variant_alternative_t<I, Variant>::name), ...);
  }(std::make_index_sequence<std::variant_size_v<Variant>>{});
  return names;
}

template <class Variant, class Make>
Variant make_alternative(std::string_view chosen, Make&& make) {
  Variant result;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (void)((chosen == std::variant_alternative_t<I, Variant>::name
                ? (result = make(std::type_identity<std::variant_alternative_t<I, Variant>>{}), true)
                : false) ||
           ...);
  }(std::make_index_sequence<std::variant_size_v<Variant>>{});
  return result;
}

class JsonObject {
 public:
  // `value` must outlive the reader; `resolved` receives what is read (may be null).
  JsonObject(const Json& value, std::string path, Json* resolved);

  const std::string& path() const { return path_; }
  std::string path_of(std::string_view key) const;
  bool has(std::string_view key) const;

  double number(std::string_view key, Range range = {});
  double number(std::string_view key, double fallback, Range range = {});
  // A number that may be absent (a default that depends on other choices): accepted here either way,
  // and only a given one reaches the resolved document.
  std::optional<double> optional_number(std::string_view key, Range range = {});
  long integer(std::string_view key, long fallback, long min, long max);
  long integer(std::string_view key, long min, long max);
  bool flag(std::string_view key, bool fallback);
  std::string text(std::string_view key);
  std::string text(std::string_view key, std::string_view fallback);
  // A name out of a fixed list: an unknown one lists the valid names.
  std::string choice(std::string_view key, const std::vector<std::string>& options);
  std::string choice(std::string_view key, const std::vector<std::string>& options, std::string_view fallback);

  JsonObject object(std::string_view key);
  // Reads `value` in place of the member at `key` (a value made from it, such as a material set
  // expanded from the library): errors name key's path, and what is read goes to key's resolved entry.
  // `value` must outlive the reader.
  JsonObject object_from(std::string_view key, const Json& value);
  std::optional<JsonObject> optional_object(std::string_view key);
  // The object at key, or an empty one when absent (so its defaults still reach the resolved document).
  JsonObject object_or_empty(std::string_view key);
  // The raw value (for fields that are a number or an expression string, or arrays).
  const Json& raw(std::string_view key);
  const Json* optional_raw(std::string_view key);
  // Copies a raw value into the resolved document under `key`.
  void resolve(std::string_view key, const Json& value);

  // Names of the object's members, in document order.
  std::vector<std::string> keys() const;
  // Every key not read is an error (with the nearest read or known key as a suggestion).
  void finish(const std::vector<std::string>& also_known = {}) const;

  [[noreturn]] void fail(std::string_view key, std::string_view expected) const;
  [[noreturn]] void fail_here(std::string_view message) const;

 private:
  const Json& member(std::string_view key) const;

  const Json& value_;
  std::string path_;
  Json* resolved_;
  mutable std::set<std::string, std::less<>> used_;
};

}  // namespace krug::scenario
