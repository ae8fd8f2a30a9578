#pragma once
//! \file unit_scale.h
//! Remeshing a closed triangle mesh (§7, meshing/inputs/mesh_oracle.h) at any scale.  The mesher's
//! constructions (circumcentres, Voronoi vertices, squared distances, products of four lengths)
//! overflow or underflow double precision for a mesh of size 1e80 or 1e-100, so MeshOracle works
//! at unit scale: it multiplies the mesh and its box by the power of two 2^-k that brings the
//! largest side of the box into [1, 2) — exact, so the scaled mesh is the same surface and every
//! exact predicate answers as on the input — and the run's lengths go in, and its output
//! vertices, lengths and locations come out, multiplied by 2^∓k (meshing/driver/scaled_run.h;
//! exact too, unless a value falls below the normal range of double).  A box whose largest side
//! lies within [2^-unit_scale_max_exponent, 2^unit_scale_max_exponent) is used as given (k = 0).

#include "meshing/core/surface_mesh.h"
#include "symbolic/surface.h"

namespace delmesh {

inline constexpr int unit_scale_max_exponent = 32;

//! The k of the file comment for `box`: 0 if its largest side w satisfies 2^-32 ≤ w < 2^32, else
//! the exponent of w (2^k ≤ w < 2^(k+1)).
int unit_scale_exponent(const Box3& box);

//! Every vertex of `mesh` times 2^e (e = −k into unit scale, k back).
void scale_mesh(SurfaceMesh& mesh, int e);
//! `box` times 2^e.
Box3 scaled_box(const Box3& box, int e);

}  // namespace delmesh
