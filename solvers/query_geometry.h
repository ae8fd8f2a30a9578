#pragma once
//! \file query_geometry.h
//! The per-query geometry that turns a direction, a line or a plane into the parameters and the
//! domain of a primitive system (primitives.h): a deterministic orthonormal frame of d⟂, a line
//! clipped to a box (SurfaceLine's parameter interval), and a plane cut by a box as a convex
//! polygon in the plane's (u, v) frame, turned into a solver Domain.  Shared by the command line
//! (`delmesh solve`) and the mesher.

#include <array>
#include <optional>
#include <vector>

#include "common/vec3.h"
#include "solvers/domain.h"
#include "symbolic/surface.h"

namespace delmesh {

//! A right-handed orthonormal frame (a, b, d): d is the unit direction it was built from and
//! (a, b) an orthonormal basis of d⟂ with a × b = d.
struct OrthonormalFrame {
  Vec3 a{}, b{}, d{};
};

//! The frame of d⟂ for a non-zero direction d.  Deterministic: a is the unit vector of
//! e_k × d, where e_k is the coordinate axis with the smallest |d_k| (the first such k on ties),
//! and b = d × a.  Throws InvalidInput if d is zero or not finite.
OrthonormalFrame orthonormal_frame(const Vec3& direction);

//! d / |d|, for any finite non-zero d (|d|² may overflow or underflow: d is then first scaled by a
//! power of two).  Throws InvalidInput if d is zero or not finite ("direction (…) is zero", "…
//! is not finite", the components in shortest form).
Vec3 unit_vector(const Vec3& d);

//! The parameter interval [t0, t1] (t0 < t1) of the points p + t v that lie in the closed box,
//! or nothing if the line misses the box or only touches it.  Precondition-free on p; throws
//! InvalidInput if v is zero or not finite.
std::optional<std::array<double, 2>> clip_line_to_box(const Vec3& p, const Vec3& v, const Box3& box);

//! A plane {o + u a + v b} cut by a box: the frame and the convex polygon plane ∩ box as
//! vertices (u, v), counter-clockwise in the (a, b) orientation.
struct PlaneSection {
  Vec3 origin{};                              //!< o, the plane origin given by the caller
  OrthonormalFrame frame;                     //!< a, b span the plane, d is its unit normal
  std::vector<std::array<double, 2>> polygon; //!< ≥ 3 vertices, counter-clockwise
};

//! The points where the plane {x : ⟨normal, x⟩ = ⟨normal, origin⟩} meets the 12 edges of the box:
//! each corner on the plane (side exactly 0) once, and one point on each edge whose ends lie
//! strictly on opposite sides, in floating point.  These are the vertices of plane ∩ box (with
//! repeats where the plane passes through a corner); empty if the plane misses the box.
std::vector<Vec3> plane_box_edge_points(const Vec3& origin, const Vec3& normal, const Box3& box);

//! The section of the plane through `origin` with normal `normal` by the box, with the frame
//! orthonormal_frame(normal).  Nothing if the plane misses the box or meets it in less than a
//! polygon of positive area (an edge or a corner).  Throws InvalidInput if normal is zero.
std::optional<PlaneSection> plane_box_section(const Vec3& origin, const Vec3& normal, const Box3& box);
//! The same with a given frame: the plane through origin spanned by frame.a, frame.b (normal
//! frame.d), the polygon in the coordinates (u, v) of that frame.  Precondition: frame orthonormal.
std::optional<PlaneSection> plane_box_section(const Vec3& origin, const OrthonormalFrame& frame,
                                              const Box3& box);

//! The solver domain of a convex polygon given counter-clockwise in (u, v): the bounding box of
//! the vertices and one half-space ⟨n_e, w⟩ ≤ ⟨n_e, w_e⟩ per edge e (n_e its outward normal).
//! Throws PreconditionViolation if there are fewer than 3 vertices.
Domain polygon_domain(const std::vector<std::array<double, 2>>& polygon);

//! The box as a solver Domain in (x, y, z).
Domain box_domain(const Box3& box);

}  // namespace delmesh
