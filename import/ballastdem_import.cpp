// BallastDEM's INPT.inp (the BallastDEM manual's figure 5.2) as a staged job: ballast stones
// (rigid clumps of lognormal masses) dropped into the box and settled for T_stable, the sleeper
// (a plate of L1 x L2) lowered onto the bed, then loaded cyclically (F_MIN to F_MAX at Freq for
// NCir cycles) with its mass MassTop.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "import/line_fates.hpp"
#include "import/program_imports.hpp"

namespace dem::import {
namespace {

const std::vector<LineFates::Expected> kBallastDemLines = {{"restart", 1},
                                                           {"pattern", 1},
                                                           {"nstep", 1},
                                                           {"Tgrowth, T_stable, iseeds", 3},
                                                           {"Tstrain", 1},
                                                           {"CTime", 1},
                                                           {"Nprint", 1},
                                                           {"Nlast", 1},
                                                           {"isearch", 1},
                                                           {"icont", 1},
                                                           {"itime", 1},
                                                           {"IPATTERN", 2},
                                                           {"Nparticle", 2},
                                                           {"N overlap particle", 1},
                                                           {"PMass", 2},
                                                           {"MLOGMEAN, MLOGSIGMA", 2},
                                                           {"MassMax/PMass", 2},
                                                           {"MassMin/PMass", 2},
                                                           {"dens_1, dens_2", 2},
                                                           {"YoungM_1, YoungM_2, PoissonR", 3},
                                                           {"rns", 1},
                                                           {"eps", 2},
                                                           {"rzs", 1},
                                                           {"amu0, amu1, amu_last", 3},
                                                           {"mxnb, maxnb_w", 2},
                                                           {"skin", 1},
                                                           {"temperature", 1},
                                                           {"NWall, NPoint", 2},
                                                           {"Length, Width, Height", 3},
                                                           {"L1, L2", 2},
                                                           {"Freq", 1},
                                                           {"gx, gy, gz", 3},
                                                           {"growth, NDrop", 2},
                                                           {"MassTop", 1},
                                                           {"F_MAX, F_MIN", 2},
                                                           {"NCir", 1}};

constexpr int kMaxSpheres = 20;  // a stone's spheres at most (ballastStones.maxSpheres)
// Stones placed at random (their bounding spheres apart) fill about a twentieth of a box with stone
// before the placement stalls: a box of Nparticle 0 is given this share, in a box four times as tall
// as the ballast box that they fall from into it.
constexpr double kPlacedStoneFraction = 0.04;
constexpr double kDropHeights = 4;
constexpr double kSeatSpeed = 0.5;  // m/s: the sleeper is lowered onto the bed at this speed

}  // namespace

void import_ballastdem(const std::vector<legacy::InptLine>& lines, const ImportOptions& options, Imported& out) {
  LineFates in(lines, kBallastDemLines, "BallastDEM");
  nlohmann::ordered_json& spec = out.spec;
  const double unit = options.length_unit;
  spec["name"] = "imported from BallastDEM's INPT.inp";
  if (!options.meshes.empty())
    throw legacy::InptError(
        "BallastDEM's box is built from INPT.inp's Length, Width and Height: it takes no mesh files");

  if (in.logical(1))
    in.dropped(1,
               ".true. read the particles from the last run's file: continue a run with `dem run SPEC --out DIR "
               "--restart DIR/restart.dat`; this spec makes the stones anew");
  else
    in.became(1, "the stones are made anew (a run without --restart)");
  in.dropped(2, "the stones are rigid clumps placed at random (ballastStones), not on a lattice");
  const long long nstep = in.integer(3);
  if (nstep < 1) in.refuse(3, "must be at least 1");
  in.dropped(3,
             "the run's length is its stages' (T_stable, the seating, NCir / Freq of loading); the step is "
             "chosen from the contacts");
  const double t_growth = in.real(4, 0), t_stable = in.real(4, 1);
  if (!(t_stable > 0)) in.refuse(4, "T_stable must be positive (got " + show(t_stable) + ")");
  in.dropped(5, "a strain-controlled length; the load stage lasts NCir cycles");
  in.dropped(6, "the run's length is its stages'");
  const long long nprint = in.integer(7);
  if (nprint < 1) in.refuse(7, "must be at least 1");
  in.dropped(9, "the neighbour lists are rebuilt whenever needed");
  in.dropped(10, "the manual does not define it: the step is 1/50 of the shortest contact time");
  in.dropped(11, "the manual does not define it");

  // 12-18: the stones' masses
  const long long ipattern = in.integer(12);
  if (ipattern != 4)
    in.refuse(12, "only 4 (lognormal masses) has a counterpart here: ballastStones' masses are lognormal (got " +
                      std::to_string(ipattern) + ")");
  in.became(12, "ballastStones' masses are lognormal (IPATTERN 4; its second value is not defined by the manual)");
  const double pmass = in.real(15, 0) * 1e-3;  // g -> kg
  if (!(pmass > 0)) in.refuse(15, "PMass must be positive (got " + in.line(15).values[0] + ")");
  in.became(15, "the scale of MassMax and MassMin (PMass in g; its second value is not defined by the manual)");
  // Read as log10 of the mass in grams: the only reading (of ln or log10, of g or kg) that puts the
  // sample's distribution (1.849, 0.611) between its bounds (100 g and 300 g): a quarter of it.
  const double log_mean = in.real(16, 0) * std::numbers::ln10 + std::log(1e-3);
  const double log_sigma = in.real(16, 1) * std::numbers::ln10;
  if (!(log_sigma >= 0)) in.refuse(16, "MLOGSIGMA must be >= 0");
  in.became(16, "ballastStones.massLogMean = MLOGMEAN ln 10 + ln 1e-3 = " + show(log_mean) +
                    ", massLogSigma = MLOGSIGMA ln 10 = " + show(log_sigma) + " (read as log10 of the mass in grams)");
  const double mass_max = in.real(17, 0) * pmass, mass_min = in.real(18, 0) * pmass;
  if (!(mass_min > 0 && mass_max > mass_min)) in.refuse(17, "MassMax/PMass must be above MassMin/PMass > 0");
  in.became(17, "ballastStones.massMax = MassMax/PMass x PMass = " + show(mass_max) +
                    " kg (its second value is not defined by the manual)");
  in.became(18, "ballastStones.massMin = " + show(mass_min) + " kg (its second value is not defined by the manual)");
  const long long spheres = in.integer(14);
  if (spheres < 1) in.refuse(14, "must be at least 1");
  const long long max_spheres = std::min<long long>(spheres, kMaxSpheres);
  in.became(14, "ballastStones.maxSpheres = " + std::to_string(max_spheres) +
                    (spheres > kMaxSpheres ? " (at most " + std::to_string(kMaxSpheres) + " here)" : ""));

  // 19-27: materials and contacts
  const double dens = in.real(19, 0), young = in.real(20, 0), poisson = in.real(20, 2);
  if (!(dens > 0)) in.refuse(19, "dens_1 must be positive (got " + show(dens) + "): the stones' sizes follow from it");
  if (!(in.real(19, 1) > 0)) in.refuse(19, "dens_2 must be positive (got " + show(in.real(19, 1)) + ")");
  const double mean_mass = 0.5 * (mass_min + mass_max);
  const double radius = std::cbrt(3 * mean_mass / (4 * std::numbers::pi * dens));
  const double kn = std::numbers::pi * radius * young / 2;  // as PDEM-EGD's import: k_n = pi R E / 2
  spec["materials"] = {{{"name", "ballast"},
                        {"density", dens},
                        {"youngsModulus", young},
                        {"poissonRatio", poisson},
                        {"normalStiffness", kn}},
                       {{"name", "steel"}, {"rigid", true}}};
  in.became(19, "materials[ballast].density = dens_1 (dens_2: no second material is used)");
  in.became(20, "materials[ballast].youngsModulus = YoungM_1, poissonRatio; normalStiffness = pi R E / 2 = " +
                    show(kn) + " N/m at the radius of a stone of the mean of massMin and massMax (YoungM_2 unused)");
  spec["contact"] = {
      {"normal", "LINEAR"}, {"tangentialStiffnessRatio", in.real(21)}, {"tangentialDampingRatio", in.real(23)}};
  in.became(21, "contact.tangentialStiffnessRatio (the manual's linear law, section 4.3)");
  in.became(23, "contact.tangentialDampingRatio");
  const double eps_stones = in.real(22, 0), eps_walls = in.real(22, 1);
  const double amu_stones = in.real(24, 0), amu_walls = in.real(24, 1);
  spec["interactions"] = {
      {{"a", "ballast"}, {"b", "ballast"}, {"restitution", eps_stones}, {"friction", amu_stones}},
      {{"a", "ballast"}, {"b", "steel"}, {"restitution", std::min(eps_walls, 1.0)}, {"friction", amu_walls}}};
  in.became(22,
            "interactions: stone-stone restitution = the first value, stone-wall = the second (the manual does "
            "not say which pair each is for)");
  in.became(24,
            "interactions: stone-stone friction = amu0, stone-wall = amu1 (amu_last unused; the manual does not "
            "say which pair each is for)");
  in.dropped(25, "the neighbour lists hold as many neighbours as there are");
  in.dropped(26, "the legacy's cell size over the diameter; the Verlet skin here is numerics.skin");
  in.dropped(27, "the manual does not use it");

  // 28-36: the box, the sleeper and its load
  in.dropped(28, "the box is four side planes and a floor (the manual's 13 walls of 4 points are its own drawing)");
  const double length = in.real(29, 0) * unit, width = in.real(29, 1) * unit, height = in.real(29, 2) * unit;
  if (!(length > 0 && width > 0 && height > 0)) in.refuse(29, "must be positive");
  const double l1 = in.real(30, 0) * unit, l2 = in.real(30, 1) * unit;
  if (!(l1 > 0 && l2 > 0 && l1 <= length && l2 <= width)) in.refuse(30, "the sleeper must be positive and fit the box");
  auto v3 = [](double x, double y, double z) { return nlohmann::ordered_json{{"x", x}, {"y", y}, {"z", z}}; };
  nlohmann::ordered_json walls = nlohmann::ordered_json::array();
  walls.push_back(
      {{"name", "floor"}, {"material", "steel"}, {"plane", {{"point", v3(0, 0, 0)}, {"normal", v3(0, 0, 1)}}}});
  walls.push_back(
      {{"name", "x0"}, {"material", "steel"}, {"plane", {{"point", v3(0, 0, 0)}, {"normal", v3(1, 0, 0)}}}});
  walls.push_back(
      {{"name", "x1"}, {"material", "steel"}, {"plane", {{"point", v3(length, 0, 0)}, {"normal", v3(-1, 0, 0)}}}});
  walls.push_back(
      {{"name", "y0"}, {"material", "steel"}, {"plane", {{"point", v3(0, 0, 0)}, {"normal", v3(0, 1, 0)}}}});
  walls.push_back(
      {{"name", "y1"}, {"material", "steel"}, {"plane", {{"point", v3(0, width, 0)}, {"normal", v3(0, -1, 0)}}}});
  spec["walls"] = walls;
  in.became(29,
            "the box: walls floor, x0, x1, y0, y1 (planes) from the origin to Length, Width, and the sleeper's "
            "start at Height");

  long long count = in.integer(13, 0);
  if (count < 0)
    in.refuse(13, "must be >= 0 (got " + std::to_string(count) + "): a count of stones, 0 for as many as fit");
  const long long nparticle = count;
  const double stone_volume = mean_mass / dens;
  if (count <= 0) {
    const double fits = kPlacedStoneFraction * length * width * kDropHeights * height / stone_volume;
    if (!(fits < 1e9)) in.refuse(13, "0 asks for as many stones as fit, and the box holds " + show(fits) + " of them");
    count = std::max(1LL, std::llround(fits));
  }
  in.became(13, "ballastStones.count = " + std::to_string(count) +
                    (nparticle > 0 ? ""
                                   : " (Nparticle 0: a twenty-fifth of the volume of the box four times as tall, in "
                                     "stone: what random placement fits)"));
  spec["ballastStones"] = {{{"count", count},
                            {"massLogMean", log_mean},
                            {"massLogSigma", log_sigma},
                            {"massMin", mass_min},
                            {"massMax", mass_max},
                            {"maxSpheres", max_spheres},
                            {"min", v3(0, 0, 0)},
                            {"max", v3(length, width, kDropHeights * height)},
                            {"material", "ballast"}}};

  const double gx = in.real(32, 0), gy = in.real(32, 1), gz = in.real(32, 2);
  if (!(gz >= 0)) in.refuse(32, "gz is the size of gravity's pull down: must be >= 0 (got " + show(gz) + ")");
  spec["gravity"] = v3(gx, gy, -gz);
  in.became(32, "gravity = (gx, gy, -gz): the sample's gz = 9.8 pulls down");
  const double growth = in.real(33, 0);
  in.dropped(33, "growth " + show(growth) +
                     ": rigid stones keep their shape (growth and clumps cannot be combined); "
                     "they are dropped into the box from up to four times its height instead (NDrop unused)");
  in.dropped(4, "Tgrowth " + show(t_growth) + ": no growth (line 33); T_stable " + show(t_stable) +
                    " s became the settle stage's duration; iseeds: the stones' seed is 1");

  const double freq = in.real(31), mass_top = in.real(34), f_max = in.real(35, 0), f_min = in.real(35, 1);
  const long long cycles = in.integer(36);
  if (!(freq > 0)) in.refuse(31, "must be positive");
  if (!(mass_top > 0)) in.refuse(34, "must be positive");
  if (!(f_max >= f_min && f_min >= 0)) in.refuse(35, "must be F_MAX >= F_MIN >= 0");
  if (cycles < 1) in.refuse(36, "must be at least 1");
  const double cx = length / 2, cy = width / 2;
  nlohmann::ordered_json sleeper = {{"name", "sleeper"},
                                    {"material", "steel"},
                                    {"plate",
                                     {{"c1", v3(cx - l1 / 2, cy - l2 / 2, height)},
                                      {"c2", v3(cx + l1 / 2, cy - l2 / 2, height)},
                                      {"c3", v3(cx + l1 / 2, cy + l2 / 2, height)},
                                      {"c4", v3(cx - l1 / 2, cy + l2 / 2, height)}}},
                                    {"motion", {{"velocity", v3(0, 0, -kSeatSpeed)}}}};
  in.became(30, "the sleeper: a plate L1 x L2 centred over the box, added at Height when the bed has settled");
  const double load_time = static_cast<double>(cycles) / freq;
  const double seat_time = height / kSeatSpeed;
  spec["stages"] = {
      {{"name", "settle"}, {"duration", t_stable}},
      {{"name", "seat"},
       {"duration", seat_time},
       {"addWalls", nlohmann::ordered_json::array({sleeper})},
       {"untilWall", "sleeper"},
       {"untilWallForce", std::max(f_min, 1e-3)},
       {"minDuration", 0}},
      {{"name", "load"},
       {"duration", load_time},
       {"wallChanges",
        {{{"wall", "sleeper"},
          {"load",
           {{"direction", v3(0, 0, -1)},
            {"mass", mass_top},
            {"cyclic", {{"fMin", f_min}, {"fMax", f_max}, {"frequency", freq}, {"cycles", cycles}}}}}}}}}};
  in.became(31, "the load stage's cyclic.frequency");
  in.became(34, "the sleeper's load.mass (kg)");
  in.became(35, "the sleeper's cyclic.fMax, fMin (N)");
  in.became(36, "the sleeper's cyclic.cycles; the load stage lasts NCir / Freq = " + show(load_time) + " s");
  const double total = t_stable + seat_time + load_time;
  spec["outputs"] = {{"interval", total / static_cast<double>(nprint)}, {"forceChains", true}};
  in.became(
      7, "outputs.interval = the stages' longest time / Nprint = " + show(total / static_cast<double>(nprint)) + " s");
  const long long nlast = in.integer(8);
  if (nlast < 0) in.refuse(8, "must be >= 0");
  if (nlast > 0) {
    spec["outputs"]["lastFrames"] = nlast;
    in.became(8, "outputs.lastFrames = " + std::to_string(nlast));
  } else {
    in.became(8, "0: every frame holds the particles");
  }
  // where each spec field came from, for the spec loader's problems
  in.feeds(19, "materials[0].density");
  for (const char* f : {"materials[0].youngsModulus", "materials[0].poissonRatio", "materials[0].normalStiffness"})
    in.feeds(20, f);
  in.feeds(21, "contact.tangentialStiffnessRatio");
  in.feeds(23, "contact.tangentialDampingRatio");
  in.feeds(22, "interactions[0].restitution");
  in.feeds(22, "interactions[1].restitution");
  in.feeds(24, "interactions[0].friction");
  in.feeds(24, "interactions[1].friction");
  in.feeds(13, "ballastStones[0]");
  in.feeds(13, "ballastStones[0].count");
  in.feeds(14, "ballastStones[0].maxSpheres");
  in.feeds(16, "ballastStones[0].massLogMean");
  in.feeds(16, "ballastStones[0].massLogSigma");
  in.feeds(17, "ballastStones[0].massMax");
  in.feeds(18, "ballastStones[0].massMin");
  in.feeds(29, "walls");
  in.feeds(30, "stages[1]");
  in.feeds(4, "stages[0]");
  in.feeds(31, "stages[2].wallChanges[0].load.cyclic.frequency");
  in.feeds(34, "stages[2].wallChanges[0].load.mass");
  in.feeds(35, "stages[2].wallChanges[0].load.cyclic");
  in.feeds(36, "stages[2].wallChanges[0].load.cyclic.cycles");
  in.feeds(32, "gravity");
  in.feeds(7, "outputs.interval");
  in.feeds(8, "outputs.lastFrames");
  out.lines = in.fates();
  out.fields = in.fields();
}

}  // namespace dem::import
