#pragma once
//! \file report_measures.h
//! The per-triangle quality measures and the histograms of the report page (`delmesh report`,
//! apps/report_html.h).  Header-only: the tests of apps/ (which do not link the subcommands) test
//! them directly.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "common/vec3.h"
#include "meshing/checks/quality.h"

namespace delmesh::app {

//! The measures of one triangle.
struct TriangleMeasures {
  std::array<double, 3> angles_deg{};  //!< at its corners a, b, c; 0 where an edge at the corner has length 0
  double min_angle_deg = 0;            //!< the smallest of angles_deg
  double radius_edge_ratio = 0;        //!< circumradius / shortest edge (meshing/checks/quality.h); +∞ if degenerate
  double area = 0;                     //!< in the squared units of the coordinates (may overflow to +∞)
};

//! The measures of the triangle abc.  The angles are atan2(|u×v|, u·v) of the edge vectors
//! scaled by a power of two to a largest component about 1, so they are accurate for thin
//! triangles and do not depend on the scale (no overflow, no underflow).  A degenerate triangle
//! (collinear corners) has angles 0, 0, 180 (or 0 at a corner with a zero-length edge) and
//! radius-edge ratio +∞.  \pre the coordinates are finite.
inline TriangleMeasures triangle_measures(const Vec3& a, const Vec3& b, const Vec3& c) {
  const std::array<Vec3, 3> corners{a, b, c};
  std::array<Vec3, 3> edge{};  // edge[i]: from corner i to corner i+1
  double largest = 0;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      edge[i][k] = corners[(i + 1) % 3][k] - corners[i][k];
      largest = std::max(largest, std::abs(edge[i][k]));
    }
  TriangleMeasures m;
  if (!(largest > 0) || !std::isfinite(largest)) {
    m.radius_edge_ratio = std::numeric_limits<double>::infinity();
    return m;
  }
  int exponent = 0;
  std::frexp(largest, &exponent);
  for (auto& e : edge)
    for (double& x : e) x = std::ldexp(x, -exponent);
  const auto cross = [](const Vec3& u, const Vec3& v) {
    return Vec3{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  };
  const auto norm = [](const Vec3& u) { return std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]); };
  const double pi = std::acos(-1.0);
  for (int i = 0; i < 3; ++i) {
    // At corner i: between the edge to corner i+1 and the reversed edge from corner i-1.
    const Vec3& u = edge[i];
    const Vec3& w = edge[(i + 2) % 3];
    const Vec3 v{-w[0], -w[1], -w[2]};
    const double sine = norm(cross(u, v)), cosine = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    m.angles_deg[i] = norm(u) > 0 && norm(v) > 0 ? std::atan2(sine, cosine) * 180 / pi : 0;
  }
  m.min_angle_deg = std::min({m.angles_deg[0], m.angles_deg[1], m.angles_deg[2]});
  m.radius_edge_ratio = radius_edge_ratio(a, b, c);
  m.area = 0.5 * std::ldexp(norm(cross(edge[0], edge[2])), 2 * exponent);
  return m;
}

//! Counts of values in `bins` equal bins over [lo, hi]; a value equal to hi is in the last bin.
struct Histogram {
  double lo = 0, hi = 1;
  std::vector<std::size_t> counts;
  std::size_t below = 0;  //!< values < lo
  std::size_t above = 0;  //!< values > hi, +∞ and NaN
  std::size_t largest() const { return counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end()); }
  double bin_width() const { return (hi - lo) / static_cast<double>(counts.size()); }
};

//! The histogram of `values` over [lo, hi] in `bins` bins.  \pre lo < hi (finite), bins > 0.
inline Histogram histogram(const std::vector<double>& values, double lo, double hi, std::size_t bins) {
  Histogram h;
  h.lo = lo;
  h.hi = hi;
  h.counts.assign(bins, 0);
  for (const double x : values) {
    if (x < lo) {
      ++h.below;
    } else if (!(x <= hi)) {
      ++h.above;
    } else {
      const auto i = static_cast<std::size_t>((x - lo) / (hi - lo) * static_cast<double>(bins));
      ++h.counts[std::min(i, bins - 1)];
    }
  }
  return h;
}

}  // namespace delmesh::app
