//! \file surface_distance_critical.cpp
//! A seventh primitive, added the way docs/extending.md describes: one builder
//! function and one registry row, in one file.  The build compiles this file into the variants
//! delmesh_extending, bench_solvers_extending and extending_tests (examples/extending/CMakeLists.txt).
//!
//! SurfaceDistanceCritical(Σ, c): the points x of Σ where the distance to c is critical, i.e.
//! where x − c is normal to Σ: w = (x − c) × ∇E = 0.  Three equations in x, y, z: E = 0 and the
//! components of w along an orthonormal frame (a, b) of d⟂.  They also hold where w ≠ 0 is
//! parallel to d (there x − c ⟂ d and ∇E ⟂ d); the side condition ⟨w, d⟩ = 0, d = a × b, drops
//! those roots.  Parameters c(3), a(3), b(3).  A genuine root with ⟨x − c, d⟩ = 0 is singular
//! for this system: make_query takes d = c − (box centre) unless --direction is given.

#include "solvers/primitive_registry.h"

#include "common/errors.h"

namespace delmesh {

namespace {

PrimitiveSystem surface_distance_critical_system(const Surface& surface) {
  PrimitiveSystem system;
  use_world_unknowns(system);
  const ExVec3 c = add_vector_parameter(system, "c"), a = add_vector_parameter(system, "a"),
               b = add_vector_parameter(system, "b");
  const ExVec3 w = cross(from_point(c), surface.gradient());
  system.equations = {surface.E(), dot(w, a), dot(w, b)};
  system.side_conditions = {dot(w, cross(a, b))};
  return system;
}

const PrimitiveRegistration surface_distance_critical{{
    "surface_distance_critical",
    "points of Σ where the distance to c is critical: E = ⟨w,a⟩ = ⟨w,b⟩ = 0, w = (x − c) × ∇E, (a, b) a frame "
    "of d⟂; roots with ⟨w,d⟩ ≠ 0 dropped; unknowns x, y, z",
    surface_distance_critical_system,
    {required_option(QueryOption::point, "c, the query point"),
     optional_option(QueryOption::direction, "d; default c minus the box centre")},
    "the box",
    [](const QueryOptions& o, const Box3& box) {
      const Vec3 c = o.at(QueryOption::point);
      Vec3 d = o.value_or(QueryOption::direction, {});
      if (!o.has(QueryOption::direction)) {
        for (int i = 0; i < 3; ++i) d[i] = c[i] - 0.5 * (box.lo[i] + box.hi[i]);
        if (d == Vec3{0, 0, 0}) throw InvalidInput("--point is the box centre: give --direction");
      }
      const OrthonormalFrame f = orthonormal_frame(d);
      return box_query(box, {c, f.a, f.b}, "point " + vector_text(c) + ", direction " + vector_text(f.d));
    },
    // The unit sphere's points nearest to and farthest from c = (0.3, −0.4, 1.2) are ±c/|c|.
    {"sphere", {{{QueryOption::point, {0.3, -0.4, 1.2}}}}, {{3. / 13, -4. / 13, 12. / 13}, {-3. / 13, 4. / 13, -12. / 13}}}}};

}  // namespace

}  // namespace delmesh
