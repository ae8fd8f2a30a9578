#pragma once
//! \file protecting_balls.h
//! Protecting balls on the sharp features of a triangle mesh (meshing/inputs/sharp_features.h): balls
//! centred on the corners and along the feature curves, sized so that the conditions below hold,
//! and a verifier for those conditions.  The balls are the weighted points a feature-preserving
//! refinement starts from; this module only places and verifies them.
//!
//! ## Source
//! The protection scheme is the one of Cheng, Dey and Ramos, *Delaunay refinement for piecewise
//! smooth complexes* (SODA 2007; DCG 43, 2010), made practical by Cheng, Dey and Levine, *A
//! practical Delaunay meshing algorithm for a large class of domains* (IMR 2007) and Dey and
//! Levine, *Delaunay meshing of piecewise smooth complexes without expensive predicates*
//! (Algorithms 2, 2009): every 0-face is protected by a ball, the balls centred on a 1-face
//! cover it, adjacent balls on a 1-face overlap without containing each other's centres, no
//! three balls have a common point, and the balls are small against the local feature size so
//! that each meets only the faces incident to its own feature.  Those papers assume the 1-faces
//! are smooth curves; a polyline of input edges is smooth between its vertices only, so a vertex
//! where the polyline turns by more than the feature angle (a *kink*: the directions of its two
//! feature edges differ by more than that angle, decided in double precision) is protected as a
//! 0-face too.  The start vertex of a closed curve without a corner is a 0-face as well (an
//! arbitrary but deterministic choice, sharp_features.h), so every curve is cut into *pieces*
//! from one *anchor* (corner, kink, or such a start) to the next.
//!
//! ## The conditions enforced (and checked by verify_protection)
//! Balls B(c, r) are closed.  Along a piece, the balls are ordered by the arc-length position of
//! their centres on the polyline (the anchors' balls at its two ends); two balls are *adjacent*
//! when they are consecutive on some piece.
//!  (A) Overlap and cover: adjacent balls B_i, B_j on a piece, whose centres are g apart along
//!      the polyline, satisfy g < r_i + r_j.  Since a point of the polyline at arc distance s
//!      from a centre lies within Euclidean distance s of it, the arc between the two centres
//!      lies in B_i ∪ B_j: the balls cover every curve, and adjacent balls intersect.
//!  (B) No centre in the other ball: adjacent balls satisfy |c_i − c_j| > max(r_i, r_j).
//!  (C) Non-adjacent balls are disjoint: |c_a − c_b| > r_a + r_b.  With (D), no three balls have a
//!      common point (three pairwise intersecting balls would be pairwise adjacent, and the
//!      adjacency graph has no triangle).
//!  (D) Counts: a piece between two different anchors holds at least one ball besides them, a
//!      piece from an anchor back to itself at least three.
//!  (E) Corner balls: the ball of an anchor contains no other anchor and meets no feature edge
//!      other than those of the pieces that end at it (distance from its centre to every other
//!      feature edge > r).
//!  (F) Curve balls: the ball of a point of a piece meets no feature edge of another piece (nor,
//!      by (B) and (C), any anchor).
//!  (G) Size: r ≤ size (the user's bound, when given) and r ≤ α · lfs(c) (α =
//!      ProtectionOptions::lfs_fraction, default 1/3), where the local feature size estimate
//!      lfs(c) is the distance from c to the nearest of: an input triangle with no vertex in
//!      N(c); a feature edge with no vertex in N(c), or (for a curve ball) on another piece; a
//!      corner without feature edges (an isolated folded vertex) other than c — where N(c) = {v}
//!      for c at a mesh vertex v and {p, q} for c inside an edge pq.  (The other anchors are ends
//!      of feature edges and count through them.)  (The true local feature size of a polyhedron is zero on its creases; this is
//!      the usual replacement: how close the input comes back to c from faces not incident to
//!      it.)  For a fine tessellation near a crease it is about one edge length.
//! (A), (B), (C) make the balls a chain along each curve in the sense of the papers above; (E)
//! and (F) are the condition that a ball meets only the features incident to its own.
//!
//! ## Tolerance
//! Arc lengths and distances are computed in double precision; every inequality above is checked
//! with a relative margin of ProtectionOptions::margin (default 1e-9: e.g. (A) as
//! g ≤ (1 − margin)(r_i + r_j), (C) as |c_a − c_b| ≥ (1 + margin)(r_a + r_b)), which exceeds the
//! rounding error of those computations by orders of magnitude for meshes within the input
//! limits (meshing/inputs/input_mesh.h).  A condition that holds only within the margin is a violation.
//!
//! ## Construction
//! Anchor balls get r = min(size, α·lfs); each piece is walked from its start: from a ball of
//! radius r at arc position s, the next centre is at s + max(r, r') + ½·min(r, r') with r' the
//! radius allowed there (shrunk until the radius allowed at the new centre is at least r'), which
//! gives (A) and, on straight stretches, (B); the last ball before the end anchor is centred
//! midway in the arc left outside its two neighbours, with a radius that reaches both.  Then
//! verify_protection runs; every ball involved in a violation halves the scale of its piece (all
//! radii allowed on it) or of its anchor, and the pieces are placed again, up to
//! ProtectionOptions::max_rounds times.  What then still fails is reported in the result (the
//! first violations, with their locations), never dropped.

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "meshing/core/surface_mesh.h"
#include "meshing/inputs/sharp_features.h"

namespace delmesh {

//! The parameters of protect_features.
struct ProtectionOptions {
  //! The user's size bound: no radius exceeds it (∞: none).  Precondition: > 0.
  double size = std::numeric_limits<double>::infinity();
  //! α of condition (G), in (0, ½) (½ would let two balls at their bounds touch).
  double lfs_fraction = 1.0 / 3.0;
  //! The relative margin of every inequality (file comment, Tolerance), in [0, 1e-3].
  double margin = 1e-9;
  //! The turning angle (degrees) above which a vertex inside a curve is a kink; in (0, 180).
  double kink_angle_deg = default_feature_angle_deg;
  //! Rounds of halving the scale of violating pieces and anchors.
  std::size_t max_rounds = 40;
  //! A placement stops once it holds this many balls (the last piece then fails (A) or (D)).
  std::size_t max_balls = 2000000;
};

//! One protecting ball.
struct ProtectingBall {
  enum class Kind { corner, kink, curve_start, curve };
  Point3 centre;
  double radius = 0;
  Kind kind = Kind::curve;
  //! For an anchor ball (corner, kink, curve_start): the vertex it is centred on.
  SurfaceMesh::Vertex_index vertex;
  //! For a curve ball: its piece (index into Protection::pieces) and arc-length position on it.
  std::size_t piece = 0;
  double arc = 0;
};

//! One piece of a curve between two anchors.
struct ProtectedPiece {
  std::size_t curve = 0;  //!< index into FeatureSet::curves
  //! The polyline of the piece (mesh vertices, first and last are anchors; equal for a loop).
  std::vector<SurfaceMesh::Vertex_index> vertices;
  std::vector<SurfaceMesh::Edge_index> edges;  //!< edges[i] joins vertices[i] and vertices[i + 1]
  //! The balls along the piece, from the start anchor's ball to the end anchor's ball.
  std::vector<std::size_t> balls;
  double length = 0;  //!< arc length
};

//! A condition that does not hold.
struct ProtectionViolation {
  char condition = 'A';  //!< 'A' … 'G' as in the file comment
  std::size_t ball = 0;  //!< the ball (and, for conditions between two balls, `other`)
  std::size_t other = 0;
  Point3 where;          //!< the centre of `ball`
  std::string message;   //!< one line: the condition, the balls, their centres and radii
};

//! The result of verify_protection.
struct ProtectionCheck {
  bool holds = true;
  std::size_t violations = 0;  //!< how many
  //! The first few violations (at most ProtectionCheck::listed), in the order found: conditions
  //! A/B/D per piece in piece order, then C over all pairs, then E, F, G per ball.
  std::vector<ProtectionViolation> first;
  static constexpr std::size_t listed = 10;
};

//! The balls protecting a feature set.
struct Protection {
  std::vector<ProtectingBall> balls;   //!< the anchors' balls first (ascending vertex), then the pieces'
  std::vector<ProtectedPiece> pieces;  //!< in curve order, each curve's pieces from its start
  std::size_t anchors = 0;             //!< balls[0, anchors) are the anchors' balls
  std::size_t kinks = 0;               //!< anchors of kind kink
  std::size_t rounds = 0;              //!< rounds of placement (1 when the first one held)
  ProtectionCheck check;               //!< verify_protection of the final placement
  double seconds = 0;
};

//! Places protecting balls on `features` of `mesh` (file comment, Construction) and verifies
//! them.  Preconditions: `features` is detect_features(mesh, …) of this mesh; options in their
//! ranges (throws PreconditionViolation otherwise).  A mesh without features gives no balls and
//! check.holds.  Never throws for geometry: a placement that still violates a condition after
//! max_rounds is returned with check.holds == false and the violations.
Protection protect_features(const SurfaceMesh& mesh, const FeatureSet& features,
                            const ProtectionOptions& options = {});

//! Checks conditions (A)–(G) of the file comment on `protection` for `mesh` and `features`, with
//! options.size, options.lfs_fraction and options.margin.  Exact up to the stated margin.
ProtectionCheck verify_protection(const SurfaceMesh& mesh, const FeatureSet& features,
                                  const Protection& protection, const ProtectionOptions& options = {});

}  // namespace delmesh
