#include "neighbor/cell_grid.hpp"

#include <algorithm>
#include <cmath>

namespace dem {

CellGrid::CellGrid(const Vec3& lo, const Vec3& hi, double cell_size, std::size_t max_cells)
    : origin_(lo), cell_(cell_size) {
  Vec3 extent = (hi - lo).cwiseMax(Vec3::Constant(cell_size));
  // A particle gone to an absurd place (a blow-up the guard is about to stop) must not make a count
  // of cells past an int (undefined behaviour, found by the sanitizer suite) or one that no growth of
  // the cells brings down (an infinite extent): such a grid is one cell.
  if (!extent.allFinite()) extent = Vec3::Constant(cell_size);
  auto dims_for = [&](double c) {
    std::array<int, 3> d;
    for (int k = 0; k < 3; ++k) d[k] = static_cast<int>(std::clamp(std::floor(extent[k] / c) + 1, 1.0, 1e9));
    return d;
  };
  dims_ = dims_for(cell_);
  // Particles far apart (a few flying away) must not make the grid huge: grow the cells instead.
  while (static_cast<double>(dims_[0]) * dims_[1] * dims_[2] > static_cast<double>(max_cells)) {
    cell_ *= 1.25;
    dims_ = dims_for(cell_);
  }
}

std::array<int, 3> CellGrid::cell_of(const Vec3& x) const {
  std::array<int, 3> c;
  for (int d = 0; d < 3; ++d) c[d] = index_of(x[d], d);
  return c;
}

void CellGrid::fill(const std::vector<Vec3>& x, const std::vector<int>& members) {
  start_.assign(cell_count() + 1, 0);
  std::vector<int> cell(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) {
    const auto c = cell_of(x[members[k]]);
    cell[k] = linear(c[0], c[1], c[2]);
    ++start_[cell[k] + 1];
  }
  for (std::size_t c = 0; c < cell_count(); ++c) start_[c + 1] += start_[c];
  items_.resize(members.size());
  std::vector<int> fill_at(start_.begin(), start_.end() - 1);
  for (std::size_t k = 0; k < members.size(); ++k) items_[fill_at[cell[k]]++] = members[k];
}

}  // namespace dem
