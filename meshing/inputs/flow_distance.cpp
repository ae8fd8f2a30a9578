// The flow distance bound of one triangle (flow_distance.h):
//  1. g: a lower bound of |∇E| on the triangle's box grown by r, the least over a shallow bisection;
//  2. e: |E| on the triangle by dyadic pieces, each cut until its bound is at most g·r;
//  3. e/g, rounded up.
#include "meshing/inputs/flow_distance.h"

#include <cmath>
#include <limits>
#include <vector>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/inputs/detail/flow_enclosure.h"

namespace delmesh {

using detail::IBox;

namespace {

//! The least lower bound of |∇E| over the leaves of a bisection of `box` (0 if a leaf at the
//! depth limit has none).  A box is bisected (in eight) while its bound is 0 or below
//! tolerances::flow_gradient_quality times |∇E| at its centre.
double gradient_bound(const CompiledSystem& system, const IBox& box) {
  struct Item {
    IBox box;
    int depth;
  };
  std::vector<Item> stack{{box, 0}};
  double least = std::numeric_limits<double>::infinity();
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const detail::Enclosure en(system, item.box);
    const double bound = detail::gradient_lower_bound(en);
    double at_centre = 0;
    for (int i = 1; i <= 3; ++i) at_centre += detail::magnitude(en.vc[i]) * detail::magnitude(en.vc[i]);
    at_centre = std::sqrt(at_centre);
    const bool good = bound > 0 && bound >= tolerances::flow_gradient_quality * at_centre;
    if (good || item.depth >= tolerances::flow_distance_gradient_depth) {
      if (!(bound > 0)) return 0;
      least = std::min(least, bound);
      continue;
    }
    const detail::P3 c = detail::centre_of(item.box);
    for (int octant = 0; octant < 8; ++octant) {
      IBox child;
      for (int k = 0; k < 3; ++k)
        child[k] = (octant >> k) & 1 ? Interval(c[k], item.box[k].sup()) : Interval(item.box[k].inf(), c[k]);
      stack.push_back({child, item.depth + 1});
    }
  }
  return least;
}

}  // namespace

FlowDistance::FlowDistance(const Surface& surface)
    : system_(detail::compile_value_and_gradient(surface.E(), surface.gradient())) {}

TriangleDistance FlowDistance::bound(const Vec3& a, const Vec3& b, const Vec3& c, double radius) const {
  if (!(radius > 0) || !std::isfinite(radius)) throw PreconditionViolation("FlowDistance::bound: radius not positive");
  TriangleDistance out;
  out.distance = std::numeric_limits<double>::infinity();
  RoundingGuard guard;
  // 1. N: the box of the triangle grown by r (rounded outwards).
  IBox grown;
  const Interval r(radius);
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({a[k], b[k], c[k]}), hi = std::max({a[k], b[k], c[k]});
    grown[k] = Interval((Interval(lo) - r).inf(), (Interval(hi) + r).sup());
  }
  out.gradient_bound = gradient_bound(system_, grown);
  if (!(out.gradient_bound > 0) || !std::isfinite(out.gradient_bound)) return out;
  const double target = (Interval(out.gradient_bound) * r).inf();

  // 2. |E| ≤ target on every piece.
  const detail::EnclosedTriangle triangle(a, b, c);
  std::vector<detail::TrianglePiece> stack{detail::TrianglePiece{}};
  double e = 0;
  while (!stack.empty()) {
    const detail::TrianglePiece piece = stack.back();
    stack.pop_back();
    std::array<IBox, 3> corner;
    IBox box;
    triangle.corners(piece, corner, box);
    const double bound = detail::magnitude(detail::Enclosure(system_, box).value_on_hull(corner));
    if (bound <= target) {
      e = std::max(e, bound);
      continue;
    }
    if (piece.depth >= tolerances::flow_triangle_max_depth ||
        std::abs(detail::centroid_value(system_, corner)) > target)
      return out;
    for (const detail::TrianglePiece& child : piece.children()) stack.push_back(child);
  }

  // 3. e/g, rounded up; e ≤ target ≤ g·r exactly, so r bounds it as well.
  out.proved = true;
  out.value_bound = e;
  out.distance = std::min((Interval(e) / Interval(out.gradient_bound)).sup(), radius);
  return out;
}

}  // namespace delmesh
