// A uniform cell grid over a box, holding particle indices sorted by cell (counting sort).
#pragma once

#include <array>
#include <cmath>
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
      lo[d] = index_of(x[d] - reach, d);
      hi[d] = index_of(x[d] + reach, d);
    }
    for (int iz = lo[2]; iz <= hi[2]; ++iz)
      for (int iy = lo[1]; iy <= hi[1]; ++iy) {
        const int row = linear(0, iy, iz);
        const int begin = start_[row + lo[0]], end = start_[row + hi[0] + 1];
        for (int k = begin; k < end; ++k) visit(items_[k]);
      }
  }

 private:
  // The cell along axis d of a coordinate, clamped to the grid before it becomes an int: a
  // coordinate past the int range, or NaN (0 then), was undefined behaviour (the saved-state fuzzer
  // reached a NaN position through a build before the stability guard saw it).
  int index_of(double coordinate, int d) const {
    const double i = std::floor((coordinate - origin_[d]) / cell_);
    return i >= 0 ? (i < dims_[d] ? static_cast<int>(i) : dims_[d] - 1) : 0;
  }

  Vec3 origin_;
  double cell_ = 1;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> start_;  // cell_count() + 1
  std::vector<int> items_;
};

}  // namespace dem
