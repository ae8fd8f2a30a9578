#include "experiments/sampling/lfs_estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "common/errors.h"

namespace delmesh {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
//! Vertex info: the index of the sample point, or -1 for a far corner.
using Vb = CGAL::Triangulation_vertex_base_with_info_3<long, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;
using SearchTraits = CGAL::Search_traits_3<K>;
using NearestSearch = CGAL::Orthogonal_k_neighbor_search<SearchTraits>;
using Tree = NearestSearch::Tree;

}  // namespace

struct PoleLfsEstimate::Impl {
  std::vector<std::array<double, 3>> poles;
  Tree tree;
};

PoleLfsEstimate::PoleLfsEstimate(const std::vector<std::array<double, 3>>& sample, const Box3& box)
    : impl_(std::make_unique<Impl>()) {
  if (sample.size() < 4) throw PreconditionViolation("PoleLfsEstimate: fewer than 4 sample points");
  for (const auto& p : sample)
    if (!box.contains(p)) throw PreconditionViolation("PoleLfsEstimate: a sample point lies outside the box");

  // Del(P) with eight corners far outside the box, so that every Voronoi cell of P is bounded.
  std::vector<std::pair<Point, long>> input;
  input.reserve(sample.size() + 8);
  for (std::size_t i = 0; i < sample.size(); ++i)
    input.emplace_back(Point(sample[i][0], sample[i][1], sample[i][2]), static_cast<long>(i));
  const double far = 2 * box.diagonal();
  for (int corner = 0; corner < 8; ++corner) {
    std::array<double, 3> c{};
    for (int a = 0; a < 3; ++a) c[a] = 0.5 * (box.lo[a] + box.hi[a]) + (((corner >> a) & 1) ? far : -far);
    input.emplace_back(Point(c[0], c[1], c[2]), -1L);
  }
  const Delaunay dt(input.begin(), input.end());

  // The poles: the Voronoi vertices of Vor(p) (circumcentres of the cells incident to p) farthest
  // from p, on the positive side and then on the negative side of p⁺ − p.
  std::vector<Delaunay::Cell_handle> cells;
  std::vector<Point> centres;
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    if (v->info() < 0) continue;
    cells.clear();
    centres.clear();
    dt.incident_cells(v, std::back_inserter(cells));
    const Point& p = v->point();
    double best = -1;
    std::size_t positive = 0;
    for (const auto& cell : cells) {
      if (dt.is_infinite(cell)) continue;
      centres.push_back(CGAL::circumcenter(cell->vertex(0)->point(), cell->vertex(1)->point(),
                                           cell->vertex(2)->point(), cell->vertex(3)->point()));
      const double d = CGAL::squared_distance(p, centres.back());
      if (d > best) {
        best = d;
        positive = centres.size() - 1;
      }
    }
    if (centres.empty()) continue;
    const K::Vector_3 axis = centres[positive] - p;
    impl_->poles.push_back({centres[positive].x(), centres[positive].y(), centres[positive].z()});
    double best_negative = -1;
    const Point* negative = nullptr;
    for (const Point& c : centres) {
      if ((c - p) * axis >= 0) continue;
      const double d = CGAL::squared_distance(p, c);
      if (d > best_negative) {
        best_negative = d;
        negative = &c;
      }
    }
    if (negative) impl_->poles.push_back({negative->x(), negative->y(), negative->z()});
  }
  for (const auto& c : impl_->poles) impl_->tree.insert(Point(c[0], c[1], c[2]));
  impl_->tree.build();
}

PoleLfsEstimate::~PoleLfsEstimate() = default;
PoleLfsEstimate::PoleLfsEstimate(PoleLfsEstimate&&) noexcept = default;
PoleLfsEstimate& PoleLfsEstimate::operator=(PoleLfsEstimate&&) noexcept = default;

double PoleLfsEstimate::operator()(const std::array<double, 3>& x) const {
  const NearestSearch search(impl_->tree, Point(x[0], x[1], x[2]), 1);
  if (search.begin() == search.end()) return std::numeric_limits<double>::infinity();
  return std::sqrt(search.begin()->second);
}

const std::vector<std::array<double, 3>>& PoleLfsEstimate::poles() const { return impl_->poles; }

LfsEstimateResult estimate_lfs(const Surface& surface, const Box3& box, const LfsEstimateOptions& options) {
  LfsEstimateResult result;
  // Pass 1: uniform sample and its pole estimate.
  DenseSampleOptions uniform = options.sample;
  uniform.max_spacing = options.first_pass_spacing;
  uniform.min_spacing = std::min(uniform.min_spacing, uniform.max_spacing);
  result.first_pass = dense_sample(surface, box, uniform);
  if (result.first_pass.points.size() < 4)
    throw InvalidInput("estimate_lfs: the uniform sample found fewer than 4 points of the surface in the box");
  const PoleLfsEstimate first(result.first_pass.points, box);

  // Pass 2: refined where lfs̃₁ is small, and the pole estimate of that sample.
  result.sample = dense_sample(surface, box, options.sample, [&first](const std::array<double, 3>& p) { return first(p); });
  if (result.sample.points.size() < 4)
    throw InvalidInput("estimate_lfs: the refined sample found fewer than 4 points of the surface in the box");
  result.estimate = std::make_unique<PoleLfsEstimate>(result.sample.points, box);
  result.values.reserve(result.sample.points.size());
  for (const auto& p : result.sample.points) result.values.push_back((*result.estimate)(p));
  return result;
}

LfsErrorSummary lfs_relative_error(const std::vector<double>& estimate, const std::vector<double>& exact) {
  if (estimate.size() != exact.size() || exact.empty())
    throw PreconditionViolation("lfs_relative_error: need two lists of the same non-zero length");
  std::vector<double> errors;
  errors.reserve(exact.size());
  LfsErrorSummary summary;
  double sum = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    if (!(exact[i] > 0)) throw PreconditionViolation("lfs_relative_error: an exact lfs is not positive");
    const double e = std::fabs(estimate[i] - exact[i]) / exact[i];
    errors.push_back(e);
    summary.max = std::max(summary.max, e);
    sum += e;
  }
  summary.points = errors.size();
  summary.mean = sum / static_cast<double>(errors.size());
  const auto middle = errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2);
  std::nth_element(errors.begin(), middle, errors.end());
  summary.median = *middle;
  return summary;
}

}  // namespace delmesh
