#pragma once
//! \file quality.h
//! Quality (§6.1, after Chew) and the size and distance controls beyond the paper.

#include <optional>

#include "meshing/core/witness.h"
#include "meshing/inputs/flow_distance.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! Circumradius of the triangle pqr (+∞ if degenerate).  Computed on the edge vectors scaled by a
//! power of two to lengths about 1, so it neither overflows nor underflows at any scale.
double circumradius(const Vec3& p, const Vec3& q, const Vec3& r);
//! ρ(t) = circumradius / shortest edge (+∞ if degenerate); scale-free like circumradius.
double radius_edge_ratio(const Vec3& p, const Vec3& q, const Vec3& r);

//! If t ∈ Tri S|Σ has ρ(t) > 1 + λ, a point of Σ on t's dual Voronoi edge (the first certified
//! crossing; the paper lets the choice be arbitrary), measured from the vertex of t at the
//! shortest edge inserted last; otherwise nothing.
std::optional<Witness> quality_witness(RestrictedDelaunay& restricted, const TriangleKey& t, double lambda);

//! Size control (`--size-bound H`): if t ∈ Tri S|Σ has surface Delaunay ball radius (the distance
//! from its dual point on Σ to its vertices) > H, that dual point.  Like Quality, it only inserts
//! points of Σ on dual Voronoi edges of restricted triangles, so Topology re-run afterwards keeps
//! the topological guarantee; the distance bound of Theorem 6.1's proof is replaced by H for the
//! points it inserts, so termination follows from packing at scale min(H, λ·lfs).
std::optional<Witness> size_witness(RestrictedDelaunay& restricted, const TriangleKey& t, double size_bound);

//! Distance control (`--max-distance δ`): if t ∈ Tri S|Σ is not proved within δ of Σ by the flow
//! distance bound (flow_distance.h, radius δ), its dual point on Σ.  Like size_witness it inserts
//! only points of Σ on dual Voronoi edges of restricted triangles, so the topological guarantee
//! is kept.  Termination: as the sample densifies, the triangles of Tri S|Σ shrink and |E| on them
//! falls quadratically with their size while |∇E| stays bounded away from 0 near Σ, so the bound
//! holds once the sample is fine enough; the termination floor bounds the insertions regardless.
//! Precondition: δ > 0 (PreconditionViolation from FlowDistance::bound otherwise).
std::optional<Witness> distance_witness(RestrictedDelaunay& restricted, const TriangleKey& t, double max_distance,
                                        const FlowDistance& flow_distance);

}  // namespace delmesh
