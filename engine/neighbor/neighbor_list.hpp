// Verlet neighbour list: for each particle i the particles j > i closer than r_i + r_j + skin, in
// compressed rows, with the contact history of each pair stored beside it.
//
// Search: one cell grid per size level (radii within a factor 2). Each particle scans its own level
// and the coarser ones with the reach r_i + r_max(level) + skin, so every pair is found once, from
// its smaller sphere: with a 10:1 size ratio no small sphere scans cells sized for the large ones
// and no large sphere scans the fine grids. Rows are sorted, so the list, and everything computed
// from it, is the same whatever the number of threads.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/particles.hpp"

namespace dem {

// Per-pair values that only change when the list is rebuilt: computed once there, not every step.
struct PairConstants {
  double sqrt_m_eff = 0;  // sqrt of the reduced mass 1/(1/m_i + 1/m_j)
  double r_eff = 0;       // reduced radius r_i r_j / (r_i + r_j)
  double i_roll = 0;      // rolling inertia of Ai et al. (2011) eq. 13: 1/I_r = sum 1/(I + m r^2)
};

// Reduced value of two bodies given by their inverses; two held bodies (both inverses zero) fall
// back to the plain reduced value so that damping stays finite.
inline double reduced(double inv_a, double inv_b, double a, double b) {
  return inv_a + inv_b > 0 ? 1 / (inv_a + inv_b) : a * b / (a + b);
}

// Constants of a sphere-sphere pair, and of a sphere against a wall (infinite mass and radius).
PairConstants pair_constants(const Particles& p, int i, int j);
PairConstants wall_constants(const Particles& p, int i);

struct NeighborList {
  std::vector<int> row_start;  // size n + 1
  std::vector<int> partner;    // j of each pair, ascending within a row
  std::vector<Vec3> shear;     // tangential spring per pair
  std::vector<Vec3> roll;      // rolling spring per pair (empty unless the rolling law has one)
  // 1 where the pair touched at the last force evaluation: the force loop counts a contact's first
  // and last step by it (contact/contact_input.hpp, spring_boundary_correction)
  std::vector<std::uint8_t> touched;
  // pair constants, one array each so that the force loop streams only those its law needs
  std::vector<double> sqrt_m_eff;
  std::vector<double> r_eff;
  std::vector<double> i_roll;

  std::size_t pair_count() const { return partner.size(); }
};

// Particles so crowded that the list would hold hundreds of neighbours each (build_neighbor_list).
class CrowdedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct NeighborBuildOptions {
  double skin = 0;
  bool keep_rolling_history = false;
};

// Builds `next` from the particles; history is carried over from `previous` (whose indices are old
// indices: new index k was old index new_to_old[k]; pass an empty map when nothing was re-sorted).
// When the roles of a pair swap (old j < old i), its stored vectors change sign.
void build_neighbor_list(const Particles& particles, const NeighborBuildOptions& options, const NeighborList& previous,
                         const std::vector<int>& new_to_old, NeighborList& next);

// A permutation (new_to_old) that orders particles along a cell grid, for memory locality.
std::vector<int> spatial_order(const Particles& particles, double cell_size);

}  // namespace dem
