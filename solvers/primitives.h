#pragma once
//! \file primitives.h
//! The six numerical primitives of §5.2: their builders, and their rows of the registry
//! (builtin_primitives(), solvers/primitive_registry.h), both in primitives.cpp.  Parameter
//! conventions (all in world coordinates, doubles supplied per query):
//!
//! | primitive              | unknowns | parameters                         | equations |
//! |------------------------|----------|------------------------------------|-----------|
//! | surface_critical       | x, y, z  | a(3), b(3): orthonormal, ⟂ d       | E, ⟨∇E,a⟩, ⟨∇E,b⟩ (∇E ∥ d) |
//! | surface_line           | t        | p(3), v(3): x = p + t v            | E(p + t v) |
//! | surface_plane_contact  | u, v     | o(3), a(3), b(3): x = o + u a + v b| E, ∂uE, ∂vE (over-determined) |
//! | curve_critical         | u, v     | o, a, b; direction d = a           | E, ∂vE = ⟨∇E, b⟩ |
//! | silhouette_plane       | u, v     | o, a, b, d(3)                      | E, ⟨∇E, d⟩ |
//! | silhouette_critical    | x, y, z  | d(3), d'(3)                        | E, G = ⟨∇E,d⟩, ⟨∇G × ∇E, d'⟩ |
//!
//! Plane frames (a, b) are orthonormal.  Parameter symbols are named after the table, component
//! by component (a0 a1 a2 b0 b1 b2, p0 … v2, o0 … b2, d0 d1 d2), except d' whose components are
//! e0 e1 e2.  world_point is (x, y, z) for the 3 × 3 systems, p + t v and o + u a + v b otherwise.
//! Every builder derives fresh parameter and reduced-unknown symbols; x, y, z are the shared
//! coordinate symbols of surface.h.  The functions below are build_primitive(name, surface) for
//! each of the six (the system with its Jacobian, ready to compile), for the tests and
//! benchmarks that use one primitive directly; a new primitive needs no such function.

#include "solvers/primitive_registry.h"
#include "symbolic/primitive_system.h"
#include "symbolic/surface.h"

namespace delmesh {

//! SurfaceCritical(Σ, d): critical points of Σ in direction d (∇E ∥ d), written as E = 0,
//! ⟨∇E, a⟩ = 0, ⟨∇E, b⟩ = 0 with (a, b) an orthonormal basis of d⟂.  §5.2.
PrimitiveSystem surface_critical_system(const Surface& surface);
//! SurfaceLine(Σ, ℓ): E(p + t v) = 0 in the single unknown t.  §5.2.
PrimitiveSystem surface_line_system(const Surface& surface);
//! SurfacePlaneContact(Σ, Π): tangential contacts of Σ with Π = {o + u a + v b}:
//! E = ⟨∇E, a⟩ = ⟨∇E, b⟩ = 0 (3 equations, 2 unknowns).  §5.2, Lemma 4.8.
PrimitiveSystem surface_plane_contact_system(const Surface& surface);
//! CurveCritical(Σ, Π, d = a): critical points of Σ ∩ Π in the in-plane direction a, and the
//! tangential contacts: E = 0, ⟨∇E, b⟩ = 0.  §5.2, Lemma 4.9.
PrimitiveSystem curve_critical_system(const Surface& surface);
//! SilhouettePlane(Σ, Π, d): J_d ∩ Π: E = 0, ⟨∇E, d⟩ = 0 in (u, v).  §5.2, Lemma 4.14.
PrimitiveSystem silhouette_plane_system(const Surface& surface);
//! SilhouetteCritical(Σ, d, d'): critical points of J_d in direction d'.  §5.2, Lemma 4.14.
PrimitiveSystem silhouette_critical_system(const Surface& surface);

}  // namespace delmesh
