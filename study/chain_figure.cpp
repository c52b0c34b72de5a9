#include "study/chain_figure.hpp"

#include <algorithm>
#include <cmath>

#include "study/svg_chart.hpp"

namespace dem::study {
namespace {

bool drawable(const Point2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

struct DrawingExtent {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  void add(const Point2& p, double r = 0) {
    if (!drawable(p) || !std::isfinite(r)) return;
    x0 = std::min(x0, p.x - r), x1 = std::max(x1, p.x + r);
    y0 = std::min(y0, p.y - r), y1 = std::max(y1, p.y + r);
  }
  bool empty() const { return !(x1 >= x0 && y1 >= y0); }
};

}  // namespace

std::string chain_figure_svg(const ChainFigureText& text, const std::vector<ChainPanel>& panels) {
  DrawingExtent extent;
  double strongest = 0;
  for (const ChainPanel& panel : panels) {
    for (const ChainDisc& d : panel.discs) extent.add(d.centre, d.radius);
    for (const auto& outline : panel.outlines)
      for (const Point2& p : outline) extent.add(p);
    for (const ChainLine& c : panel.chains)
      if (std::isfinite(c.normal_force)) strongest = std::max(strongest, c.normal_force);
  }
  if (extent.empty()) extent = {0, 1, 0, 1};
  const double span_x = std::max(extent.x1 - extent.x0, 1e-300), span_y = std::max(extent.y1 - extent.y0, 1e-300);
  // each panel's drawing at most 300 px wide and 420 px tall, at one scale for all
  const double scale = std::min(300 / span_x, 420 / span_y);
  const double draw_w = span_x * scale, draw_h = span_y * scale;
  const int gap = 30, head = 28, foot = 40;
  const int columns = std::max(1, std::min<int>(4, static_cast<int>(panels.size())));
  const int rows = std::max(1, (static_cast<int>(panels.size()) + columns - 1) / columns);
  // room for a panel's title and scale bar (about 170 px) however narrow the scene
  const double cell_w = std::max(draw_w, 190.0) + gap, cell_h = head + draw_h + foot;
  // The strongest line is at most 0.6 of a typical particle across as drawn (the median disc), so
  // that a bed of small particles stays readable under its chains; at most 6 px.
  std::vector<double> diameters;
  for (const ChainPanel& panel : panels)
    for (const ChainDisc& d : panel.discs)
      if (std::isfinite(d.radius)) diameters.push_back(2 * d.radius * scale);
  double widest = 6;
  if (!diameters.empty()) {
    std::nth_element(diameters.begin(), diameters.begin() + diameters.size() / 2, diameters.end());
    widest = std::clamp(0.6 * diameters[diameters.size() / 2], 0.8, 6.0);
  }
  const double thinnest = std::min(0.4, widest / 4);
  const std::string legend =
      strongest > 0 ? "line width " + svg_number(thinnest) + " px + " + svg_number(widest - thinnest) +
                          " px × Fn / Fmax (" + svg_number(widest) + " px at Fn = " + svg_number(strongest) +
                          " N, the strongest contact); contacts under " + svg_number(100 * kWeakestChainDrawn) +
                          "% of it, and pulling ones, not drawn"
                    : std::string("no contact carries a force");
  // wide enough for the title (16 px: about 9 px a character) and the legend (12 px: about 7)
  const double width = std::max({gap + columns * cell_w, 2.0 * gap + 9.0 * static_cast<double>(text.title.size()),
                                 gap + 38 + 6.5 * static_cast<double>(legend.size())});
  const double height = 50 + rows * cell_h + 40;

  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + svg_pixels(width) + "\" height=\"" +
                    svg_pixels(height) + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += svg_figure_title(text.title, gap);
  for (std::size_t k = 0; k < panels.size(); ++k) {
    const ChainPanel& panel = panels[k];
    // (named copies, not a structured binding: clang before C++20 cannot capture one in a lambda)
    const CellOrigin cell = grid_cell(k, columns, cell_w, cell_h, gap);
    const double ox = cell.x, oy = cell.y;
    const double top = oy + head;
    auto sx = [&](double x) { return ox + (x - extent.x0) * scale; };
    auto sy = [&](double y) { return top + draw_h - (y - extent.y0) * scale; };
    svg += "<text x=\"" + svg_pixels(ox) + "\" y=\"" + svg_pixels(oy + 16) + "\" font-size=\"13\">" +
           xml_escaped(panel.title) + "</text>\n";
    svg += "<g fill=\"#9aa7b4\" fill-opacity=\"0.18\" stroke=\"none\">\n";
    for (const ChainDisc& d : panel.discs)
      if (drawable(d.centre) && std::isfinite(d.radius))
        svg += "<circle cx=\"" + svg_pixels(sx(d.centre.x)) + "\" cy=\"" + svg_pixels(sy(d.centre.y)) + "\" r=\"" +
               svg_pixels(std::max(0.5, d.radius * scale)) + "\"/>\n";
    svg += "</g>\n";
    for (const auto& outline : panel.outlines) {
      std::string points;
      for (const Point2& p : outline)
        if (drawable(p)) {
          if (!points.empty()) points += ' ';
          points += svg_pixels(sx(p.x)) + "," + svg_pixels(sy(p.y));
        }
      if (!points.empty())
        svg += "<polygon points=\"" + points + "\" fill=\"none\" stroke=\"#444\" stroke-width=\"1.5\"/>\n";
    }
    // weakest first, so the strong chains are drawn over them
    std::vector<const ChainLine*> drawn;
    for (const ChainLine& c : panel.chains)
      if (drawable(c.a) && drawable(c.b) && std::isfinite(c.normal_force) && strongest > 0 &&
          c.normal_force >= kWeakestChainDrawn * strongest)
        drawn.push_back(&c);
    std::stable_sort(drawn.begin(), drawn.end(),
                     [](const ChainLine* p, const ChainLine* q) { return p->normal_force < q->normal_force; });
    svg += "<g stroke=\"#b2182b\" stroke-linecap=\"round\">\n";
    for (const ChainLine* c : drawn) {
      const double share = c->normal_force / strongest;
      svg += "<line x1=\"" + svg_pixels(sx(c->a.x)) + "\" y1=\"" + svg_pixels(sy(c->a.y)) + "\" x2=\"" +
             svg_pixels(sx(c->b.x)) + "\" y2=\"" + svg_pixels(sy(c->b.y)) + "\" stroke-width=\"" +
             svg_number(thinnest + (widest - thinnest) * share) + "\" stroke-opacity=\"" +
             svg_number(0.35 + 0.65 * share) + "\"/>\n";
    }
    svg += "</g>\n";
    // a scale bar under the drawing, with the plane's axes named
    const double bar = scale_bar_length(span_x);
    const double bar_y = top + draw_h + 16;
    svg += "<line x1=\"" + svg_pixels(ox) + "\" y1=\"" + svg_pixels(bar_y) + "\" x2=\"" + svg_pixels(ox + bar * scale) +
           "\" y2=\"" + svg_pixels(bar_y) + "\" stroke=\"#222\" stroke-width=\"2\"/>\n";
    svg += "<text x=\"" + svg_pixels(ox + bar * scale + 6) + "\" y=\"" + svg_pixels(bar_y + 4) + "\">" +
           svg_number(bar) + " " + xml_escaped(text.unit.empty() ? "length unit" : text.unit) + "</text>\n";
    svg += "<text x=\"" + svg_pixels(ox + draw_w) + "\" y=\"" + svg_pixels(bar_y + 4) +
           "\" text-anchor=\"end\" fill=\"#666\">" + xml_escaped(text.x_label + " →, " + text.y_label + " ↑") +
           "</text>\n";
  }
  const double legend_y = height - 18;
  svg += "<line x1=\"" + std::to_string(gap) + "\" y1=\"" + svg_pixels(legend_y - 4) + "\" x2=\"" +
         std::to_string(gap + 30) + "\" y2=\"" + svg_pixels(legend_y - 4) + "\" stroke=\"#b2182b\" stroke-width=\"" +
         svg_number(widest) + "\"/>\n";
  svg += "<text x=\"" + std::to_string(gap + 38) + "\" y=\"" + svg_pixels(legend_y) + "\">" + xml_escaped(legend) +
         "</text>\n";
  svg += "</svg>\n";
  return svg;
}

}  // namespace dem::study
