#pragma once
//! \file facet_contact.h
//! FacetContact(F) (§5.3, Lemma 4.8): a tangential contact of the facet's plane with Σ inside F.

#include <optional>

#include "meshing/core/witness.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! SurfacePlaneContact(Σ, Π) over the facet polygon F of the Delaunay edge pq, in exclusion mode
//! ({E, ∂uE, ∂vE} has no solution for a non-tangent plane, so certification is not needed): every
//! region that cannot be excluded is a possible contact; its centre projected onto Σ is returned
//! if it lies in F (the one furthest from p = the smaller id, then the others as fall-backs).
//! Nothing if every region of F is excluded.  A region whose projection fails or leaves F is
//! unsettled (meshing/checks/detail/candidates.h).  The facet frame is RestrictedDelaunay::facet(pq).
//! A degenerate facet (numerically without area) is unsettled unless Σ is proved to miss it or
//! the gradient cone proves it clean for both facet checks over the hull of its points
//! (RestrictedDelaunay::facet_section_certified); it is reported here for both (FacetCycle skips it).
CheckResult facet_contact_witness(RestrictedDelaunay& restricted, const EdgeKey& pq);

}  // namespace delmesh
