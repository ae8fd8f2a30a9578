#include "meshing/detail/convex_polytope.h"

#include <algorithm>
#include <limits>

namespace delmesh::detail {

ConvexPolytope::ConvexPolytope(const Box3& box) {
  const auto& l = box.lo;
  const auto& h = box.hi;
  auto P = [&](int i, int j, int k) { return V3{i ? h[0] : l[0], j ? h[1] : l[1], k ? h[2] : l[2]}; };
  // Outward-facing loops are not needed (only planarity and convexity are used).
  faces_.push_back({-1, {P(0, 0, 0), P(0, 1, 0), P(0, 1, 1), P(0, 0, 1)}});
  faces_.push_back({-2, {P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1)}});
  faces_.push_back({-3, {P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1)}});
  faces_.push_back({-4, {P(0, 1, 0), P(1, 1, 0), P(1, 1, 1), P(0, 1, 1)}});
  faces_.push_back({-5, {P(0, 0, 0), P(1, 0, 0), P(1, 1, 0), P(0, 1, 0)}});
  faces_.push_back({-6, {P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1)}});
}

void ConvexPolytope::clip(const V3& n, double c, int label) {
  const double scale = norm(n);
  if (!(scale > 0)) return;
  std::vector<PolytopeFace> out;
  std::vector<V3> cut;
  double extent = 0;
  for (const auto& f : faces_)
    for (const auto& p : f.loop) extent = std::max(extent, std::abs(dot(n, p) - c) / scale);
  const double eps = 1e-13 * std::max(extent, 1e-300);
  {
    // Nothing to cut: every vertex is inside.
    bool cuts = false;
    for (const auto& f : faces_) {
      for (const auto& p : f.loop)
        if ((dot(n, p) - c) / scale > eps) {
          cuts = true;
          break;
        }
      if (cuts) break;
    }
    if (!cuts) return;
  }
  for (const auto& f : faces_) {
    std::vector<V3> loop;
    const std::size_t m = f.loop.size();
    for (std::size_t i = 0; i < m; ++i) {
      const V3& a = f.loop[i];
      const V3& b = f.loop[(i + 1) % m];
      const double sa = (dot(n, a) - c) / scale, sb = (dot(n, b) - c) / scale;
      if (sa <= eps) loop.push_back(a);
      if ((sa < -eps && sb > eps) || (sa > eps && sb < -eps)) {
        const V3 x = a + (sa / (sa - sb)) * (b - a);
        loop.push_back(x);
        cut.push_back(x);
      } else if (std::abs(sa) <= eps) {
        cut.push_back(a);
      }
    }
    if (loop.size() >= 3) out.push_back({f.label, std::move(loop)});
  }
  if (cut.size() >= 3) {
    // Order the cut points around their centroid in the clipping plane.
    V3 g{0, 0, 0};
    for (const auto& p : cut) g = g + p;
    g = (1.0 / cut.size()) * g;
    const V3 nn = normalized(n);
    V3 a = std::abs(nn[0]) < 0.9 ? V3{1, 0, 0} : V3{0, 1, 0};
    a = normalized(a - dot(a, nn) * nn);
    const V3 b = cross(nn, a);
    // Monotone pseudo-angle in [0, 4) (cheaper than atan2, same order).
    auto pseudo_angle = [&](const V3& p) {
      const double x = dot(p - g, a), y = dot(p - g, b);
      const double r = std::abs(x) + std::abs(y);
      if (r == 0) return 0.0;
      const double t = y / r;  // in [-1, 1]
      return x >= 0 ? (t >= 0 ? t : 4 + t) : 2 - t;
    };
    std::sort(cut.begin(), cut.end(), [&](const V3& p, const V3& q) { return pseudo_angle(p) < pseudo_angle(q); });
    std::vector<V3> loop;
    for (const auto& p : cut)
      if (loop.empty() || distance(loop.back(), p) > eps) loop.push_back(p);
    if (loop.size() >= 3 && distance(loop.front(), loop.back()) <= eps) loop.pop_back();
    if (loop.size() >= 3) out.push_back({label, std::move(loop)});
  }
  faces_ = std::move(out);
}

std::array<V3, 2> ConvexPolytope::bounding_box() const {
  const double inf = std::numeric_limits<double>::infinity();
  V3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  for (const auto& f : faces_)
    for (const auto& p : f.loop)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
  return {lo, hi};
}

}  // namespace delmesh::detail
