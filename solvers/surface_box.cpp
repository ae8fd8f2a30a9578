#include "solvers/surface_box.h"

#include <algorithm>
#include <array>
#include <optional>
#include <vector>

#include "common/errors.h"
#include "symbolic/scalar_traits.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

namespace {

struct KeyedBox {
  std::array<Interval, 3> x;
  double key;  // the box's end along the searched axis, negated for a lower bound
  bool operator<(const KeyedBox& o) const { return key < o.key; }
};

bool excludes_zero(const Interval& v) { return v.inf() > 0 || v.sup() < 0; }

//! Whether an enclosure of E on X excludes 0: the natural form, then the mean-value form about
//! X's centre.  Precondition: a live RoundingGuard.
bool misses_surface(const CompiledSystem& E, const std::array<Interval, 3>& x) {
  Interval value, gradient[3];
  E.values_and_jacobian<Interval>(x.data(), nullptr, &value, gradient);
  if (excludes_zero(value)) return true;
  Interval centre[3], mean_value;
  for (int k = 0; k < 3; ++k) centre[k] = Interval(CGAL::to_double(x[k]));
  E.values<Interval>(centre, nullptr, &mean_value);
  for (int k = 0; k < 3; ++k) mean_value += gradient[k] * (x[k] - centre[k]);
  return excludes_zero(mean_value);
}

//! One side's search (file comment): the bound of x_axis over Σ ∩ B from above (upper) or below,
//! or nothing when Σ ∩ B = ∅ is proved.  Adds the boxes examined to `evaluations`.
std::optional<double> side_bound(const CompiledSystem& E, const Box3& box, int axis, bool upper,
                                 const SurfaceBoxOptions& options, std::size_t& evaluations) {
  auto key = [&](const std::array<Interval, 3>& x) { return upper ? x[axis].sup() : -x[axis].inf(); };
  const double stop = options.resolution * (box.hi[axis] - box.lo[axis]);
  std::vector<KeyedBox> heap;
  KeyedBox root;
  for (int k = 0; k < 3; ++k) root.x[k] = Interval(box.lo[k], box.hi[k]);
  root.key = key(root.x);
  heap.push_back(root);
  for (std::size_t examined = 0; !heap.empty() && examined < options.evaluations_per_side; ++examined) {
    if (CGAL::width(heap.front().x[axis]) < stop) break;
    std::pop_heap(heap.begin(), heap.end());
    const KeyedBox top = heap.back();
    heap.pop_back();
    ++evaluations;
    if (misses_surface(E, top.x)) continue;
    int side = 0;
    for (int k = 1; k < 3; ++k)
      if (CGAL::width(top.x[k]) > CGAL::width(top.x[side])) side = k;
    const double lo = top.x[side].inf(), hi = top.x[side].sup(), mid = 0.5 * (lo + hi);
    if (!(lo < mid && mid < hi)) {
      heap.push_back(top);  // no longer splits: its key stands
      std::push_heap(heap.begin(), heap.end());
      break;
    }
    for (const Interval half : {Interval(lo, mid), Interval(mid, hi)}) {
      KeyedBox child = top;
      child.x[side] = half;
      child.key = key(child.x);
      heap.push_back(child);
      std::push_heap(heap.begin(), heap.end());
    }
  }
  if (heap.empty()) return std::nullopt;
  return upper ? heap.front().key : -heap.front().key;
}

}  // namespace

SurfaceBox surface_bounding_box(const CompiledSystem& E, const Box3& box, const SurfaceBoxOptions& options) {
  if (E.n_equations() != 1 || E.n_unknowns() != 3 || E.n_parameters() != 0)
    throw PreconditionViolation("surface_bounding_box: E must be one equation in (x, y, z) without parameters");
  if (!(options.resolution > 0 && options.resolution <= 1) || options.evaluations_per_side == 0)
    throw PreconditionViolation("surface_bounding_box: the resolution must be in (0, 1] and the budget positive");
  RoundingGuard guard;
  SurfaceBox result;
  result.box = box;
  for (int axis = 0; axis < 3; ++axis) {
    for (const bool upper : {false, true}) {
      const std::optional<double> bound = side_bound(E, box, axis, upper, options, result.evaluations);
      if (!bound) {
        result.empty = true;
        result.box = box;
        return result;
      }
      if (upper) {
        result.box.hi[axis] = std::min(box.hi[axis], *bound);
      } else {
        result.box.lo[axis] = std::max(box.lo[axis], *bound);
      }
    }
  }
  return result;
}

}  // namespace delmesh
