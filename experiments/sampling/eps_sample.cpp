#include "experiments/sampling/eps_sample.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <tuple>
#include <utility>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "common/errors.h"

namespace delmesh {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, Tds>;

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

class FarthestPointSelection {
 public:
  FarthestPointSelection(const std::vector<std::array<double, 3>>& points, const std::vector<double>& lfs)
      : points_(points), lfs_(lfs), dist_(points.size()), owner_(points.size()) {}

  //! The largest ratio d(x, C)/lfs(x) over R and the point attaining it (the lowest index on ties).
  std::pair<double, std::size_t> top() {
    while (true) {
      const auto [ratio, negative_index, chosen, version] = heap_.top();
      if (version == versions_[chosen]) return {ratio, static_cast<std::size_t>(-negative_index)};
      heap_.pop();
    }
  }

  //! Adds R's point i to C and reassigns the points whose nearest chosen point becomes i.
  void choose(std::size_t i) {
    const std::size_t c = order_.size();
    order_.push_back(i);
    members_.emplace_back();
    versions_.push_back(0);
    if (c == 0) {
      for (std::size_t j = 0; j < points_.size(); ++j) {
        dist_[j] = distance(points_[j], points_[i]);
        owner_[j] = 0;
        members_[0].push_back(j);
      }
      refresh(0);
      return;
    }
    const auto vertex = dt_.insert(K::Point_3(points_[i][0], points_[i][1], points_[i][2]));
    vertex->info() = c;
    // Only the cells of c's Delaunay neighbours can lose points to c (all of C below dimension 3).
    std::vector<std::size_t> neighbours;
    if (dt_.dimension() < 3) {
      for (std::size_t v = 0; v < c; ++v) neighbours.push_back(v);
    } else {
      std::vector<Delaunay::Vertex_handle> adjacent;
      dt_.finite_adjacent_vertices(vertex, std::back_inserter(adjacent));
      for (const auto& a : adjacent) neighbours.push_back(a->info());
      std::sort(neighbours.begin(), neighbours.end());
    }
    for (std::size_t v : neighbours) {
      std::vector<std::size_t> kept;
      kept.reserve(members_[v].size());
      bool changed = false;
      for (std::size_t j : members_[v]) {
        const double d = distance(points_[j], points_[i]);
        if (d < dist_[j]) {
          dist_[j] = d;
          owner_[j] = c;
          members_[c].push_back(j);
          changed = true;
        } else {
          kept.push_back(j);
        }
      }
      if (changed) {
        members_[v].swap(kept);
        refresh(v);
      }
    }
    std::sort(members_[c].begin(), members_[c].end());
    refresh(c);
  }

  void start(std::size_t i) {
    choose(i);
    dt_.insert(K::Point_3(points_[i][0], points_[i][1], points_[i][2]))->info() = 0;
  }

  const std::vector<std::size_t>& order() const { return order_; }

 private:
  //! Recomputes the largest ratio among chosen point v's members and pushes it on the heap.
  void refresh(std::size_t v) {
    ++versions_[v];
    double best = -1;
    std::size_t at = 0;
    for (std::size_t j : members_[v]) {
      const double ratio = dist_[j] / lfs_[j];
      if (ratio > best || (ratio == best && j < at)) {
        best = ratio;
        at = j;
      }
    }
    if (best >= 0) heap_.emplace(best, -static_cast<long long>(at), v, versions_[v]);
  }

  const std::vector<std::array<double, 3>>& points_;
  const std::vector<double>& lfs_;
  std::vector<double> dist_;
  std::vector<std::size_t> owner_;
  std::vector<std::vector<std::size_t>> members_;
  std::vector<std::size_t> versions_;
  std::vector<std::size_t> order_;
  //! (ratio, −index, chosen point, version): the largest ratio first, then the lowest index.
  std::priority_queue<std::tuple<double, long long, std::size_t, std::size_t>> heap_;
  Delaunay dt_;
};

}  // namespace

EpsSampleResult eps_sample(const std::vector<std::array<double, 3>>& points, const std::vector<double>& lfs,
                           std::vector<double> epsilons) {
  if (points.empty()) throw PreconditionViolation("eps_sample: no reference points");
  if (lfs.size() != points.size()) throw PreconditionViolation("eps_sample: one lfs value per point is needed");
  for (double value : lfs)
    if (!(value > 0 && std::isfinite(value))) throw PreconditionViolation("eps_sample: lfs values must be finite and > 0");
  if (epsilons.empty()) throw PreconditionViolation("eps_sample: no epsilon");
  for (double eps : epsilons)
    if (!(eps > 0)) throw PreconditionViolation("eps_sample: epsilon must be > 0");
  std::sort(epsilons.begin(), epsilons.end(), std::greater<>());

  EpsSampleResult result;
  result.epsilons = epsilons;
  FarthestPointSelection selection(points, lfs);
  selection.start(0);
  for (double eps : epsilons) {
    for (auto next = selection.top(); next.first > eps; next = selection.top()) selection.choose(next.second);
    result.sizes.push_back(selection.order().size());
    result.covering.push_back(selection.top().first);
  }
  result.order = selection.order();
  return result;
}

}  // namespace delmesh
