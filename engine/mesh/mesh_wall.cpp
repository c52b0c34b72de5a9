#include "mesh/mesh_wall.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dem {

void TriangleGrid::build(const std::vector<Vec3>& vertices, const std::vector<std::array<int, 3>>& triangles,
                         double min_cell) {
  Vec3 lo = vertices[0], hi = vertices[0];
  for (const Vec3& v : vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  // the typical (median) triangle extent: each triangle then spans about one to eight cells
  std::vector<double> extent(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Vec3 a = vertices[tri[0]], b = vertices[tri[1]], c = vertices[tri[2]];
    extent[t] = (a.cwiseMax(b).cwiseMax(c) - a.cwiseMin(b).cwiseMin(c)).maxCoeff();
  }
  std::nth_element(extent.begin(), extent.begin() + extent.size() / 2, extent.end());
  cell_ = std::max({min_cell, extent[extent.size() / 2], 1e-12});
  const Vec3 size = hi - lo;
  constexpr double kMaxCells = 4e6;
  auto cells_for = [&](double cell) {
    double total = 1;
    for (int d = 0; d < 3; ++d) total *= std::floor(size[d] / cell) + 1;
    return total;
  };
  while (cells_for(cell_) > kMaxCells) cell_ *= 1.25;
  origin_ = lo;
  for (int d = 0; d < 3; ++d) dims_[d] = static_cast<int>(std::floor(size[d] / cell_)) + 1;
  const std::size_t cells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];

  auto cell_range = [&](int t, std::array<int, 3>& a, std::array<int, 3>& b) {
    const auto& tri = triangles[t];
    const Vec3 p = vertices[tri[0]], q = vertices[tri[1]], r = vertices[tri[2]];
    const Vec3 tlo = p.cwiseMin(q).cwiseMin(r), thi = p.cwiseMax(q).cwiseMax(r);
    for (int d = 0; d < 3; ++d) {
      a[d] = std::clamp(static_cast<int>(std::floor((tlo[d] - origin_[d]) / cell_)), 0, dims_[d] - 1);
      b[d] = std::clamp(static_cast<int>(std::floor((thi[d] - origin_[d]) / cell_)), 0, dims_[d] - 1);
    }
  };
  auto for_cells = [&](int t, auto&& use) {
    std::array<int, 3> a, b;
    cell_range(t, a, b);
    for (int iz = a[2]; iz <= b[2]; ++iz)
      for (int iy = a[1]; iy <= b[1]; ++iy)
        for (int ix = a[0]; ix <= b[0]; ++ix)
          use(ix + static_cast<std::size_t>(dims_[0]) * (iy + static_cast<std::size_t>(dims_[1]) * iz));
  };
  start_.assign(cells + 1, 0);
  const int nt = static_cast<int>(triangles.size());
  for (int t = 0; t < nt; ++t) for_cells(t, [&](std::size_t c) { ++start_[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  items_.resize(start_[cells]);
  std::vector<int> fill(start_.begin(), start_.end() - 1);
  for (int t = 0; t < nt; ++t) for_cells(t, [&](std::size_t c) { items_[fill[c]++] = t; });
}

MeshWall MeshWall::from(const WallInit& init, int boundary) {
  const MeshShape& shape = std::get<MeshShape>(init.shape);
  MeshWall m;
  m.material = init.material;
  m.boundary = boundary;
  m.vertices0 = shape.vertices;
  m.triangles = shape.triangles;
  m.topology = MeshTopology(TriangleMesh{shape.vertices, shape.triangles});
  m.vertices = shape.vertices;
  m.update_planes();
  // how far the neighbour across each edge rises out of the triangle's plane (a rigid motion keeps it)
  m.fold.assign(m.triangles.size(), {0, 0, 0});
  m.across.assign(m.triangles.size(), {-1, -1, -1});
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int j = 0; j < 3; ++j) {
      const int e = m.topology.triangle_edges[t][j];
      const int first = m.topology.edge_triangle_start[e], count = m.topology.edge_triangle_start[e + 1] - first;
      if (count != 2) continue;  // an open edge, or one of more than two triangles: no valley
      const int u = m.topology.edge_triangles[first] == static_cast<int>(t) ? m.topology.edge_triangles[first + 1]
                                                                            : m.topology.edge_triangles[first];
      const auto& edge = m.topology.edges[e];
      int far = m.triangles[u][0];
      for (int v : m.triangles[u])
        if (v != edge[0] && v != edge[1]) far = v;
      const Vec3 p0 = m.vertices[edge[0]];
      const double rise = m.normals[t].dot(m.vertices[far] - p0) / (m.vertices[edge[1]] - p0).norm();
      m.fold[t][j] = std::abs(rise) > 1e-12 ? rise : 0;  // flat within rounding: a seam
      if (m.fold[t][j] != 0) m.across[t][j] = u;
    }
  return m;
}

void MeshWall::update_planes() {
  normals.resize(triangles.size());
  offsets.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    normals[t] = (vertices[tri[1]] - vertices[tri[0]]).cross(vertices[tri[2]] - vertices[tri[0]]).normalized();
    offsets[t] = normals[t].dot(vertices[tri[0]]);
  }
}

Vec3 MeshWall::centroid() const {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& v : vertices) sum += v;
  return sum / static_cast<double>(vertices.size());
}

void MeshWall::move_to(const WallPose& next) {
  pose = next;
  grid_stale = true;
  for (std::size_t v = 0; v < vertices.size(); ++v) vertices[v] = next.place(vertices0[v]);
  update_planes();
}

namespace {

// Relative slack of the Voronoi tests: a centre exactly above a shared edge or vertex must pass
// them despite rounding (the duplicate is then removed by the feature and point tests).
constexpr double kSlack = 1e-9;

// The centre lies in the region of the surface closest to edge e: outside every triangle on e,
// across e (d . m >= 0 with m the in-plane normal of e pointing away from the triangle).
bool in_edge_region(const MeshWall& mesh, int e, const Vec3& d) {
  const auto& edge = mesh.topology.edges[e];
  const Vec3 p0 = mesh.vertices[edge[0]], p1 = mesh.vertices[edge[1]];
  const Vec3 u = (p1 - p0).normalized();
  const double d_len = d.norm();
  for (int k = mesh.topology.edge_triangle_start[e]; k < mesh.topology.edge_triangle_start[e + 1]; ++k) {
    const auto& tri = mesh.triangles[mesh.topology.edge_triangles[k]];
    int opposite = tri[0];
    for (int v : tri)
      if (v != edge[0] && v != edge[1]) opposite = v;
    Vec3 m = p0 - mesh.vertices[opposite];
    m -= m.dot(u) * u;
    if (d.dot(m) < -kSlack * d_len * m.norm()) return false;
  }
  return true;
}

// The centre lies in the region closest to vertex v: no edge from v leads towards it.
bool in_vertex_region(const MeshWall& mesh, int v, const Vec3& d) {
  const double d_len = d.norm();
  const Vec3 pv = mesh.vertices[v];
  for (int k = mesh.topology.vertex_neighbor_start[v]; k < mesh.topology.vertex_neighbor_start[v + 1]; ++k) {
    const Vec3 along = mesh.vertices[mesh.topology.vertex_neighbors[k]] - pv;
    if (d.dot(along) > kSlack * d_len * along.norm()) return false;
  }
  return true;
}

bool triangle_has_edge(const MeshWall& mesh, int t, int e) {
  const auto& edges = mesh.topology.triangle_edges[t];
  return edges[0] == e || edges[1] == e || edges[2] == e;
}

bool triangle_has_vertex(const MeshWall& mesh, int t, int v) {
  const auto& tri = mesh.triangles[t];
  return tri[0] == v || tri[1] == v || tri[2] == v;
}

// In-plane unit normal of triangle t's edge j pointing into t.
Vec3 inward_normal(const MeshWall& mesh, int t, int j) {
  const auto& tri = mesh.triangles[t];
  const Vec3 p0 = mesh.vertices[tri[j]], p1 = mesh.vertices[tri[(j + 1) % 3]],
             opposite = mesh.vertices[tri[(j + 2) % 3]];
  Vec3 m = mesh.normals[t].cross(p1 - p0).normalized();
  return m.dot(opposite - p0) < 0 ? Vec3(-m) : m;
}

// How far point p (in t's plane) lies inside t across its edge j (negative: outside).
double inside_by(const MeshWall& mesh, int t, int j, const Vec3& p) {
  return inward_normal(mesh, t, j).dot(p - mesh.vertices[mesh.triangles[t][j]]);
}

struct Point2 {
  double x, y;
};
double cross2(const Point2& a, const Point2& b) { return a.x * b.y - a.y * b.x; }
double dot2(const Point2& a, const Point2& b) { return a.x * b.x + a.y * b.y; }

// The disc |q| <= a (about the origin) inside the triangle (0, b, c), signed as the triangle: the
// part of the segment bc inside the circle gives a triangle, the parts outside circular sectors.
// Also the length of bc inside the circle and the angle of the sectors (the arc inside).
struct DiscPart {
  double area = 0, chord = 0, angle = 0;
};
DiscPart disc_in_triangle(const Point2& b, const Point2& c, double a) {
  const Point2 d{c.x - b.x, c.y - b.y};
  const double qa = dot2(d, d), qb = 2 * dot2(b, d), qc = dot2(b, b) - a * a;
  DiscPart out;
  auto sector = [&](const Point2& p, const Point2& q) {
    const double angle = std::atan2(cross2(p, q), dot2(p, q));
    out.area += 0.5 * a * a * angle;
    out.angle += angle;
  };
  const double disc = qb * qb - 4 * qa * qc;
  const double root = disc > 0 ? std::sqrt(disc) : 0;
  const double s1 = qa > 0 ? std::clamp((-qb - root) / (2 * qa), 0.0, 1.0) : 0;
  const double s2 = qa > 0 ? std::clamp((-qb + root) / (2 * qa), 0.0, 1.0) : 0;
  if (!(qa > 0) || disc <= 0 || s1 >= s2) {  // the segment misses the circle
    sector(b, c);
    return out;
  }
  const Point2 p{b.x + s1 * d.x, b.y + s1 * d.y}, q{b.x + s2 * d.x, b.y + s2 * d.y};
  sector(b, p);
  out.area += 0.5 * cross2(p, q);
  out.chord = (s2 - s1) * std::sqrt(qa);
  sector(q, c);
  return out;
}

}  // namespace

DiscShare disc_share(const MeshWall& mesh, int t, const Vec3& p, double a, const int* edges, int edge_count) {
  DiscShare out;
  if (!(a > 0)) return out;
  const auto& tri = mesh.triangles[t];
  const Vec3 n = mesh.normals[t];
  const Vec3 e1 = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).normalized(), e2 = n.cross(e1);
  // each edge's half-plane m . q + h >= 0, q in the plane's coordinates about p
  Vec3 inward[3];
  Point2 m[3];
  double h[3];
  for (int k = 0; k < edge_count; ++k) {
    inward[k] = inward_normal(mesh, t, edges[k]);
    m[k] = {inward[k].dot(e1), inward[k].dot(e2)};
    h[k] = inward[k].dot(p - mesh.vertices[tri[edges[k]]]);
  }
  if (edge_count == 1) {  // a disc cut by one chord: its segment in closed form
    const double u = std::clamp(h[0] / a, -1.0, 1.0), root = std::sqrt(1 - u * u);
    out.share = 0.5 + (u * root + std::asin(u)) / std::numbers::pi;
    const double slope = 2 / std::numbers::pi * root;  // d share / d u
    out.d_centre = (slope / a) * inward[0];
    out.d_radius = -slope * u / a;
    return out;
  }
  // The square about the disc clipped by each half-plane (Sutherland-Hodgman), every polygon edge
  // labelled with the line it lies on (-1: the square's, outside the disc); then the disc's area
  // inside that convex polygon, fan by fan from the centre. Its derivatives: moving the disc along
  // a line's inward normal gains that line's chord inside the disc; growing it gains the arc inside.
  Point2 poly[8] = {{-a, -a}, {a, -a}, {a, a}, {-a, a}}, next[8];
  int line[8] = {-1, -1, -1, -1}, next_line[8];
  int count = 4;
  for (int k = 0; k < edge_count && count > 0; ++k) {
    int kept = 0;
    for (int i = 0; i < count; ++i) {
      const Point2 &u = poly[i], &w = poly[(i + 1) % count];
      const double fu = dot2(m[k], u) + h[k], fw = dot2(m[k], w) + h[k];
      auto cut = [&] {
        const double s = fu / (fu - fw);
        return Point2{u.x + s * (w.x - u.x), u.y + s * (w.y - u.y)};
      };
      if (fu >= 0) {
        next[kept] = u;
        next_line[kept++] = line[i];
        if (fw < 0) {  // leaving: the polygon follows line k from here
          next[kept] = cut();
          next_line[kept++] = k;
        }
      } else if (fw >= 0) {  // entering: the rest of this edge
        next[kept] = cut();
        next_line[kept++] = line[i];
      }
    }
    count = kept;
    std::copy(next, next + count, poly);
    std::copy(next_line, next_line + count, line);
  }
  double area = 0, angle = 0;
  Vec3 d_centre = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    const DiscPart part = disc_in_triangle(poly[i], poly[(i + 1) % count], a);
    area += part.area;
    angle += part.angle;
    if (line[i] >= 0) d_centre += part.chord * inward[line[i]];
  }
  const double full = std::numbers::pi * a * a;
  out.share = std::clamp(area / full, 0.0, 1.0);
  out.d_centre = d_centre / full;
  out.d_radius = (angle / std::numbers::pi - 2 * out.share) / a;  // (arc a) / (pi a^2) - 2 share / a
  return out;
}

namespace {

// A valley edge j of triangle t, for a centre whose signed distance to t's plane has sign `side`:
// the other face rises on the centre's side of t, and the centre lies on the side of the other face
// where t rises (a convex edge seen from behind t, with the centre above the other face, is none).
bool is_valley(const MeshWall& mesh, int t, int j, const Vec3& x, double side) {
  if (!(side * mesh.fold[t][j] > 0)) return false;
  const int u = mesh.across[t][j];
  const Vec3& t_far = mesh.vertices[mesh.triangles[t][(j + 2) % 3]];
  return (mesh.normals[u].dot(x) - mesh.offsets[u]) * (mesh.normals[u].dot(t_far) - mesh.offsets[u]) > 0;
}

// Face t's share of a contact at its valleys and the share's gradient in the centre: the part of
// the contact disc (the sphere's section by t's plane, about the centre's projection) on t's side
// of each valley edge that cuts it; 1 without one.
struct ValleyShare {
  double share = 1;
  Vec3 gradient = Vec3::Zero();
};

// A disc share's gradient in the sphere's centre, for the disc of radius a about the centre's
// projection on t's plane at signed distance d (sign `side`): through the projection (in the plane)
// and through the radius a = sqrt(r^2 - d^2), which shrinks as the centre moves off the plane.
Vec3 share_gradient(const MeshWall& mesh, int t, const DiscShare& share, double signed_d, double a, double side) {
  return share.d_centre - share.d_radius * (std::abs(signed_d) / a) * side * mesh.normals[t];
}
ValleyShare valley_share(const MeshWall& mesh, int t, const Vec3& x, double r) {
  ValleyShare out;
  const double signed_d = mesh.normals[t].dot(x) - mesh.offsets[t];
  const double a2 = r * r - signed_d * signed_d;
  if (!(a2 > 0)) return out;
  const double side = signed_d >= 0 ? 1 : -1, a = std::sqrt(a2);
  const Vec3 p = x - signed_d * mesh.normals[t];
  int valleys[3], count = 0;
  for (int j = 0; j < 3; ++j)
    if (is_valley(mesh, t, j, x, side) && inside_by(mesh, t, j, p) < a) valleys[count++] = j;
  if (count == 0) return out;
  const DiscShare share = disc_share(mesh, t, p, a, valleys, count);
  out.share = share.share;
  out.gradient = share_gradient(mesh, t, share, signed_d, a, side);
  return out;
}

// The weight of a contact with edge e at its closest point q: continuous with the contacts of the
// faces on either side, which carry their valley shares up to the edge. Across the edge's region (a
// wedge between the two faces' normals) it turns from one face's share to the other's with the
// angle; an open edge carries its one face's. A weighted face whose contact passed over a ridge or
// an open edge to that edge's contact of weight 1 gained the rest of a contact's energy at once (an
// independent tester's elastic bounce on a bumpy terrain came off 14% faster).
ValleyShare edge_weight(const MeshWall& mesh, int e, const Vec3& x, double r, const Vec3& q) {
  const int first = mesh.topology.edge_triangle_start[e], count = mesh.topology.edge_triangle_start[e + 1] - first;
  if (count < 1 || count > 2) return {};
  const int t0 = mesh.topology.edge_triangles[first];
  const ValleyShare w0 = valley_share(mesh, t0, x, r);
  if (count == 1) return w0;
  const int t2 = mesh.topology.edge_triangles[first + 1];
  const ValleyShare w2 = valley_share(mesh, t2, x, r);
  if (w0.share == 1 && w2.share == 1 && w0.gradient.isZero(0) && w2.gradient.isZero(0)) return {};
  // the faces' normals towards the centre, and the centre's angle from the first about the edge
  const Vec3 d = x - q;
  const Vec3 a0 = (mesh.normals[t0].dot(x) - mesh.offsets[t0] >= 0 ? 1.0 : -1.0) * mesh.normals[t0];
  const Vec3 a2 = (mesh.normals[t2].dot(x) - mesh.offsets[t2] >= 0 ? 1.0 : -1.0) * mesh.normals[t2];
  const Vec3 turn = a0.cross(a2);
  const double opening = std::atan2(turn.norm(), a0.dot(a2));
  ValleyShare out;
  if (!(opening > 1e-9) || !(d.squaredNorm() > 0)) {  // a flat seam: its region is a line
    out.share = 0.5 * (w0.share + w2.share);
    out.gradient = 0.5 * (w0.gradient + w2.gradient);
    return out;
  }
  const Vec3 k = turn / turn.norm();
  const double angle = std::atan2(a0.cross(d).dot(k), a0.dot(d));
  const double s = std::clamp(angle / opening, 0.0, 1.0);
  out.share = (1 - s) * w0.share + s * w2.share;
  out.gradient = (1 - s) * w0.gradient + s * w2.gradient;
  if (s > 0 && s < 1) out.gradient += (w2.share - w0.share) / opening * k.cross(d) / d.squaredNorm();
  return out;
}

}  // namespace

int mesh_touches(const MeshWall& mesh, const int* candidates, int candidate_count, const Vec3& x, double r,
                 MeshTouch* out, int out_capacity) {
  // The triangles within r, then their contacts by feature: faces first, so that an edge or vertex
  // of a touched face (the common case on a flat patch) is dismissed before its Voronoi test.
  constexpr int kNear = 32;
  struct Near {
    int triangle;
    ClosestPoint cp;
    double d2;
  } near[kNear];
  int near_count = 0;
  // Planes of the touched faces found so far: a triangle in one of them cannot add a contact (an
  // edge or vertex point there is dominated or outside its region), so it is not tested at all.
  // This is what keeps a terrain cheap: most candidates are coplanar neighbours of the face below.
  // Candidates come nearest first (ordered at the list build), so the face is usually found first.
  constexpr int kPlanes = 4;
  int face_tri[kPlanes];
  int planes = 0;
  for (int c = 0; c < candidate_count && near_count < kNear; ++c) {
    const int t = candidates[c];
    bool in_touched_plane = false;
    for (int k = 0; k < planes && !in_touched_plane; ++k) {
      const int f = face_tri[k];
      in_touched_plane =
          mesh.normals[t].dot(mesh.normals[f]) > 1 - 1e-12 && std::abs(mesh.offsets[t] - mesh.offsets[f]) <= kSlack * r;
    }
    if (in_touched_plane) continue;
    const auto& tri = mesh.triangles[t];
    const ClosestPoint cp = closest_on_triangle(x, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    const double d2 = (x - cp.point).squaredNorm();
    if (d2 >= r * r) continue;
    near[near_count++] = {t, cp, d2};
    if (cp.feature == Feature::Face && planes < kPlanes) face_tri[planes++] = t;
  }
  int written = 0;
  auto accept = [&](const Near& n, int key, double weight = 1, const Vec3& weight_gradient = Vec3::Zero()) {
    for (int k = 0; k < written; ++k)  // the same point reached through another triangle
      if ((out[k].point - n.cp.point).squaredNorm() <= kSlack * kSlack * r * r) return;
    if (written == out_capacity) return;
    MeshTouch& touch = out[written++];
    touch.feature = n.cp.feature;
    touch.key = key;
    touch.triangle = n.triangle;
    touch.point = n.cp.point;
    const double dist = std::sqrt(n.d2);
    if (dist > 0) {
      touch.normal = (x - n.cp.point) / dist;
    } else {  // centre on the surface: the face normal, either side will do
      const auto& tri = mesh.triangles[n.triangle];
      touch.normal = (mesh.vertices[tri[1]] - mesh.vertices[tri[0]])
                         .cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]])
                         .normalized();
    }
    touch.delta = r - dist;
    touch.weight = weight;
    touch.weight_gradient = weight_gradient;
  };
  // Faces: the centre's projection inside the triangle, or beyond valley edges only with some of
  // the contact disc still on the triangle's side; weighted where a valley edge crosses the disc.
  for (int k = 0; k < near_count; ++k) {
    const int t = near[k].triangle;
    const bool inside = near[k].cp.feature == Feature::Face;
    const double signed_d = mesh.normals[t].dot(x) - mesh.offsets[t];
    const double side = signed_d >= 0 ? 1 : -1;
    const Vec3 p = x - signed_d * mesh.normals[t];
    const double a2 = r * r - signed_d * signed_d;
    if (!(a2 > 0)) continue;
    const double a = std::sqrt(a2);
    int valleys[3], valley_count = 0;
    bool beyond_other_edge = false;
    for (int j = 0; j < 3; ++j) {
      const bool valley = is_valley(mesh, t, j, x, side);
      if (inside && !valley) continue;  // inside: only valley edges can cut the disc's share
      const double h = inside_by(mesh, t, j, p);
      if (valley && h < a) {
        if (h <= -a) beyond_other_edge = true;  // the disc lies wholly beyond this valley edge
        valleys[valley_count++] = j;
      } else if (!valley && h < 0) {
        beyond_other_edge = true;  // past a ridge, a seam or an open edge: its edge or vertex rules
      }
    }
    if (beyond_other_edge || (!inside && valley_count == 0)) continue;
    DiscShare share;
    if (valley_count) {
      share = disc_share(mesh, t, p, a, valleys, valley_count);
      if (share.share <= 0) continue;
    }
    Near face = near[k];
    face.cp = {p, Feature::Face, 0};
    face.d2 = signed_d * signed_d;
    accept(face, t, share.share, share_gradient(mesh, t, share, signed_d, a, side));
  }
  for (int k = 0; k < near_count; ++k) {
    if (near[k].cp.feature != Feature::Edge) continue;
    const int e = mesh.topology.triangle_edges[near[k].triangle][near[k].cp.index];
    bool covered = false;
    for (int o = 0; o < written && !covered; ++o)
      covered = (out[o].feature == Feature::Face && triangle_has_edge(mesh, out[o].key, e)) ||
                (out[o].feature == Feature::Edge && out[o].key == e);
    if (!covered && in_edge_region(mesh, e, x - near[k].cp.point)) {
      const ValleyShare w = edge_weight(mesh, e, x, r, near[k].cp.point);
      if (w.share > 0) accept(near[k], e, w.share, w.gradient);
    }
  }
  for (int k = 0; k < near_count; ++k) {
    if (near[k].cp.feature != Feature::Vertex) continue;
    const int v = mesh.triangles[near[k].triangle][near[k].cp.index];
    bool covered = false;
    for (int o = 0; o < written && !covered; ++o) {
      if (out[o].feature == Feature::Face)
        covered = triangle_has_vertex(mesh, out[o].key, v);
      else if (out[o].feature == Feature::Edge)
        covered = mesh.topology.edges[out[o].key][0] == v || mesh.topology.edges[out[o].key][1] == v;
      else
        covered = out[o].key == v;
    }
    if (!covered && in_vertex_region(mesh, v, x - near[k].cp.point)) accept(near[k], v);
  }
  return written;
}

}  // namespace dem
