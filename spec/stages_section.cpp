// A staged run (JobSpec.stages): the PDEM-EGD manual's fill, grow, bond and release, the BallastDEM
// manual's settle and load, as one job. Each stage's changes are checked against the walls,
// materials and bonds of the spec and of the stages before it.
#include <algorithm>
#include <limits>
#include <map>
#include <set>

#include "contact/models.hpp"
#include "spec/section_loaders.hpp"

namespace dem::spec {
namespace {

constexpr int kMaxStages = 1000;
constexpr std::size_t kMaxStageName = 200;

bool any_rolling(const std::vector<Interaction>& table) {
  for (const Interaction& in : table)
    if (in.rolling_friction > 0) return true;
  return false;
}

// The walls by name, and where each is there: a stage may name only a wall it has.
class WallNames {
 public:
  explicit WallNames(const Scene& scene) : scene_(scene) {
    for (std::size_t k = 0; k < scene.walls.size(); ++k) add(static_cast<int>(k));
  }
  void add(int k) {
    if (!index_.emplace(scene_.walls[k].name, k).second) twice_.insert(scene_.walls[k].name);
  }
  bool taken(const std::string& name) const { return index_.count(name) > 0; }
  // The wall named, there at `stage`; -1 (reported at `path`) when there is none such.
  int present(const std::string& name, int stage, const std::string& path, Checker& check) const {
    const auto it = index_.find(name);
    if (it == index_.end()) {
      check.fail(path, "no wall is named \"" + name + "\"");
      return -1;
    }
    if (twice_.count(name)) {
      check.fail(path, "more than one wall is named \"" + name + "\": give them names of their own");
      return -1;
    }
    const WallInit& w = scene_.walls[it->second];
    if (stage < w.first_stage || stage > w.last_stage) {
      check.fail(path, "wall \"" + name + "\" is not there at this stage (" +
                           (stage < w.first_stage ? "it is added at stage " + std::to_string(w.first_stage + 1)
                                                  : "it was removed at stage " + std::to_string(w.last_stage + 2)) +
                           ")");
      return -1;
    }
    return it->second;
  }

 private:
  const Scene& scene_;
  std::map<std::string, int> index_;
  std::set<std::string> twice_;
};

void check_stage_name(const std::string& name, const std::string& path, Checker& check) {
  if (name.size() > kMaxStageName)
    check.fail(path,
               "must be at most " + std::to_string(kMaxStageName) + " bytes (got " + std::to_string(name.size()) + ")");
  for (std::size_t k = 0; k < name.size(); ++k) {
    const auto c = static_cast<unsigned char>(name[k]);
    const auto next = k + 1 < name.size() ? static_cast<unsigned char>(name[k + 1]) : 0;
    const auto third = k + 2 < name.size() ? static_cast<unsigned char>(name[k + 2]) : 0;
    // C0 and DEL; C1 (U+0080..U+009F: C2 80..C2 9F in UTF-8); U+2028 and U+2029 (E2 80 A8/A9):
    // each of them ends a line for some reader of the one-line-a-stage file
    if (c < 0x20 || c == 0x7F || (c == 0xC2 && next >= 0x80 && next <= 0x9F) ||
        (c == 0xE2 && next == 0x80 && (third == 0xA8 || third == 0xA9))) {
      check.fail(path, "must not hold control characters or line separators (it is written into output files)");
      return;
    }
  }
}

}  // namespace

void load_stages(const api::JobSpec& spec, SpecContext& ctx) {
  if (spec.stages().empty()) return;
  Checker& check = ctx.check;
  Scene& scene = ctx.scene;
  if (spec.stages_size() > kMaxStages)
    throw SpecError(
        {"stages: at most " + std::to_string(kMaxStages) + " stages (got " + std::to_string(spec.stages_size()) + ")"});
  if (spec.time().duration() != 0 || spec.time().steps() != 0)
    check.fail("time", "a staged run lasts as long as its stages: leave time.duration and time.steps out");
  if (spec.has_growth())
    check.fail("growth", "a staged run grows its particles in a stage (stages[].growthFactor): leave growth out");
  WallNames walls(scene);
  std::vector<Interaction> table = scene.interactions;
  const bool rolling_at_start = any_rolling(table);
  const int nm = static_cast<int>(scene.materials.size());
  int bonding_stage = -1;
  double grown = 1;
  for (int k = 0; k < spec.stages_size(); ++k) {
    const api::Stage& in = spec.stages(k);
    const std::string path = at("stages", k);
    Stage s;
    s.name = in.name().empty() ? "stage " + std::to_string(k + 1) : in.name();
    check_stage_name(in.name(), path + ".name", check);

    // how long it runs, and what may end it early
    if ((in.duration() != 0) == (in.steps() != 0)) check.fail(path, "give its duration (s) or its steps, one of them");
    if (in.duration() != 0) check.positive(path + ".duration", in.duration(), kDuration);
    if (in.steps() < 0) check.fail(path + ".steps", "must be >= 1 (got " + std::to_string(in.steps()) + ")");
    s.duration = in.duration();
    s.steps = in.steps();
    check.non_negative(path + ".untilKineticEnergy", in.until_kinetic_energy(), kEnergy);
    s.until_kinetic_energy = in.until_kinetic_energy();
    s.until_wall_force = in.until_wall_force();
    const bool ends_early = s.until_kinetic_energy > 0 || !in.until_wall().empty();
    if (in.has_min_duration()) {
      check.non_negative(path + ".minDuration", in.min_duration(), kDuration);
      if (!ends_early)
        check.fail(path + ".minDuration",
                   "delays an end condition, and the stage has none (untilKineticEnergy, "
                   "untilWall)");
      if (in.duration() > 0 && in.min_duration() > in.duration())
        check.fail(path + ".minDuration", "must be at most the stage's duration (" + num(in.duration()) + " s; got " +
                                              num(in.min_duration()) + ")");
      s.min_duration = in.min_duration();
    }

    // what changes at its start
    if (in.has_gravity()) {
      check.vector(path + ".gravity", in.gravity(), kAcceleration);
      s.gravity = vec(in.gravity());
    }
    if (in.has_local_damping()) {
      check.in_range(path + ".localDamping", in.local_damping(), 0, 1, false, true);
      s.local_damping = in.local_damping();
    }
    std::set<int> pairs_here;
    for (int j = 0; j < in.interactions_size(); ++j) {
      const std::string ip = at(path + ".interactions", j);
      const std::optional<PairInteraction> pair = load_interaction(in.interactions(j), ip, ctx);
      if (!pair) continue;
      if (!pairs_here.insert(std::min(pair->a, pair->b) * nm + std::max(pair->a, pair->b)).second)
        check.fail(ip, "a second interaction for \"" + in.interactions(j).a() + "\" and \"" + in.interactions(j).b() +
                           "\" in this stage");
      table[pair->a * nm + pair->b] = table[pair->b * nm + pair->a] = pair->value;
      ctx.interaction_given[pair->a * nm + pair->b] = ctx.interaction_given[pair->b * nm + pair->a] = 1;
    }
    if (in.interactions_size() > 0) {
      // the force loop is chosen once, with or without rolling springs (contact/models.hpp)
      if (any_rolling(table) != rolling_at_start)
        check.fail(path + ".interactions",
                   rolling_at_start ? "takes every pair's rolling friction to 0: a run keeps its rolling model "
                                      "from start to end; keep one pair's"
                                    : "gives rolling friction where the run started with none: a run keeps its "
                                      "rolling model from start to end; give some pair a little from the start");
      s.interactions = table;
    }
    std::set<int> added_here;
    for (int j = 0; j < in.add_walls_size(); ++j) {
      const std::string wp = at(path + ".addWalls", j);
      WallInit w =
          load_wall(in.add_walls(j), wp, "stage" + std::to_string(k + 1) + "wall" + std::to_string(j + 1), ctx);
      if (walls.taken(w.name)) {
        check.fail(wp + ".name", "another wall is named \"" + w.name + "\": the stages name walls to change them");
        continue;
      }
      w.first_stage = k;
      added_here.insert(static_cast<int>(scene.walls.size()));
      scene.walls.push_back(std::move(w));
      walls.add(static_cast<int>(scene.walls.size()) - 1);
    }
    if (scene.walls.size() > static_cast<std::size_t>(check.limits.max_walls))
      throw SpecError({path + ".addWalls: at most " + std::to_string(check.limits.max_walls) +
                       " walls in all, stages' included (got " + std::to_string(scene.walls.size()) + ")"});
    for (int j = 0; j < in.remove_walls_size(); ++j) {
      const std::string rp = at(path + ".removeWalls", j);
      const int w = walls.present(in.remove_walls(j), k, rp, check);
      if (w >= 0 && added_here.count(w)) {
        check.fail(rp, "wall \"" + in.remove_walls(j) + "\" is added by this stage: add it at the stage it is wanted");
      } else if (w >= 0) {
        scene.walls[w].last_stage = k - 1;
      }
    }
    // the end condition's wall is one there in this stage (walls just added included, just removed not)
    if (!in.until_wall().empty()) {
      s.until_wall = walls.present(in.until_wall(), k, path + ".untilWall", check);
      check.positive(path + ".untilWallForce", in.until_wall_force(), kForce);
    } else if (in.until_wall_force() != 0) {
      check.fail(path + ".untilWallForce", "needs untilWall, the wall whose force ends the stage");
    }

    std::set<int> changed;
    for (int j = 0; j < in.wall_changes_size(); ++j) {
      const api::WallChange& change = in.wall_changes(j);
      const std::string cp = at(path + ".wallChanges", j);
      WallChange c;
      c.wall = walls.present(change.wall(), k, cp + ".wall", check);
      if (c.wall >= 0 && !changed.insert(c.wall).second)
        check.fail(cp + ".wall", "wall \"" + change.wall() + "\" is changed twice in this stage: give it one change");
      if (change.has_motion() && change.has_load()) check.fail(cp, "has both a motion and a load: give one");
      if (change.has_motion()) {
        c.motion = load_motion(change.motion(), cp + ".motion", check);
        if (change.motion().has_center())
          check.fail(cp + ".motion.center",
                     "a stage's motion turns the wall about its centre where the stage finds it: leave center out");
      }
      if (change.has_load()) c.load = load_control(change.load(), cp + ".load", check);
      if (c.wall >= 0) s.wall_changes.push_back(std::move(c));
    }

    if (in.bond()) {
      if (!spec.has_bonds())
        check.fail(path + ".bond", "needs the spec's \"bonds\" block (the bonds' model, stiffness and strength)");
      else if (bonding_stage >= 0)
        check.fail(path + ".bond",
                   "only one stage may glue bonds (stage " + std::to_string(bonding_stage + 1) + " does already)");
      bonding_stage = k;
      s.glue_bonds = true;
    }
    if (in.growth_factor() != 0) {
      check.in_range(path + ".growthFactor", in.growth_factor(), 1, 3, false, false);
      s.growth_factor = in.growth_factor();
      grown *= in.growth_factor();
      if (grown > 3)
        check.fail(path + ".growthFactor", "the stages' growth factors multiply to " + num(grown) +
                                               " by here, more than 3 (a packing grown that far is no longer one)");
      if (ends_early && s.growth_factor != 1)
        check.fail(path + ".growthFactor",
                   "a stage that grows the particles runs its whole length: leave out its "
                   "end condition (untilKineticEnergy, untilWall)");
      if (!scene.clumps.empty() && s.growth_factor != 1)
        check.fail(path + ".growthFactor",
                   "radius growth and rigid clumps cannot be combined (a clump's shape is "
                   "fixed)");
    }
    scene.stages.push_back(std::move(s));
  }
}

}  // namespace dem::spec
