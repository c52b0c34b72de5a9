// A small SVG chart: panels side by side, each with its title, axes with round ticks, and series of
// points (markers, a joining line, or both). Studies' figures and `dem plot` draw with it.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace dem::study {

struct Series {
  std::vector<std::pair<double, double>> points;
  bool line = true;      // joined in the given order
  bool markers = false;  // a dot at each point
  std::string name;      // in the panel's legend; no legend when no series has one
};

struct Panel {
  std::string title;
  std::string x_label, y_label;
  std::vector<Series> series;
  // x tick labels in place of numbers (a study's non-numeric values): the label of x = k is labels[k]
  std::vector<std::string> x_categories;
};

// The chart, up to three panels a row; a panel without points says so. Points that are not finite or
// beyond 1e300 (whose spans would overflow) are left out.
std::string chart_svg(const std::string& title, const std::vector<Panel>& panels);

// Text for SVG: <, >, & and " escaped.
std::string xml_escaped(const std::string& text);

// Numbers in the figures: a coordinate to a tenth of a pixel ("12.3"), a value to four significant
// digits ("0.1234", "5.6e+07").
std::string svg_pixels(double v);
std::string svg_number(double v);

// The largest round length (1, 2, 5 x 10^k) at most a quarter of `span`: a drawing's scale bar.
double scale_bar_length(double span);

// A figure of drawings in a grid (dem chains, dem deposits): its title line, and where the k-th
// drawing's cell begins, `columns` a row of cells w x h, `gap` from the left, under the title.
std::string svg_figure_title(const std::string& title, int gap);
struct CellOrigin {
  double x = 0, y = 0;
};
CellOrigin grid_cell(std::size_t k, int columns, double cell_w, double cell_h, int gap);

}  // namespace dem::study
