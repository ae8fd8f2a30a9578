#pragma once
// Turning undecided solver regions into candidate witnesses (design notes: an undecided region
// near a face is a candidate witness; inserting a false witness is harmless by §3 and Lemma 5.1),
// and choosing the witness furthest from a sample.

#include <optional>
#include <vector>

#include "meshing/surface_oracle.h"
#include "meshing/voronoi_geometry.h"

namespace delmesh::detail {

//! Half the widest side of the region, in world units (its world size for plane/line systems,
//! whose frames are orthonormal).
double region_radius(const UndecidedBox& region);

//! The projection onto Σ of the region's centre if it lies in the facet (up to tolerance).
std::optional<Vec3> facet_candidate(const SurfaceOracle& oracle, const VoronoiFacet& facet,
                                    const UndecidedBox& region);
//! The projection onto Σ of the region's centre if it lies in the cell (up to tolerance).
std::optional<Vec3> cell_candidate(const SurfaceOracle& oracle, const VoronoiCell& cell,
                                   const UndecidedBox& region);
//! Whether a world point lies in the facet (plane distance and polygon, up to tolerance).
bool facet_contains(const VoronoiFacet& facet, const Vec3& x, double tolerance);

//! Index of the point furthest from p (first on ties); precondition: non-empty.
std::size_t furthest_index(const std::vector<Vec3>& points, const Vec3& p);

}  // namespace delmesh::detail
