// Arithmetic written once for one contact (T = double) or several side by side (T = Lanes<W>, GCC
// vector extensions, one contact per lane). The contact laws are written against these helpers,
// so the vector loop and the scalar loop perform the same IEEE operations in the same order and
// give bit-identical results; the vector loop only runs several contacts in one instruction.
//
// Branches become selections: both sides are computed and each lane keeps its own.
#pragma once

#include <cmath>
#include <cstring>
#include <type_traits>

#include "core/vec.hpp"

#define DEM_LANES_INLINE [[gnu::always_inline]] inline

namespace dem {

// (vector_size cannot depend on a template parameter: GCC would drop it and leave a plain double)
typedef double Lanes4 __attribute__((vector_size(32)));
template <int W>
struct LanesOf;
template <>
struct LanesOf<1> {
  using type = double;
};
template <>
struct LanesOf<4> {
  using type = Lanes4;
};
template <int W>
using Lanes = typename LanesOf<W>::type;
static_assert(sizeof(Lanes4) == 4 * sizeof(double));
typedef double Lanes2 __attribute__((vector_size(16)));

// Two consecutive doubles as one 16-byte load (no alignment needed).
DEM_LANES_INLINE Lanes2 load_pair(const double* p) {
  Lanes2 r;
  std::memcpy(&r, p, sizeof r);
  return r;
}

template <class T>
constexpr int lane_count() {
  if constexpr (std::is_same_v<T, double>)
    return 1;
  else
    return sizeof(T) / sizeof(double);
}

// The same value in every lane.
template <class T>
DEM_LANES_INLINE T splat(double value) {
  if constexpr (std::is_same_v<T, double>)
    return value;
  else
    return T{} + value;
}

template <class T>
DEM_LANES_INLINE T lane_sqrt(T a) {
  if constexpr (std::is_same_v<T, double>) {
    return std::sqrt(a);
  } else {
    T r;
    for (int l = 0; l < lane_count<T>(); ++l) r[l] = std::sqrt(a[l]);  // one vsqrtpd once vectorised
    return r;
  }
}

// Lane-wise m ? a : b, for a mask from a comparison of T values.
template <class M, class T>
DEM_LANES_INLINE T select(M mask, T a, T b) {
  return mask ? a : b;
}

// std::max and std::min, lane-wise, with the same tie and signed-zero rules.
template <class T>
DEM_LANES_INLINE T lane_max(T a, T b) {
  return select(a < b, b, a);
}
template <class T>
DEM_LANES_INLINE T lane_min(T a, T b) {
  return select(b < a, b, a);
}
template <class T>
DEM_LANES_INLINE T lane_abs(T a) {
  return select(a < T{}, -a, a);
}

template <class M>
DEM_LANES_INLINE bool any_lane(M mask) {
  if constexpr (std::is_same_v<M, bool>) {
    return mask;
  } else {
    for (int l = 0; l < static_cast<int>(sizeof(M) / sizeof(mask[0])); ++l)
      if (mask[l]) return true;
    return false;
  }
}

// Lane-wise a and b of two masks (for one lane, bool && bool: & would give an int).
template <class M>
DEM_LANES_INLINE M lane_and(M a, M b) {
  if constexpr (std::is_same_v<M, bool>)
    return a && b;
  else
    return a & b;
}

// Mask of the lanes below `count`.
template <class T>
DEM_LANES_INLINE auto lanes_below(int count) {
  if constexpr (std::is_same_v<T, double>)
    return count > 0;
  else
    return T{0, 1, 2, 3} < splat<T>(count);
}

template <class M>
DEM_LANES_INLINE bool lane_on(M mask, int l) {
  if constexpr (std::is_same_v<M, bool>)
    return mask;
  else
    return mask[l] != 0;
}

template <class T>
DEM_LANES_INLINE double lane(const T& a, int l) {
  if constexpr (std::is_same_v<T, double>)
    return a;
  else
    return a[l];
}

template <class T>
DEM_LANES_INLINE void set_lane(T& a, int l, double value) {
  if constexpr (std::is_same_v<T, double>)
    a = value;
  else
    a[l] = value;
}

// A 3-vector of lanes (x, y and z each hold one component of every lane's vector).
template <class T>
struct V3 {
  T x, y, z;

  DEM_LANES_INLINE static V3 zero() { return {splat<T>(0), splat<T>(0), splat<T>(0)}; }
  DEM_LANES_INLINE V3 operator+(const V3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  DEM_LANES_INLINE V3 operator-(const V3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  DEM_LANES_INLINE V3 operator-() const { return {-x, -y, -z}; }
  DEM_LANES_INLINE V3 operator*(T s) const { return {x * s, y * s, z * s}; }
  DEM_LANES_INLINE friend V3 operator*(T s, const V3& v) { return {s * v.x, s * v.y, s * v.z}; }

  // Lane l as an Eigen vector, and back.
  DEM_LANES_INLINE Vec3 get(int l) const { return {lane(x, l), lane(y, l), lane(z, l)}; }
  DEM_LANES_INLINE void set(int l, const Vec3& v) {
    set_lane(x, l, v.x());
    set_lane(y, l, v.y());
    set_lane(z, l, v.z());
  }
};

DEM_LANES_INLINE V3<double> to_v3(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
DEM_LANES_INLINE Vec3 as_vec3(const Lanes4& q) { return {q[0], q[1], q[2]}; }  // (x, y, z, pad)

template <class T>
DEM_LANES_INLINE V3<T> broadcast(const Vec3& v) {
  return {splat<T>(v.x()), splat<T>(v.y()), splat<T>(v.z())};
}

// values[index[l]] in lane l.
template <class T>
DEM_LANES_INLINE T gather(const double* values, const int* index) {
  if constexpr (std::is_same_v<T, double>)
    return values[index[0]];
  else
    return T{values[index[0]], values[index[1]], values[index[2]], values[index[3]]};
}
// Vectors: x and y of each lane as one 16-byte load, two of them joined and interleaved (4 shuffles
// for x and y of four lanes instead of 8 single loads and their inserts); z as four single loads.
template <class T>
DEM_LANES_INLINE V3<T> gather(const Vec3* values, const int* index) {
  if constexpr (std::is_same_v<T, double>) {
    return to_v3(values[index[0]]);
  } else {
    const double *a = values[index[0]].data(), *b = values[index[1]].data(), *c = values[index[2]].data(),
                 *d = values[index[3]].data();
    const T ac = __builtin_shufflevector(load_pair(a), load_pair(c), 0, 1, 2, 3);  // ax ay cx cy
    const T bd = __builtin_shufflevector(load_pair(b), load_pair(d), 0, 1, 2, 3);  // bx by dx dy
    return {__builtin_shufflevector(ac, bd, 0, 4, 2, 6), __builtin_shufflevector(ac, bd, 1, 5, 3, 7),
            T{a[2], b[2], c[2], d[2]}};
  }
}

// Each lane's vector as four doubles (x, y, z, 0), the form of the padded sums (sim/state.hpp).
template <class T>
DEM_LANES_INLINE void lane_quads(const V3<T>& v, Lanes4 (&out)[lane_count<T>()]) {
  if constexpr (std::is_same_v<T, double>) {
    out[0] = Lanes4{v.x, v.y, v.z, 0.0};
  } else {  // a 4x4 transpose of (x, y, z, 0)
    const T zero{};
    const T xy02 = __builtin_shufflevector(v.x, v.y, 0, 4, 2, 6), xy13 = __builtin_shufflevector(v.x, v.y, 1, 5, 3, 7);
    const T z02 = __builtin_shufflevector(v.z, zero, 0, 4, 2, 6), z13 = __builtin_shufflevector(v.z, zero, 1, 5, 3, 7);
    out[0] = __builtin_shufflevector(xy02, z02, 0, 1, 4, 5);
    out[1] = __builtin_shufflevector(xy13, z13, 0, 1, 4, 5);
    out[2] = __builtin_shufflevector(xy02, z02, 2, 3, 6, 7);
    out[3] = __builtin_shufflevector(xy13, z13, 2, 3, 6, 7);
  }
}

template <class T>
DEM_LANES_INLINE T dot(const V3<T>& a, const V3<T>& b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
template <class T>
DEM_LANES_INLINE T squared_norm(const V3<T>& a) {
  return dot(a, a);
}
template <class T>
DEM_LANES_INLINE V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class M, class T>
DEM_LANES_INLINE V3<T> select(M mask, const V3<T>& a, const V3<T>& b) {
  return {select(mask, a.x, b.x), select(mask, a.y, b.y), select(mask, a.z, b.z)};
}

}  // namespace dem
