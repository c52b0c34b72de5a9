// A figure of deposits (SVG): side by side, each run's particles at one frame seen from above (or
// along another axis) as discs coloured by the piece they belong to, over the terrain's contour
// lines, all at one scale (the PDEM-EGD manual's figure 4.17: the landslide's final deposits for
// five bond strengths).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "study/chain_figure.hpp"

namespace dem::study {

struct DepositDisc {
  Point2 centre;
  double radius = 0;
  int piece = 0;  // the frame's `part`: spheres with one number hold together
};

struct ContourSegment {
  Point2 a, b;
  bool major = false;  // every fifth level, drawn darker
};

struct DepositPanel {
  std::string title;     // the run's name
  std::string subtitle;  // its time and step
  std::vector<DepositDisc> discs;
};

struct DepositFigureText {
  std::string title;
  std::string x_label, y_label;  // the plane's axes ("x", "y")
  std::string unit;              // of lengths, for the scale bar ("m"; "" says "length unit")
  std::string contours;          // what the contour lines are ("contours every 50 m"); "" without
};

// Colours a piece gets by its rank among the frame's pieces by sphere count (largest first): the
// first kRankedPieces get their own colour; smaller pieces of two or more spheres share one, and
// a sphere alone another.
inline constexpr int kRankedPieces = 8;

// Every panel at one scale (the extent of all their discs, with a margin, and of the contours: the
// whole terrain), up to five a row; the contour lines are the same under every panel.
std::string deposit_figure_svg(const DepositFigureText& text, const std::vector<DepositPanel>& panels,
                               const std::vector<ContourSegment>& contours);

// The segments where the levels (multiples of `interval` along axis `depth`, the one not drawn)
// cut a mesh's triangles, in the drawing plane's axes `right` and `up`: marching triangles. Every
// fifth level (multiples of 5 `interval`) is major.
struct MeshTriangle {
  std::array<std::array<double, 3>, 3> corners;
};
std::vector<ContourSegment> contour_segments(const std::vector<MeshTriangle>& triangles, int right, int up, int depth,
                                             double interval);

// A round contour interval (1, 2, 5 x 10^k) that gives about 10 to 25 levels over `relief`.
double contour_interval(double relief);

}  // namespace dem::study
