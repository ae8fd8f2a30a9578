#include "meshing/voronoi/detail/convex_polytope.h"

#include <algorithm>
#include <limits>

#include "common/tolerances.h"

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

// Clipping by {x : <n, x> <= c}, in four steps: (1) the signed distance of every loop vertex to
// the plane, and the tolerance eps below which a vertex counts as on it; (2) nothing to do if no
// vertex lies more than eps outside; (3) each face clipped to its part inside, the points where
// its loop crosses the plane (or touches it) collected; (4) those points ordered around their
// centroid form the new face.  The faces are written into the scratch faces and swapped in.
void ConvexPolytope::clip(const V3& n, double c, int label) {
  const double scale = norm(n);
  if (!(scale > 0)) return;
  const double eps = signed_distances(n, c, scale);
  if (std::none_of(side_.begin(), side_.end(), [&](double s) { return s > eps; })) return;
  std::size_t count = clip_faces(eps);
  if (cut_.size() >= 3) add_cut_face(n, eps, label, count);
  // The new faces are spare_[0, count); the old faces become the next scratch, and so do the
  // unused slots past `count` (with their buffers).
  faces_.swap(spare_);
  for (std::size_t k = count; k < faces_.size(); ++k) spare_.push_back(std::move(faces_[k]));
  faces_.resize(count);
}

double ConvexPolytope::signed_distances(const V3& n, double c, double scale) {
  // Computed once per vertex, face by face, and read three times by clip_faces().
  side_.clear();
  double extent = 0;
  for (const auto& f : faces_)
    for (const auto& p : f.loop) {
      const double s = (dot(n, p) - c) / scale;
      side_.push_back(s);
      extent = std::max(extent, std::abs(s));
    }
  return tolerances::polytope_clip_relative_tolerance * std::max(extent, tolerances::polytope_clip_min_extent);
}

PolytopeFace& ConvexPolytope::next_slot(std::size_t count) {
  if (count == spare_.size()) spare_.emplace_back();
  PolytopeFace& slot = spare_[count];
  slot.loop.clear();
  return slot;
}

std::size_t ConvexPolytope::clip_faces(double eps) {
  cut_.clear();
  std::size_t count = 0;  // faces written to spare_
  std::size_t base = 0;   // index of the face's first vertex in side_
  for (const auto& f : faces_) {
    PolytopeFace& slot = next_slot(count);
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
        cut_.push_back(x);
      } else if (std::abs(sa) <= eps) {
        cut_.push_back(a);
      }
    }
    base += m;
    if (loop.size() >= 3) {
      slot.label = f.label;
      ++count;
    }
  }
  return count;
}

void ConvexPolytope::add_cut_face(const V3& n, double eps, int label, std::size_t& count) {
  // Order the cut points around their centroid in the clipping plane.
  V3 g{0, 0, 0};
  for (const auto& p : cut_) g = g + p;
  g = (1.0 / cut_.size()) * g;
  const V3 nn = normalized(n);
  // An axis not nearly parallel to nn (|nn[0]| < 0.9), made orthogonal to it: the frame (a, b).
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
  // Each angle is computed once and sorted with its point.
  by_angle_.clear();
  for (const auto& p : cut_) by_angle_.push_back({pseudo_angle(p), p});
  std::sort(by_angle_.begin(), by_angle_.end(),
            [](const AngledPoint& p, const AngledPoint& q) { return p.angle < q.angle; });
  // Points closer than eps to the previous one are the same vertex (it lay on the plane).
  PolytopeFace& slot = next_slot(count);
  std::vector<V3>& loop = slot.loop;
  for (const auto& [angle, p] : by_angle_)
    if (loop.empty() || distance(loop.back(), p) > eps) loop.push_back(p);
  if (loop.size() >= 3 && distance(loop.front(), loop.back()) <= eps) loop.pop_back();
  if (loop.size() >= 3) {
    slot.label = label;
    ++count;
  }
}

std::array<V3, 2> ConvexPolytope::bounding_box() const {
  BoundingBox box;
  for (const auto& f : faces_)
    for (const auto& p : f.loop) box.add(p);
  return {box.lo, box.hi};
}

}  // namespace delmesh::detail
