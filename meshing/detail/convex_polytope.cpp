#include "meshing/detail/convex_polytope.h"

#include <algorithm>
#include <limits>

namespace delmesh::detail {

ConvexPolytope::ConvexPolytope(const Box3& box) { reset(box); }

void ConvexPolytope::reset(const Box3& box) {
  const auto& l = box.lo;
  const auto& h = box.hi;
  auto P = [&](int i, int j, int k) { return V3{i ? h[0] : l[0], j ? h[1] : l[1], k ? h[2] : l[2]}; };
  for (std::size_t k = 6; k < faces_.size(); ++k) spare_.push_back(std::move(faces_[k]));
  faces_.resize(6);
  // Outward-facing loops are not needed (only planarity and convexity are used).
  auto set = [&](int i, int label, const V3& a, const V3& b, const V3& c, const V3& d) {
    faces_[i].label = label;
    faces_[i].loop.assign({a, b, c, d});
  };
  set(0, -1, P(0, 0, 0), P(0, 1, 0), P(0, 1, 1), P(0, 0, 1));
  set(1, -2, P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1));
  set(2, -3, P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1));
  set(3, -4, P(0, 1, 0), P(1, 1, 0), P(1, 1, 1), P(0, 1, 1));
  set(4, -5, P(0, 0, 0), P(1, 0, 0), P(1, 1, 0), P(0, 1, 0));
  set(5, -6, P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1));
}

void ConvexPolytope::clip(const V3& n, double c, int label) {
  const double scale = norm(n);
  if (!(scale > 0)) return;
  // Signed distances of every loop vertex, face by face (computed once, used three times).
  side_.clear();
  double extent = 0;
  for (const auto& f : faces_)
    for (const auto& p : f.loop) {
      const double s = (dot(n, p) - c) / scale;
      side_.push_back(s);
      extent = std::max(extent, std::abs(s));
    }
  const double eps = 1e-13 * std::max(extent, 1e-300);
  {
    // Nothing to cut: every vertex is inside.
    bool cuts = false;
    for (double s : side_)
      if (s > eps) {
        cuts = true;
        break;
      }
    if (!cuts) return;
  }
  std::vector<V3>& cut = cut_;
  cut.clear();
  std::size_t count = 0;  // faces written to spare_
  std::size_t base = 0;   // index of the face's first vertex in side_
  auto next_slot = [&]() -> PolytopeFace& {
    if (count == spare_.size()) spare_.emplace_back();
    PolytopeFace& slot = spare_[count];
    slot.loop.clear();
    return slot;
  };
  for (const auto& f : faces_) {
    PolytopeFace& slot = next_slot();
    std::vector<V3>& loop = slot.loop;
    const std::size_t m = f.loop.size();
    for (std::size_t i = 0; i < m; ++i) {
      const V3& a = f.loop[i];
      const std::size_t j = i + 1 == m ? 0 : i + 1;
      const V3& b = f.loop[j];
      const double sa = side_[base + i], sb = side_[base + j];
      if (sa <= eps) loop.push_back(a);
      if ((sa < -eps && sb > eps) || (sa > eps && sb < -eps)) {
        const V3 x = a + (sa / (sa - sb)) * (b - a);
        loop.push_back(x);
        cut.push_back(x);
      } else if (std::abs(sa) <= eps) {
        cut.push_back(a);
      }
    }
    base += m;
    if (loop.size() >= 3) {
      slot.label = f.label;
      ++count;
    }
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
    PolytopeFace& slot = next_slot();
    std::vector<V3>& loop = slot.loop;
    for (const auto& p : cut)
      if (loop.empty() || distance(loop.back(), p) > eps) loop.push_back(p);
    if (loop.size() >= 3 && distance(loop.front(), loop.back()) <= eps) loop.pop_back();
    if (loop.size() >= 3) {
      slot.label = label;
      ++count;
    }
  }
  // The new faces are spare_[0, count); the old faces become the next scratch, and so do the
  // unused slots past `count` (with their buffers).
  faces_.swap(spare_);
  for (std::size_t k = count; k < faces_.size(); ++k) spare_.push_back(std::move(faces_[k]));
  faces_.resize(count);
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
