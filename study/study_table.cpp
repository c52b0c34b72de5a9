#include "study/study_table.hpp"

#include "study/svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>

namespace dem::study {
namespace {

using json = nlohmann::json;

void flatten_into(const json& value, const std::string& key, std::vector<std::pair<std::string, json>>& out) {
  if (value.is_object()) {
    for (const auto& [name, inner] : value.items()) flatten_into(inner, key.empty() ? name : key + "." + name, out);
  } else if (value.is_array()) {
    // A list of numbers, or one of results.json's lists of walls and sources (a column each field of
    // each); other lists of objects (cycles, size bins, quantile rows) stay in the JSON table.
    const bool numbers = std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); });
    if (!numbers && key != "loadedWalls" && key != "sources") return;
    for (std::size_t k = 0; k < value.size(); ++k) flatten_into(value[k], key + "." + std::to_string(k), out);
  } else {
    out.emplace_back(key, value);
  }
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csv_value(const json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return csv_field(v.get<std::string>());
  return csv_field(v.dump());
}

}  // namespace

std::optional<json> result_at(const StudyRow& row, const std::string& key) {
  if (!row.results.is_object()) return std::nullopt;
  for (auto& [name, value] : flatten(row.results))
    if (name == key) return std::move(value);
  return std::nullopt;
}

std::optional<double> number_at(const StudyRow& row, const std::string& key) {
  const std::optional<json> value = result_at(row, key);
  if (!value || !value->is_number()) return std::nullopt;
  return value->get<double>();
}

std::string run_label(const StudyPlan& plan, int index, const std::vector<json>& values) {
  return "run " + std::to_string(index) + " (" + describe_values(plan.parameters, values) + ")";
}

StudyRow row_of(const StudyRun& run) {
  StudyRow row;
  row.index = run.index;
  row.values = run.values;
  row.state = "not run";
  return row;
}

std::vector<std::pair<std::string, json>> flatten(const json& results) {
  std::vector<std::pair<std::string, json>> out;
  flatten_into(results, "", out);
  return out;
}

std::vector<std::string> plot_keys(const StudyPlan& plan, const std::vector<StudyRow>& rows) {
  if (!plan.plot.empty()) return plan.plot;
  static const char* kPreferred[] = {"motion.runout.length",
                                     "motion.deposit.area",
                                     "fragments.count",
                                     "fragments.crushedMassFraction",
                                     "loadedWalls.0.permanentSettlement",
                                     "loadedWalls.0.resilient"};
  std::vector<std::string> keys;
  for (const char* key : kPreferred)
    if (std::any_of(rows.begin(), rows.end(), [&](const StudyRow& r) { return number_at(r, key).has_value(); }))
      keys.emplace_back(key);
  if (keys.empty()) keys.emplace_back("runSeconds");
  return keys;
}

json table_json(const StudyPlan& plan, const std::vector<StudyRow>& rows) {
  json parameters = json::array();
  for (const StudyParameter& p : plan.parameters) parameters.push_back(p.path);
  json out_rows = json::array();
  for (const StudyRow& row : rows) {
    json values = json::object();
    for (std::size_t k = 0; k < plan.parameters.size() && k < row.values.size(); ++k)
      values[plan.parameters[k].path] = row.values[k];
    json r = {{"run", row.index}, {"parameters", values}, {"state", row.state}, {"results", row.results}};
    if (row.job >= 0) r["job"] = row.job;
    if (!row.error.empty()) r["error"] = row.error;
    out_rows.push_back(std::move(r));
  }
  return {{"name", plan.name}, {"parameters", parameters}, {"plot", plot_keys(plan, rows)}, {"rows", out_rows}};
}

std::string table_csv(const StudyPlan& plan, const std::vector<StudyRow>& rows) {
  // the columns: every result any row has, in the order they first appear
  std::vector<std::string> columns;
  std::set<std::string> seen;
  std::vector<std::map<std::string, json>> flat(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (auto& [key, value] : flatten(rows[r].results.is_null() ? json::object() : rows[r].results)) {
      if (seen.insert(key).second) columns.push_back(key);
      flat[r][key] = value;
    }
  std::string csv = "run";
  const bool jobs = std::any_of(rows.begin(), rows.end(), [](const StudyRow& r) { return r.job >= 0; });
  if (jobs) csv += ",job";
  // (',' then the field: GCC 12 warns falsely of overlapping copies in "," + a temporary string)
  for (const StudyParameter& p : plan.parameters) (csv += ',') += csv_field(p.path);
  csv += ",state,error";
  for (const std::string& c : columns) (csv += ',') += csv_field(c);
  csv += "\n";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const StudyRow& row = rows[r];
    csv += std::to_string(row.index);
    if (jobs) {
      csv += ',';
      if (row.job >= 0) csv += std::to_string(row.job);
    }
    for (std::size_t k = 0; k < plan.parameters.size(); ++k) {
      csv += ',';
      if (k < row.values.size()) csv += csv_value(row.values[k]);
    }
    ((((csv += ',') += csv_field(row.state)) += ',') += csv_field(row.error));
    for (const std::string& c : columns) {
      const auto found = flat[r].find(c);
      csv += ',';
      if (found != flat[r].end()) csv += csv_value(found->second);
    }
    csv += "\n";
  }
  return csv;
}

std::string figure_svg(const StudyPlan& plan, const std::vector<StudyRow>& rows) {
  const std::vector<std::string> keys = plot_keys(plan, rows);
  const std::string x_name = plan.parameters.empty() ? "run" : plan.parameters[0].path;
  // x: the first parameter's value when all are numbers, else its position in the list of values
  std::vector<json> distinct;
  for (const StudyRow& row : rows)
    if (!row.values.empty() && std::find(distinct.begin(), distinct.end(), row.values[0]) == distinct.end())
      distinct.push_back(row.values[0]);
  const bool numeric =
      !distinct.empty() && std::all_of(distinct.begin(), distinct.end(), [](const json& v) { return v.is_number(); });
  auto x_of = [&](const StudyRow& row) -> double {
    if (row.values.empty()) return row.index;
    if (numeric) return row.values[0].get<double>();
    return static_cast<double>(std::find(distinct.begin(), distinct.end(), row.values[0]) - distinct.begin());
  };
  std::vector<Panel> panels;
  for (const std::string& key : keys) {
    Panel panel;
    panel.title = key;
    panel.x_label = x_name;
    if (!numeric)
      for (const json& v : distinct) panel.x_categories.push_back(v.is_string() ? v.get<std::string>() : v.dump());
    Series runs{{}, false, true, ""}, means{{}, true, false, ""};
    std::map<double, std::pair<double, int>> sums;  // the mean at each x, joined
    for (const StudyRow& row : rows)
      if (const auto y = number_at(row, key); y && row.state == "succeeded") {
        runs.points.emplace_back(x_of(row), *y);
        sums[x_of(row)].first += *y;
        ++sums[x_of(row)].second;
      }
    for (const auto& [x, sum] : sums) means.points.emplace_back(x, sum.first / sum.second);
    panel.series = {means, runs};
    panels.push_back(std::move(panel));
  }
  // a run that failed or was cancelled is not a point: its numbers (a stopped run's results) are not
  // an outcome of its values, and would pull the mean
  const auto drawn = std::count_if(rows.begin(), rows.end(), [](const StudyRow& r) { return r.state == "succeeded"; });
  const std::string runs = std::to_string(rows.size()) + " runs";
  return chart_svg(plan.name + ": " +
                       (drawn == static_cast<std::ptrdiff_t>(rows.size())
                            ? runs
                            : std::to_string(drawn) + " of " + runs + " (those that succeeded)"),
                   panels);
}

}  // namespace dem::study
