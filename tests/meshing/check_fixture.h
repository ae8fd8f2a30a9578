#pragma once
// A hand-built sample set on a given surface, for the tests of the checks of §5.3.
#include <memory>
#include <string>
#include <vector>

#include "meshing/restricted_delaunay.h"
#include "meshing/surface_oracle.h"

namespace delmesh::test {

struct CheckFixture {
  Box3 box;
  SurfaceOracle oracle;
  Delaunay del;
  RestrictedDelaunay restricted;
  CheckFixture(const std::string& equation, double half_width, const std::vector<Vec3>& points)
      : box(Box3::cube(half_width)),
        oracle(Surface::parse(equation), box, SolverBackend::subdivision),
        restricted(del, oracle, 1) {
    for (const auto& p : points) del.insert(p, false);
  }
};

inline const char* unit_sphere = "x^2+y^2+z^2-1";

}  // namespace delmesh::test
