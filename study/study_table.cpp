#include "study/study_table.hpp"

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
    const bool numbers = std::all_of(value.begin(), value.end(), [](const json& v) { return v.is_number(); });
    if (!numbers && key != "loadedWalls") return;  // cycles and size bins: the JSON table has them
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

std::string xml_escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// A result of a row by dotted name, when it is a number.
std::optional<double> number_at(const StudyRow& row, const std::string& key) {
  if (row.results.is_null()) return std::nullopt;
  for (const auto& [name, value] : flatten(row.results))
    if (name == key && value.is_number()) return value.get<double>();
  return std::nullopt;
}

// Round tick steps (1, 2, 5 x 10^k) covering [lo, hi].
std::vector<double> ticks(double lo, double hi) {
  const double span = hi - lo;
  const double raw = span / 5;
  const double unit = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / unit < 1.5 ? unit : raw / unit < 3.5 ? 2 * unit : raw / unit < 7.5 ? 5 * unit : 10 * unit;
  std::vector<double> out;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * span; t += step)
    out.push_back(std::abs(t) < 1e-12 * span ? 0 : t);
  return out;
}

}  // namespace

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
  for (const StudyParameter& p : plan.parameters) csv += "," + csv_field(p.path);
  csv += ",state,error";
  for (const std::string& c : columns) csv += "," + csv_field(c);
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
    csv += "," + csv_field(row.state) + "," + csv_field(row.error);
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

  const int panel_w = 360, panel_h = 260, margin_l = 70, margin_b = 50, margin_t = 40, gap = 30;
  const int columns = std::min<int>(3, static_cast<int>(keys.size()));
  const int panel_rows = (static_cast<int>(keys.size()) + columns - 1) / columns;
  const int width = columns * (panel_w + gap) + gap, height = panel_rows * (panel_h + margin_t + gap) + 50;
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
                    std::to_string(height) + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + std::to_string(gap) + "\" y=\"24\" font-size=\"16\">" + xml_escaped(plan.name) + ": " +
         std::to_string(rows.size()) + " runs</text>\n";
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const int ox = gap + static_cast<int>(k % columns) * (panel_w + gap);
    const int oy = 50 + static_cast<int>(k / columns) * (panel_h + margin_t + gap);
    const int px = ox + margin_l, pw = panel_w - margin_l, ph = panel_h - margin_b;
    const int py = oy + margin_t;
    std::vector<std::pair<double, double>> points;
    for (const StudyRow& row : rows)
      if (const auto y = number_at(row, keys[k])) points.emplace_back(x_of(row), *y);
    svg += "<text x=\"" + std::to_string(ox) + "\" y=\"" + std::to_string(oy + 20) + "\" font-size=\"13\">" +
           xml_escaped(keys[k]) + "</text>\n";
    svg += "<rect x=\"" + std::to_string(px) + "\" y=\"" + std::to_string(py) + "\" width=\"" + std::to_string(pw) +
           "\" height=\"" + std::to_string(ph) + "\" fill=\"none\" stroke=\"#888\"/>\n";
    if (points.empty()) {
      svg += "<text x=\"" + std::to_string(px + 10) + "\" y=\"" + std::to_string(py + ph / 2) +
             "\" fill=\"#888\">no run has this result yet</text>\n";
      continue;
    }
    double x0 = points[0].first, x1 = x0, y0 = points[0].second, y1 = y0;
    for (const auto& [x, y] : points) {
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    if (y0 > 0 && y0 < 0.5 * y1) y0 = 0;  // from zero when that costs little room
    const double xpad = x1 > x0 ? 0.06 * (x1 - x0) : 1,
                 ypad = y1 > y0 ? 0.08 * (y1 - y0) : std::max(1.0, std::abs(y1) * 0.1);
    x0 -= xpad, x1 += xpad, y1 += ypad;
    if (y0 != 0) y0 -= ypad;
    auto sx = [&](double x) { return px + (x - x0) / (x1 - x0) * pw; };
    auto sy = [&](double y) { return py + ph - (y - y0) / (y1 - y0) * ph; };
    for (double t : ticks(y0, y1))
      svg += "<line x1=\"" + fmt(px - 4) + "\" x2=\"" + fmt(px) + "\" y1=\"" + fmt(sy(t)) + "\" y2=\"" + fmt(sy(t)) +
             "\" stroke=\"#888\"/><text x=\"" + fmt(px - 6) + "\" y=\"" + fmt(sy(t) + 4) + "\" text-anchor=\"end\">" +
             fmt(t) + "</text>\n";
    if (numeric) {
      for (double t : ticks(x0, x1))
        svg += "<line x1=\"" + fmt(sx(t)) + "\" x2=\"" + fmt(sx(t)) + "\" y1=\"" + fmt(py + ph) + "\" y2=\"" +
               fmt(py + ph + 4) + "\" stroke=\"#888\"/><text x=\"" + fmt(sx(t)) + "\" y=\"" + fmt(py + ph + 18) +
               "\" text-anchor=\"middle\">" + fmt(t) + "</text>\n";
    } else {
      for (std::size_t d = 0; d < distinct.size(); ++d)
        svg += "<text x=\"" + fmt(sx(static_cast<double>(d))) + "\" y=\"" + fmt(py + ph + 18) +
               "\" text-anchor=\"middle\">" +
               xml_escaped(distinct[d].is_string() ? distinct[d].get<std::string>() : distinct[d].dump()) + "</text>\n";
    }
    svg += "<text x=\"" + fmt(px + pw / 2.0) + "\" y=\"" + fmt(py + ph + 38) + "\" text-anchor=\"middle\">" +
           xml_escaped(x_name) + "</text>\n";
    // the mean at each x, joined
    std::map<double, std::pair<double, int>> means;
    for (const auto& [x, y] : points) {
      means[x].first += y;
      ++means[x].second;
    }
    std::string line;
    for (const auto& [x, sum] : means) {
      if (!line.empty()) line += ' ';
      line += fmt(sx(x)) + "," + fmt(sy(sum.first / sum.second));
    }
    svg += "<polyline points=\"" + line + "\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"2\"/>\n";
    for (const auto& [x, y] : points)
      svg += "<circle cx=\"" + fmt(sx(x)) + "\" cy=\"" + fmt(sy(y)) +
             "\" r=\"3.5\" fill=\"#ff7f0e\" fill-opacity=\"0.8\"/>\n";
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace dem::study
