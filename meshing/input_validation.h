#pragma once
//! \file input_validation.h
//! Checks made before meshing (issue 4, part 6), each failing with InvalidInput and a clear
//! message.  Every check has a budget; none can hang.  (The third input condition, Σ non-empty in
//! the box, is checked by SampleTopology: no critical point in the height direction means no
//! component of Σ, since a compact component has a maximum.)

#include "symbolic/surface.h"

namespace delmesh {

//! Certifies E ≠ 0 on each of the six faces of the box by interval subdivision of the face
//! (quadtree, bounded number of boxes).  Throws InvalidInput naming the face if E changes sign
//! (or vanishes) at sample points of a face — Σ meets the box boundary — or "cannot certify" if
//! the budget runs out undecided.
void validate_box_faces(const Surface& surface, const Box3& box);

//! Certifies that ∇E does not vanish on Σ ∩ box: exclusion-mode subdivision of
//! {E, ∂xE, ∂yE, ∂zE} over the box.  Throws InvalidInput with the location of a region that
//! cannot be excluded (a singular point such as a cone's apex), or if the budget runs out.
void validate_regular(const Surface& surface, const Box3& box);

//! Both checks above.
void validate_input(const Surface& surface, const Box3& box);

}  // namespace delmesh
