#include "study/deposit_figure.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "study/svg_chart.hpp"

namespace dem::study {
namespace {

bool finite_point(const Point2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

// The largest pieces' colours (matplotlib's tab10 without its grey and olive, which the small pieces
// and the terrain use), then the small pieces' and the loose spheres'.
constexpr const char* kPieceColours[kRankedPieces] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                                      "#9467bd", "#17becf", "#8c564b", "#e377c2"};
constexpr const char* kSmallPieceColour = "#c8ad7f";
constexpr const char* kLooseSphereColour = "#8a8a8a";

// Each piece's class: 0 to kRankedPieces - 1 for the largest (by sphere count among the panel's
// pieces; ties: the lower number first), kRankedPieces for a smaller piece of two spheres or more,
// kRankedPieces + 1 for a sphere alone.
std::map<int, int> piece_classes(const std::vector<DepositDisc>& discs) {
  std::map<int, int> count;
  for (const DepositDisc& d : discs) ++count[d.piece];
  std::vector<std::pair<int, int>> ranked(count.begin(), count.end());
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& p, const auto& q) { return p.second > q.second; });
  std::map<int, int> classes;
  for (std::size_t k = 0; k < ranked.size(); ++k)
    classes[ranked[k].first] = ranked[k].second == 1 ? kRankedPieces + 1
                               : k < kRankedPieces   ? static_cast<int>(k)
                                                     : kRankedPieces;
  return classes;
}

const char* class_colour(int piece_class) {
  return piece_class < kRankedPieces    ? kPieceColours[piece_class]
         : piece_class == kRankedPieces ? kSmallPieceColour
                                        : kLooseSphereColour;
}

}  // namespace

double contour_interval(double relief) {
  if (!(relief > 0) || !std::isfinite(relief)) return 1;
  // the largest round interval that still gives at least 10 levels
  const double raw = relief / 10;
  const double unit = std::pow(10.0, std::floor(std::log10(raw)));
  return raw / unit >= 5 ? 5 * unit : raw / unit >= 2 ? 2 * unit : unit;
}

std::vector<ContourSegment> contour_segments(const std::vector<MeshTriangle>& triangles, int right, int up, int depth,
                                             double interval) {
  std::vector<ContourSegment> out;
  if (!(interval > 0) || !std::isfinite(interval)) return out;
  for (const MeshTriangle& t : triangles) {
    const auto& c = t.corners;
    const double lo = std::min({c[0][depth], c[1][depth], c[2][depth]});
    const double hi = std::max({c[0][depth], c[1][depth], c[2][depth]});
    if (!std::isfinite(lo) || !std::isfinite(hi)) continue;
    for (double k = std::ceil(lo / interval); k * interval <= hi; ++k) {
      const double level = k * interval;
      // a corner at the level counts as above it, so a level through a corner is drawn once
      Point2 ends[2];
      int found = 0;
      for (int e = 0; e < 3 && found < 2; ++e) {
        const auto& p = c[e];
        const auto& q = c[(e + 1) % 3];
        if ((p[depth] >= level) == (q[depth] >= level)) continue;
        const double s = (level - p[depth]) / (q[depth] - p[depth]);
        ends[found++] = {p[right] + s * (q[right] - p[right]), p[up] + s * (q[up] - p[up])};
      }
      // (a level through a corner alone cuts the triangle in a point: nothing to draw)
      const bool line = found == 2 && (ends[0].x != ends[1].x || ends[0].y != ends[1].y);
      if (line) out.push_back({ends[0], ends[1], std::fmod(std::abs(k), 5.0) == 0});
    }
  }
  return out;
}

std::string deposit_figure_svg(const DepositFigureText& text, const std::vector<DepositPanel>& panels,
                               const std::vector<ContourSegment>& contours) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const DepositPanel& panel : panels)
    for (const DepositDisc& d : panel.discs)
      if (finite_point(d.centre) && std::isfinite(d.radius)) {
        x0 = std::min(x0, d.centre.x - d.radius), x1 = std::max(x1, d.centre.x + d.radius);
        y0 = std::min(y0, d.centre.y - d.radius), y1 = std::max(y1, d.centre.y + d.radius);
      }
  // a margin of a twentieth of the larger side, so the deposits' edges sit on the terrain drawn
  if (x1 >= x0 && y1 >= y0) {
    const double margin = 0.05 * std::max({x1 - x0, y1 - y0, 1e-300});
    x0 -= margin, x1 += margin, y0 -= margin, y1 += margin;
  }
  // the whole terrain, when its contours are drawn: a deposit is seen where it lies on the map
  for (const ContourSegment& s : contours)
    for (const Point2& p : {s.a, s.b})
      if (finite_point(p))
        x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  if (!(x1 > x0 && y1 > y0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  const double span_x = x1 - x0, span_y = y1 - y0;
  const double scale = std::min(240 / span_x, 420 / span_y);  // each drawing at most 240 x 420 px
  const double draw_w = span_x * scale, draw_h = span_y * scale;
  const int gap = 30, head = 42, foot = 34;
  const int columns = std::max(1, std::min<int>(5, static_cast<int>(panels.size())));
  const int rows = std::max(1, (static_cast<int>(panels.size()) + columns - 1) / columns);
  const double cell_w = std::max(draw_w, 170.0) + gap, cell_h = head + draw_h + foot;
  std::string legend_tail = "smaller pieces; loose spheres";
  if (!text.contours.empty()) legend_tail += "; " + text.contours;
  const double width = std::max({gap + columns * cell_w, 2.0 * gap + 9.0 * static_cast<double>(text.title.size()),
                                 gap + 8 * 14 + 150 + 6.5 * static_cast<double>(legend_tail.size())});
  const double height = 50 + rows * cell_h + 36;

  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"" +
                    svg_pixels(width) + "\" height=\"" + svg_pixels(height) +
                    "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // the contours once, in a drawing's own pixels, and each panel shows them through its window
  svg += "<defs>\n<clipPath id=\"drawing\"><rect width=\"" + svg_pixels(draw_w) + "\" height=\"" + svg_pixels(draw_h) +
         "\"/></clipPath>\n<g id=\"terrain\" fill=\"none\">\n";
  std::string minor, major;
  for (const ContourSegment& s : contours) {
    if (!finite_point(s.a) || !finite_point(s.b)) continue;
    std::string& path = s.major ? major : minor;
    path += 'M';
    path += svg_pixels((s.a.x - x0) * scale) + " " + svg_pixels((y1 - s.a.y) * scale) + "L" +
            svg_pixels((s.b.x - x0) * scale) + " " + svg_pixels((y1 - s.b.y) * scale);
  }
  if (!minor.empty()) svg += "<path stroke=\"#b9b28f\" stroke-width=\"0.6\" d=\"" + minor + "\"/>\n";
  if (!major.empty()) svg += "<path stroke=\"#8f875f\" stroke-width=\"1.1\" d=\"" + major + "\"/>\n";
  svg += "</g>\n</defs>\n";
  svg += svg_figure_title(text.title, gap);

  for (std::size_t k = 0; k < panels.size(); ++k) {
    const DepositPanel& panel = panels[k];
    // (named copies, not a structured binding: clang before C++20 cannot capture one in a lambda)
    const CellOrigin cell = grid_cell(k, columns, cell_w, cell_h, gap);
    const double ox = cell.x, oy = cell.y;
    const double top = oy + head;
    const std::map<int, int> classes = piece_classes(panel.discs);
    svg += "<text x=\"" + svg_pixels(ox) + "\" y=\"" + svg_pixels(oy + 14) + "\" font-size=\"13\">" +
           xml_escaped(panel.title) + "</text>\n";
    svg += "<text x=\"" + svg_pixels(ox) + "\" y=\"" + svg_pixels(oy + 30) + "\" fill=\"#555\">" +
           xml_escaped(panel.subtitle) + "</text>\n";
    svg += "<g transform=\"translate(" + svg_pixels(ox) + "," + svg_pixels(top) + ")\" clip-path=\"url(#drawing)\">\n";
    svg += "<rect width=\"" + svg_pixels(draw_w) + "\" height=\"" + svg_pixels(draw_h) +
           "\" fill=\"#fbfaf5\" stroke=\"#ccc\"/>\n";
    svg += "<use xlink:href=\"#terrain\" href=\"#terrain\"/>\n";
    // small pieces first, so the large ones are drawn over them
    std::vector<const DepositDisc*> order;
    for (const DepositDisc& d : panel.discs)
      if (finite_point(d.centre) && std::isfinite(d.radius)) order.push_back(&d);
    std::stable_sort(order.begin(), order.end(), [&](const DepositDisc* p, const DepositDisc* q) {
      return classes.at(p->piece) > classes.at(q->piece);
    });
    for (const DepositDisc* d : order)
      svg += "<circle cx=\"" + svg_pixels((d->centre.x - x0) * scale) + "\" cy=\"" +
             svg_pixels((y1 - d->centre.y) * scale) + "\" r=\"" + svg_pixels(std::max(0.6, d->radius * scale)) +
             "\" fill=\"" + class_colour(classes.at(d->piece)) + "\"/>\n";
    svg += "</g>\n";
    const double bar = scale_bar_length(span_x), bar_y = top + draw_h + 16;
    svg += "<line x1=\"" + svg_pixels(ox) + "\" y1=\"" + svg_pixels(bar_y) + "\" x2=\"" + svg_pixels(ox + bar * scale) +
           "\" y2=\"" + svg_pixels(bar_y) + "\" stroke=\"#222\" stroke-width=\"2\"/>\n";
    svg += "<text x=\"" + svg_pixels(ox + bar * scale + 6) + "\" y=\"" + svg_pixels(bar_y + 4) + "\">" +
           svg_number(bar) + " " + xml_escaped(text.unit.empty() ? "length unit" : text.unit) + "</text>\n";
    svg += "<text x=\"" + svg_pixels(ox + std::max(draw_w, 170.0)) + "\" y=\"" + svg_pixels(bar_y + 4) +
           "\" text-anchor=\"end\" fill=\"#666\">" + xml_escaped(text.x_label + " →, " + text.y_label + " ↑") +
           "</text>\n";
  }
  // the legend: the ranked colours, then the small pieces', the loose spheres' and the contours
  const double ly = height - 16;
  double lx = gap;
  svg += "<text x=\"" + svg_pixels(lx) + "\" y=\"" + svg_pixels(ly) + "\">pieces, largest first:</text>\n";
  lx += 130;
  for (const char* c : kPieceColours) {
    svg += "<circle cx=\"" + svg_pixels(lx) + "\" cy=\"" + svg_pixels(ly - 4) + "\" r=\"5\" fill=\"" + c + "\"/>\n";
    lx += 14;
  }
  svg += "<circle cx=\"" + svg_pixels(lx + 6) + "\" cy=\"" + svg_pixels(ly - 4) + "\" r=\"5\" fill=\"" +
         kSmallPieceColour + "\"/>\n";
  svg += "<circle cx=\"" + svg_pixels(lx + 20) + "\" cy=\"" + svg_pixels(ly - 4) + "\" r=\"5\" fill=\"" +
         kLooseSphereColour + "\"/>\n";
  svg +=
      "<text x=\"" + svg_pixels(lx + 32) + "\" y=\"" + svg_pixels(ly) + "\">" + xml_escaped(legend_tail) + "</text>\n";
  svg += "</svg>\n";
  return svg;
}

}  // namespace dem::study
