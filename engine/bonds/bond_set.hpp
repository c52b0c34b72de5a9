// The bonds of a scene: created once between touching neighbours, stepped with the particles,
// broken for good; and the fragments they hold together.
#pragma once

#include <vector>

#include "bonds/bond_law.hpp"
#include "core/particles.hpp"
#include "core/scene.hpp"
#include "neighbor/neighbor_list.hpp"

namespace dem {

struct BondCounts {
  int intact = 0, tension = 0, shear = 0;
};

class BondSet {
 public:
  BondSet() = default;
  // Glues every listed pair whose gap is within the tolerance (settings.region, zones, spread)
  // and whose particles are of one stone: stone[id] (by particle id; -1 for loose particles, which
  // glue to each other). Members of rigid clumps are never bonded. The particles need orientations.
  BondSet(const BondSettings& settings, const Particles& p, const NeighborList& pairs, const std::vector<int>& stone);

  bool empty() const { return bonds_.empty(); }
  void restore(std::vector<Bond> saved) { bonds_ = std::move(saved); }  // a saved state's bonds
  const std::vector<Bond>& bonds() const { return bonds_; }

  // One step: adds each intact bond's force and moments to f and t (in bond order, serially: the
  // same sums for any thread count; the loads themselves are found on all threads). Breaks bonds
  // past their strength.
  void step(const Particles& p, double time, std::vector<Vec3>& f, std::vector<Vec3>& t);

  // After particles are re-sorted (new index k was old index new_to_old[k]).
  void renumber(const std::vector<int>& new_to_old);

  BondCounts counts() const;
  // Energy stored in the intact bonds' springs, J.
  double elastic_energy() const;

  // Fragment of each particle (by particle index): particles joined by intact bonds share one;
  // fragments are numbered from 1 in the order of their lowest particle id (`id`). `body`: each
  // particle's rigid clump (-1: none; empty: no clumps), whose members are one piece.
  std::vector<int> fragments(const std::vector<int>& id, const std::vector<int>& body = {}) const;

 private:
  // Fewer bonds than this are loaded on one thread: a parallel region costs about as much as
  // a few hundred bonds' loads (about 90 ns each, 2026-12-07).
  static constexpr int kParallelMinBonds = 1024;

  std::vector<Bond> bonds_;
  std::vector<BondLoad> loads_;  // scratch of step(): each bond's load, and whether it had one
  std::vector<char> loaded_;
};

}  // namespace dem
