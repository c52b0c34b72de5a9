#include "spec/lattice.hpp"

#include <array>
#include <cmath>

namespace dem::spec {
namespace {

bool inside(const Vec3& c, const Vec3& lo, const Vec3& hi, double r, bool planar) {
  const double eps = 1e-12 * (hi - lo).norm();
  for (int d = 0; d < 3; ++d)
    if ((d != 1 || !planar) && (c[d] - r < lo[d] - eps || c[d] + r > hi[d] + eps)) return false;
  return true;
}

int cells(double length, double step) { return static_cast<int>(std::floor(length / step)) + 2; }

// A 2D run's lattice: sites at y = 0, layers along z, rows along x (lattice_sites, `planar`). With counts,
// counts[0] sites per layer and counts[2] layers; otherwise every site whose disc lies in [lo, hi] in x and z.
std::vector<Vec3> planar_sites(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing,
                               const std::array<int, 3>* counts) {
  const double s = spacing * 2 * radius;
  const Vec3 start(lo.x() + radius, 0, lo.z() + radius);
  const Vec3 extent = hi - lo;
  // FCC's cube face: the even points of a grid of s / sqrt(2); HEX: layers s sqrt(3)/2 apart, odd ones shifted
  const double step_x = kind == LatticeKind::Fcc ? s / std::sqrt(2.0) : s;
  const double step_z = kind == LatticeKind::Fcc   ? s / std::sqrt(2.0)
                        : kind == LatticeKind::Hex ? s * std::sqrt(3.0) / 2
                                                   : s;
  const int layers = counts ? (*counts)[2] : cells(extent.z(), step_z);
  std::vector<Vec3> out;
  for (int k = 0; k < layers; ++k) {
    const int per_layer = counts ? (*counts)[0] : cells(extent.x(), step_x);
    for (int n = 0; n < per_layer; ++n) {
      double x = 0;
      if (kind == LatticeKind::Fcc) {
        const int i = counts ? 2 * n + k % 2 : n;  // counted: every other point of the row
        if (!counts && (i + k) % 2 != 0) continue;
        x = step_x * i;
      } else {
        x = step_x * n + (kind == LatticeKind::Hex && k % 2 ? s / 2 : 0);
      }
      const Vec3 c = start + Vec3(x, 0, step_z * k);
      if (counts || inside(c, lo, hi, radius, true)) out.push_back(c);
    }
  }
  return out;
}

}  // namespace

std::vector<Vec3> lattice_sites(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing,
                                bool planar) {
  if (planar) return planar_sites(kind, lo, hi, radius, spacing, nullptr);
  const double s = spacing * 2 * radius;  // nearest-neighbour distance
  const Vec3 start = lo + Vec3::Constant(radius);
  const Vec3 extent = hi - lo;
  std::vector<Vec3> out;
  if (kind == LatticeKind::Cubic) {
    for (int k = 0; k < cells(extent.z(), s); ++k)
      for (int j = 0; j < cells(extent.y(), s); ++j)
        for (int i = 0; i < cells(extent.x(), s); ++i) {
          const Vec3 c = start + s * Vec3(i, j, k);
          if (inside(c, lo, hi, radius, false)) out.push_back(c);
        }
  } else if (kind == LatticeKind::Fcc) {
    // cubic cell of side a = sqrt(2) s with four sites; taken in half-cell layers so the order is by z
    const double a = std::sqrt(2.0) * s;
    const double h = a / 2;
    for (int k = 0; k < cells(extent.z(), h); ++k)
      for (int j = 0; j < cells(extent.y(), h); ++j)
        for (int i = 0; i < cells(extent.x(), h); ++i) {
          if ((i + j + k) % 2 != 0) continue;  // fcc sites are the even points of the half-cell grid
          const Vec3 c = start + h * Vec3(i, j, k);
          if (inside(c, lo, hi, radius, false)) out.push_back(c);
        }
  } else {
    // hexagonal close packing: triangular layers, ABAB stacked at s sqrt(2/3)
    const double row = s * std::sqrt(3.0) / 2, layer = s * std::sqrt(2.0 / 3.0);
    for (int k = 0; k < cells(extent.z(), layer); ++k) {
      const Vec3 shift = (k % 2) ? Vec3(s / 2, s / (2 * std::sqrt(3.0)), 0) : Vec3::Zero();
      for (int j = 0; j < cells(extent.y(), row); ++j)
        for (int i = 0; i < cells(extent.x(), s); ++i) {
          const Vec3 c = start + shift + Vec3(s * (i + 0.5 * (j % 2)), row * j, layer * k);
          if (inside(c, lo, hi, radius, false)) out.push_back(c);
        }
    }
  }
  return out;
}

std::vector<Vec3> lattice_sites_counted(LatticeKind kind, const Vec3& lo, double radius, double spacing,
                                        const std::array<int, 3>& n, bool planar) {
  if (planar) return planar_sites(kind, lo, lo, radius, spacing, &n);
  const double s = spacing * 2 * radius;
  const Vec3 start = lo + Vec3::Constant(radius);
  std::vector<Vec3> out;
  if (kind == LatticeKind::Cubic) {
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) out.push_back(start + s * Vec3(i, j, k));
  } else if (kind == LatticeKind::Fcc) {
    const double h = std::sqrt(2.0) * s / 2;
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = (j + k) % 2; i < 2 * n[0]; i += 2) out.push_back(start + h * Vec3(i, j, k));
  } else {
    const double row = s * std::sqrt(3.0) / 2, layer = s * std::sqrt(2.0 / 3.0);
    for (int k = 0; k < n[2]; ++k) {
      const Vec3 shift = (k % 2) ? Vec3(s / 2, s / (2 * std::sqrt(3.0)), 0) : Vec3::Zero();
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) out.push_back(start + shift + Vec3(s * (i + 0.5 * (j % 2)), row * j, layer * k));
    }
  }
  return out;
}

double lattice_site_bound(LatticeKind kind, const Vec3& lo, const Vec3& hi, double radius, double spacing,
                          bool planar) {
  const double s = spacing * 2 * radius;
  Vec3 room = (hi - lo).array() - 2 * radius;  // where centres may lie
  if (planar) room.y() = 0;
  if ((room.array() < 0).any()) return 0;
  // centres a step apart along an axis, the first at its start
  auto along = [](double length, double step) { return std::floor(length / step * (1 + 1e-12)) + 1; };
  if (planar) {
    if (kind == LatticeKind::Cubic) return along(room.x(), s) * along(room.z(), s);
    if (kind == LatticeKind::Fcc)
      return std::ceil(along(room.x(), s / std::sqrt(2.0)) * along(room.z(), s / std::sqrt(2.0)) / 2);
    return along(room.x(), s) * along(room.z(), s * std::sqrt(3.0) / 2);
  }
  if (kind == LatticeKind::Cubic) return along(room.x(), s) * along(room.y(), s) * along(room.z(), s);
  if (kind == LatticeKind::Fcc) {
    const double h = std::sqrt(2.0) * s / 2;
    return std::ceil(along(room.x(), h) * along(room.y(), h) * along(room.z(), h) / 2);
  }
  return along(room.x(), s) * along(room.y(), s * std::sqrt(3.0) / 2) * along(room.z(), s * std::sqrt(2.0 / 3.0));
}

}  // namespace dem::spec
