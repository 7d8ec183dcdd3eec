// Scenario edits by JSON path, a variant read from them, and the variants of a sweep, in memory
// (edit.hpp). Writing the variants and their table is output's (krug/output/sweep_files.hpp).
#include "krug/scenario/edit.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "json_reader.hpp"
#include "krug/core/error.hpp"

namespace krug::scenario {

namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;  // variants keep the file's key order

// One step of a path: a key or an array index.
struct Step {
  std::string key;
  long index = -1;  // >= 0: an array index
};

std::vector<Step> parse_path(const std::string& path) {
  std::vector<Step> steps;
  std::size_t i = 0;
  auto bad = [&](const std::string& why) -> std::vector<Step> {
    throw InputError(fmt::format("{}: {} (write a path like materials.steel.density or "
                                 "bodies[0].initial.velocity[0])", path, why));
  };
  while (i < path.size()) {
    if (path[i] == '[') {
      const auto close = path.find(']', i);
      if (close == std::string::npos) return bad("an unclosed [");
      const std::string digits = path.substr(i + 1, close - i - 1);
      if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) {
        return bad("an array index must be a number");
      }
      steps.push_back({"", std::stol(digits)});
      i = close + 1;
      if (i < path.size() && path[i] == '.') ++i;
    } else {
      const auto end = path.find_first_of(".[", i);
      const std::string key = path.substr(i, end == std::string::npos ? std::string::npos : end - i);
      if (key.empty()) return bad("an empty key");
      steps.push_back({key, -1});
      i = end == std::string::npos ? path.size() : end;
      if (i < path.size() && path[i] == '.') ++i;
    }
  }
  if (steps.empty()) return bad("an empty path");
  return steps;
}

void set_path(OrderedJson& document, const std::string& path, const OrderedJson& value) {
  const std::vector<Step> steps = parse_path(path);
  OrderedJson* at = &document;
  std::string where;
  for (std::size_t s = 0; s < steps.size(); ++s) {
    const Step& step = steps[s];
    const bool last = s + 1 == steps.size();
    if (step.index >= 0) {
      if (!at->is_array()) {
        throw InputError(fmt::format("{}: {} is not an array", path, where.empty() ? "(top level)" : where));
      }
      if (static_cast<std::size_t>(step.index) >= at->size()) {
        throw InputError(fmt::format("{}: {} has {} items", path, where, at->size()));
      }
      where += fmt::format("[{}]", step.index);
      at = &(*at)[static_cast<std::size_t>(step.index)];
    } else {
      if (at->is_string() && s == 2 && steps[0].key == "materials" && steps[0].index < 0) {
        *at = OrderedJson{{"base", at->get<std::string>()}};  // a library material: its values, overridden
      }
      if (!at->is_object()) {
        throw InputError(fmt::format("{}: {} is not an object", path, where.empty() ? "(top level)" : where));
      }
      where += (where.empty() ? "" : ".") + step.key;
      if (!at->contains(step.key)) {
        if (!last && steps[s + 1].index >= 0) {
          throw InputError(fmt::format("{}: {} does not exist", path, where));
        }
        (*at)[step.key] = OrderedJson::object();  // a default made explicit
      }
      at = &(*at)[step.key];
    }
    if (last) *at = value;
  }
}

// The value as JSON if it is JSON, else as a string (material names, models).
OrderedJson value_of(const std::string& text, const std::string& path) {
  check_document_shape(text, "the value for " + path);
  try {
    return OrderedJson::parse(text);
  } catch (const nlohmann::json::exception&) {
    return OrderedJson(text);
  }
}

std::string leaf_name(const std::string& path) {
  const std::vector<Step> steps = parse_path(path);
  std::string name;
  std::size_t s = steps.size();
  while (s > 0 && steps[s - 1].index >= 0) --s;  // indices after the last key
  name = s > 0 ? steps[s - 1].key : "item";
  for (std::size_t k = s; k < steps.size(); ++k) name += std::to_string(steps[k].index);
  return name;
}

std::string file_safe(const std::string& text) {
  std::string out;
  for (char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                    c == '-' || c == '+' || c == '_';
    out += ok ? c : '_';
  }
  return out.substr(0, 40);
}

// An edit's errors, with "--set " before them for the sweep's messages.
template <typename F>
auto as_set(F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(std::string("--set ") + e.what());
  }
}

}  // namespace

std::string edit_scenario(const std::string& text, const std::vector<ScenarioEdit>& edits, const std::string& origin) {
  OrderedJson document = parse_document<OrderedJson>(text, origin);
  for (const ScenarioEdit& edit : edits) set_path(document, edit.path, value_of(edit.value, edit.path));
  return document.dump(2) + "\n";
}

Scenario scenario_variant(const std::string& text, const std::vector<ScenarioEdit>& edits, const std::string& origin) {
  return parse_scenario(edit_scenario(text, edits, origin), origin);
}

SweepParameter parse_sweep_set(const std::string& argument) {
  const auto equals = argument.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 >= argument.size()) {
    throw InputError(fmt::format("--set {}: expected PATH=VALUE1,VALUE2,...", argument));
  }
  SweepParameter p;
  p.path = argument.substr(0, equals);
  (void)as_set([&] { return parse_path(p.path); });
  const std::string list = argument.substr(equals + 1);
  int depth = 0;
  bool in_string = false;
  std::string current;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const char c = list[i];
    if (in_string) {
      if (c == '\\' && i + 1 < list.size()) {
        current += c;
        current += list[++i];
        continue;
      }
      if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      --depth;
    } else if (c == ',' && depth == 0) {
      p.values.push_back(current);
      current.clear();
      continue;
    }
    current += c;
  }
  p.values.push_back(current);
  for (const std::string& v : p.values) {
    if (v.empty()) throw InputError(fmt::format("--set {}: an empty value", argument));
  }
  return p;
}

SweepPlan plan_sweep(const std::filesystem::path& scenario_file, const std::vector<SweepParameter>& parameters,
                     const std::filesystem::path& directory) {
  OrderedJson base = parse_document<OrderedJson>(read_text_file(scenario_file, "scenario file"), scenario_file.string());
  if (parameters.empty()) throw InputError("krug sweep: give at least one --set PATH=VALUE1,VALUE2,...");
  std::size_t count = 1;
  for (const SweepParameter& p : parameters) {
    count *= p.values.size();
    if (count > 100000) throw InputError("krug sweep: more than 100000 variants");
  }
  const std::string base_text = base.dump();
  std::vector<SweepVariant> variants;
  std::vector<std::string> texts;
  for (std::size_t v = 0; v < count; ++v) {
    SweepVariant variant;
    std::size_t rest = v;
    std::vector<std::size_t> choice(parameters.size());
    for (std::size_t k = parameters.size(); k-- > 0;) {  // last parameter varies fastest
      choice[k] = rest % parameters[k].values.size();
      rest /= parameters[k].values.size();
    }
    variant.name = fmt::format("{:03d}", v);
    std::vector<ScenarioEdit> edits;
    for (std::size_t k = 0; k < parameters.size(); ++k) {
      const std::string& text = parameters[k].values[choice[k]];
      const OrderedJson value = as_set([&] { return value_of(text, parameters[k].path); });
      variant.values.push_back(value.dump());
      edits.push_back({parameters[k].path, value.dump()});
      variant.name += fmt::format("_{}={}", file_safe(leaf_name(parameters[k].path)),
                                  file_safe(value.is_string() ? value.get<std::string>() : value.dump()));
    }
    // The title says which variant this is, so that no picture or log of the 400 m/s variant reads as
    // the base scenario's "at 800 m/s" (unless a --set gives the title itself).
    std::string settings;
    bool title_set = false;
    for (std::size_t k = 0; k < parameters.size(); ++k) {
      settings += fmt::format("{}{}={}", k == 0 ? "" : ", ", parameters[k].path, variant.values[k]);
      title_set = title_set || parameters[k].path == "title";
    }
    if (!title_set) {
      const std::string base_title = base.contains("title") && base["title"].is_string() ? base["title"].get<std::string>() : "";
      variant.title = fmt::format("{}{}sweep variant {}: {}", base_title, base_title.empty() ? "" : " - ", variant.name.substr(0, 3),
                                  settings);
      edits.push_back({"title", OrderedJson(variant.title).dump()});
    }
    variant.directory = directory / variant.name;
    variant.scenario = variant.directory / "scenario.json";
    std::string text = as_set([&] { return edit_scenario(base_text, edits, scenario_file.string()); });
    try {
      (void)parse_scenario(text, variant.scenario.string());
    } catch (const InputError& e) {
      throw InputError(fmt::format("krug sweep: variant {} is not a valid scenario: {}", variant.name, e.what()));
    }
    variants.push_back(variant);
    texts.push_back(std::move(text));
  }
  return {std::move(variants), std::move(texts)};
}

}  // namespace krug::scenario
