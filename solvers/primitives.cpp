#include "solvers/primitives.h"

#include <cmath>

#include "common/errors.h"
#include "common/tolerances.h"

namespace delmesh {

namespace {

using GiNaC::ex;
using GiNaC::symbol;
using Q = QueryOption;

double dot3(const Vec3& p, const Vec3& q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; }
Vec3 cross3(const Vec3& p, const Vec3& q) {
  return {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
}

// ---- the builders ----------------------------------------------------------------------------

PrimitiveSystem surface_critical_builder(const Surface& surface) {
  PrimitiveSystem system;
  use_world_unknowns(system);
  const ExVec3 a = add_vector_parameter(system, "a"), b = add_vector_parameter(system, "b");
  system.equations = {surface.E(), dot(surface.gradient(), a), dot(surface.gradient(), b)};
  return system;
}

PrimitiveSystem surface_line_builder(const Surface& surface) {
  PrimitiveSystem system;
  const symbol t("t");
  system.unknowns = {t};
  const ExVec3 p = add_vector_parameter(system, "p"), v = add_vector_parameter(system, "v");
  for (int i = 0; i < 3; ++i) system.world_point[i] = p[i] + t * v[i];
  system.equations = {at_world_point(system, surface.E())};
  return system;
}

PrimitiveSystem surface_plane_contact_builder(const Surface& surface) {
  PrimitiveSystem system;
  const PlaneRestriction plane = use_plane(system, surface);
  system.equations = {plane.E, dot(plane.gradient, plane.a), dot(plane.gradient, plane.b)};
  return system;
}

PrimitiveSystem curve_critical_builder(const Surface& surface) {
  PrimitiveSystem system;
  const PlaneRestriction plane = use_plane(system, surface);
  system.equations = {plane.E, dot(plane.gradient, plane.b)};
  return system;
}

PrimitiveSystem silhouette_plane_builder(const Surface& surface) {
  PrimitiveSystem system;
  const PlaneRestriction plane = use_plane(system, surface);
  const ExVec3 d = add_vector_parameter(system, "d");
  system.equations = {plane.E, dot(plane.gradient, d)};
  return system;
}

PrimitiveSystem silhouette_critical_builder(const Surface& surface) {
  PrimitiveSystem system;
  use_world_unknowns(system);
  const ExVec3 d = add_vector_parameter(system, "d"), e = add_vector_parameter(system, "e");  // e stands for d'
  const GiNaC::matrix& H = surface.hessian();
  // G = ⟨∇E, d⟩ and ∇G = H d (H symmetric).
  ExVec3 grad_G;
  for (unsigned i = 0; i < 3; ++i) grad_G[i] = H(i, 0) * d[0] + H(i, 1) * d[1] + H(i, 2) * d[2];
  system.equations = {surface.E(), dot(surface.gradient(), d), dot(cross(grad_G, surface.gradient()), e)};
  return system;
}

// ---- the queries that need more than a helper of primitive_query.h ---------------------------

//! The plane of --plane-origin, --plane-normal in the frame of its normal.
OrthonormalFrame plane_frame(const QueryOptions& o) { return orthonormal_frame(unit_vector(o.at(Q::plane_normal))); }

//! curve_critical: the component of --direction in the plane becomes a, and b = n × a.
PrimitiveQuery curve_critical_query(const QueryOptions& o, const Box3& box) {
  const Vec3 normal = unit_vector(o.at(Q::plane_normal));
  OrthonormalFrame frame = orthonormal_frame(normal);
  const Vec3 given = o.at(Q::direction);
  const double along = dot3(given, normal);
  const Vec3 in_plane{given[0] - along * normal[0], given[1] - along * normal[1], given[2] - along * normal[2]};
  if (std::sqrt(dot3(in_plane, in_plane)) <= tolerances::query_parallel_directions * std::sqrt(dot3(given, given))) {
    throw InvalidInput("--direction must not be normal to the plane for curve_critical");
  }
  frame.a = unit_vector(in_plane);
  frame.b = cross3(frame.d, frame.a);
  return plane_query(box, o.at(Q::plane_origin), frame, {}, "");
}

PrimitiveQuery silhouette_critical_query(const QueryOptions& o, const Box3& box) {
  const Vec3 d = unit_vector(o.at(Q::direction)), e = unit_vector(o.at(Q::direction2));
  const Vec3 c = cross3(d, e);
  if (std::sqrt(dot3(c, c)) <= tolerances::query_parallel_directions) throw InvalidInput("--direction and --direction2 must not be parallel");
  return box_query(box, {d, e}, "direction " + vector_text(d) + ", direction2 " + vector_text(e));
}

}  // namespace

// ---- the registry rows: name, summary, builder, options, domain, make_query, known answer ----

const std::vector<PrimitiveInfo>& builtin_primitives() {
  static const std::vector<PrimitiveInfo> rows = {
      {"surface_critical", "critical points of Σ in direction d: E = ⟨∇E,a⟩ = ⟨∇E,b⟩ = 0, (a, b) a frame of d⟂; "
       "unknowns x, y, z",
       surface_critical_builder,
       {optional_option(Q::direction, "d, the height direction; default 0,0,1")},
       "the box",
       [](const QueryOptions& o, const Box3& box) {
         const OrthonormalFrame f = orthonormal_frame(o.value_or(Q::direction, {0, 0, 1}));
         return box_query(box, {f.a, f.b}, "direction " + vector_text(f.d));
       },
       // The unit sphere's critical points in direction (1, 2, 2) are ±(1, 2, 2)/3.
       {"sphere", {{{Q::direction, {1, 2, 2}}}}, {{1. / 3, 2. / 3, 2. / 3}, {-1. / 3, -2. / 3, -2. / 3}}}},

      {"surface_line", "Σ ∩ the line p + t v: E(p + t v) = 0; unknown t", surface_line_builder,
       {required_option(Q::point, "p, a point of the line"), required_option(Q::direction, "v, its direction")},
       "the line clipped to the box",
       [](const QueryOptions& o, const Box3& box) { return line_query(box, o.at(Q::point), o.at(Q::direction)); },
       // The x axis meets the torus (R = 1, r = 0.4) at x = ±0.6, ±1.4.
       {"torus", {{{Q::point, {0, 0, 0}}, {Q::direction, {1, 0, 0}}}},
        {{-1.4, 0, 0}, {-0.6, 0, 0}, {0.6, 0, 0}, {1.4, 0, 0}}}},

      {"surface_plane_contact", "tangential contacts of Σ with the plane o + u a + v b: E = ∂uE = ∂vE = 0 "
       "(over-determined: proves absence only); unknowns u, v",
       surface_plane_contact_builder,
       {required_option(Q::plane_origin, "o, a point of the plane"), required_option(Q::plane_normal, "n, its normal")},
       "the polygon plane ∩ box",
       [](const QueryOptions& o, const Box3& box) { return plane_query(box, o.at(Q::plane_origin), plane_frame(o), {}, ""); },
       // The plane z = 1/2 cuts the unit sphere transversally: no contact.
       {"sphere", {{{Q::plane_origin, {0, 0, 0.5}}, {Q::plane_normal, {0, 0, 1}}}}, {}}},

      {"curve_critical", "critical points of Σ ∩ plane in the in-plane direction a: E = ⟨∇E,b⟩ = 0; unknowns u, v",
       curve_critical_builder,
       {required_option(Q::plane_origin, "o, a point of the plane"), required_option(Q::plane_normal, "n, its normal"),
        required_option(Q::direction, "a, the in-plane direction; its component in the plane is used")},
       "the polygon plane ∩ box",
       curve_critical_query,
       // The plane y = 0 cuts the torus in the circles (x ∓ 1)² + z² = 0.16; their critical
       // points in direction x are (±0.6, 0, 0) and (±1.4, 0, 0).
       {"torus", {{{Q::plane_origin, {0, 0, 0}}, {Q::plane_normal, {0, 1, 0}}, {Q::direction, {1, 0, 0}}}},
        {{-1.4, 0, 0}, {-0.6, 0, 0}, {0.6, 0, 0}, {1.4, 0, 0}}}},

      {"silhouette_plane", "the silhouette J_d ∩ plane: E = ⟨∇E,d⟩ = 0; unknowns u, v", silhouette_plane_builder,
       {required_option(Q::plane_origin, "o, a point of the plane"), required_option(Q::plane_normal, "n, its normal"),
        required_option(Q::direction, "d, the silhouette direction")},
       "the polygon plane ∩ box",
       [](const QueryOptions& o, const Box3& box) {
         const Vec3 d = unit_vector(o.at(Q::direction));
         return plane_query(box, o.at(Q::plane_origin), plane_frame(o), {d}, ", direction " + vector_text(d));
       },
       // On the torus ∂xE = 4x(|x|² − 1.16): J_x meets the plane y = 0 at (±1, 0, ±0.4).
       {"torus", {{{Q::plane_origin, {0, 0, 0}}, {Q::plane_normal, {0, 1, 0}}, {Q::direction, {1, 0, 0}}}},
        {{-1, 0, -0.4}, {-1, 0, 0.4}, {1, 0, -0.4}, {1, 0, 0.4}}}},

      {"silhouette_critical", "critical points of J_d in direction d': E = G = ⟨∇G × ∇E, d'⟩ = 0, G = ⟨∇E,d⟩; "
       "unknowns x, y, z",
       silhouette_critical_builder,
       {required_option(Q::direction, "d, the silhouette direction"),
        required_option(Q::direction2, "d', the direction of the critical points; not parallel to d")},
       "the box",
       silhouette_critical_query,
       // The unit sphere's J_d for d = (3, 4, 0)/5 is the great circle through ±e_z; its critical
       // points in direction e_z are ±e_z.
       {"sphere", {{{Q::direction, {3, 4, 0}}, {Q::direction2, {0, 0, 1}}}}, {{0, 0, -1}, {0, 0, 1}}}},
  };
  return rows;
}

PrimitiveSystem surface_critical_system(const Surface& surface) { return build_primitive("surface_critical", surface); }
PrimitiveSystem surface_line_system(const Surface& surface) { return build_primitive("surface_line", surface); }
PrimitiveSystem surface_plane_contact_system(const Surface& surface) {
  return build_primitive("surface_plane_contact", surface);
}
PrimitiveSystem curve_critical_system(const Surface& surface) { return build_primitive("curve_critical", surface); }
PrimitiveSystem silhouette_plane_system(const Surface& surface) { return build_primitive("silhouette_plane", surface); }
PrimitiveSystem silhouette_critical_system(const Surface& surface) {
  return build_primitive("silhouette_critical", surface);
}

}  // namespace delmesh
