#include "experiments/sampling/dense_sample.h"

#include <cmath>
#include <optional>

#include "common/errors.h"
#include "common/tolerances.h"
#include "symbolic/compiled_system.h"
#include "symbolic/scalar_traits.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

namespace {

using Vec = std::array<double, 3>;

//! splitmix64: a small generator whose output is fixed by its seed on every platform.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  //! Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t state_;
};

struct Cell {
  Vec lo, hi;
  double longest_edge() const { return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}); }
  Vec centre() const { return {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])}; }
  bool contains_half_open(const Vec& p) const {
    for (int i = 0; i < 3; ++i)
      if (!(lo[i] <= p[i] && p[i] < hi[i])) return false;
    return true;
  }
};

class Sampler {
 public:
  Sampler(const Surface& surface, const Box3& box, const DenseSampleOptions& options, const LfsFunction& lfs)
      : E_({surface.E()}, {coordinate_x(), coordinate_y(), coordinate_z()}, {}),
        box_(box),
        options_(options),
        lfs_(lfs),
        random_(options.seed),
        diagonal_(box.diagonal()) {}

  DenseSample run() {
    // Step 1: the top grid, cells of edge ≤ max_spacing · diagonal.
    const double top = options_.max_spacing * diagonal_;
    std::array<int, 3> n{};
    for (int i = 0; i < 3; ++i) n[i] = std::max(1, static_cast<int>(std::ceil((box_.hi[i] - box_.lo[i]) / top)));
    for (int i = 0; i < n[0]; ++i)
      for (int j = 0; j < n[1]; ++j)
        for (int k = 0; k < n[2]; ++k) {
          const std::array<int, 3> index{i, j, k};
          Cell cell;
          for (int a = 0; a < 3; ++a) {
            const double width = box_.hi[a] - box_.lo[a];
            cell.lo[a] = box_.lo[a] + width * index[a] / n[a];
            cell.hi[a] = index[a] + 1 == n[a] ? box_.hi[a] : box_.lo[a] + width * (index[a] + 1) / n[a];
          }
          visit(cell);
          if (result_.status == DenseSampleStatus::point_limit) return std::move(result_);
        }
    return std::move(result_);
  }

 private:
  //! Step 2: false if an interval enclosure of E over the cell excludes 0: the natural enclosure
  //! intersected with the centred (mean-value) form E(c) + ∇E(cell)·(cell − c), which is tight for
  //! small cells.
  bool may_meet_surface(const Cell& cell) const {
    const RoundingGuard guard;
    const Interval x[3] = {Interval(cell.lo[0], cell.hi[0]), Interval(cell.lo[1], cell.hi[1]),
                           Interval(cell.lo[2], cell.hi[2])};
    Interval value, gradient[3];
    E_.values_and_jacobian<Interval>(x, nullptr, &value, gradient);
    if (certainly_nonzero(value)) return false;
    const Vec c = cell.centre();
    const Interval centre[3] = {Interval(c[0]), Interval(c[1]), Interval(c[2])};
    Interval centred;
    E_.values<Interval>(centre, nullptr, &centred);
    for (int i = 0; i < 3; ++i) centred += gradient[i] * (x[i] - centre[i]);
    return !certainly_nonzero(centred);
  }

  //! Newton steps x ← x − E(x) ∇E(x)/|∇E(x)|² (the mesher's projection, tolerances.h).
  std::optional<Vec> project(Vec x) const {
    const double tolerance = tolerances::projection_relative_tolerance * diagonal_;
    for (int it = 0; it < tolerances::projection_iterations; ++it) {
      double value = 0;
      Vec g{};
      E_.values_and_jacobian<double>(x.data(), nullptr, &value, g.data());
      const double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
      if (!(gg > 0) || !std::isfinite(value)) return std::nullopt;
      const double step = value / gg;
      for (int i = 0; i < 3; ++i) x[i] -= step * g[i];
      if (!box_.contains(x)) return std::nullopt;
      if (std::fabs(step) * std::sqrt(gg) <= tolerance) return x;
    }
    return std::nullopt;
  }

  //! Step 3: whether the cell is fine enough for the lfs near it.
  bool fine_enough(const Cell& cell) const {
    const double s = cell.longest_edge();
    if (s <= options_.min_spacing * diagonal_) return true;
    if (!lfs_) return true;
    const Vec c = cell.centre();
    const std::optional<Vec> p = project(c);
    if (!p) return false;
    const double moved = std::hypot((*p)[0] - c[0], (*p)[1] - c[1], (*p)[2] - c[2]);
    const double bound = lfs_(*p) - moved - s * std::sqrt(3.0) / 2;
    return s <= options_.relative_spacing * bound;
  }

  void visit(const Cell& cell) {
    if (!may_meet_surface(cell)) return;
    if (!fine_enough(cell)) {
      const Vec m = cell.centre();
      for (int octant = 0; octant < 8; ++octant) {
        Cell child;
        for (int a = 0; a < 3; ++a) {
          const bool upper = (octant >> a) & 1;
          child.lo[a] = upper ? m[a] : cell.lo[a];
          child.hi[a] = upper ? cell.hi[a] : m[a];
        }
        visit(child);
        if (result_.status == DenseSampleStatus::point_limit) return;
      }
      return;
    }
    // Step 4: one point per leaf cell, from a seeded random start, else from the centre.
    ++result_.cells;
    if (cell.longest_edge() <= options_.min_spacing * diagonal_ && lfs_) ++result_.finest_cells;
    Vec start;
    for (int a = 0; a < 3; ++a) start[a] = cell.lo[a] + (cell.hi[a] - cell.lo[a]) * random_.uniform();
    for (const Vec& from : {start, cell.centre()}) {
      const std::optional<Vec> p = project(from);
      if (p && cell.contains_half_open(*p)) {
        result_.points.push_back(*p);
        if (result_.points.size() >= options_.max_points) result_.status = DenseSampleStatus::point_limit;
        return;
      }
    }
  }

  CompiledSystem E_;
  Box3 box_;
  DenseSampleOptions options_;
  LfsFunction lfs_;
  Random random_;
  double diagonal_;
  DenseSample result_;
};

}  // namespace

DenseSample dense_sample(const Surface& surface, const Box3& box, const DenseSampleOptions& options,
                         const LfsFunction& lfs) {
  for (int i = 0; i < 3; ++i)
    if (!(box.lo[i] < box.hi[i])) throw PreconditionViolation("dense_sample: empty box");
  if (!(options.min_spacing > 0 && options.min_spacing <= options.max_spacing && options.max_spacing <= 1))
    throw PreconditionViolation("dense_sample: need 0 < min_spacing <= max_spacing <= 1");
  if (!(options.relative_spacing > 0)) throw PreconditionViolation("dense_sample: relative_spacing must be > 0");
  return Sampler(surface, box, options, lfs).run();
}

}  // namespace delmesh
