#pragma once
// A convex polytope in R^3 as a list of planar faces (vertex loops), built from a box and clipped
// by half-spaces {x : <n, x> <= c}.  Each face remembers the label of the half-space it lies on
// (-1 .. -6 for the box faces).  Used for the bounding box and the facet list of a clipped
// Voronoi cell.  Floating point; faces of area ~0 are dropped.

#include <vector>

#include "meshing/core/detail/vec3.h"
#include "symbolic/surface.h"

namespace delmesh::detail {

struct PolytopeFace {
  int label = 0;
  std::vector<V3> loop;
};

class ConvexPolytope {
 public:
  ConvexPolytope() = default;  //!< empty; call reset() before use
  explicit ConvexPolytope(const Box3& box);
  //! Back to the box (reusing the buffers of earlier clips).
  void reset(const Box3& box);
  //! Intersects with {x : <n, x> <= c}; the new face (if any) gets `label`.  A vertex within
  //! polytope_clip_relative_tolerance (common/tolerances.h) of the largest distance of a vertex
  //! to the plane counts as on the plane.  n = 0: nothing happens.
  void clip(const V3& n, double c, int label);
  bool empty() const { return faces_.empty(); }
  const std::vector<PolytopeFace>& faces() const { return faces_; }
  //! Bounding box [lo, hi] of the vertices.  Precondition: !empty().
  std::array<V3, 2> bounding_box() const;

 private:
  // The steps of clip().  signed_distances: side_ for every loop vertex, and the returned eps.
  double signed_distances(const V3& n, double c, double scale);
  // The next scratch face spare_[count], emptied.
  PolytopeFace& next_slot(std::size_t count);
  // Each face's part inside into spare_[0, count) (count returned); crossings into cut_.
  std::size_t clip_faces(double eps);
  // The face on the clipping plane from cut_, as spare_[count] (count incremented if kept).
  void add_cut_face(const V3& n, double eps, int label, std::size_t& count);

  std::vector<PolytopeFace> faces_;
  // Scratch reused by clip() (no allocation per clip once warmed up).
  std::vector<PolytopeFace> spare_;
  std::vector<double> side_;
  std::vector<V3> cut_;
  struct AngledPoint {
    double angle;
    V3 point;
  };
  std::vector<AngledPoint> by_angle_;  // cut_ with each point's angle about the cut's centroid
};

}  // namespace delmesh::detail
