#include "spec/stone_fill.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

namespace dem::spec {

std::vector<Vec3> fill_with_spheres(const std::vector<MemberSphere>& shape, double r) {
  // fcc sites: (i, j, k) a/2 with i + j + k even and cube edge a = 2 sqrt(2) r, so that nearest
  // neighbours, at (+-1, +-1, 0) and its permutations, are 2 r apart (touching)
  const double half = std::sqrt(2.0) * r;
  double reach = 0;
  for (const MemberSphere& s : shape) reach = std::max(reach, s.centre.cwiseAbs().maxCoeff() + s.radius);
  const int n = static_cast<int>(std::ceil(reach / half));
  // lattice index -> position in `inside` (-1: outside the shape), over the cube [-n, n]^3
  const int side = 2 * n + 1;
  std::vector<int> site(static_cast<std::size_t>(side) * side * side, -1);
  auto cell = [&](int i, int j, int k) -> int* {
    if (std::abs(i) > n || std::abs(j) > n || std::abs(k) > n) return nullptr;
    return &site[(static_cast<std::size_t>(i + n) * side + (j + n)) * side + (k + n)];
  };
  std::vector<std::array<int, 3>> inside;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) {
        if ((i + j + k) % 2 != 0) continue;
        const Vec3 x = half * Vec3(i, j, k);
        const bool in_union = std::any_of(shape.begin(), shape.end(), [&](const MemberSphere& s) {
          return (x - s.centre).squaredNorm() <= s.radius * s.radius;
        });
        if (!in_union) continue;
        *cell(i, j, k) = static_cast<int>(inside.size());
        inside.push_back({i, j, k});
      }

  // connected pieces through the 12 touching neighbours; the largest wins (ties: the first found)
  static const std::array<std::array<int, 3>, 12> kNeighbours{{{1, 1, 0},
                                                               {1, -1, 0},
                                                               {-1, 1, 0},
                                                               {-1, -1, 0},
                                                               {1, 0, 1},
                                                               {1, 0, -1},
                                                               {-1, 0, 1},
                                                               {-1, 0, -1},
                                                               {0, 1, 1},
                                                               {0, 1, -1},
                                                               {0, -1, 1},
                                                               {0, -1, -1}}};
  std::vector<int> piece(inside.size(), -1);
  std::vector<int> piece_size;
  for (std::size_t start = 0; start < inside.size(); ++start) {
    if (piece[start] >= 0) continue;
    const int label = static_cast<int>(piece_size.size());
    piece_size.push_back(0);
    std::vector<int> stack{static_cast<int>(start)};
    piece[start] = label;
    while (!stack.empty()) {
      const std::array<int, 3> at = inside[stack.back()];
      stack.pop_back();
      ++piece_size[label];
      for (const auto& d : kNeighbours) {
        const int* found = cell(at[0] + d[0], at[1] + d[1], at[2] + d[2]);
        if (found == nullptr || *found < 0 || piece[*found] >= 0) continue;
        piece[*found] = label;
        stack.push_back(*found);
      }
    }
  }
  std::vector<Vec3> centres;
  if (piece_size.empty()) return centres;
  const int largest = static_cast<int>(std::max_element(piece_size.begin(), piece_size.end()) - piece_size.begin());
  for (std::size_t s = 0; s < inside.size(); ++s)
    if (piece[s] == largest) centres.push_back(half * Vec3(inside[s][0], inside[s][1], inside[s][2]));
  return centres;
}

}  // namespace dem::spec
