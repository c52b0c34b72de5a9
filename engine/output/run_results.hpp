// What a run found, in numbers a study compares: how far the mass travelled and spread (a landslide's
// runout and deposit), what the bonds held together (fragments, crushed mass), how loaded walls
// settled cycle by cycle (a sleeper on a ballast bed), and the run's size, time and energy balance.
// ResultsRecorder watches a run and makes them; results/results_json.hpp writes them as results.json.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "output/legacy_output.hpp"
#include "sim/runner.hpp"

namespace dem {

// Travel and spreading from the reference instant (the start of the run's last stage: a staged
// landslide's release; step 0 without stages) to the end. "Horizontal" is across gravity (across z
// without gravity); the travel direction is the centre of mass's horizontal travel (+x when it did
// not move).
struct MotionResults {
  std::int64_t reference_step = 0;
  double reference_time = 0;
  std::string reference_stage;  // "" without stages
  Vec3 com_start = Vec3::Zero(), com_end = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();  // horizontal unit vector of travel
  double com_travel = 0;           // horizontal, m
  double com_drop = 0;             // vertical, m (down positive)
  double com_travel_angle = 0;     // atan(drop / travel), degrees
  // The front: the farthest particle surface along the travel direction, at the start and the end.
  double front_start = 0, front_end = 0;
  // Runout as landslide studies measure it (Heim's Fahrboeschung): L, the horizontal distance from
  // the top of the source mass (its highest particle at the reference) to the deposit's toe (the
  // front at the end), and H, the drop between them; H/L is the equivalent friction coefficient.
  double runout_length = 0, fall_height = 0, h_over_l = 0;
  // The deposit at the end: its extent along and across the travel direction, and the horizontal
  // area its particles cover (their footprints rasterised on cells of one mean diameter); a 2D run
  // has no area (0).
  double deposit_length = 0, deposit_width = 0, deposit_area = 0, deposit_cell = 0;
  // Each piece's travel: the horizontal distance its centre of mass moved from the reference to the
  // end, a piece being what holds together at the end (a rock, a clump, a fragment, a loose
  // sphere). A rockfall's runout distribution: its quantiles over the pieces (by count) at the
  // fractions 0, 0.05, ..., 1 (kPieceQuantiles values, the first the least travel, the last the most).
  static constexpr int kPieceQuantiles = 21;
  int pieces = 0;
  double piece_travel_mean = 0;
  std::vector<double> piece_travel;  // kPieceQuantiles values, empty without pieces
};

// Fragments: particles held together by intact bonds (a rigid clump is one piece with its members).
struct FragmentBin {
  int min_particles = 1, max_particles = 1;  // the bin's sizes: 1, 2-3, 4-7, 8-15, ...
  int fragments = 0;
  double mass = 0;  // kg
};

struct FragmentResults {
  int count = 0;          // at the end
  int initial_count = 0;  // at the reference
  double largest_mass_fraction = 0;
  std::vector<FragmentBin> sizes;  // by number of particles; empty bins left out
  // Mass broken off the pieces the reference had: for each piece, its mass minus its largest part
  // at the end (a stone's crushed mass; a block's detached mass).
  double crushed_mass = 0;           // kg
  double crushed_mass_fraction = 0;  // of the mass in pieces of more than one particle at the reference
  int bonds_initial = 0;             // intact at the reference
  int bonds_intact = 0, bonds_broken_tension = 0, bonds_broken_shear = 0;  // at the end, broken since the start
};

// One load cycle of a cyclic load, from one minimum of the load to the next.
struct LoadCycle {
  int cycle = 0;  // 1, 2, ...
  std::int64_t end_step = 0;
  double end_time = 0;
  double displacement = 0;              // along the load at the cycle's end (under F_min), m since the load began
  double peak_displacement = 0;         // the most during the cycle, m
  double resilient = 0;                 // peak - displacement: what the bed gave back, m
  double force_min = 0, force_max = 0;  // the force the wall applied to the particles, N
};

struct LoadedWallResults {
  std::string wall;  // its name
  int index = 0;     // in Scene::walls
  bool cyclic = false;
  double start_time = 0;                // when the load began
  double start_displacement = 0;        // along the load direction, m from the wall's start position
  double end_displacement = 0;          // at the end, m since the load began
  double force_min = 0, force_max = 0;  // the force the wall applied, since the load began, N
  std::vector<LoadCycle> cycles;        // the cycles completed
};

// What a source (Scene::sources) put into the run, and where its particles are at the end: the
// BallastDEM manual's wind-blown sand, how much entered and how deep into the ballast it went.
struct SourceResults {
  std::string name;
  std::int64_t inserted = 0;  // particles
  double mass = 0;            // kg
  std::int64_t crowded_batches = 0;
  std::optional<bool> total_reached;  // whether it inserted its mass or count: none given, none
  // Its particles' centres along up (against gravity; +z without it), m, at the end: their mean and
  // quantiles at the fractions 0, 0.05, ..., 1 (empty when none is left).
  static constexpr int kHeightQuantiles = 21;
  double height_mean = 0;
  std::vector<double> heights;
};

struct RunResults {
  bool ok = true;
  std::string error;
  std::size_t particles = 0;
  std::int64_t steps = 0;
  double simulated_time = 0;  // s
  double run_seconds = 0;     // wall time of this run's stepping loop
  double time_step = 0;
  // Energy balance, J: the mechanical energy at the start and the end, the work fed in, and what
  // damping and friction took out (start + input - end).
  double energy_start = 0, energy_end = 0, energy_input = 0, energy_dissipated = 0, kinetic_end = 0;
  std::vector<std::string> notes;            // what the numbers do not cover (a continuation without its track file)
  std::optional<MotionResults> motion;       // none before the reference or without free particles
  std::optional<FragmentResults> fragments;  // with bonds
  std::vector<LoadedWallResults> loaded_walls;
  std::vector<SourceResults> sources;  // one per source of the scene, in its order
};

// Watches a run (every step, a few numbers per loaded wall) and makes its RunResults at the end.
// What it must remember across a restart (the reference instant's particles, the cycles completed)
// it appends to a track file in the run's folder, lines only ever added: a resumed run (the
// server's checkpoints cut a folder's files back to their lengths then) reads it back.
class ResultsRecorder final : public Observer {
 public:
  // `track`: the track file's path; `append`: a continued run (reads the file, then adds to it).
  ResultsRecorder(const Simulation& sim, const std::string& track, bool append);
  void frame(const Simulation& sim) override;
  bool wants_steps() const override { return true; }
  void step(const Simulation& sim) override;
  void finish(const Simulation& sim, const RunOutcome& outcome) override;

  const RunResults& results() const { return results_; }

  static constexpr const char* kTrackName = "results_track.dat";

 private:
  struct Reference {
    std::int64_t step = 0;
    double time = 0;
    int bonds_intact = 0;
    std::string stage;
    std::map<int, Vec3> position;  // by particle id
    std::map<int, int> fragment;   // by particle id
  };
  struct WallTrack {
    double start_time = 0;
    double start_displacement = 0;
    std::vector<LoadCycle> cycles;
    // the cycle under way, and the load's whole range
    int cycle = 0;
    double peak = 0, f_min = 0, f_max = 0;
    double all_f_min = 0, all_f_max = 0;
    bool any_force = false;
    bool cyclic = false;
    bool open = false;  // a cycle's numbers are being gathered
  };

  void take_positions(const Simulation& sim);      // the reference's positions (pending_)
  void complete_reference(const Simulation& sim);  // its pieces: reference_ from pending_
  void add_entered(const Simulation& sim);         // particles a source inserted since
  void track_loads(const Simulation& sim);
  void read_track(const std::string& path, std::int64_t up_to_step, int walls, std::size_t particles);
  void write_line(const std::string& line);
  MotionResults motion(const Simulation& sim) const;
  FragmentResults fragment_results(const Simulation& sim) const;

  OutputFile track_;
  std::optional<Reference> reference_;
  std::optional<Reference> pending_;  // positions taken, pieces not yet
  std::vector<std::string> notes_;
  std::map<int, WallTrack> walls_;  // by scene wall
  RunResults results_;
};

}  // namespace dem
