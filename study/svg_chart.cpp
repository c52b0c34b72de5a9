#include "study/svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dem::study {
namespace {

// A point the chart can place: finite and not so large that the axes' spans overflow.
bool placeable(double x, double y) { return std::abs(x) <= 1e300 && std::abs(y) <= 1e300; }

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// A tick's label: 4 significant digits, an exponent without its '+' and leading zeros (4e6, not
// 4e+06), so that a study's values in pascals fit under their ticks.
std::string tick_label(double v) {
  std::string text = fmt(v);
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = !exponent.empty() && exponent[0] == '-';
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.erase(0, 1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

// Round tick steps (1, 2, 5 x 10^k) covering [lo, hi].
std::vector<double> ticks(double lo, double hi) {
  const double span = hi - lo;
  const double raw = span / 5;
  const double unit = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / unit < 1.5 ? unit : raw / unit < 3.5 ? 2 * unit : raw / unit < 7.5 ? 5 * unit : 10 * unit;
  std::vector<double> out;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * span && out.size() < 50; t += step)
    out.push_back(std::abs(t) < 1e-12 * span ? 0 : t);
  return out;
}

// Ten colours (matplotlib's tab10); past ten, the colours again dashed, then dotted.
const char* kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                          "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
const char* kDashes[] = {"", " stroke-dasharray=\"7 4\"", " stroke-dasharray=\"2 3\""};

const char* colour_of(std::size_t series) { return kColours[series % std::size(kColours)]; }
const char* dash_of(std::size_t series) { return kDashes[(series / std::size(kColours)) % std::size(kDashes)]; }

}  // namespace

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
    else if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
      out += ' ';  // control characters are not allowed in XML 1.0
    else
      out += c;
  }
  return out;
}

std::string chart_svg(const std::string& title, const std::vector<Panel>& panels) {
  const int panel_w = 360, panel_h = 260, margin_l = 70, margin_b = 50, margin_t = 40, gap = 30;
  const int columns = std::max(1, std::min<int>(3, static_cast<int>(panels.size())));
  const int panel_rows = std::max(1, (static_cast<int>(panels.size()) + columns - 1) / columns);
  // wide enough for the title too (16 px sans-serif: about 9 px a character), as one panel's is narrow
  const int width = std::max(columns * (panel_w + gap) + gap, 2 * gap + 9 * static_cast<int>(title.size()));
  // the named lines' legend under the panels: the first panel's names (an overlay's runs name the
  // same lines in every panel), laid out in rows
  std::vector<std::string> legend;
  for (const Panel& panel : panels) {
    for (const Series& series : panel.series) legend.push_back(series.name);
    if (std::any_of(legend.begin(), legend.end(), [](const std::string& n) { return !n.empty(); })) break;
    legend.clear();
  }
  std::vector<std::pair<double, int>> legend_at;  // each entry's x and row
  for (double x = gap; const std::string& name : legend) {
    const double w = 44 + 7 * static_cast<double>(name.size());
    const int row = legend_at.empty() ? 0 : legend_at.back().second;
    if (x > gap && x + w > width - gap) {
      legend_at.emplace_back(gap, row + 1);
      x = gap + w;
    } else {
      legend_at.emplace_back(x, row);
      x += w;
    }
  }
  const int panels_height = panel_rows * (panel_h + margin_t + gap) + 50;
  const int height = panels_height + (legend_at.empty() ? 0 : 18 * (legend_at.back().second + 1) + 4);
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(width) + "\" height=\"" +
                    std::to_string(height) + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + std::to_string(gap) + "\" y=\"24\" font-size=\"16\">" + xml_escaped(title) + "</text>\n";
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const Panel& panel = panels[k];
    const int ox = gap + static_cast<int>(k % columns) * (panel_w + gap);
    const int oy = 50 + static_cast<int>(k / columns) * (panel_h + margin_t + gap);
    const int px = ox + margin_l, pw = panel_w - margin_l, ph = panel_h - margin_b;
    const int py = oy + margin_t;
    svg += "<text x=\"" + std::to_string(ox) + "\" y=\"" + std::to_string(oy + 20) + "\" font-size=\"13\">" +
           xml_escaped(panel.title) + "</text>\n";
    svg += "<rect x=\"" + std::to_string(px) + "\" y=\"" + std::to_string(py) + "\" width=\"" + std::to_string(pw) +
           "\" height=\"" + std::to_string(ph) + "\" fill=\"none\" stroke=\"#888\"/>\n";
    bool any = false;
    double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
    for (const Series& s : panel.series)
      for (const auto& [x, y] : s.points) {
        if (!placeable(x, y)) continue;
        x0 = any ? std::min(x0, x) : x, x1 = any ? std::max(x1, x) : x;
        y0 = any ? std::min(y0, y) : y, y1 = any ? std::max(y1, y) : y;
        any = true;
      }
    if (!any) {
      svg += "<text x=\"" + std::to_string(px + 10) + "\" y=\"" + std::to_string(py + ph / 2) +
             "\" fill=\"#888\">no data yet</text>\n";
      continue;
    }
    if (y0 > 0 && y0 < 0.5 * y1) y0 = 0;  // from zero when that costs little room
    const double xpad = x1 > x0 ? 0.04 * (x1 - x0) : std::max(1.0, std::abs(x1) * 0.1);
    const double ypad = y1 > y0 ? 0.08 * (y1 - y0) : std::max(1e-300, std::abs(y1) * 0.1 + (y1 == 0 ? 1 : 0));
    x0 -= xpad, x1 += xpad, y1 += ypad;
    if (y0 != 0) y0 -= ypad;
    auto sx = [&](double x) { return px + (x - x0) / (x1 - x0) * pw; };
    auto sy = [&](double y) { return py + ph - (y - y0) / (y1 - y0) * ph; };
    for (double t : ticks(y0, y1))
      svg += "<line x1=\"" + fmt(px - 4) + "\" x2=\"" + fmt(px) + "\" y1=\"" + fmt(sy(t)) + "\" y2=\"" + fmt(sy(t)) +
             "\" stroke=\"#888\"/><text x=\"" + fmt(px - 6) + "\" y=\"" + fmt(sy(t) + 4) + "\" text-anchor=\"end\">" +
             tick_label(t) + "</text>\n";
    if (panel.x_categories.empty()) {
      // every tick marked; a label only where it clears the last one (about 7 px a character)
      double last_right = -1e300;
      for (double t : ticks(x0, x1)) {
        svg += "<line x1=\"" + fmt(sx(t)) + "\" x2=\"" + fmt(sx(t)) + "\" y1=\"" + fmt(py + ph) + "\" y2=\"" +
               fmt(py + ph + 4) + "\" stroke=\"#888\"/>";
        const std::string label = tick_label(t);
        const double half = 3.5 * static_cast<double>(label.size());
        if (sx(t) - half >= last_right + 6) {
          svg += "<text x=\"" + fmt(sx(t)) + "\" y=\"" + fmt(py + ph + 18) + "\" text-anchor=\"middle\">" + label +
                 "</text>";
          last_right = sx(t) + half;
        }
        svg += "\n";
      }
    } else {
      for (std::size_t c = 0; c < panel.x_categories.size(); ++c)
        svg += "<text x=\"" + fmt(sx(static_cast<double>(c))) + "\" y=\"" + fmt(py + ph + 18) +
               "\" text-anchor=\"middle\">" + xml_escaped(panel.x_categories[c]) + "</text>\n";
    }
    svg += "<text x=\"" + fmt(px + pw / 2.0) + "\" y=\"" + fmt(py + ph + 38) + "\" text-anchor=\"middle\">" +
           xml_escaped(panel.x_label) + "</text>\n";
    if (!panel.y_label.empty())
      svg += "<text transform=\"translate(" + fmt(ox + 12) + "," + fmt(py + ph / 2.0) +
             ") rotate(-90)\" text-anchor=\"middle\">" + xml_escaped(panel.y_label) + "</text>\n";
    for (std::size_t s = 0; s < panel.series.size(); ++s) {
      const Series& series = panel.series[s];
      const char* colour = colour_of(s);
      if (series.line) {
        std::string line;
        for (const auto& [x, y] : series.points) {
          if (!placeable(x, y)) continue;
          if (!line.empty()) line += ' ';
          line += fmt(sx(x)) + "," + fmt(sy(y));
        }
        svg += "<polyline points=\"" + line + "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"2\"" +
               dash_of(s) + "/>\n";
      }
      if (series.markers)
        for (const auto& [x, y] : series.points)
          if (placeable(x, y))
            svg += "<circle cx=\"" + fmt(sx(x)) + "\" cy=\"" + fmt(sy(y)) + "\" r=\"3.5\" fill=\"" + colour +
                   "\" fill-opacity=\"0.8\"/>\n";
    }
  }
  for (std::size_t k = 0; k < legend.size(); ++k) {
    if (legend[k].empty()) continue;
    const double lx = legend_at[k].first, ly = panels_height - 8 + 18 * legend_at[k].second;
    svg += "<line x1=\"" + fmt(lx) + "\" x2=\"" + fmt(lx + 24) + "\" y1=\"" + fmt(ly - 4) + "\" y2=\"" + fmt(ly - 4) +
           "\" stroke=\"" + colour_of(k) + "\" stroke-width=\"2\"" + dash_of(k) + "/><text x=\"" + fmt(lx + 30) +
           "\" y=\"" + fmt(ly) + "\">" + xml_escaped(legend[k]) + "</text>\n";
  }
  svg += "</svg>\n";
  return svg;
}

std::string svg_pixels(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

std::string svg_number(double v) { return fmt(v); }

double scale_bar_length(double span) {
  const double raw = span / 4;
  const double unit = std::pow(10.0, std::floor(std::log10(raw)));
  return raw / unit >= 5 ? 5 * unit : raw / unit >= 2 ? 2 * unit : unit;
}

std::string svg_figure_title(const std::string& title, int gap) {
  return "<text x=\"" + std::to_string(gap) + "\" y=\"24\" font-size=\"16\">" + xml_escaped(title) + "</text>\n";
}

CellOrigin grid_cell(std::size_t k, int columns, double cell_w, double cell_h, int gap) {
  const std::size_t column = k % static_cast<std::size_t>(columns), row = k / static_cast<std::size_t>(columns);
  return {gap + static_cast<double>(column) * cell_w, 50 + static_cast<double>(row) * cell_h};
}

}  // namespace dem::study
