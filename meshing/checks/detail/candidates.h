#pragma once
// Collecting a check's witnesses (design notes: an undecided region near a face is a candidate
// witness; inserting a false witness is harmless by §3 and Lemma 5.1) and what it could not
// settle, ordered as the paper chooses: the witness furthest from the check's sample first.
//
// Candidate acceptance.  Let R be an undecided region of a system over a face F, of diameter δ
// in world units (its unknowns are world coordinates, or coordinates in an orthonormal plane
// frame), and suppose R holds a zero z ∈ Σ ∩ F.  Its centre c satisfies |c − z| ≤ δ/2, and the
// projection x of c onto Σ (Newton along ∇E, which to first order is the closest point of Σ)
// satisfies |x − c| ≤ dist(c, Σ) ≤ |c − z|, so |x − z| ≤ δ and dist(x, F) ≤ δ.  A projection
// within max(δ, face_membership_relative_tolerance · diag) of F is therefore a candidate witness;
// one that fails or lands further away is not a point the region's zero could be, and the region
// is reported unsettled with its centre (it is never dropped, and its centre is never inserted).

#include <optional>
#include <vector>

#include "meshing/core/surface_oracle.h"
#include "meshing/core/witness.h"
#include "meshing/voronoi/voronoi_geometry.h"

namespace delmesh::detail {

//! The world diameter of the region (its box's diagonal in the solver's unknowns).
double region_diameter(const UndecidedBox& region);

//! Whether a world point lies in the facet (plane distance and polygon, up to tolerance).
bool facet_contains(const VoronoiFacet& facet, const Vec3& x, double tolerance);

class WitnessCollector {
 public:
  //! Witnesses of check `kind`, measured from the sample `from` at `from_point`.
  WitnessCollector(CheckKind kind, VertexId from, const Vec3& from_point)
      : kind_(kind), from_(from), from_point_(from_point) {}

  //! A point of Σ in the face (a certified root, a crossing, a projected candidate).
  void add(const Vec3& x, bool from_undecided = false) { points_.push_back({x, from_undecided}); }
  //! An undecided region of a system over the facet or the cell: a candidate if its projection
  //! lies in the face up to the acceptance tolerance above, otherwise unsettled.
  void add_region(const SurfaceOracle& oracle, const VoronoiFacet& facet, const UndecidedBox& region);
  void add_region(const SurfaceOracle& oracle, const VoronoiCell& cell, const UndecidedBox& region);
  //! An undecided region of SurfaceLine: its projection onto Σ, or unsettled if that fails.
  void add_line_region(const SurfaceOracle& oracle, const UndecidedBox& region);
  //! A primitive's answer over `face` (a VoronoiFacet or a VoronoiCell): its certified roots,
  //! then its undecided regions as add_region() takes them.
  template <class Face>
  void add_result(const SurfaceOracle& oracle, const Face& face, const SolveResult& result) {
    for (const auto& root : result.roots) add(root.world);
    for (const auto& region : result.undecided) add_region(oracle, face, region);
  }
  void add_unsettled(UnsettledReason reason, const Vec3& where) { unsettled_.push_back({kind_, reason, where}); }
  //! A degenerate facet (VoronoiFacet::degenerate): unsettled unless E has a proved sign on the
  //! bounding box of its points, widened by face_membership_relative_tolerance · diag.
  void add_degenerate_facet(const SurfaceOracle& oracle, const VoronoiFacet& facet);

  std::size_t points() const { return points_.size(); }
  //! Forgets the points added so far (not the unsettled findings).
  void drop_points() { points_.clear(); }
  //! The witnesses, furthest from the sample first (ties: in the order added), and the unsettled
  //! regions.  Leaves the collector empty.
  CheckResult take();

 private:
  std::optional<Vec3> projection(const SurfaceOracle& oracle, const UndecidedBox& region);
  double tolerance(const SurfaceOracle& oracle, const UndecidedBox& region) const;

  struct Point {
    Vec3 x;
    bool from_undecided;
  };
  CheckKind kind_;
  VertexId from_;
  Vec3 from_point_;
  std::vector<Point> points_;
  std::vector<Unsettled> unsettled_;
};

}  // namespace delmesh::detail
