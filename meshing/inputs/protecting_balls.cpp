// Protecting balls on the sharp features of a triangle mesh.  See protecting_balls.h.
#include "meshing/inputs/protecting_balls.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iterator>
#include <map>
#include <array>
#include <set>
#include <sstream>
#include <unordered_set>
#include <utility>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/box_intersection_d.h>

#include "common/errors.h"

namespace delmesh {

namespace {

using Vertex = SurfaceMesh::Vertex_index;
using Edge = SurfaceMesh::Edge_index;
using Face = SurfaceMesh::Face_index;
using Segment3 = Kernel::Segment_3;
using Kind = ProtectingBall::Kind;

using FacePrimitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using FaceTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, FacePrimitive>>;
using SegmentIterator = std::vector<Segment3>::const_iterator;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, SegmentIterator>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;


CGAL::Bbox_3 box_around(const Point3& c, double r) {
  return {c.x() - r, c.y() - r, c.z() - r, c.x() + r, c.y() + r, c.z() + r};
}

double distance(const Point3& a, const Point3& b) { return std::sqrt(CGAL::squared_distance(a, b)); }

std::string describe(const Point3& c, double r) {
  std::ostringstream s;
  s.precision(9);
  s << "centre (" << c.x() << ", " << c.y() << ", " << c.z() << ") radius " << r;
  return s.str();
}

//! The mesh's features prepared for distance queries: the feature edges as segments (with their
//! piece), the triangles, and the anchors.
class FeatureGeometry {
 public:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  FeatureGeometry(const SurfaceMesh& mesh, const FeatureSet& features, const ProtectionOptions& options)
      : mesh_(mesh), options_(options) {
    // Anchors: corners, kinks, starts of closed curves without corner.
    std::vector<std::pair<Vertex, Kind>> anchors;
    for (Vertex v : features.corners) anchors.emplace_back(v, Kind::corner);
    const double kink_cosine = std::cos(options.kink_angle_deg * M_PI / 180);
    for (const FeatureCurve& curve : features.curves) {
      if (curve.without_corner) anchors.emplace_back(curve.vertices.front(), Kind::curve_start);
      const std::size_t n = curve.vertices.size();
      for (std::size_t i = 1; i + 1 < n; ++i) {
        const Point3 &a = mesh.point(curve.vertices[i - 1]), &b = mesh.point(curve.vertices[i]),
                     &c = mesh.point(curve.vertices[i + 1]);
        const Vector3 u = b - a, w = c - b;
        if (u * w < kink_cosine * std::sqrt(u.squared_length() * w.squared_length()))
          anchors.emplace_back(curve.vertices[i], Kind::kink);
      }
    }
    std::sort(anchors.begin(), anchors.end());
    anchors.erase(std::unique(anchors.begin(), anchors.end(),
                              [](const auto& x, const auto& y) { return x.first == y.first; }),
                  anchors.end());
    for (const auto& [v, kind] : anchors) {
      anchor_index_.emplace(v, anchor_vertex_.size());
      anchor_vertex_.push_back(v);
      anchor_kind_.push_back(kind);
    }
    // Pieces: each curve cut at its anchors.
    for (std::size_t k = 0; k < features.curves.size(); ++k) {
      const FeatureCurve& curve = features.curves[k];
      ProtectedPiece piece;
      piece.curve = k;
      piece.vertices.push_back(curve.vertices.front());
      for (std::size_t i = 0; i < curve.edges.size(); ++i) {
        piece.edges.push_back(curve.edges[i]);
        piece.vertices.push_back(curve.vertices[i + 1]);
        if (is_anchor(curve.vertices[i + 1])) {
          pieces_.push_back(piece);
          piece.vertices.assign(1, curve.vertices[i + 1]);
          piece.edges.clear();
        }
      }
    }
    // Arc lengths, and the segments with their pieces.
    for (std::size_t p = 0; p < pieces_.size(); ++p) {
      ProtectedPiece& piece = pieces_[p];
      std::vector<double> cumulative{0};
      for (std::size_t i = 0; i < piece.edges.size(); ++i) {
        const Point3 &a = mesh.point(piece.vertices[i]), &b = mesh.point(piece.vertices[i + 1]);
        cumulative.push_back(cumulative.back() + distance(a, b));
        segments_.emplace_back(a, b);
        segment_piece_.push_back(p);
        segment_ends_.push_back({piece.vertices[i], piece.vertices[i + 1]});
      }
      piece.length = cumulative.back();
      cumulative_.push_back(std::move(cumulative));
    }
    anchor_pieces_.resize(anchor_vertex_.size());
    for (std::size_t p = 0; p < pieces_.size(); ++p) {
      anchor_pieces_[anchor_of(pieces_[p].vertices.front())].push_back(p);
      anchor_pieces_[anchor_of(pieces_[p].vertices.back())].push_back(p);
    }
    for (std::size_t a = 0; a < anchor_vertex_.size(); ++a)
      if (anchor_pieces_[a].empty()) isolated_anchors_.push_back(a);
    if (!segments_.empty()) {
      segment_tree_.insert(segments_.cbegin(), segments_.cend());
      segment_tree_.build();
    }
    face_tree_.insert(faces(mesh).first, faces(mesh).second, mesh);
    face_tree_.build();
    const CGAL::Bbox_3 box = CGAL::bbox_3(mesh.points().begin(), mesh.points().end());
    diagonal_ = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                          CGAL::square(box.zmax() - box.zmin()));
  }

  std::size_t anchors() const { return anchor_vertex_.size(); }
  const Point3& at_vertex(Vertex v) const { return mesh_.point(v); }
  Vertex anchor_vertex(std::size_t a) const { return anchor_vertex_[a]; }
  Kind anchor_kind(std::size_t a) const { return anchor_kind_[a]; }
  bool is_anchor(Vertex v) const { return anchor_index_.count(v) > 0; }
  std::size_t anchor_of(Vertex v) const { return anchor_index_.at(v); }
  const std::vector<std::size_t>& pieces_at(std::size_t a) const { return anchor_pieces_[a]; }
  const std::vector<ProtectedPiece>& pieces() const { return pieces_; }

  //! The point at arc position s of piece p, and N of protecting_balls.h (G).
  std::pair<Point3, std::vector<Vertex>> at(std::size_t p, double s) const {
    const ProtectedPiece& piece = pieces_[p];
    const std::vector<double>& cumulative = cumulative_[p];
    s = std::clamp(s, 0.0, piece.length);
    std::size_t k = static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), s) -
                                             cumulative.begin());
    k = std::min(k == 0 ? 0 : k - 1, piece.edges.size() - 1);
    if (s == cumulative[k]) return {mesh_.point(piece.vertices[k]), {piece.vertices[k]}};
    if (s == cumulative[k + 1]) return {mesh_.point(piece.vertices[k + 1]), {piece.vertices[k + 1]}};
    const double t = (s - cumulative[k]) / (cumulative[k + 1] - cumulative[k]);
    const Point3 &a = mesh_.point(piece.vertices[k]), &b = mesh_.point(piece.vertices[k + 1]);
    return {a + t * (b - a), {piece.vertices[k], piece.vertices[k + 1]}};
  }

  //! lfs(c) of protecting_balls.h (G), or `upper` when it is at least that.
  //! `piece`: the ball's piece (curve balls), or npos (anchor balls): the feature edges of other
  //! pieces count even when they have a vertex in N.
  double lfs(const Point3& c, const std::vector<Vertex>& near, std::size_t piece, double upper) const {
    const auto excluded = [&](Vertex v) { return std::find(near.begin(), near.end(), v) != near.end(); };
    double best = upper;
    for (std::size_t a : isolated_anchors_)
      if (!excluded(anchor_vertex_[a])) best = std::min(best, distance(c, mesh_.point(anchor_vertex_[a])));
    double reach = std::max(std::min(best, diagonal_ * 1e-3), std::numeric_limits<double>::min());
    std::vector<FacePrimitive::Id> faces;
    std::vector<SegmentPrimitive::Id> segments;
    while (true) {
      const CGAL::Bbox_3 box = box_around(c, reach);
      faces.clear();
      face_tree_.all_intersected_primitives(box, std::back_inserter(faces));
      for (Face f : faces) {
        bool incident = false;
        for (Vertex v : CGAL::vertices_around_face(mesh_.halfedge(f), mesh_)) incident = incident || excluded(v);
        if (incident) continue;
        const auto h = mesh_.halfedge(f);
        const Kernel::Triangle_3 t(mesh_.point(mesh_.source(h)), mesh_.point(mesh_.target(h)),
                                   mesh_.point(mesh_.target(mesh_.next(h))));
        best = std::min(best, std::sqrt(CGAL::squared_distance(c, t)));
      }
      if (!segments_.empty()) {
        segments.clear();
        segment_tree_.all_intersected_primitives(box, std::back_inserter(segments));
        for (SegmentIterator it : segments) {
          const std::size_t k = static_cast<std::size_t>(it - segments_.cbegin());
          const auto& ends = segment_ends_[k];
          if ((excluded(ends[0]) || excluded(ends[1])) && (piece == npos || segment_piece_[k] == piece)) continue;
          best = std::min(best, std::sqrt(CGAL::squared_distance(c, *it)));
        }
      }
      if (best <= reach || reach >= upper) return best;
      reach *= 4;
    }
  }

  //! Calls f(piece of the segment, distance) for every feature segment within `reach` of c
  //! (a superset: those whose bounding box meets c's box).
  void segments_near(const Point3& c, double reach, const std::function<void(std::size_t, double)>& f) const {
    if (segments_.empty()) return;
    std::vector<SegmentPrimitive::Id> found;
    segment_tree_.all_intersected_primitives(box_around(c, reach), std::back_inserter(found));
    for (SegmentIterator it : found)
      f(segment_piece_[static_cast<std::size_t>(it - segments_.cbegin())], std::sqrt(CGAL::squared_distance(c, *it)));
  }

  //! The radius allowed at c by (G), before any scale.
  double allowed(const Point3& c, const std::vector<Vertex>& near, std::size_t piece = npos) const {
    const double upper = std::isfinite(options_.size) ? options_.size / options_.lfs_fraction : 2 * diagonal_;
    return std::min(options_.size, options_.lfs_fraction * lfs(c, near, piece, upper));
  }

 private:
  const SurfaceMesh& mesh_;
  const ProtectionOptions& options_;
  std::vector<Vertex> anchor_vertex_;
  std::vector<Kind> anchor_kind_;
  std::map<Vertex, std::size_t> anchor_index_;
  std::vector<std::vector<std::size_t>> anchor_pieces_;
  std::vector<std::size_t> isolated_anchors_;
  std::vector<ProtectedPiece> pieces_;
  std::vector<std::vector<double>> cumulative_;
  std::vector<Segment3> segments_;
  std::vector<std::size_t> segment_piece_;
  std::vector<std::array<Vertex, 2>> segment_ends_;
  SegmentTree segment_tree_;
  FaceTree face_tree_;
  double diagonal_ = 0;
};

void require_options(const ProtectionOptions& o) {
  if (!(o.size > 0)) throw PreconditionViolation("protect_features: the size bound must be > 0");
  if (!(o.lfs_fraction > 0 && o.lfs_fraction < 0.5))
    throw PreconditionViolation("protect_features: lfs_fraction must lie in (0, 1/2)");
  if (!(o.margin >= 0 && o.margin <= 1e-3)) throw PreconditionViolation("protect_features: margin must lie in [0, 1e-3]");
  if (!(o.kink_angle_deg > 0 && o.kink_angle_deg < 180))
    throw PreconditionViolation("protect_features: the kink angle must lie in (0, 180) degrees");
}

//! What a violation involves: its condition and its balls.
using Report = std::function<void(char condition, std::size_t ball, std::size_t other, const std::string& message)>;

//! Checks (A)–(G); calls `report` for each violation.
void check_all(const FeatureGeometry& geometry, const Protection& protection, const ProtectionOptions& options,
               const Report& report) {
  const double m = options.margin;
  const auto& balls = protection.balls;
  const auto name = [&](std::size_t i) {
    const ProtectingBall& b = balls[i];
    return "ball " + std::to_string(i) + " (" + describe(b.centre, b.radius) + ")";
  };
  std::unordered_set<std::uint64_t> adjacent;
  const auto key = [](std::size_t a, std::size_t b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
  };
  for (std::size_t p = 0; p < protection.pieces.size(); ++p) {
    const ProtectedPiece& piece = protection.pieces[p];
    const bool loop = piece.vertices.front() == piece.vertices.back();
    const std::size_t inner = piece.balls.size() >= 2 ? piece.balls.size() - 2 : 0;
    if (inner < (loop ? 3u : 1u))
      report('D', piece.balls.front(), piece.balls.back(),
             "(D) a piece of curve " + std::to_string(piece.curve) + " holds " + std::to_string(inner) +
                 " balls between its anchors, fewer than " + (loop ? "3" : "1") + ", at " + name(piece.balls.front()));
    const auto arc = [&](std::size_t k) {
      if (k == 0) return 0.0;
      if (k + 1 == piece.balls.size()) return piece.length;
      return balls[piece.balls[k]].arc;
    };
    for (std::size_t k = 0; k + 1 < piece.balls.size(); ++k) {
      const std::size_t i = piece.balls[k], j = piece.balls[k + 1];
      adjacent.insert(key(i, j));
      const double g = arc(k + 1) - arc(k), ri = balls[i].radius, rj = balls[j].radius;
      if (!(g <= (1 - m) * (ri + rj)))
        report('A', i, j, "(A) adjacent balls do not overlap along the curve: arc gap " + std::to_string(g) + " between " +
                              name(i) + " and " + name(j));
      if (!(distance(balls[i].centre, balls[j].centre) >= (1 + m) * std::max(ri, rj)))
        report('B', i, j, "(B) adjacent balls contain each other's centre: " + name(i) + " and " + name(j));
    }
  }
  // (C) and the anchor part of (E), over the pairs whose boxes meet.
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
  std::vector<Box> boxes;
  boxes.reserve(balls.size());
  for (std::size_t i = 0; i < balls.size(); ++i)
    boxes.emplace_back(box_around(balls[i].centre, balls[i].radius * (1 + 2 * m) + 1e-300), i);
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    const std::size_t a = std::min(x.info(), y.info()), b = std::max(x.info(), y.info());
    const double d = distance(balls[a].centre, balls[b].centre);
    if (!adjacent.count(key(a, b)) && !(d >= (1 + m) * (balls[a].radius + balls[b].radius)))
      report('C', a, b, "(C) non-adjacent balls meet: " + name(a) + " and " + name(b));
    if (a < protection.anchors && b < protection.anchors && !(d >= (1 + m) * std::max(balls[a].radius, balls[b].radius)))
      report('E', a, b, "(E) an anchor's ball contains another anchor: " + name(a) + " and " + name(b));
  });
  // (E), (F): the feature edges a ball meets; (G) its size.
  for (std::size_t i = 0; i < balls.size(); ++i) {
    const ProtectingBall& b = balls[i];
    std::vector<std::size_t> allowed_pieces;
    std::vector<Vertex> near;
    Point3 c = b.centre;
    if (i < protection.anchors) {
      allowed_pieces = geometry.pieces_at(geometry.anchor_of(b.vertex));
      near = {b.vertex};
    } else {
      allowed_pieces = {b.piece};
      near = geometry.at(b.piece, b.arc).second;
    }
    bool met = false;
    geometry.segments_near(c, b.radius * (1 + m), [&](std::size_t piece, double d) {
      if (met || d >= (1 + m) * b.radius) return;
      if (std::find(allowed_pieces.begin(), allowed_pieces.end(), piece) != allowed_pieces.end()) return;
      met = true;
      report(i < protection.anchors ? 'E' : 'F', i, i,
             std::string(i < protection.anchors ? "(E) an anchor's" : "(F) a curve's") + " ball meets a feature edge of "
             "another piece: " + name(i));
    });
    if (!(b.radius <= options.size * (1 + m)))
      report('G', i, i, "(G) the radius exceeds the size bound: " + name(i));
    else if (!(b.radius <= (1 + m) * geometry.allowed(c, near, i < protection.anchors ? FeatureGeometry::npos : b.piece)))
      report('G', i, i, "(G) the radius exceeds lfs_fraction times the local feature size: " + name(i));
  }
}

//! One placement at the given scales (protecting_balls.h, Construction).
Protection place(const FeatureGeometry& geometry, const std::vector<double>& piece_scale,
                 const std::vector<double>& anchor_scale, const ProtectionOptions& options) {
  const double m = options.margin;
  Protection protection;
  protection.pieces = geometry.pieces();
  protection.anchors = geometry.anchors();
  for (std::size_t a = 0; a < geometry.anchors(); ++a) {
    ProtectingBall ball;
    ball.vertex = geometry.anchor_vertex(a);
    ball.kind = geometry.anchor_kind(a);
    protection.kinks += ball.kind == Kind::kink;
    ball.centre = geometry.at_vertex(ball.vertex);
    ball.radius = anchor_scale[a] * geometry.allowed(ball.centre, {ball.vertex});
    protection.balls.push_back(ball);
  }
  for (std::size_t p = 0; p < protection.pieces.size(); ++p) {
    ProtectedPiece& piece = protection.pieces[p];
    const std::size_t start = geometry.anchor_of(piece.vertices.front()), end = geometry.anchor_of(piece.vertices.back());
    const bool loop = start == end;
    const std::size_t wanted = loop ? 3 : 1;
    const double length = piece.length;
    const Point3 end_centre = protection.balls[end].centre;
    const double end_radius = protection.balls[end].radius;
    const auto radius_at = [&](double s) {
      const auto [c, near] = geometry.at(p, s);
      return piece_scale[p] * geometry.allowed(c, near, p);
    };
    piece.balls.push_back(start);
    double s = 0, r = protection.balls[start].radius;
    std::size_t placed = 0;
    const auto add = [&](double t, double radius) {
      ProtectingBall ball;
      ball.kind = Kind::curve;
      ball.piece = p;
      ball.arc = t;
      ball.centre = geometry.at(p, t).first;
      ball.radius = radius;
      piece.balls.push_back(protection.balls.size());
      protection.balls.push_back(ball);
      ++placed;
    };
    while (protection.balls.size() < options.max_balls) {
      const Point3 here = geometry.at(p, s).first;
      if (placed >= wanted && length - s <= (1 - m) * (r + end_radius) &&
          distance(here, end_centre) >= (1 + m) * std::max(r, end_radius))
        break;
      const double free = length - s - r - end_radius;  // arc left outside this ball and the end's
      if (!(free > 0)) break;                             // cannot be finished: left to verification
      // The next centre t and its radius: shrink the radius until the one allowed at t is at least it.
      double next = radius_at(s + 1.5 * r), t = s;
      for (int step = 0; step < 12; ++step) {
        t = s + std::max(r, next) + 0.5 * std::min(r, next);
        const double there = radius_at(t);
        if (there >= next) break;
        next = there;
      }
      if (t + 0.5 * next >= length - end_radius) {
        // The last ball: midway in the free arc, overlapping both neighbours.
        const double middle = s + r + 0.5 * free;
        add(middle, std::min(radius_at(middle), 0.5 * free + 0.5 * std::min(r, end_radius)));
        if (placed >= wanted) break;
        s = middle;
        r = protection.balls.back().radius;
        continue;
      }
      add(t, next);
      s = t;
      r = next;
    }
    piece.balls.push_back(end);
  }
  return protection;
}

}  // namespace

Protection protect_features(const SurfaceMesh& mesh, const FeatureSet& features, const ProtectionOptions& options) {
  require_options(options);
  const auto started = std::chrono::steady_clock::now();
  const FeatureGeometry geometry(mesh, features, options);
  std::vector<double> piece_scale(geometry.pieces().size(), 1.0), anchor_scale(geometry.anchors(), 1.0);
  Protection protection;
  for (std::size_t round = 1;; ++round) {
    protection = place(geometry, piece_scale, anchor_scale, options);
    protection.rounds = round;
    std::set<std::size_t> halve_pieces, halve_anchors;
    ProtectionCheck& check = protection.check;
    check_all(geometry, protection, options, [&](char condition, std::size_t a, std::size_t b, const std::string& message) {
      check.holds = false;
      if (check.violations++ < ProtectionCheck::listed)
        check.first.push_back({condition, a, b, protection.balls[a].centre, message});
      for (std::size_t i : {a, b}) {
        if (i < protection.anchors) {
          halve_anchors.insert(i);
          for (std::size_t p : geometry.pieces_at(i)) halve_pieces.insert(p);
        } else {
          halve_pieces.insert(protection.balls[i].piece);
        }
      }
    });
    if (check.holds || round >= options.max_rounds || protection.balls.size() >= options.max_balls) break;
    for (std::size_t p : halve_pieces) piece_scale[p] *= 0.5;
    for (std::size_t a : halve_anchors) anchor_scale[a] *= 0.5;
  }
  protection.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return protection;
}

ProtectionCheck verify_protection(const SurfaceMesh& mesh, const FeatureSet& features, const Protection& protection,
                                  const ProtectionOptions& options) {
  require_options(options);
  const FeatureGeometry geometry(mesh, features, options);
  ProtectionCheck check;
  if (protection.anchors != geometry.anchors() || protection.pieces.size() != geometry.pieces().size())
    throw PreconditionViolation("verify_protection: the protection was not placed on these features");
  check_all(geometry, protection, options, [&](char condition, std::size_t a, std::size_t b, const std::string& message) {
    check.holds = false;
    if (check.violations++ < ProtectionCheck::listed)
      check.first.push_back({condition, a, b, protection.balls[a].centre, message});
  });
  return check;
}

}  // namespace delmesh
