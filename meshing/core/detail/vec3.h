#pragma once
// Small inline vector helpers on std::array<double, 3> used throughout meshing/.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace delmesh::detail {

using V3 = std::array<double, 3>;

inline V3 operator+(const V3& a, const V3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V3 operator-(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V3 operator*(double s, const V3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }
inline double distance(const V3& a, const V3& b) { return norm(a - b); }
inline V3 normalized(const V3& a) {
  const double n = norm(a);
  return n > 0 ? (1.0 / n) * a : a;
}

//! The bounding box [lo, hi] of the points added so far (lo = +∞, hi = −∞ while empty).
struct BoundingBox {
  V3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity()};
  V3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity()};
  void add(const V3& x) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], x[k]);
      hi[k] = std::max(hi[k], x[k]);
    }
  }
  //! Whether no point has been added.
  bool empty() const { return !(lo[0] <= hi[0]); }
  //! Moves every side outward by `margin`.
  void enlarge(double margin) {
    for (int k = 0; k < 3; ++k) {
      lo[k] -= margin;
      hi[k] += margin;
    }
  }
};

}  // namespace delmesh::detail
