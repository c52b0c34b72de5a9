#include "study/study_plan.hpp"

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "spec/json_field_key.hpp"

namespace dem::study {
namespace {

using json = nlohmann::json;

std::string joined(const std::vector<std::string>& problems) {
  std::string text = "invalid study:";
  for (const std::string& p : problems) text += "\n  " + p;
  return text;
}

// The value a pointer's parent leads to, or why there is none.
const json* parent_of(const json& base, const json::json_pointer& pointer, std::string& why) {
  const json::json_pointer parent = pointer.parent_pointer();
  bool there = false;
  try {
    there = base.contains(parent);
  } catch (const json::exception&) {  // an index past what a number holds
  }
  if (!there) {
    why = "the base spec has no " + (parent.empty() ? std::string("root") : "\"" + parent.to_string() + "\"");
    return nullptr;
  }
  const json& p = base.at(parent);
  const std::string& last = pointer.back();
  if (p.is_object()) return &p;
  if (p.is_array()) {
    std::size_t k = 0;
    try {
      std::size_t used = 0;
      k = std::stoul(last, &used);
      if (used != last.size()) throw std::invalid_argument(last);
    } catch (const std::exception&) {
      why = "\"" + parent.to_string() + "\" is a list: \"" + last + "\" is not an index of it";
      return nullptr;
    }
    if (k >= p.size()) {
      why = "\"" + parent.to_string() + "\" has " + std::to_string(p.size()) + " entries: there is no " + last;
      return nullptr;
    }
    return &p;
  }
  why = "\"" + parent.to_string() + "\" is a value, not an object or a list";
  return nullptr;
}

// The pointer to the field as the base spells it, segment by segment: protobuf takes a field by
// any spelling (json_field_key), so a study's path in another spelling than the base's would have
// set the field a second time (refused as given twice) or not found its parent. Past where the base
// ends, the path's own names.
json::json_pointer as_the_base_spells_it(const json& base, const json::json_pointer& pointer) {
  std::vector<std::string> tokens;
  for (json::json_pointer rest = pointer; !rest.empty(); rest.pop_back()) tokens.insert(tokens.begin(), rest.back());
  json::json_pointer spelled;
  const json* at = &base;
  for (const std::string& token : tokens) {
    std::string name = token;
    const json* next = nullptr;
    if (at != nullptr && at->is_object()) {
      if (const auto found = at->find(token); found != at->end()) {
        next = &*found;
      } else {
        for (auto it = at->begin(); it != at->end(); ++it)
          if (spec::json_field_key(it.key()) == spec::json_field_key(token)) {
            name = it.key();
            next = &*it;
            break;
          }
      }
    } else if (at != nullptr && at->is_array() && !token.empty() &&
               token.find_first_not_of("0123456789") == std::string::npos && token.size() < 10 &&
               std::stoul(token) < at->size()) {
      next = &(*at)[std::stoul(token)];
    }
    spelled /= name;
    at = next;
  }
  return spelled;
}

// The pointer with each name in its snake_case spelling: two spellings of one field are one field.
std::string one_spelling(const json::json_pointer& pointer) {
  std::string text;
  for (json::json_pointer rest = pointer; !rest.empty(); rest.pop_back())
    text.insert(0, "/" + spec::json_field_key(rest.back()));
  return text;
}

std::string cut_name(std::string name) {
  if (name.size() <= 200) return name;
  name.resize(197);
  while (!name.empty() && (static_cast<unsigned char>(name.back()) & 0xC0) == 0x80) name.pop_back();  // whole UTF-8
  if (!name.empty() && static_cast<unsigned char>(name.back()) >= 0xC0) name.pop_back();
  return name + "...";
}

}  // namespace

StudyError::StudyError(std::vector<std::string> problems)
    : std::runtime_error(joined(problems)), problems_(std::move(problems)) {}

std::string to_pointer(const std::string& path) {
  if (path.empty()) throw std::invalid_argument("an empty path");
  if (path[0] == '/') {
    (void)json::json_pointer(path);  // throws on a bad escape
    if (path.back() == '/' || path.find("//") != std::string::npos)
      throw std::invalid_argument("an empty name in \"" + path + "\"");
    return path;
  }
  // dotted: names split by '.', list entries as [k]
  std::string pointer;
  std::string name;
  auto end_name = [&] {
    if (name.empty()) throw std::invalid_argument("an empty name in \"" + path + "\"");
    std::string escaped;
    for (char c : name) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    pointer += "/" + escaped;
    name.clear();
  };
  for (std::size_t k = 0; k < path.size(); ++k) {
    const char c = path[k];
    if (c == '.') {
      if (k > 0 && path[k - 1] == ']') continue;
      end_name();
    } else if (c == '[') {
      if (!name.empty()) end_name();
      const std::size_t close = path.find(']', k);
      const std::string index = close == std::string::npos ? "" : path.substr(k + 1, close - k - 1);
      if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos)
        throw std::invalid_argument("\"" + path + "\": a list index is [0], [1], ...");
      pointer += "/" + index;
      k = close;
    } else {
      name += c;
    }
  }
  if (!name.empty())
    end_name();
  else if (path.back() == '.')
    throw std::invalid_argument("\"" + path + "\" ends with '.'");
  return pointer;
}

std::string describe_values(const std::vector<StudyParameter>& parameters, const std::vector<json>& values) {
  std::string text;
  for (std::size_t k = 0; k < parameters.size() && k < values.size(); ++k) {
    if (!text.empty()) text += ", ";
    // several fields set to one value read "a = b = 4e6", not "a = b=4e6"
    const bool several = parameters[k].pointers.size() > 1;
    text += parameters[k].path + (several ? " = " : "=") +
            (values[k].is_string() ? values[k].get<std::string>() : values[k].dump());
  }
  return text;
}

StudyPlan plan_study(const json& study, const json& base_from_file) {
  std::vector<std::string> problems;
  StudyPlan plan;
  if (!study.is_object()) throw StudyError({"a study is a JSON object (name, base, parameters, combine, plot)"});
  static const std::set<std::string> kKnown = {"name", "description", "base", "parameters", "combine", "plot"};
  for (const auto& [key, value] : study.items())
    if (!kKnown.count(key))
      problems.push_back(key + ": unknown field (a study has name, description, base, parameters, combine, plot)");

  const json* base = nullptr;
  if (!study.contains("base")) {
    problems.push_back("base: missing (the base job spec, inline or as the name of its file)");
  } else if (study["base"].is_object()) {
    base = &study["base"];
  } else if (study["base"].is_string()) {
    if (base_from_file.is_object())
      base = &base_from_file;
    else
      problems.push_back("base: the file \"" + study["base"].get<std::string>() + "\" holds no JSON object");
  } else {
    problems.push_back("base: a job spec (an object) or the name of its file (a string)");
  }

  if (study.contains("name") && !study["name"].is_string()) problems.push_back("name: a string");
  plan.name = study.value("name", json()).is_string() ? study["name"].get<std::string>() : "";
  if (plan.name.empty() && base && base->value("name", json()).is_string()) plan.name = (*base)["name"];
  if (plan.name.empty()) plan.name = "study";

  const std::string combine = study.value("combine", json("grid")).is_string() ? study.value("combine", "grid") : "";
  if (combine != "grid" && combine != "zip")
    problems.push_back("combine: \"grid\" (every combination of the values) or \"zip\" (the k-th value of each)");
  plan.grid = combine != "zip";

  if (study.contains("plot")) {
    if (!study["plot"].is_array())
      problems.push_back("plot: a list of results to plot (\"fragments.count\", ...)");
    else
      for (std::size_t k = 0; k < study["plot"].size(); ++k) {
        if (study["plot"][k].is_string() && !study["plot"][k].get<std::string>().empty())
          plan.plot.push_back(study["plot"][k]);
        else
          problems.push_back("plot[" + std::to_string(k) + "]: a result's dotted name (\"motion.runout.length\")");
      }
  }

  const json& parameters = study.contains("parameters") ? study["parameters"] : json();
  if (!parameters.is_array() || parameters.empty())
    problems.push_back("parameters: a non-empty list of {\"path\": ..., \"values\": [...]}");
  std::set<std::string> pointers;
  std::vector<std::pair<std::string, std::string>> varied;  // each field's pointer and where it is named
  for (std::size_t k = 0; parameters.is_array() && k < parameters.size(); ++k) {
    const std::string where = "parameters[" + std::to_string(k) + "]";
    const json& p = parameters[k];
    if (!p.is_object()) {
      problems.push_back(where + ": an object {\"path\": ..., \"values\": [...]}");
      continue;
    }
    for (const auto& [key, value] : p.items())
      if (key != "path" && key != "values") problems.push_back(where + "." + key + ": unknown field (path, values)");
    StudyParameter parameter;
    // one field, or several that take each value together
    std::vector<std::string> paths;
    if (p.contains("path") && p["path"].is_string()) paths.push_back(p["path"]);
    bool named = !paths.empty();
    if (p.contains("path") && p["path"].is_array() && !p["path"].empty()) {
      named = true;
      for (std::size_t f = 0; f < p["path"].size(); ++f)
        if (p["path"][f].is_string())
          paths.push_back(p["path"][f]);
        else
          problems.push_back(where + ".path[" + std::to_string(f) + "]: a field's path, as text (got " +
                             p["path"][f].dump() + ")");
      if (paths.size() < p["path"].size()) paths.clear();
    }
    if (!named)
      problems.push_back(where +
                         ".path: the field to vary, as \"bonds.tensileStrength\" or \"/bonds/tensileStrength\", or "
                         "a list of fields that take each value together");
    for (std::size_t f = 0; f < paths.size(); ++f) {
      const std::string& path = paths[f];
      const std::string field = p["path"].is_array() ? where + ".path[" + std::to_string(f) + "]" : where + ".path";
      if (f > 0) parameter.path += " = ";
      parameter.path += path;
      try {
        std::string pointer_text = to_pointer(path);
        std::string why;
        const json::json_pointer pointer =
            base ? as_the_base_spells_it(*base, json::json_pointer(pointer_text)) : json::json_pointer(pointer_text);
        pointer_text = pointer.to_string();
        const json* parent = base && !pointer.empty() ? parent_of(*base, pointer, why) : nullptr;
        if (pointer.empty())
          problems.push_back(field + ": \"" + path + "\" is the whole spec, not a field of it");
        else if (base && parent == nullptr)
          problems.push_back(field + ": \"" + path + "\": " + why);
        else if (!pointers.insert(one_spelling(pointer)).second)
          problems.push_back(field + ": \"" + path + "\" is varied twice");
        else
          for (const auto& [other, other_field] : varied) {
            // a field and one that holds it: the later would overwrite (part of) the earlier's value
            const std::string key = one_spelling(pointer);
            const bool holds = other.rfind(key + "/", 0) == 0, held = key.rfind(other + "/", 0) == 0;
            if (holds || held)
              problems.push_back(field + ": \"" + path + "\" " + (holds ? "holds" : "is part of") + " a field " +
                                 other_field + " varies: vary one of them");
          }
        varied.emplace_back(one_spelling(pointer), field);
        parameter.pointers.push_back(pointer_text);
      } catch (const std::exception& e) {
        problems.push_back(field + ": not a field's path: " + e.what());
      }
    }
    if (!p.contains("values") || !p["values"].is_array() || p["values"].empty())
      problems.push_back(where + ".values: a non-empty list of the values to run");
    else
      parameter.values = p["values"].get<std::vector<json>>();
    plan.parameters.push_back(std::move(parameter));
  }

  // how many runs
  double runs = plan.parameters.empty() ? 0 : 1;
  for (const StudyParameter& p : plan.parameters) {
    if (plan.grid)
      runs *= static_cast<double>(p.values.size());
    else if (p.values.size() != plan.parameters[0].values.size() && !p.values.empty() &&
             !plan.parameters[0].values.empty())
      problems.push_back(
          "parameters: \"combine\": \"zip\" takes the k-th value of each, so every list needs as many "
          "values (" +
          plan.parameters[0].path + " has " + std::to_string(plan.parameters[0].values.size()) + ", " + p.path +
          " has " + std::to_string(p.values.size()) + ")");
  }
  if (!plan.grid && !plan.parameters.empty()) runs = static_cast<double>(plan.parameters[0].values.size());
  if (runs > kMaxRuns) {
    char count[40];
    std::snprintf(count, sizeof count, "%.0f", runs);
    problems.push_back(std::string("parameters: ") + count + " runs, more than a study may have (" +
                       std::to_string(kMaxRuns) + ")");
  }
  if (!problems.empty()) throw StudyError(std::move(problems));

  const int count = static_cast<int>(runs);
  for (int r = 0; r < count; ++r) {
    StudyRun run;
    run.index = r + 1;
    run.spec = *base;
    int rest = r;
    // a grid counts like an odometer: the last parameter turns fastest
    std::vector<std::size_t> pick(plan.parameters.size());
    for (std::size_t k = plan.parameters.size(); k-- > 0;) {
      const std::size_t n = plan.parameters[k].values.size();
      pick[k] = plan.grid ? static_cast<std::size_t>(rest) % n : static_cast<std::size_t>(r);
      if (plan.grid) rest /= static_cast<int>(n);
    }
    for (std::size_t k = 0; k < plan.parameters.size(); ++k) {
      const StudyParameter& p = plan.parameters[k];
      for (const std::string& pointer : p.pointers) run.spec[json::json_pointer(pointer)] = p.values[pick[k]];
      run.values.push_back(p.values[pick[k]]);
    }
    if (!pointers.count("/name"))
      run.spec["name"] = cut_name(plan.name + " #" + std::to_string(run.index) + " (" +
                                  describe_values(plan.parameters, run.values) + ")");
    plan.runs.push_back(std::move(run));
  }
  return plan;
}

}  // namespace dem::study
