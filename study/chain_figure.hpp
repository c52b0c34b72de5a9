// A figure of force chains (SVG): side by side, the particles of a few frames projected on a plane
// as discs, the plates as outlines, and each particle-particle contact as a line between the two
// centres whose width and darkness grow with its normal force, on one scale for every panel (the
// BallastDEM manual's figure 5.5: the chains under a sleeper at four instants of a load cycle).
#pragma once

#include <string>
#include <vector>

namespace dem::study {

struct Point2 {
  double x = 0, y = 0;  // in the drawing plane, y up
};

struct ChainDisc {
  Point2 centre;
  double radius = 0;
};

struct ChainLine {
  Point2 a, b;
  double normal_force = 0;  // N
};

struct ChainPanel {
  std::string title;
  std::vector<ChainDisc> discs;
  std::vector<std::vector<Point2>> outlines;  // closed polygons (plates)
  std::vector<ChainLine> chains;
};

struct ChainFigureText {
  std::string title;
  std::string x_label, y_label;  // the plane's axes ("x", "z")
  std::string unit;              // of lengths, for the scale bar ("mm"; "" says "length unit")
};

// Contacts under this fraction of the strongest one are left out: they would be hairlines, and a
// bed's thousands of them would make the file large without changing the picture.
inline constexpr double kWeakestChainDrawn = 0.01;

// Every panel at one scale (the extent of all their discs and outlines), up to four a row. A line's
// width grows linearly with its normal force, on one scale for every panel: from 0.4 px to 6 px at
// the strongest force over all panels, or to 0.6 of a typical particle as drawn when that is less
// (a bed of small particles stays visible); the legend states the rule and the force in newtons.
// Pulling contacts (Fn < 0, without noTensileForce) are not drawn.
std::string chain_figure_svg(const ChainFigureText& text, const std::vector<ChainPanel>& panels);

}  // namespace dem::study
