#include "json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "krug/core/error.hpp"

namespace krug::scenario {

std::string Range::describe() const {
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max) return fmt::format("a number in [{}, {}]", min, max);
  if (has_min) return fmt::format("a number {} {}", min_exclusive ? ">" : ">=", min);
  if (has_max) return fmt::format("a number <= {}", max);
  return "a finite number";
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  if (min_exclusive ? !(v > min) : !(v >= min)) return false;
  return v <= max;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::optional<std::string> nearest(std::string_view word, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

namespace {

// A SAX pass over the text that stops at the first nesting past the limit or repeated key, keeping the
// JSON path of where it is for the message.
class ShapeCheck : public nlohmann::json_sax<Json> {
 public:
  std::string problem;  // empty: the shape is fine (syntax errors are left to the parser proper)

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& key) override {
    Frame& frame = frames_.back();
    frame.key.clear();  // the path of the new key is this object's path plus the key
    if (!frame.keys.insert(key).second) {
      problem = fmt::format("{}: the key \"{}\" appears twice in one object; give each key once",
                            path_with(key), key);
      return false;
    }
    frame.key = key;
    return true;
  }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  struct Frame {
    bool object = false;
    std::set<std::string> keys;
    std::string key;
    long index = -1;
  };
  std::vector<Frame> frames_;

  std::string path() const {
    std::string text;
    for (const Frame& f : frames_) {
      if (f.object) {
        if (!f.key.empty()) text += (text.empty() ? "" : ".") + f.key;
      } else if (f.index >= 0) {
        text += fmt::format("[{}]", f.index);
      }
    }
    return text.empty() ? "(top level)" : text;
  }
  std::string path_with(const std::string& key) const {
    const std::string base = path();
    return base == "(top level)" ? key : base + "." + key;
  }
  // A value begins: in an array it is the next element.
  void begin_value() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  bool value() {
    begin_value();
    return true;
  }
  bool open(bool object) {
    begin_value();
    if (static_cast<int>(frames_.size()) >= max_json_depth) {
      std::string where = path();
      if (where.size() > 80) where = where.substr(0, 60) + "...";
      problem = fmt::format("{}: arrays and objects nested more than {} deep; a scenario needs a few levels",
                            where, max_json_depth);
      return false;
    }
    frames_.push_back({object, {}, {}, -1});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return true;
  }
};

}  // namespace

std::string read_text_file(const std::filesystem::path& file, std::string_view what, std::uintmax_t max_bytes) {
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (error || !std::filesystem::exists(status)) {
    throw InputError(fmt::format("{}: cannot open the {}: no such file", file.string(), what));
  }
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(fmt::format("{}: the {} is not a regular file (a directory, a pipe or a device)", file.string(), what));
  }
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (!error && size > max_bytes) {
    throw InputError(fmt::format("{}: the {} is {} bytes, more than the {} a {} may have", file.string(), what, size,
                                 max_bytes, what));
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the {}", file.string(), what));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void check_document_shape(const std::string& text, const std::string& origin) {
  ShapeCheck check;
  (void)Json::sax_parse(text, &check);
  if (!check.problem.empty()) throw InputError(fmt::format("{}: {}", origin, check.problem));
}

template <class Document>
Document parse_document(const std::string& text, const std::string& origin) {
  check_document_shape(text, origin);
  try {
    return Document::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax errors, and numbers too large for a double (1e400)
    throw InputError(fmt::format("{}: not valid JSON: {}", origin, e.what()));
  }
}

template Json parse_document<Json>(const std::string&, const std::string&);
template nlohmann::ordered_json parse_document<nlohmann::ordered_json>(const std::string&, const std::string&);

std::string describe_value(const Json& value) {
  std::string text = value.dump();
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  const char* type = value.is_null() ? "null" : value.is_boolean() ? "a boolean" : value.is_number() ? "a number"
                     : value.is_string() ? "a string" : value.is_array() ? "an array" : "an object";
  return fmt::format("{} {}", type, text);
}

JsonObject::JsonObject(const Json& value, std::string path, Json* resolved)
    : value_(value), path_(std::move(path)), resolved_(resolved) {
  if (!value_.is_object()) {
    throw InputError(fmt::format("{}: expected an object, found {}", path_.empty() ? "(top level)" : path_,
                                 describe_value(value_)));
  }
  if (resolved_ && !resolved_->is_object()) *resolved_ = Json::object();
}

std::string JsonObject::path_of(std::string_view key) const {
  return path_.empty() ? std::string(key) : fmt::format("{}.{}", path_, key);
}

bool JsonObject::has(std::string_view key) const { return value_.contains(key); }

const Json& JsonObject::member(std::string_view key) const {
  used_.emplace(key);
  const auto it = value_.find(key);
  if (it == value_.end()) fail(key, "a value (the key is required)");
  return *it;
}

void JsonObject::fail(std::string_view key, std::string_view expected) const {
  const auto it = value_.find(key);
  if (it == value_.end()) {
    // A near-miss key in the same object is most likely a typo of this one.
    const auto typo = nearest(key, keys());
    throw InputError(fmt::format("{}: missing; expected {}{}", path_of(key), expected,
                                 typo ? fmt::format(" (found \"{}\": did you mean \"{}\"?)", *typo, key) : ""));
  }
  throw InputError(fmt::format("{}: expected {}, found {}", path_of(key), expected, describe_value(*it)));
}

void JsonObject::fail_here(std::string_view message) const {
  throw InputError(fmt::format("{}: {}", path_.empty() ? "(top level)" : path_, message));
}

void JsonObject::resolve(std::string_view key, const Json& value) {
  if (resolved_) (*resolved_)[std::string(key)] = value;
}

double JsonObject::number(std::string_view key, Range range) {
  const Json& v = member(key);
  if (!v.is_number()) fail(key, range.describe());
  const double x = v.get<double>();
  if (!range.contains(x)) fail(key, range.describe());
  resolve(key, x);
  return x;
}

double JsonObject::number(std::string_view key, double fallback, Range range) {
  if (!has(key)) {
    used_.emplace(key);
    resolve(key, fallback);
    return fallback;
  }
  return number(key, range);
}

std::optional<double> JsonObject::optional_number(std::string_view key, Range range) {
  if (!has(key)) {
    used_.emplace(key);
    return std::nullopt;
  }
  return number(key, range);
}

long JsonObject::integer(std::string_view key, long min, long max) {
  const Json& v = member(key);
  const std::string expected = fmt::format("an integer in [{}, {}]", min, max);
  if (!v.is_number_integer() && !(v.is_number() && std::floor(v.get<double>()) == v.get<double>())) fail(key, expected);
  const double x = v.get<double>();
  if (!(x >= static_cast<double>(min) && x <= static_cast<double>(max))) fail(key, expected);
  resolve(key, static_cast<long>(x));
  return static_cast<long>(x);
}

long JsonObject::integer(std::string_view key, long fallback, long min, long max) {
  if (!has(key)) {
    used_.emplace(key);
    resolve(key, fallback);
    return fallback;
  }
  return integer(key, min, max);
}

bool JsonObject::flag(std::string_view key, bool fallback) {
  if (!has(key)) {
    used_.emplace(key);
    resolve(key, fallback);
    return fallback;
  }
  const Json& v = member(key);
  if (!v.is_boolean()) fail(key, "true or false");
  resolve(key, v.get<bool>());
  return v.get<bool>();
}

std::string JsonObject::text(std::string_view key) {
  const Json& v = member(key);
  if (!v.is_string()) fail(key, "a string");
  resolve(key, v);
  return v.get<std::string>();
}

std::string JsonObject::text(std::string_view key, std::string_view fallback) {
  if (!has(key)) {
    used_.emplace(key);
    resolve(key, std::string(fallback));
    return std::string(fallback);
  }
  return text(key);
}

std::string JsonObject::choice(std::string_view key, const std::vector<std::string>& options) {
  const Json& v = member(key);
  std::string list;
  for (const auto& o : options) list += (list.empty() ? "\"" : ", \"") + o + "\"";
  if (!v.is_string()) fail(key, "one of " + list);
  const std::string s = v.get<std::string>();
  if (std::find(options.begin(), options.end(), s) == options.end()) {
    const auto guess = nearest(s, options);
    throw InputError(fmt::format("{}: unknown name \"{}\"; expected one of {}{}", path_of(key), s, list,
                                 guess ? fmt::format(" (did you mean \"{}\"?)", *guess) : ""));
  }
  resolve(key, s);
  return s;
}

std::string JsonObject::choice(std::string_view key, const std::vector<std::string>& options,
                               std::string_view fallback) {
  if (!has(key)) {
    used_.emplace(key);
    resolve(key, std::string(fallback));
    return std::string(fallback);
  }
  return choice(key, options);
}

JsonObject JsonObject::object(std::string_view key) {
  const Json& v = member(key);
  if (!v.is_object()) fail(key, "an object");
  Json* child = nullptr;
  if (resolved_) {
    (*resolved_)[std::string(key)] = Json::object();
    child = &(*resolved_)[std::string(key)];
  }
  return JsonObject(v, path_of(key), child);
}

JsonObject JsonObject::object_from(std::string_view key, const Json& value) {
  (void)member(key);  // marks it read; a missing key fails here
  Json* child = nullptr;
  if (resolved_) {
    (*resolved_)[std::string(key)] = Json::object();
    child = &(*resolved_)[std::string(key)];
  }
  return JsonObject(value, path_of(key), child);
}

std::optional<JsonObject> JsonObject::optional_object(std::string_view key) {
  if (!has(key)) {
    used_.emplace(key);
    return std::nullopt;
  }
  return object(key);
}

JsonObject JsonObject::object_or_empty(std::string_view key) {
  static const Json empty = Json::object();
  if (has(key)) return object(key);
  used_.emplace(key);
  Json* child = nullptr;
  if (resolved_) {
    (*resolved_)[std::string(key)] = Json::object();
    child = &(*resolved_)[std::string(key)];
  }
  return JsonObject(empty, path_of(key), child);
}

const Json& JsonObject::raw(std::string_view key) { return member(key); }

const Json* JsonObject::optional_raw(std::string_view key) {
  used_.emplace(key);
  const auto it = value_.find(key);
  return it == value_.end() ? nullptr : &*it;
}

std::vector<std::string> JsonObject::keys() const {
  std::vector<std::string> names;
  for (auto it = value_.begin(); it != value_.end(); ++it) names.push_back(it.key());
  return names;
}

void JsonObject::finish(const std::vector<std::string>& also_known) const {
  std::vector<std::string> known(used_.begin(), used_.end());
  known.insert(known.end(), also_known.begin(), also_known.end());
  for (auto it = value_.begin(); it != value_.end(); ++it) {
    if (used_.count(it.key())) continue;
    const auto guess = nearest(it.key(), known);
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throw InputError(fmt::format("{}: unknown key{}; valid keys here: {}", path_of(it.key()),
                                 guess ? fmt::format(" (did you mean \"{}\"?)", *guess) : "", list));
  }
}

}  // namespace krug::scenario
