// PDEM-EGD's INPT.inp (the PDEM-EGD manual's figure 4.14) as a staged job: the key block filled into
// the funnel mesh as a lattice (HEX, FCC) or a loose packing (LOS), filled for NFILL steps, grown by
// GROWTH over NGROWTH steps, bonded in one step, and released onto the terrain mesh with the funnel
// gone for the rest of nstep.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "import/line_fates.hpp"
#include "import/program_imports.hpp"

namespace dem::import {
namespace {

const std::vector<LineFates::Expected> kPdemEgdLines = {{"restart", 1},
                                                        {"pattern", 1},
                                                        {"BOND_MODEL", 1},
                                                        {"nstep", 1},
                                                        {"NFILL, NGROWTH", 2},
                                                        {"CTime", 1},
                                                        {"MPrint", 1},
                                                        {"NLast", 1},
                                                        {"isearch", 1},
                                                        {"icont", 1},
                                                        {"IPATTERN", 1},
                                                        {"Dmax/D, Dmin/D", 2},
                                                        {"cc", 1},
                                                        {"D", 1},
                                                        {"dens", 1},
                                                        {"YoungM, PoissonR", 2},
                                                        {"rns", 1},
                                                        {"rzs", 1},
                                                        {"amu, eps", 2},
                                                        {"X0, Y0, Z0", 3},
                                                        {"mxnb, MAXNB_W", 2},
                                                        {"GROWTH", 1},
                                                        {"skin", 1},
                                                        {"temperature", 1},
                                                        {"nu_Wall, eps_Wall", 2},
                                                        {"gz", 1},
                                                        {"ARF", 1},
                                                        {"RPBN, RPBS", 2},
                                                        {"BSTRENGTH", 1},
                                                        {"BRATIO", 1},
                                                        {"NICEX, NICEY, NICEZ", 3},
                                                        {"TContact", 1}};

// Random sequential placement stalls near a solid fraction of 0.35: a loose packing asked for more
// is placed at this and grown to it.
constexpr double kLoosePlaced = 0.25;

}  // namespace

void import_pdem_egd(const std::vector<legacy::InptLine>& lines, const ImportOptions& options, Imported& out) {
  if (options.meshes.size() > 2)
    throw legacy::InptError("PDEM-EGD takes at most two mesh files (the terrain, then the funnel): got " +
                            std::to_string(options.meshes.size()));
  LineFates in(lines, kPdemEgdLines, "PDEM-EGD");
  nlohmann::ordered_json& spec = out.spec;
  const double unit = options.length_unit;
  const bool has_terrain = !options.meshes.empty(), has_funnel = options.meshes.size() >= 2;
  spec["name"] = "imported from PDEM-EGD's INPT.inp";

  // 1-3: restart, the packing, the bonds
  if (in.logical(1))
    in.dropped(1,
               ".true. read the particles from the last run's file: continue a run with `dem run SPEC --out DIR "
               "--restart DIR/restart.dat`; this spec builds the key block anew");
  else
    in.became(1, "the key block is built anew (a run without --restart)");
  const std::string pattern = in.word(2);
  if (pattern != "HEX" && pattern != "FCC" && pattern != "LOS")
    in.refuse(2, "must be HEX, FCC or LOS (got \"" + in.line(2).values[0] + "\")");
  const bool loose = pattern == "LOS";
  const std::string bond_model = in.word(3);
  if (bond_model != "P" && bond_model != "C")
    in.refuse(3, "must be P (parallel bond) or C (contact bond) (got \"" + in.line(3).values[0] + "\")");

  // 4-10: the run's length and outputs
  const long long nstep = in.integer(4);
  if (nstep < 1) in.refuse(4, "must be at least 1 (got " + std::to_string(nstep) + ")");
  const long long nfill = in.integer(5, 0), ngrowth = in.integer(5, 1);
  if (nfill < 0 || ngrowth < 0) in.refuse(5, "must be >= 0");
  long long total = nstep;
  if (in.word(6) == "NSTEP") {
    in.became(6, "the run is nstep steps: the stages' steps add up to " + std::to_string(nstep));
  } else {
    total = in.integer(6);
    if (total < 1) in.refuse(6, "must be nstep or a number of steps >= 1");
    in.became(6, "the run is " + std::to_string(total) + " steps: the stages' steps add up to it");
  }
  if (nfill + ngrowth + 1 >= total)
    in.refuse(5, "NFILL + NGROWTH + 1 (the bond step) must leave steps for the release before the run's end at " +
                     std::to_string(total));
  in.became(4, has_funnel || nfill + ngrowth > 0 ? "the stages' steps (below)" : "time.steps");
  const long long mprint = in.integer(7);
  if (mprint < 1) in.refuse(7, "must be at least 1 (got " + std::to_string(mprint) + ")");
  const long long every = std::max(1LL, total / mprint);
  spec["outputs"] = {{"everySteps", every}, {"forceChains", true}};
  in.became(7, "outputs.everySteps = nstep / MPrint = " + std::to_string(every));
  const long long nlast = in.integer(8);
  if (nlast < 0) in.refuse(8, "must be >= 0 (got " + std::to_string(nlast) + ")");
  if (nlast > 0) {
    spec["outputs"]["lastFrames"] = nlast;
    in.became(8, "outputs.lastFrames = " + std::to_string(nlast) +
                     " (the particle files hold the last NLast frames; the time series every frame)");
  } else {
    in.became(8, "0: every frame holds the particles (outputs.lastFrames left out)");
  }
  in.dropped(9,
             "the neighbour lists are rebuilt whenever a particle has moved half the skin (numerics.searchInterval "
             "only adds rebuilds)");
  in.dropped(10,
             "the manual does not define the time step refinement: the step is chosen from the contacts "
             "(time.dtFraction 1/50 of the shortest contact time, the manual's own rule)");

  // 11-14: sizes
  const long long ipattern = in.integer(11);
  if (ipattern < 0 || ipattern > 4) in.refuse(11, "must be 0 to 4 (got " + std::to_string(ipattern) + ")");
  const double dmax_ratio = in.real(12, 0), dmin_ratio = in.real(12, 1);
  const double d = in.real(14) * unit;
  // a nanometre to a kilometre: what a spec's radii allow (and the stiffness made from D stays finite)
  if (!(d >= 1e-9 && d <= 1e3))
    in.refuse(14,
              "must be a diameter from 1e-9 m to 1000 m (got " + in.line(14).values[0] + " x " + show(unit) + " m)");
  if (!(dmin_ratio > 0) || !(dmax_ratio >= dmin_ratio))
    in.refuse(12, "must be Dmax/D >= Dmin/D > 0 (got " + show(dmax_ratio) + ", " + show(dmin_ratio) + ")");
  static const char* kKinds[] = {"ONE_SIZE", "TWO_SIZES", "UNIFORM", "NORMAL", "LOGNORMAL"};
  nlohmann::ordered_json sizes = {{"kind", kKinds[ipattern]}};
  if (ipattern == 0) {
    sizes["mean"] = d;
    in.dropped(12, "IPATTERN 0 is one size: D");
  } else {
    sizes["dMin"] = dmin_ratio * d;
    sizes["dMax"] = dmax_ratio * d;
    if (ipattern >= 3) {
      sizes["mean"] = d;
      sizes["spread"] = (dmax_ratio - dmin_ratio) * d / 4;
    }
    in.became(12, "sizes.dMax = Dmax/D x D = " + show(dmax_ratio * d) + " m, sizes.dMin = " + show(dmin_ratio * d) +
                      " m" + (ipattern >= 3 ? " (spread: a quarter of dMax - dMin, for which INPT has no line)" : ""));
  }
  in.became(11, std::string("sizes.kind = ") + kKinds[ipattern]);
  const double cc = in.real(13);
  double loose_growth = 1;
  if (loose) {
    if (!(cc > 0 && cc < 0.74)) in.refuse(13, "must be in (0, 0.74) (got " + show(cc) + ")");
    const double placed = std::min(cc, kLoosePlaced);
    loose_growth = std::cbrt(cc / placed);
    in.became(13, "packings[0].solidFraction = " + show(placed) +
                      (placed < cc ? ", grown by (cc / " + show(placed) + ")^(1/3) = " + show(loose_growth) +
                                         " in the grow stage (random placement stalls near 0.35)"
                                   : ""));
  } else {
    in.dropped(13, "a " + pattern + " lattice's density is its spacing (touching spheres)");
  }
  in.became(14, loose ? "packings[0].sizes (diameters, m)" : "the lattice's sizes (diameters, m)");

  // 15-19: the material and the contacts
  const double dens = in.real(15), young = in.real(16, 0), poisson = in.real(16, 1);
  const long long tcontact = in.integer(32);
  if (tcontact != 1 && tcontact != 2)
    in.refuse(32, "must be 1 (linear) or 2 (nonlinear) (got " + std::to_string(tcontact) + ")");
  const bool linear = tcontact == 1;
  // A sphere pair's normal stiffness from the modulus: the contact as a cylinder of the spheres' cross
  // section pi R^2 and length 2R (Potyondy & Cundall 2004's deformability, k_n = A E / L): pi R E / 2.
  const double radius = d / 2;
  const double kn = std::numbers::pi * radius * young / 2;
  nlohmann::ordered_json rock = {
      {"name", "rock"}, {"density", dens}, {"youngsModulus", young}, {"poissonRatio", poisson}};
  if (linear) rock["normalStiffness"] = kn;
  spec["materials"] = nlohmann::ordered_json::array({rock});
  if (has_terrain) spec["materials"].push_back({{"name", "terrain"}, {"rigid", true}});
  in.became(15, "materials[rock].density");
  in.became(16, std::string("materials[rock].youngsModulus, poissonRatio") +
                    (linear ? "; normalStiffness = pi R E / 2 = " + show(kn) +
                                  " N/m at R = D/2 (the manuals give the linear law no k_n: docs/spec.md)"
                            : ""));
  spec["contact"] = {{"normal", linear ? "LINEAR" : "HERTZ"}};
  in.became(32, linear ? "contact.normal = LINEAR" : "contact.normal = HERTZ");
  const double rns = in.real(17), rzs = in.real(18);
  if (linear) {
    spec["contact"]["tangentialStiffnessRatio"] = rns;
    spec["contact"]["tangentialDampingRatio"] = rzs;
    in.became(17, "contact.tangentialStiffnessRatio");
    in.became(18, "contact.tangentialDampingRatio");
  } else {
    in.dropped(17, "Hertz-Mindlin's tangential stiffness follows from E and the Poisson ratio");
    in.dropped(18, "Hertz-Mindlin's tangential damping follows from the restitution");
  }
  const double amu = in.real(19, 0), eps = in.real(19, 1);
  const double nu_wall = in.real(25, 0), eps_wall = in.real(25, 1);
  nlohmann::ordered_json interactions = nlohmann::ordered_json::array();
  interactions.push_back({{"a", "rock"}, {"b", "rock"}, {"restitution", eps}, {"friction", amu}});
  if (has_terrain)
    interactions.push_back({{"a", "rock"}, {"b", "terrain"}, {"restitution", eps_wall}, {"friction", nu_wall}});
  const double arf = in.real(27);
  if (arf > 0 && arf <= 1) {
    spec["contact"]["rolling"] = "CDT";
    for (auto& i : interactions) i["rollingFriction"] = arf;
    in.became(27, "contact.rolling = CDT, interactions[].rollingFriction = " + show(arf));
  } else if (arf == 0) {
    in.dropped(27, "0: no rolling resistance");
  } else {
    in.dropped(27, show(arf) +
                       " is not a rolling friction coefficient in [0, 1] (the manual does not define ARF "
                       "further): give interactions[].rollingFriction and contact.rolling by hand");
  }
  spec["interactions"] = interactions;
  in.became(19, "interactions[rock, rock].friction, restitution");
  if (has_terrain)
    in.became(25, "interactions[rock, terrain].friction (nu_Wall is the wall friction), restitution");
  else
    in.dropped(25, "no terrain mesh was given");

  // 20-24: placement and numerics
  const double x0 = in.real(20, 0) * unit, y0 = in.real(20, 1) * unit, z0 = in.real(20, 2) * unit;
  in.dropped(21, "the neighbour lists hold as many neighbours as there are");
  const double growth = in.real(22);
  if (!(growth >= 1 && growth <= 3)) in.refuse(22, "must be in [1, 3] (got " + show(growth) + ")");
  in.dropped(23, "the legacy's cell size over the diameter; the Verlet skin here is numerics.skin (default 0.1)");
  in.dropped(24, "the manual does not use it");
  const double gz = in.real(26);
  if (!(gz >= 0)) in.refuse(26, "the size of gravity, which pulls down: must be >= 0 (got " + show(gz) + ")");
  spec["gravity"] = {{"z", -gz}};
  in.became(26, "gravity = (0, 0, -gz)");

  // 28-31: bonds and the lattice's counts
  const double rpbn = in.real(28, 0), rpbs = in.real(28, 1), strength = in.real(29) * 1e6;
  if (!(rpbn > 0) || !(rpbs > 0)) in.refuse(28, "must be positive");
  // the bond's normal stiffness (Eb / 2R) pi R^2 is RPBN times the contact's pi R E / 2 at lambda = 1
  spec["bonds"] = {{"model", bond_model == "P" ? "PARALLEL" : "CONTACT"},
                   {"youngsModulus", rpbn * young},
                   {"shearStiffnessRatio", rpbs / rpbn * (linear ? rns : 1.0)},
                   {"tensileStrength", strength},
                   {"shearStrength", strength}};
  in.became(3, std::string("bonds.model = ") + (bond_model == "P" ? "PARALLEL" : "CONTACT"));
  in.became(28,
            "bonds.youngsModulus = RPBN x YoungM (the bond RPBN times as stiff as the contact of pi R E / 2), "
            "bonds.shearStiffnessRatio = RPBS / RPBN x rns");
  in.became(29, "bonds.tensileStrength = bonds.shearStrength = BSTRENGTH x 1e6 Pa");
  in.dropped(30,
             "the zone whose bonds it scales is not in INPT.inp: give bonds.zones (min, max, strengthRatio) by hand");
  const long long nx = in.integer(31, 0), ny = in.integer(31, 1), nz = in.integer(31, 2);
  nlohmann::ordered_json inside;
  if (has_funnel) inside = {{"file", options.meshes[1]}, {"scale", unit}};
  if (loose) {
    nlohmann::ordered_json packing = {
        {"sizes", sizes}, {"solidFraction", std::min(cc, kLoosePlaced)}, {"material", "rock"}};
    if (has_funnel) {
      packing["inside"] = inside;
    } else {
      const double side = std::cbrt(static_cast<double>(std::max(1LL, nx * ny * nz))) * d;
      packing["min"] = {{"x", x0}, {"y", y0}, {"z", z0}};
      packing["max"] = {{"x", x0 + side}, {"y", y0 + side}, {"z", z0 + side}};
    }
    spec["packings"] = nlohmann::ordered_json::array({packing});
    in.became(2, "packings[0] (random loose packing)" + std::string(has_funnel ? " inside the funnel mesh" : ""));
    in.dropped(31, "a loose packing fills its region to cc");
  } else {
    if (nx < 1 || ny < 1 || nz < 1) in.refuse(31, "must be at least 1 each");
    nlohmann::ordered_json lattice = {
        {"kind", pattern}, {"material", "rock"}, {"countX", nx}, {"countY", ny}, {"countZ", nz}};
    if (ipattern == 0)
      lattice["radius"] = radius;
    else
      lattice["sizes"] = sizes;
    if (has_funnel)
      lattice["inside"] = inside;
    else
      lattice["min"] = {{"x", x0}, {"y", y0}, {"z", z0}};
    spec["lattices"] = nlohmann::ordered_json::array({lattice});
    in.became(2, "lattices[0].kind = " + pattern + (has_funnel ? ", inside the funnel mesh" : ""));
    in.became(
        31, "lattices[0].countX, countY, countZ" +
                std::string(has_funnel ? " (from the funnel's lowest corner; the sites outside it are left out)" : ""));
  }
  if (has_funnel)
    in.dropped(20, "the lattice starts at the funnel mesh's lowest corner");
  else
    in.became(20, loose ? "packings[0].min" : "lattices[0].min");

  // the walls: the terrain, and the funnel until the release
  if (has_terrain) {
    spec["walls"] = nlohmann::ordered_json::array();
    spec["walls"].push_back(
        {{"name", "terrain"}, {"material", "terrain"}, {"mesh", {{"file", options.meshes[0]}, {"scale", unit}}}});
    if (has_funnel) spec["walls"].push_back({{"name", "funnel"}, {"material", "terrain"}, {"mesh", inside}});
  }

  // the stages: fill, grow, bond, release
  nlohmann::ordered_json stages = nlohmann::ordered_json::array();
  if (nfill > 0) stages.push_back({{"name", "fill"}, {"steps", nfill}});
  const double grow_by = growth * loose_growth;
  if (ngrowth > 0) {
    nlohmann::ordered_json grow = {{"name", "grow"}, {"steps", ngrowth}};
    if (grow_by != 1) grow["growthFactor"] = grow_by;
    stages.push_back(grow);
  } else if (grow_by != 1) {
    in.refuse(5, "NGROWTH is 0 and the particles are to grow (GROWTH, or a loose packing's cc): give NGROWTH steps");
  }
  stages.push_back({{"name", "bond"}, {"steps", 1}, {"bond", true}});
  nlohmann::ordered_json release = {{"name", "release"}, {"steps", total - nfill - ngrowth - 1}};
  if (has_funnel) release["removeWalls"] = nlohmann::ordered_json::array({"funnel"});
  stages.push_back(release);
  spec["stages"] = stages;
  in.became(5, "stages fill (" + std::to_string(nfill) + " steps), grow (" + std::to_string(ngrowth) +
                   " steps), then bond (1 step) and release (" + std::to_string(total - nfill - ngrowth - 1) +
                   " steps" + (has_funnel ? ", the funnel removed" : "") + ")");
  if (grow_by != 1)
    in.became(22, "stages[grow].growthFactor = " + show(grow_by));
  else
    in.dropped(22, "1.0: no growth");
  // where each spec field came from, for the spec loader's problems
  for (const char* f : {"materials[0].density"}) in.feeds(15, f);
  for (const char* f : {"materials[0].youngsModulus", "materials[0].poissonRatio", "materials[0].normalStiffness"})
    in.feeds(16, f);
  in.feeds(17, "contact.tangentialStiffnessRatio");
  in.feeds(18, "contact.tangentialDampingRatio");
  in.feeds(19, "interactions[0]");
  in.feeds(25, "interactions[1]");
  in.feeds(27, "interactions[0].rollingFriction");
  in.feeds(27, "interactions[1].rollingFriction");
  const std::string packed = loose ? "packings[0]" : "lattices[0]";
  in.feeds(2, packed);
  in.feeds(11, packed + ".sizes.kind");
  in.feeds(12, packed + ".sizes");
  in.feeds(14, packed + ".sizes.mean");
  in.feeds(14, packed + ".radius");
  in.feeds(13, packed + ".solidFraction");
  for (const char* axis : {"countX", "countY", "countZ"}) in.feeds(31, packed + "." + axis);
  in.feeds(20, packed + ".min");
  in.feeds(3, "bonds.model");
  in.feeds(28, "bonds.youngsModulus");
  in.feeds(28, "bonds.shearStiffnessRatio");
  in.feeds(29, "bonds.tensileStrength");
  in.feeds(29, "bonds.shearStrength");
  in.feeds(26, "gravity");
  in.feeds(7, "outputs.everySteps");
  in.feeds(8, "outputs.lastFrames");
  in.feeds(5, "stages");
  in.feeds(22, "stages[1].growthFactor");
  out.lines = in.fates();
  out.fields = in.fields();
}

}  // namespace dem::import
