#include "meshing/detail/candidates.h"

#include <algorithm>
#include <cmath>

#include "common/tolerances.h"
#include "meshing/detail/vec3.h"

namespace delmesh::detail {

double region_radius(const UndecidedBox& region) {
  double w = 0;
  for (const auto& b : region.box.bounds) w = std::max(w, b[1] - b[0]);
  return 0.5 * w;
}

bool facet_contains(const VoronoiFacet& facet, const Vec3& x, double tolerance) {
  if (!facet.valid) return false;
  if (std::abs(dot(x - facet.origin, facet.normal)) > tolerance) return false;
  const auto uv = facet.plane_coordinates(x);
  return facet.contains(uv[0], uv[1], tolerance);
}

std::optional<Vec3> facet_candidate(const SurfaceOracle& oracle, const VoronoiFacet& facet,
                                    const UndecidedBox& region) {
  const auto x = oracle.project(region.world);
  if (!x) return std::nullopt;
  const double tol = std::max(tolerances::face_membership_relative_tolerance * oracle.diagonal(),
                              2 * region_radius(region));
  if (!facet_contains(facet, *x, tol)) return std::nullopt;
  return x;
}

std::optional<Vec3> cell_candidate(const SurfaceOracle& oracle, const VoronoiCell& cell,
                                   const UndecidedBox& region) {
  const auto x = oracle.project(region.world);
  if (!x) return std::nullopt;
  const double tol = std::max(tolerances::face_membership_relative_tolerance * oracle.diagonal(),
                              2 * region_radius(region));
  if (!cell.contains(*x, tol)) return std::nullopt;
  return x;
}

std::size_t furthest_index(const std::vector<Vec3>& points, const Vec3& p) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (distance(points[i], p) > distance(points[best], p)) best = i;
  return best;
}

}  // namespace delmesh::detail
