#pragma once
// A small JSON Schema validator for the subset docs/scenario.schema.json uses (draft 2020-12 words):
// type (string or list; "integer" is a number with no fraction), properties, required,
// additionalProperties (false or a schema), minProperties, enum, const, minimum, maximum,
// exclusiveMinimum, exclusiveMaximum, minLength, items, minItems, maxItems, oneOf, anyOf and local
// "$ref": "#/$defs/NAME". Annotation words (title, description, default, $id, $schema, $defs) are
// ignored; any other word is an error, so the schema cannot use a rule this validator would skip.
// Test code: shared by tests/app/test_schema.cpp and tests/unit/test_scenario_fuzz.cpp.
#include <cmath>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace krug::test {

class SchemaValidator {
 public:
  using Json = nlohmann::json;

  explicit SchemaValidator(Json schema) : root_(std::move(schema)) { check_words(root_, "#"); }

  // Every violation as "path: what", empty when the instance is valid.
  std::vector<std::string> validate(const Json& instance) const {
    std::vector<std::string> errors;
    validate(instance, root_, "", errors);
    return errors;
  }
  bool valid(const Json& instance) const { return validate(instance).empty(); }

  // Visits every object of `instance` with the object schema that applies to it: references
  // followed, and of oneOf/anyOf the first branch that validates the object. A schema whose objects
  // are name -> value maps (additionalProperties a schema, no properties) is reported with
  // `is_map` true. Objects for which no branch validates are skipped (validate() reports them).
  using Visitor = std::function<void(const std::string& path, const Json& object, const Json& schema, bool is_map)>;
  void walk(const Json& instance, const Visitor& visit) const { walk(instance, root_, "", visit); }

  // The object schema that applies to `instance` at this level, or null.
  const Json* object_schema(const Json& instance, const Json& schema) const {
    const Json& s = deref(schema);
    if (s.contains("properties") || (s.contains("additionalProperties") && s["additionalProperties"].is_object())) {
      return &s;
    }
    for (const char* word : {"oneOf", "anyOf"}) {
      if (!s.contains(word)) continue;
      for (const Json& branch : s[word]) {
        std::vector<std::string> errors;
        validate(instance, branch, "", errors);
        if (errors.empty()) return object_schema(instance, branch);
      }
    }
    return nullptr;
  }

  const Json& root() const { return root_; }
  const Json& deref(const Json& schema) const {
    if (!schema.is_object() || !schema.contains("$ref")) return schema;
    const std::string ref = schema["$ref"].get<std::string>();
    const std::string prefix = "#/$defs/";
    if (ref.rfind(prefix, 0) != 0) throw std::runtime_error("unsupported $ref " + ref);
    return deref(root_.at("$defs").at(ref.substr(prefix.size())));
  }

 private:
  static std::string child(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  static bool is_type(const Json& v, const std::string& type) {
    if (type == "object") return v.is_object();
    if (type == "array") return v.is_array();
    if (type == "string") return v.is_string();
    if (type == "boolean") return v.is_boolean();
    if (type == "null") return v.is_null();
    if (type == "number") return v.is_number() && std::isfinite(v.get<double>());
    if (type == "integer") {
      if (!v.is_number()) return false;
      const double x = v.get<double>();
      return std::isfinite(x) && std::floor(x) == x;
    }
    throw std::runtime_error("unknown type " + type);
  }

  static bool equal(const Json& a, const Json& b) {
    if (a.is_number() && b.is_number()) return a.get<double>() == b.get<double>();
    return a == b;
  }

  void check_words(const Json& schema, const std::string& where) const {
    static const std::set<std::string> words = {
        "type", "properties", "required", "additionalProperties", "minProperties", "enum", "const", "minimum",
        "maximum", "exclusiveMinimum", "exclusiveMaximum", "minLength", "items", "minItems", "maxItems", "oneOf",
        "anyOf", "$ref", "title", "description", "default", "$id", "$schema", "$defs"};
    if (!schema.is_object()) throw std::runtime_error(where + ": a schema must be an object");
    for (auto it = schema.begin(); it != schema.end(); ++it) {
      if (!words.count(it.key())) throw std::runtime_error(where + ": schema word \"" + it.key() + "\" not supported");
    }
    if (schema.contains("properties")) {
      for (auto it = schema["properties"].begin(); it != schema["properties"].end(); ++it) {
        check_words(*it, where + "/properties/" + it.key());
      }
    }
    if (schema.contains("$defs")) {
      for (auto it = schema["$defs"].begin(); it != schema["$defs"].end(); ++it) check_words(*it, where + "/$defs/" + it.key());
    }
    if (schema.contains("additionalProperties") && schema["additionalProperties"].is_object()) {
      check_words(schema["additionalProperties"], where + "/additionalProperties");
    }
    if (schema.contains("items")) check_words(schema["items"], where + "/items");
    for (const char* word : {"oneOf", "anyOf"}) {
      if (!schema.contains(word)) continue;
      for (std::size_t i = 0; i < schema[word].size(); ++i) {
        check_words(schema[word][i], where + "/" + word + "/" + std::to_string(i));
      }
    }
    if (schema.contains("$ref")) (void)deref(schema);
  }

  void validate(const Json& v, const Json& schema_in, const std::string& path, std::vector<std::string>& errors) const {
    const Json& s = deref(schema_in);
    const std::string here = path.empty() ? "(top level)" : path;
    auto fail = [&](const std::string& what) { errors.push_back(here + ": " + what); };
    if (s.contains("type")) {
      const Json& t = s["type"];
      bool ok = false;
      if (t.is_string()) {
        ok = is_type(v, t.get<std::string>());
      } else {
        for (const Json& one : t) ok = ok || is_type(v, one.get<std::string>());
      }
      if (!ok) return fail("expected type " + t.dump() + ", found " + v.dump());
    }
    if (s.contains("const") && !equal(v, s["const"])) fail("expected " + s["const"].dump());
    if (s.contains("enum")) {
      bool found = false;
      for (const Json& option : s["enum"]) found = found || equal(v, option);
      if (!found) fail("expected one of " + s["enum"].dump() + ", found " + v.dump());
    }
    if (v.is_number()) {
      const double x = v.get<double>();
      if (!std::isfinite(x)) fail("not a finite number");
      if (s.contains("minimum") && !(x >= s["minimum"].get<double>())) fail("below minimum");
      if (s.contains("maximum") && !(x <= s["maximum"].get<double>())) fail("above maximum");
      if (s.contains("exclusiveMinimum") && !(x > s["exclusiveMinimum"].get<double>())) fail("not above exclusiveMinimum");
      if (s.contains("exclusiveMaximum") && !(x < s["exclusiveMaximum"].get<double>())) fail("not below exclusiveMaximum");
    }
    if (v.is_string() && s.contains("minLength") && v.get<std::string>().size() < s["minLength"].get<std::size_t>()) {
      fail("string too short");
    }
    if (v.is_array()) {
      if (s.contains("minItems") && v.size() < s["minItems"].get<std::size_t>()) fail("too few items");
      if (s.contains("maxItems") && v.size() > s["maxItems"].get<std::size_t>()) fail("too many items");
      if (s.contains("items")) {
        for (std::size_t i = 0; i < v.size(); ++i) validate(v[i], s["items"], path + "[" + std::to_string(i) + "]", errors);
      }
    }
    if (v.is_object()) {
      if (s.contains("required")) {
        for (const Json& key : s["required"]) {
          if (!v.contains(key.get<std::string>())) fail("missing required key \"" + key.get<std::string>() + "\"");
        }
      }
      if (s.contains("minProperties") && v.size() < s["minProperties"].get<std::size_t>()) fail("too few members");
      for (auto it = v.begin(); it != v.end(); ++it) {
        if (s.contains("properties") && s["properties"].contains(it.key())) {
          validate(*it, s["properties"][it.key()], child(path, it.key()), errors);
        } else if (s.contains("additionalProperties")) {
          const Json& extra = s["additionalProperties"];
          if (extra.is_boolean()) {
            if (!extra.get<bool>()) fail("unknown key \"" + it.key() + "\"");
          } else {
            validate(*it, extra, child(path, it.key()), errors);
          }
        }
      }
    }
    if (s.contains("anyOf")) {
      bool any = false;
      for (const Json& branch : s["anyOf"]) {
        std::vector<std::string> branch_errors;
        validate(v, branch, path, branch_errors);
        any = any || branch_errors.empty();
      }
      if (!any) fail("matches none of anyOf");
    }
    if (s.contains("oneOf")) {
      int matches = 0;
      std::vector<std::string> first_errors;
      for (const Json& branch : s["oneOf"]) {
        std::vector<std::string> branch_errors;
        validate(v, branch, path, branch_errors);
        if (branch_errors.empty()) ++matches;
        else if (first_errors.empty()) first_errors = branch_errors;
      }
      if (matches != 1) {
        fail("matches " + std::to_string(matches) + " branches of oneOf" +
             (first_errors.empty() ? std::string() : " (first branch: " + first_errors.front() + ")"));
      }
    }
  }

  void walk(const Json& v, const Json& schema, const std::string& path, const Visitor& visit) const {
    if (v.is_array()) {
      const Json& s = deref(schema);
      const Json* items = s.contains("items") ? &s["items"] : nullptr;
      if (!items) {
        for (const char* word : {"oneOf", "anyOf"}) {
          if (!s.contains(word)) continue;
          for (const Json& branch : s[word]) {
            std::vector<std::string> errors;
            validate(v, branch, "", errors);
            if (errors.empty() && deref(branch).contains("items")) {
              items = &deref(branch)["items"];
              break;
            }
          }
        }
      }
      if (!items) return;
      for (std::size_t i = 0; i < v.size(); ++i) walk(v[i], *items, path + "[" + std::to_string(i) + "]", visit);
      return;
    }
    if (!v.is_object()) return;
    const Json* s = object_schema(v, schema);
    if (!s) return;
    const bool is_map = !s->contains("properties");
    visit(path, v, *s, is_map);
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (s->contains("properties") && (*s)["properties"].contains(it.key())) {
        walk(*it, (*s)["properties"][it.key()], child(path, it.key()), visit);
      } else if (s->contains("additionalProperties") && (*s)["additionalProperties"].is_object()) {
        walk(*it, (*s)["additionalProperties"], child(path, it.key()), visit);
      }
    }
  }

  Json root_;
};

}  // namespace krug::test
