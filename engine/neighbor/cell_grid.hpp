// A uniform cell grid over a box, holding particle indices sorted by cell (counting sort).
#pragma once

#include <array>
#include <vector>

#include "core/vec.hpp"

namespace dem {

class CellGrid {
 public:
  // Cells of at least `cell_size`, enlarged if the box would need more than `max_cells` cells.
  CellGrid(const Vec3& lo, const Vec3& hi, double cell_size, std::size_t max_cells);

  std::array<int, 3> cell_of(const Vec3& x) const;
  int linear(int ix, int iy, int iz) const { return ix + dims_[0] * (iy + dims_[1] * iz); }
  std::size_t cell_count() const { return static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2]; }

  // Fills the cells with the given particle indices (kept in ascending order within a cell).
  void fill(const std::vector<Vec3>& x, const std::vector<int>& members);

  // Calls visit(j) for every stored particle in the cells overlapping [x - reach, x + reach].
  template <class Visit>
  void for_each_near(const Vec3& x, double reach, Visit&& visit) const {
    std::array<int, 3> lo, hi;
    for (int d = 0; d < 3; ++d) {
      lo[d] = clamp_index(static_cast<int>(std::floor((x[d] - reach - origin_[d]) / cell_)), d);
      hi[d] = clamp_index(static_cast<int>(std::floor((x[d] + reach - origin_[d]) / cell_)), d);
    }
    for (int iz = lo[2]; iz <= hi[2]; ++iz)
      for (int iy = lo[1]; iy <= hi[1]; ++iy) {
        const int row = linear(0, iy, iz);
        const int begin = start_[row + lo[0]], end = start_[row + hi[0] + 1];
        for (int k = begin; k < end; ++k) visit(items_[k]);
      }
  }

 private:
  int clamp_index(int i, int d) const { return i < 0 ? 0 : (i >= dims_[d] ? dims_[d] - 1 : i); }

  Vec3 origin_;
  double cell_ = 1;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> start_;  // cell_count() + 1
  std::vector<int> items_;
};

}  // namespace dem
