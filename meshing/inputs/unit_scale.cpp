#include "meshing/inputs/unit_scale.h"

#include <algorithm>
#include <cmath>

namespace delmesh {

int unit_scale_exponent(const Box3& box) {
  double side = 0;
  for (int i = 0; i < 3; ++i) side = std::max(side, box.hi[i] - box.lo[i]);
  if (!(side > 0) || !std::isfinite(side)) return 0;
  const int k = std::ilogb(side);
  return (k >= -unit_scale_max_exponent && k < unit_scale_max_exponent) ? 0 : k;
}

void scale_mesh(SurfaceMesh& mesh, int e) {
  if (e == 0) return;
  for (auto v : mesh.vertices()) {
    const Point3 p = mesh.point(v);
    mesh.point(v) = Point3(std::ldexp(p.x(), e), std::ldexp(p.y(), e), std::ldexp(p.z(), e));
  }
}

Box3 scaled_box(const Box3& box, int e) {
  Box3 out = box;
  for (int i = 0; i < 3; ++i) {
    out.lo[i] = std::ldexp(box.lo[i], e);
    out.hi[i] = std::ldexp(box.hi[i], e);
  }
  return out;
}

}  // namespace delmesh
