// A worked check (docs/extending.md): graded sizing by a user field h.  A restricted triangle
// t fails it when its surface Delaunay ball (centre c, the point where t's dual Voronoi edge
// meets Σ; radius r, the distance from c to the vertices of t) is larger than the field there,
// r > h(c); the witness is c, a point of Σ on the dual edge of a restricted triangle, as for
// Quality and the size bound, so Topology re-run afterwards keeps the topological guarantee.
// Termination: the Delaunay ball is empty, so c is at distance r > h(c) ≥ min h > 0 from every
// sample, and a packing argument bounds the points this check inserts.
//
// The field: finest on the mid-plane z = z_mid of the box (2 % of the box diagonal), coarser away
// from it, h(x) = 0.02·diag + 0.5·|x_z − z_mid|.
#include <cmath>

#include "meshing/checks/check_registry.h"
#include "meshing/core/detail/vec3.h"

namespace delmesh {

namespace {

double mid_plane_field(const Vec3& x, const Box3& box) {
  return 0.02 * box.diagonal() + 0.5 * std::abs(x[2] - 0.5 * (box.lo[2] + box.hi[2]));
}

CheckResult sizing_field_witness(const CheckContext& context, const DelaunayFace& face) {
  const TriangleKey t = face;
  const VoronoiEdgeRecord& record = context.restricted.voronoi_edge_record(t);
  if (!record.restricted) return {};
  const Vec3 c = record.dual_point();
  const double r = detail::distance(c, context.restricted.delaunay().point(t[0]));
  if (r <= mid_plane_field(c, context.restricted.oracle().box())) return {};
  CheckResult result;
  result.witnesses.push_back({c, context.kind, t[0], false});
  return result;
}

}  // namespace

const CheckRegistration sizing_field{{
    "sizing_field",
    "graded sizing: surface Delaunay ball radius r ≤ h(c) at its centre c, h(x) = 0.02·diag + 0.5·|x_z − z_mid|; "
    "witness c",
    FaceKind::triangle, Dirtied::restricted_triangles, CheckPhase::geometry, sizing_field_witness}};

}  // namespace delmesh
