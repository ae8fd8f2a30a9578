#pragma once
//! \file restricted_delaunay.h
//! Tri S|Σ (§5.1): the Delaunay triangles whose dual Voronoi edge meets Σ, where a zero of E at a
//! Voronoi vertex v of the edge uv counts only as the paper's perturbation Σ′ says: if
//! ⟨u − v, n_v⟩ > 0 and uv meets Σ nowhere else, the triangle is excluded; otherwise it is kept.
//!
//! The intersections of every Voronoi edge with Σ are computed once (SurfaceLine on the clipped
//! edge) and cached per Delaunay triangle (keyed by sorted vertex ids) until the triangle is
//! dirtied by an insertion or removal (invalidate()).  Facet geometry (Voronoi facets with their
//! seeded generic frames) is cached per Delaunay edge in the same way.
//!
//! Zeros at a Voronoi vertex are reported by the isolator as undecided boundary_root regions at an
//! endpoint of the edge; they are resolved here by the rule above (this is the one kind of
//! undecided region that is not a candidate witness: it is the §5.1 degeneracy).  Any other
//! undecided region on the edge (a tangency, Lemma 4.7(ii), or an exhausted budget) is projected
//! onto Σ and kept as a candidate witness for VorEdge.

#include <array>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "meshing/delaunay.h"
#include "meshing/surface_oracle.h"
#include "meshing/voronoi_geometry.h"

namespace delmesh {

//! The Voronoi edge of one Delaunay triangle and its intersections with Σ.
struct EdgeRecord {
  VoronoiEdge edge;
  std::vector<Vec3> crossings;   //!< all points of e ∩ Σ (certified, and zeros at Voronoi vertices)
  std::vector<Vec3> candidates;  //!< projected undecided regions (tangency candidates)
  std::size_t unresolved = 0;    //!< undecided regions whose projection failed or left the edge
  bool restricted = false;       //!< the triangle is in Tri S|Σ (with the §5.1 rule)
  Vec3 dual_point{};             //!< a counted point of e ∩ Σ when restricted
};

class RestrictedDelaunay {
 public:
  RestrictedDelaunay(const Delaunay& del, SurfaceOracle& oracle, std::uint64_t seed);

  //! The record of a current Delaunay triangle (computed on first use, then cached).
  const EdgeRecord& edge_record(const TriangleKey& t);
  //! The facet of a current Delaunay edge (computed on first use, then cached).
  const VoronoiFacet& facet(const EdgeKey& e);
  //! The seeded rotation of the frame of facet e (generic in-plane direction d = a).
  double facet_rotation(const EdgeKey& e) const;

  //! Forgets every cached record of a simplex all of whose vertices are in `vertices` (sorted),
  //! and of every simplex incident to a removed vertex.
  void invalidate(const std::vector<VertexId>& vertices);

  //! Restricted triangles incident to p (current Delaunay triangles only).
  std::vector<TriangleKey> star(VertexId p);
  //! All of Tri S|Σ, ascending.
  std::vector<TriangleKey> triangles();

  const Delaunay& delaunay() const { return del_; }
  SurfaceOracle& oracle() { return oracle_; }
  std::uint64_t seed() const { return seed_; }
  std::size_t unresolved() const { return unresolved_; }

 private:
  EdgeRecord compute(const TriangleKey& t);

  const Delaunay& del_;
  SurfaceOracle& oracle_;
  std::uint64_t seed_;
  std::map<TriangleKey, EdgeRecord> edges_;
  std::map<EdgeKey, VoronoiFacet> facets_;
  std::size_t unresolved_ = 0;
};

//! A deterministic pseudo-random number in [0, 1) from a seed and up to three integers
//! (splitmix64); used for every "generic" choice of the mesher.
double seeded_uniform(std::uint64_t seed, std::int64_t a, std::int64_t b = 0, std::int64_t c = 0);

}  // namespace delmesh
