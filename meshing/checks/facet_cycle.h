#pragma once
//! \file facet_cycle.h
//! FacetCycle(F) (§5.3, Lemma 4.9): guards against F ∩ Σ containing a closed curve.

#include <optional>

#include "meshing/core/witness.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! CurveCritical(Σ, Π, d) with d = a, the first axis of the facet's frame (a seeded generic
//! in-plane direction, RestrictedDelaunay::facet_rotation(pq, attempt): attempt 0 is the cached
//! facet's frame, attempt k > 0 the k-th alternative), over the polygon F.  For each
//! critical point x in F (certified, or the centre of an undecided region), the line ℓ_x through
//! x parallel to d is clipped to F and SurfaceLine(Σ, ℓ_x ∩ F) is solved; if it has ≥ 2 points
//! (undecided regions on ℓ_x count, projected onto Σ), the one furthest from p (the smaller id of
//! pq) is returned, the others as fall-backs.  The witnesses of a line through the centre of an
//! undecided region are marked from_undecided (that centre is not known to be critical); when
//! that line has fewer than two points, the region is reported unsettled
//! (undecided_critical_region, at its centre): a closed curve of Σ ∩ F inside the region may miss
//! the line, so nothing is proved there.  An undecided region of SurfaceLine whose projection onto
//! Σ fails is unsettled, never a witness.
//! Precondition (the paper's): FacetContact(F) returned nothing.
CheckResult facet_cycle_witness(RestrictedDelaunay& restricted, const EdgeKey& pq, int attempt = 0);

}  // namespace delmesh
