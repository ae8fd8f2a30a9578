#include "meshing/checks/detail/candidates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/tolerances.h"
#include "meshing/core/detail/vec3.h"

namespace delmesh::detail {

double region_diameter(const UndecidedBox& region) {
  double squared = 0;
  for (const auto& b : region.box.bounds) squared += (b[1] - b[0]) * (b[1] - b[0]);
  return std::sqrt(squared);
}

bool facet_contains(const VoronoiFacet& facet, const Vec3& x, double tolerance) {
  if (!facet.valid) return false;
  if (std::abs(dot(x - facet.origin, facet.normal)) > tolerance) return false;
  const auto uv = facet.plane_coordinates(x);
  return facet.contains(uv[0], uv[1], tolerance);
}

double WitnessCollector::tolerance(const SurfaceOracle& oracle, const UndecidedBox& region) const {
  return std::max(tolerances::face_membership_relative_tolerance * oracle.diagonal(), region_diameter(region));
}

std::optional<Vec3> WitnessCollector::projection(const SurfaceOracle& oracle, const UndecidedBox& region) {
  const auto x = oracle.project(region.world);
  if (!x) add_unsettled(UnsettledReason::unprojectable_region, region.world);
  return x;
}

void WitnessCollector::add_region(const SurfaceOracle& oracle, const VoronoiFacet& facet, const UndecidedBox& region) {
  const auto x = projection(oracle, region);
  if (!x) return;
  if (facet_contains(facet, *x, tolerance(oracle, region)))
    add(*x, true);
  else
    add_unsettled(UnsettledReason::region_outside_face, region.world);
}

void WitnessCollector::add_region(const SurfaceOracle& oracle, const VoronoiCell& cell, const UndecidedBox& region) {
  const auto x = projection(oracle, region);
  if (!x) return;
  if (cell.contains(*x, tolerance(oracle, region)))
    add(*x, true);
  else
    add_unsettled(UnsettledReason::region_outside_face, region.world);
}

void WitnessCollector::add_degenerate_facet(const SurfaceOracle& oracle, const VoronoiFacet& facet) {
  if (!facet.degenerate) return;
  const double margin = tolerances::face_membership_relative_tolerance * oracle.diagonal();
  Vec3 lo{}, hi{};
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::numeric_limits<double>::infinity();
    hi[k] = -lo[k];
  }
  for (const auto& w : facet.polygon) {
    const Vec3 x = facet.world(w[0], w[1]);
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], x[k] - margin);
      hi[k] = std::max(hi[k], x[k] + margin);
    }
  }
  if (oracle.value_sign(lo, hi) == 0) add_unsettled(UnsettledReason::degenerate_face, 0.5 * (lo + hi));
}

void WitnessCollector::add_line_region(const SurfaceOracle& oracle, const UndecidedBox& region) {
  if (const auto x = projection(oracle, region)) add(*x, region.reason != UndecidedReason::boundary_root);
}

CheckResult WitnessCollector::take() {
  std::vector<std::size_t> order(points_.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return distance(points_[i].x, from_point_) > distance(points_[j].x, from_point_);
  });
  CheckResult result;
  for (std::size_t i : order) result.witnesses.push_back(Witness{points_[i].x, kind_, from_, points_[i].from_undecided});
  result.unsettled = std::move(unsettled_);
  points_.clear();
  unsettled_.clear();
  return result;
}

}  // namespace delmesh::detail
