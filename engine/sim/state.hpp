// Everything the force loop reads and writes, in one place.
#pragma once

#include <cstdint>
#include <vector>

#include "contact/pair_params.hpp"
#include "core/particles.hpp"
#include "neighbor/neighbor_list.hpp"
#include "walls/wall.hpp"

namespace dem {

// Particle-wall candidates of each particle (compressed rows), rebuilt with the neighbour list.
struct WallContacts {
  std::vector<int> row_start;  // size n + 1
  std::vector<int> wall;       // wall index of each entry
  std::vector<Vec3> shear;     // tangential spring per entry
  std::vector<Vec3> roll;      // rolling spring per entry (EPSD only)
  std::vector<double> fn;      // normal force of the last step (0 when apart)
  std::vector<double> ft;      // tangential force magnitude of the last step
  std::vector<std::uint8_t> touching;
};

// Results of the last force evaluation per listed pair; read by the gather and by observers.
struct PairResults {
  std::vector<Vec3> force;        // on i
  std::vector<Vec3> lever;        // n x F_s: torque -r_i lever on i, -r_j lever on j
  std::vector<Vec3> roll_moment;  // on i (rolling laws only)
  std::vector<double> fn;
  std::vector<std::uint8_t> touching;
  std::vector<int> as_partner_start;  // pairs in which particle p is j, compressed rows (size n + 1)
  std::vector<int> as_partner;        // ascending pair indices
};

struct SimState {
  Particles particles;
  NeighborList neighbors;
  PairResults pairs;
  std::vector<Wall> walls;
  WallContacts wall_contacts;
  PairTable table;
  Vec3 gravity = Vec3::Zero();
  double dt = 0;
};

}  // namespace dem
