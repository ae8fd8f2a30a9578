// The gradient-flow isotopy certificate: the steps of the proof in gradient_flow_certificate.h.
//  1. read the soup; check that it is a closed orientable 2-manifold and orient each component;
//  2. on every triangle, by pieces: a bound of |E| (giving ε) and the sign of ⟨∇E, n⟩ (d);
//  3. (a) |E| > ε′ on the faces of B and (b) |∇E| ≥ G on T, by subdivision;
//  4. (e) the critical points of a height function on Σ and one counting path along the flow through each;
//  5. the Hausdorff bound ε/G and the per-triangle bounds.
// Steps 2–5 run with the flow of E, and again with that of the normalised function F when a
// condition that depends on the function was not proved with E; then once more with F and the
// one-sided tube if F's flow did not prove such a condition either.
#include "meshing/verify/gradient_flow_certificate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include <ginac/ginac.h>

#include "common/errors.h"
#include "common/run_limits.h"
#include "common/seeded_uniform.h"
#include "common/tolerances.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/inputs/detail/flow_enclosure.h"
#include "meshing/inputs/flow_distance.h"
#include "meshing/inputs/implicit_oracle.h"
#include "meshing/inputs/input_validation.h"
#include "meshing/inputs/seed_solve.h"
#include "solvers/domain.h"
#include "symbolic/compiled_system.h"
#include "symbolic/scalar_traits.h"

namespace delmesh {

namespace {

using Clock = std::chrono::steady_clock;
using detail::centre_of;
using detail::Enclosure;
using detail::finite;
using detail::IBox;
using detail::interval_point;
using detail::magnitude;
using detail::P3;
using detail::width_of;

//! Thrown inside the certificate when the interrupt flag or the deadline is seen.
struct Stopped {};

//! A condition that could not be proved, or a refutation: ends the certificate with `status`.
struct Verdict {
  FlowCertificateStatus status;
  std::string reason;
  std::optional<P3> location;
  //! False for what does not depend on the function whose flow is used: the seed solve on Σ and
  //! the crossing count (a topological invariant of M and Σ).
  bool depends_on_function = true;
  //! False for what does not depend on the tube: the transversality of the triangles.
  bool depends_on_tube = true;
};

IBox interval_point(const Point3& p) { return {Interval(p.x()), Interval(p.y()), Interval(p.z())}; }

//! T = {lower ≤ E ≤ upper}, lower < 0 < upper.
struct Tube {
  double lower, upper;
  //! The interval lies above or below T (proved).
  bool outside(const Interval& v) const { return finite(v) && (v.inf() > upper || v.sup() < lower); }
  //! The interval lies in T (proved).
  bool holds(const Interval& v) const { return finite(v) && v.inf() >= lower && v.sup() <= upper; }
  std::string text() const;
};

//! The certificate's state: the system, the limits, the counters.
class FlowProof {
 public:
  //! `function`'s flow, in B = `box`: at most `round_budget` more boxes than out.boxes holds now
  //! (counted in out.boxes), in up to `rounds` rounds of that many (see next_box).
  FlowProof(const Surface& function, const Box3& box, const FlowCertificateOptions& options, FlowCertificate& out,
            std::size_t round_budget, std::size_t rounds)
      : distance_(function),
        box_(box),
        options_(options),
        out_(out),
        round_budget_(round_budget),
        box_limit_(out.boxes + round_budget),
        max_rounds_(rounds) {
    for (int k = 0; k < 3; ++k) domain_width_ = std::max(domain_width_, box.hi[k] - box.lo[k]);
  }

  const CompiledSystem& system() const { return distance_.system(); }
  const FlowDistance& distance() const { return distance_; }
  //! The rounds of the box budget begun so far.
  std::size_t rounds() const { return rounds_; }

  //! The function is 2^−k E / sqrt(|∇E|² + η²) for the E of `system_of_E` (which must outlive
  //! this), k its Surface's normalization_exponent(): the tube proofs also use
  //! detail::NormalizedEnclosure from E's enclosures, scaled by 2^−k (exactly).
  void compose_from(const CompiledSystem& system_of_E, double eta, int normalization_exponent) {
    system_of_E_ = &system_of_E;
    eta_ = eta;
    scale_ = std::ldexp(1.0, -normalization_exponent);
  }

  //! Throws Stopped once the interrupt flag or the deadline is seen.
  void poll() const {
    if (options_.interrupt && options_.interrupt->load(std::memory_order_relaxed)) {
      out_.interrupted = true;
      throw Stopped{};
    }
    if (options_.deadline && ++polls_ % 64 == 0 && Clock::now() >= *options_.deadline) {
      out_.time_limited = true;
      throw Stopped{};
    }
  }

  //! Records a value E takes on the mesh (up to rounding): largest_value_met() estimates max |E|
  //! over M from below, least_value_met() and greatest_value_met() min E and max E (each 0 at
  //! least), and the pieces' bounds are refined towards them.
  void met_value(double e) {
    if (!std::isfinite(e)) return;
    largest_value_met_ = std::max(largest_value_met_, std::abs(e));
    least_value_met_ = std::min(least_value_met_, e);
    greatest_value_met_ = std::max(greatest_value_met_, e);
  }
  double largest_value_met() const { return largest_value_met_; }
  double least_value_met() const { return least_value_met_; }
  double greatest_value_met() const { return greatest_value_met_; }

  //! The tube is {a ≤ E ≤ b} with a and b from min E and max E on M separately (file comment, "The
  //! one-sided tube"), instead of ±ε′.
  void make_one_sided() { one_sided_ = true; }
  bool one_sided() const { return one_sided_; }

  //! (a): E ∉ [lower, upper] on every face of B, by subdividing each face (flat boxes).
  void prove_faces(const Tube& tube) {
    const double min_width = tolerances::flow_min_box_relative_width * domain_width_;
    const std::string failure = "the tube " + tube.text() + " may reach the boundary of the box";
    for (int axis = 0; axis < 3; ++axis)
      for (double fixed : {box_.lo[axis], box_.hi[axis]}) {
        std::array<double, 6> face{box_.lo[0], box_.hi[0], box_.lo[1], box_.hi[1], box_.lo[2], box_.hi[2]};
        face[2 * axis] = face[2 * axis + 1] = fixed;
        std::vector<std::array<double, 6>> stack{face};
        begin_stack(stack);
        while (!stack.empty()) {
          const auto b = next_box(stack);
          if (examine(interval_box(b), tube, nullptr).outside_tube) continue;
          split_or_fail(b, stack, min_width, failure);
        }
      }
  }

  //! (b): |∇E| ≥ G on T; returns G.  A box meeting T is kept once its lower bound
  //! ℓ > 0 reaches tolerances::flow_gradient_quality times the smaller of |∇E| at its centre and
  //! `reference`, the least |∇E| met so far at points of T (M's vertices, then the centres of
  //! boxes with E(c) ∈ T proved): where |∇E| is well above its least value on T, a
  //! looser ℓ does not lower G.
  double prove_gradient(const Tube& tube, double reference) {
    const double min_width = tolerances::flow_min_box_relative_width * domain_width_;
    const std::string failure = "the gradient of E may vanish in the tube " + tube.text();
    double least = std::numeric_limits<double>::infinity();
    std::vector<std::array<double, 6>> stack{{box_.lo[0], box_.hi[0], box_.lo[1], box_.hi[1], box_.lo[2], box_.hi[2]}};
    begin_stack(stack);
    while (!stack.empty()) {
      const auto b = next_box(stack);
      const IBox x = interval_box(b);
      const BoxFacts f = examine(x, tube, &reference);
      if (f.outside_tube) continue;
      if (f.bound > 0 && (f.bound >= f.wanted || width_of(x) < min_width)) {
        least = std::min(least, f.bound);
        continue;
      }
      split_or_fail(b, stack, min_width, failure);
    }
    return least;
  }

  static std::string text(double x) {
    std::ostringstream s;
    s.precision(3);
    s << x;
    return s.str();
  }

 private:
  //! What one box of B gave.
  struct BoxFacts {
    bool outside_tube = false;  //!< the box lies outside T, proved
    double bound = 0;           //!< a lower bound of |∇function| on the box (0: none)
    double wanted = 0;          //!< the bound that keeps the box (prove_gradient)
  };

  //! The enclosures of one box: whether it lies outside the tube and, unless it does or
  //! `reference` is null, a lower bound of the gradient's length, with `reference` lowered to
  //! |∇function| at the centre when the function is proved within the tube there.  With
  //! compose_from, the composed enclosures come first and the function's own (natural and
  //! mean-value forms of its symbolic derivatives) only when those do not decide the box; where
  //! both are computed the bounds are met.
  BoxFacts examine(const IBox& x, const Tube& tube, double* reference) const {
    BoxFacts f;
    RoundingGuard guard;
    const auto outside = [&tube](const Interval& v) { return tube.outside(v); };
    const auto within = [&tube](const Interval& v) { return tube.holds(v); };
    const auto wanted = [&](double at_centre, const Interval& at_centre_value) {
      if (within(at_centre_value) && at_centre > 0 && at_centre < *reference) *reference = at_centre;
      return tolerances::flow_gradient_quality * std::min(at_centre, *reference);
    };
    Interval value = Interval::largest();
    bool have_wanted = false;
    if (system_of_E_) {
      const detail::NormalizedEnclosure composed(*system_of_E_, x, eta_);
      const Interval scale(scale_);
      value = composed.value() * scale;
      if (outside(value)) {
        f.outside_tube = true;
        return f;
      }
      if (reference && composed.usable) {
        const P3 g = composed.centre_gradient(*system_of_E_);
        f.wanted = wanted(scale_ * std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]), composed.value_at_centre() * scale);
        have_wanted = true;
        f.bound = scale_ * detail::gradient_lower_bound(composed, g, f.wanted / scale_);
        if (f.bound > 0 && f.bound >= f.wanted) return f;
      }
    }
    const Enclosure own(system(), x);
    f.outside_tube = outside(detail::meet(value, own.value()));
    if (f.outside_tube || !reference) return f;
    if (!have_wanted) {
      const double at_centre = std::sqrt(magnitude(own.vc[1]) * magnitude(own.vc[1]) +
                                         magnitude(own.vc[2]) * magnitude(own.vc[2]) +
                                         magnitude(own.vc[3]) * magnitude(own.vc[3]));
      f.wanted = wanted(at_centre, own.vc[0]);
    }
    f.bound = std::max(f.bound, detail::gradient_lower_bound(own, f.wanted));
    return f;
  }

  //! The measure of a box of a stack: the product of its sides of positive length (the faces'
  //! boxes are flat).
  static double measure(const std::array<double, 6>& b) {
    double m = 1;
    for (int k = 0; k < 3; ++k)
      if (b[2 * k + 1] > b[2 * k]) m *= b[2 * k + 1] - b[2 * k];
    return m;
  }

  //! A new subdivision starts: its unexplored measure is the root's.
  void begin_stack(const std::vector<std::array<double, 6>>& stack) {
    unexplored_before_ = 0;
    for (const auto& b : stack) unexplored_before_ += measure(b);
  }

  //! Takes the next box (lo, hi per axis) off the stack, after the limits and the budget.  When a
  //! round of the budget is used up, another begins if fewer than the allowed rounds have begun
  //! and the stack's unexplored measure is below what it was when the round began (or when this
  //! subdivision began, if that was later); otherwise the budget has run out (undecided).
  std::array<double, 6> next_box(std::vector<std::array<double, 6>>& stack) {
    poll();
    if (++out_.boxes > box_limit_) {
      double unexplored = 0;
      for (const auto& b : stack) unexplored += measure(b);
      if (rounds_ < max_rounds_ && unexplored < unexplored_before_) {
        ++rounds_;
        box_limit_ += round_budget_;
        unexplored_before_ = unexplored;
      } else {
        throw Verdict{FlowCertificateStatus::undecided,
                      "the budget of " + std::to_string(rounds_) + " x " + std::to_string(round_budget_) +
                          " boxes of the tube proofs ran out" +
                          (rounds_ < max_rounds_ ? " (the last round left no less unexplored volume)" : ""),
                      std::nullopt};
      }
    }
    const auto b = stack.back();
    stack.pop_back();
    return b;
  }

  static IBox interval_box(const std::array<double, 6>& b) {
    return {Interval(b[0], b[1]), Interval(b[2], b[3]), Interval(b[4], b[5])};
  }

  //! Bisects the widest side of b onto the stack, or throws the verdict `failure` (undecided)
  //! located at b's centre once b is narrower than min_width.
  void split_or_fail(const std::array<double, 6>& b, std::vector<std::array<double, 6>>& stack, double min_width,
                     const std::string& failure) {
    int side = 0;
    for (int k = 1; k < 3; ++k)
      if (b[2 * k + 1] - b[2 * k] > b[2 * side + 1] - b[2 * side]) side = k;
    const double lo = b[2 * side], hi = b[2 * side + 1], split = 0.5 * (lo + hi);
    if (hi - lo < min_width || !(split > lo && split < hi)) {
      const P3 at{0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])};
      throw Verdict{FlowCertificateStatus::undecided, failure, at};
    }
    auto lower = b, upper = b;
    lower[2 * side + 1] = split;
    upper[2 * side] = split;
    stack.push_back(upper);
    stack.push_back(lower);
  }

  FlowDistance distance_;
  Box3 box_;
  const FlowCertificateOptions& options_;
  FlowCertificate& out_;
  double domain_width_ = 0;
  double largest_value_met_ = 0, least_value_met_ = 0, greatest_value_met_ = 0;
  bool one_sided_ = false;
  const CompiledSystem* system_of_E_ = nullptr;
  double eta_ = 0, scale_ = 1;
  std::size_t round_budget_;
  std::size_t box_limit_;
  std::size_t max_rounds_;
  std::size_t rounds_ = 1;
  double unexplored_before_ = 0;
  mutable std::uint32_t polls_ = 0;
};

std::string Tube::text() const {
  if (lower == -upper) return "|E| <= " + FlowProof::text(upper);
  return FlowProof::text(lower) + " <= E <= " + FlowProof::text(upper);
}

// ---- 1. the soup ----

//! Checks the indices and coordinates (InvalidInput as certificate.h's certify_mesh).
void check_soup(const std::vector<Point3>& points, const std::vector<std::array<std::size_t, 3>>& triangles) {
  if (triangles.empty()) throw InvalidInput("the mesh has no triangle to certify");
  for (const auto& t : triangles) {
    for (std::size_t i : t)
      if (i >= points.size())
        throw InvalidInput("a triangle refers to vertex " + std::to_string(i) + " of " + std::to_string(points.size()));
    if (t[0] == t[1] || t[0] == t[2] || t[1] == t[2]) throw InvalidInput("a triangle repeats a vertex index");
    for (std::size_t i : t) {
      const Point3& p = points[i];
      if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())))
        throw InvalidInput("vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
}

//! Consistent orientations of a closed orientable 2-manifold soup: flip[t] = ±1 so that across
//! every edge the two triangles, t reversed where flip[t] = −1, run through it in opposite
//! directions; and the component of each triangle.
struct Orientation {
  std::vector<int> flip;
  std::vector<std::size_t> component;
  std::size_t components = 0;
};

Orientation orient(const std::vector<std::array<std::size_t, 3>>& triangles) {
  // Each directed edge a → b of each triangle, by its undirected key.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<std::size_t, bool>>> edges;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      edges[std::minmax(a, b)].push_back({t, a < b});
    }
  Orientation o;
  o.flip.assign(triangles.size(), 0);
  o.component.assign(triangles.size(), 0);
  std::vector<std::size_t> stack;
  for (std::size_t root = 0; root < triangles.size(); ++root) {
    if (o.flip[root] != 0) continue;
    o.flip[root] = 1;
    o.component[root] = o.components;
    stack.push_back(root);
    while (!stack.empty()) {
      const std::size_t t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const std::size_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
        const bool forward = a < b;
        for (const auto& [u, u_forward] : edges[std::minmax(a, b)]) {
          if (u == t) continue;
          // Consistent: u runs through the edge the other way, after both flips.
          const int want = forward != u_forward ? o.flip[t] : -o.flip[t];
          if (o.flip[u] == 0) {
            o.flip[u] = want;
            o.component[u] = o.components;
            stack.push_back(u);
          }
        }
      }
    }
    ++o.components;
  }
  return o;
}

// ---- 2. the triangles ----

//! What one triangle gave: the bound of |E| on it, bounds of min E and max E, and the sign of its
//! flux (0: undecided).
struct TriangleProof {
  double e_bound = 0;
  double lower = 0, upper = 0;
  int sign = 0;
  P3 undecided_at{};
};

TriangleProof prove_triangle(FlowProof& proof, const Point3& a, const Point3& b, const Point3& c,
                             std::size_t& pieces) {
  TriangleProof out;
  RoundingGuard guard;
  const detail::EnclosedTriangle triangle(P3{a.x(), a.y(), a.z()}, P3{b.x(), b.y(), b.z()}, P3{c.x(), c.y(), c.z()});
  std::vector<detail::TrianglePiece> stack{detail::TrianglePiece{}};
  while (!stack.empty()) {
    proof.poll();
    const detail::TrianglePiece piece = stack.back();
    stack.pop_back();
    ++pieces;
    std::array<IBox, 3> corner;
    IBox x;
    triangle.corners(piece, corner, x);
    const Enclosure en(proof.system(), x);
    const Interval e = en.value_on_hull(corner);
    const Interval flux = en.directional(triangle.normal());
    const int sign = certainly_nonzero(flux) && finite(flux) ? (flux.inf() > 0 ? 1 : -1) : 0;
    proof.met_value(detail::centroid_value(proof.system(), corner));
    const double slack = tolerances::flow_epsilon_slack;
    const bool tight =
        piece.depth >= tolerances::flow_triangle_max_depth ||
        (proof.one_sided() ? e.sup() <= slack * proof.greatest_value_met() && e.inf() >= slack * proof.least_value_met()
                           : magnitude(e) <= slack * proof.largest_value_met());
    const bool consistent = sign != 0 && (out.sign == 0 || out.sign == sign);
    if (consistent && tight) {
      out.sign = sign;
      out.e_bound = std::max(out.e_bound, magnitude(e));
      out.lower = std::min(out.lower, finite(e) ? e.inf() : -std::numeric_limits<double>::infinity());
      out.upper = std::max(out.upper, finite(e) ? e.sup() : std::numeric_limits<double>::infinity());
      continue;
    }
    if ((sign == 0 || consistent) && piece.depth < tolerances::flow_triangle_max_depth) {
      for (const detail::TrianglePiece& child : piece.children()) stack.push_back(child);
      continue;
    }
    // Undecided at the depth limit, or pieces of opposite proved signs (the flux vanishes between).
    out.sign = 0;
    out.undecided_at = en.c;
    return out;
  }
  return out;
}

// ---- 4. the counting paths ----

//! The algebraic number of crossings of the segment pq with the positively oriented triangles,
//! or nothing if the segment passes through an edge or a vertex of one (or lies in its plane),
//! or if an end that may lie on M (p unless p_off_mesh, q unless q_off_mesh) lies in the plane of
//! a triangle near the segment.  An end off M (|E| > ε′ there) in a triangle's plane is not in
//! the triangle.
std::optional<int> crossings(const Point3& p, const Point3& q, bool p_off_mesh, bool q_off_mesh,
                             const std::vector<Point3>& points, const std::vector<std::array<std::size_t, 3>>& oriented) {
  const CGAL::Bbox_3 segment = p.bbox() + q.bbox();
  int count = 0;
  for (const auto& t : oriented) {
    const Point3 &a = points[t[0]], &b = points[t[1]], &c = points[t[2]];
    if (!CGAL::do_overlap(segment, a.bbox() + b.bbox() + c.bbox())) continue;
    const CGAL::Orientation op = CGAL::orientation(a, b, c, p), oq = CGAL::orientation(a, b, c, q);
    if (op == CGAL::COPLANAR && oq == CGAL::COPLANAR) return std::nullopt;
    if ((op == CGAL::COPLANAR && !p_off_mesh) || (oq == CGAL::COPLANAR && !q_off_mesh)) return std::nullopt;
    if (op == oq || op == CGAL::COPLANAR || oq == CGAL::COPLANAR) continue;
    const CGAL::Orientation s[3] = {CGAL::orientation(p, q, a, b), CGAL::orientation(p, q, b, c),
                                    CGAL::orientation(p, q, c, a)};
    const bool positive = s[0] == CGAL::POSITIVE || s[1] == CGAL::POSITIVE || s[2] == CGAL::POSITIVE;
    const bool negative = s[0] == CGAL::NEGATIVE || s[1] == CGAL::NEGATIVE || s[2] == CGAL::NEGATIVE;
    if (positive && negative) continue;  // the line misses the triangle
    if (s[0] == CGAL::COPLANAR || s[1] == CGAL::COPLANAR || s[2] == CGAL::COPLANAR) return std::nullopt;
    count += op == CGAL::NEGATIVE ? 1 : -1;  // from the back to the front: along ∇E
  }
  return count;
}

//! Whether ⟨∇E, q − p⟩ > 0 on the segment pq, by pieces of its parameter range.
bool increasing_along(FlowProof& proof, const Point3& p, const Point3& q) {
  RoundingGuard guard;
  const IBox ip = interval_point(p), iq = interval_point(q);
  IBox w;
  for (int k = 0; k < 3; ++k) w[k] = iq[k] - ip[k];
  std::vector<std::pair<double, double>> stack{{0.0, 1.0}};
  constexpr int max_pieces = 1 << 12;
  int pieces = 0;
  while (!stack.empty()) {
    proof.poll();
    const auto [t0, t1] = stack.back();
    stack.pop_back();
    IBox x;
    for (int k = 0; k < 3; ++k) x[k] = ip[k] + Interval(t0, t1) * w[k];
    const Interval s = Enclosure(proof.system(), x).directional(w);
    if (finite(s) && s.inf() > 0) continue;
    if (++pieces > max_pieces || (finite(s) && s.sup() < 0)) return false;
    const double m = 0.5 * (t0 + t1);
    stack.push_back({m, t1});
    stack.push_back({t0, m});
  }
  return true;
}

//! E at a point, enclosed.
Interval value_at(const CompiledSystem& system, const Point3& p) {
  RoundingGuard guard;
  const IBox x = interval_point(p);
  Interval v[4];
  system.values<Interval>(x.data(), nullptr, v);
  return v[0];
}

//! A polyline from `start` along the flow of ±∇E (sign): the first step in direction `first`,
//! the next along ∇E at each new point (times sign), every segment proved to increase E (sign +1)
//! or decrease it (−1), ending where E > tube.upper (resp. < tube.lower) is proved.  The step starts at
//! `step` and doubles after a proved segment, halves after a failed one.  Nothing if no such
//! polyline is found within tolerances::flow_path_steps steps or the step falls below 2^−30 of
//! the first.
std::optional<std::vector<Point3>> flow_path(FlowProof& proof, const Point3& start, P3 direction, int sign, double step,
                                             const Tube& tube) {
  const CompiledSystem& system = proof.system();
  std::vector<Point3> path{start};
  const double least = std::ldexp(step, -30);
  for (int n = 0; n < tolerances::flow_path_steps; ++n) {
    const Point3& x = path.back();
    const Point3 y(x.x() + step * direction[0], x.y() + step * direction[1], x.z() + step * direction[2]);
    const bool proved = sign > 0 ? increasing_along(proof, x, y) : increasing_along(proof, y, x);
    if (!proved) {
      step *= 0.5;
      if (!(step >= least)) return std::nullopt;
      continue;
    }
    path.push_back(y);
    const Interval e = value_at(system, path.back());
    if (!finite(e)) return std::nullopt;
    if (sign > 0 ? e.inf() > tube.upper : e.sup() < tube.lower) return path;
    const P3 at{y.x(), y.y(), y.z()};
    double values[4];
    system.values<double>(at.data(), nullptr, values);
    const double norm = std::sqrt(values[1] * values[1] + values[2] * values[2] + values[3] * values[3]);
    if (!(norm > 0) || !std::isfinite(norm)) return std::nullopt;
    for (int k = 0; k < 3; ++k) direction[k] = sign * values[1 + k] / norm;
    step *= 2;
  }
  return std::nullopt;
}

//! (e) for one critical point z with root box `root`: a path through z, monotone in E, from
//! E < tube.lower to E > tube.upper, and its algebraic crossing count with M.
int count_through(FlowProof& proof, const P3& z, const std::vector<std::array<double, 2>>& root, const Tube& tube,
                  const std::vector<Point3>& points, const std::vector<std::array<std::size_t, 3>>& oriented,
                  std::uint64_t seed, std::size_t index) {
  const CompiledSystem& system = proof.system();
  {
    RoundingGuard guard;
    IBox x;
    for (int k = 0; k < 3; ++k) x[k] = Interval(root[k][0], root[k][1]);
    const Interval e = Enclosure(system, x).value();
    if (!tube.holds(e))
      throw Verdict{FlowCertificateStatus::undecided, "the box of a critical point of the height function is not proved inside the tube", z};
  }
  double values[4];
  system.values<double>(z.data(), nullptr, values);
  const P3 gradient{values[1], values[2], values[3]};
  const double length = std::sqrt(gradient[0] * gradient[0] + gradient[1] * gradient[1] + gradient[2] * gradient[2]);
  if (!(length > 0) || !std::isfinite(length))
    throw Verdict{FlowCertificateStatus::undecided, "the gradient of E is not usable at a critical point", z};
  for (int attempt = 0; attempt < tolerances::flow_segment_attempts; ++attempt) {
    P3 g;
    for (int k = 0; k < 3; ++k) {
      const double jitter = attempt == 0 ? 0 : 0.05 * attempt * (2 * seeded_uniform(seed, static_cast<std::int64_t>(index), attempt * 3 + k, generic_stream::flow_segment) - 1);
      g[k] = gradient[k] / length + jitter;
    }
    const Point3 start(z[0], z[1], z[2]);
    const std::optional<std::vector<Point3>> up = flow_path(proof, start, g, +1, tube.upper / length, tube);
    if (!up) continue;
    const std::optional<std::vector<Point3>> down =
        flow_path(proof, start, P3{-g[0], -g[1], -g[2]}, -1, -tube.lower / length, tube);
    if (!down) continue;
    // The path from E < tube.lower to E > tube.upper: down reversed, then up.
    std::vector<Point3> path(down->rbegin(), down->rend());
    path.insert(path.end(), up->begin() + 1, up->end());
    int count = 0;
    bool generic = true;
    for (std::size_t i = 0; i + 1 < path.size() && generic; ++i) {
      const auto c = crossings(path[i], path[i + 1], i == 0, i + 2 == path.size(), points, oriented);
      if (c) count += *c;
      generic = c.has_value();
    }
    if (generic) return count;
  }
  throw Verdict{FlowCertificateStatus::undecided,
                "no path through a critical point of the height function could be proved to cross the tube "
                "monotonically and generically",
                z};
}

// ---- 5. the distances ----

//! The distance bound of one triangle of a certified mesh: the least of e/G (the theorem) and the
//! bounds of flow_distance.h within the radius e/G (always applicable: the arc from a point of the
//! triangle to Σ is at most e/G long) and within `radius` if it is positive.
double local_distance_bound(const FlowDistance& distance, const std::vector<Point3>& points,
                            const std::array<std::size_t, 3>& triangle, double e, double min_gradient, double radius) {
  double global;
  {
    RoundingGuard guard;
    global = (Interval(e) / Interval(min_gradient)).sup();
  }
  if (!(global > 0)) return global;
  const auto at = [&](int i) {
    const Point3& p = points[triangle[i]];
    return Vec3{p.x(), p.y(), p.z()};
  };
  double best = global;
  for (double r : {global, radius})
    if (r > 0 && std::isfinite(r)) best = std::min(best, distance.bound(at(0), at(1), at(2), r).distance);
  return best;
}

}  // namespace

namespace {

//! What every attempt shares: the soup, its orientation, Σ and the options.
struct FlowInput {
  const std::vector<Point3>& points;
  const std::vector<std::array<std::size_t, 3>>& triangles;
  const Orientation& orientation;
  const Surface& surface;
  const Box3& box;
  const FlowCertificateOptions& options;
};

//! The critical points of a generic height function on Σ (the seed solve of meshing/inputs/seed_solve.h on
//! E), computed once: they do not depend on the function whose flow the attempt uses.
const SolveResult& critical_points(const FlowInput& in, std::optional<SolveResult>& solved, FlowCertificate& c) {
  if (solved) return *solved;
  ImplicitOracle oracle(in.surface, in.box, SolverBackend::subdivision);
  oracle.set_run_controls(in.options.seed, in.options.deadline);
  const Box3& box = in.box;
  const Domain domain = Domain::from_box({{box.lo[0], box.hi[0]}, {box.lo[1], box.hi[1]}, {box.lo[2], box.hi[2]}});
  for (int k = 0; k < tolerances::mesher_height_direction_retries && !solved; ++k) {
    SolveResult r = seed_solve(oracle, generic_direction(in.options.seed, k), domain);
    if (r.status == SolveStatus::time_limit) {
      c.time_limited = true;
      throw Stopped{};
    }
    if (r.status != SolveStatus::non_isolated) solved = std::move(r);
  }
  if (!solved)
    throw Verdict{FlowCertificateStatus::undecided, "no generic height direction was found for the surface",
                  std::nullopt, false};
  if (solved->status != SolveStatus::complete || !solved->undecided.empty())
    throw Verdict{FlowCertificateStatus::undecided,
                  "the critical points of the height function on the surface were not all certified (" +
                      std::to_string(solved->undecided.size()) + " regions undecided)",
                  solved->undecided.empty() ? std::nullopt : std::optional<P3>(solved->undecided.front().world), false};
  return *solved;
}

//! Step 2's per-triangle results: the bound of |E|, the flux sign (in the orientation of
//! Orientation), and bounds of min E and max E on M.
struct TriangleBounds {
  std::vector<double> e_bound;
  std::vector<int> sign;
  double lower = 0, upper = 0;
};

//! 2. ε and the transversality of every triangle.
TriangleBounds prove_triangles(FlowProof& proof, const FlowInput& in, FlowCertificate& c) {
  const auto& points = in.points;
  const auto& triangles = in.triangles;
  TriangleBounds b;
  b.e_bound.resize(triangles.size());
  b.sign.resize(triangles.size());
  c.epsilon = 0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const TriangleProof tp = prove_triangle(proof, points[tri[0]], points[tri[1]], points[tri[2]], c.triangle_pieces);
    if (tp.sign == 0)
      throw Verdict{FlowCertificateStatus::undecided,
                    "triangle " + std::to_string(t) + " is not proved transverse to the gradient of E", tp.undecided_at,
                    true, false};
    b.e_bound[t] = tp.e_bound;
    b.sign[t] = tp.sign * in.orientation.flip[t];
    c.epsilon = std::max(c.epsilon, tp.e_bound);
    b.lower = std::min(b.lower, tp.lower);
    b.upper = std::max(b.upper, tp.upper);
  }
  return b;
}

//! One direction of the flux per component, or undecided; returns the triangles oriented so that
//! the flux crosses every one of them the same way.
std::vector<std::array<std::size_t, 3>> orient_by_flux(const FlowInput& in, const std::vector<int>& sign) {
  const auto& triangles = in.triangles;
  const Orientation& orientation = in.orientation;
  std::vector<int> component_sign(orientation.components, 0);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    int& s = component_sign[orientation.component[t]];
    if (s == 0) s = sign[t];
    if (s != sign[t]) {
      const Point3& a = in.points[triangles[t][0]];
      throw Verdict{FlowCertificateStatus::undecided,
                    "the gradient of E crosses the triangles of one component of the mesh in both directions "
                    "(at triangle " + std::to_string(t) + ")",
                    P3{a.x(), a.y(), a.z()}, true, false};
    }
  }
  std::vector<std::array<std::size_t, 3>> oriented = triangles;
  for (std::size_t t = 0; t < triangles.size(); ++t)
    if (orientation.flip[t] * component_sign[orientation.component[t]] < 0) std::swap(oriented[t][1], oriented[t][2]);
  return oriented;
}

//! T's bounds: ±ε′, or with a one-sided proof the factor times the bounds of E on M (file comment).
Tube choose_tube(const FlowProof& proof, const TriangleBounds& b, FlowCertificate& c) {
  if (!std::isfinite(c.epsilon))
    throw Verdict{FlowCertificateStatus::undecided, "|E| on the mesh could not be bounded", std::nullopt};
  c.tube = std::max(tolerances::flow_tube_factor * c.epsilon, std::numeric_limits<double>::min());
  Tube tube{-c.tube, c.tube};
  if (proof.one_sided()) {
    if (!(std::isfinite(b.lower) && std::isfinite(b.upper)))
      throw Verdict{FlowCertificateStatus::undecided, "E on the mesh could not be bounded", std::nullopt};
    tube.lower = std::min(tolerances::flow_tube_factor * b.lower, -std::numeric_limits<double>::min());
    tube.upper = std::max(tolerances::flow_tube_factor * b.upper, std::numeric_limits<double>::min());
  }
  c.tube_lower = tube.lower;
  c.tube_upper = tube.upper;
  c.one_sided_tube = proof.one_sided();
  return tube;
}

//! The least |∇| at the mesh's vertices (points of T): the gradient proof need not cut a box for a
//! bound above it.
double least_gradient_at_vertices(FlowProof& proof, const std::vector<Point3>& points) {
  double reference = std::numeric_limits<double>::infinity();
  for (const Point3& p : points) {
    const double at[3] = {p.x(), p.y(), p.z()};
    double values[4];
    proof.system().values<double>(at, nullptr, values);
    const double length = std::sqrt(values[1] * values[1] + values[2] * values[2] + values[3] * values[3]);
    if (length > 0 && std::isfinite(length)) reference = std::min(reference, length);
  }
  return reference;
}

//! 4. (e): the critical points of a generic height function and one path through each, which must
//! cross the mesh once (with sign).
void count_critical_paths(FlowProof& proof, const FlowInput& in, std::optional<SolveResult>& solved,
                          FlowCertificate& c, const Tube& tube, const std::vector<std::array<std::size_t, 3>>& oriented) {
  std::size_t index = 0;
  c.critical_points = 0;
  for (const CertifiedRoot& root : critical_points(in, solved, c).roots) {
    if (!root.inside_domain) continue;
    const int count =
        count_through(proof, root.world, root.box.bounds, tube, in.points, oriented, in.options.seed, index++);
    if (count != 1)
      throw Verdict{FlowCertificateStatus::undecided,
                    "a path across the tube through a critical point of the surface meets the mesh " +
                        std::to_string(count) + " times (with sign): the mesh covers that component of the surface " +
                        std::to_string(count) + " times, not once",
                    root.world, false};
    ++c.critical_points;
  }
  if (c.critical_points == 0)
    throw Verdict{FlowCertificateStatus::refuted,
                  "the surface is empty in the box (a generic height function has no critical point on it, "
                  "certified) but the mesh is not",
                  std::nullopt, false};
}

//! Steps 2–5 of the file comment with the flow of proof's function: fills c (status certified)
//! or throws Verdict or Stopped.
void prove_with(FlowProof& proof, const FlowInput& in, std::optional<SolveResult>& solved, FlowCertificate& c) {
  const TriangleBounds bounds = prove_triangles(proof, in, c);
  const std::vector<std::array<std::size_t, 3>> oriented = orient_by_flux(in, bounds.sign);
  const Tube tube = choose_tube(proof, bounds, c);

  // 3. (a) and (b).
  proof.prove_faces(tube);
  c.min_gradient = proof.prove_gradient(tube, least_gradient_at_vertices(proof, in.points));
  if (!(c.min_gradient > 0))
    throw Verdict{FlowCertificateStatus::undecided, "no lower bound of the gradient of E was proved", std::nullopt};

  count_critical_paths(proof, in, solved, c, tube, oriented);

  // 5. Certified: the Hausdorff bounds, rounded up.
  c.status = FlowCertificateStatus::certified;
  RoundingGuard guard;
  c.triangle_distance_bounds.resize(in.triangles.size());
  c.hausdorff_upper_bound = 0;
  for (std::size_t t = 0; t < in.triangles.size(); ++t) {
    proof.poll();
    c.triangle_distance_bounds[t] = local_distance_bound(proof.distance(), in.points, in.triangles[t],
                                                         bounds.e_bound[t], c.min_gradient, in.options.distance_radius);
    c.hausdorff_upper_bound = std::max(c.hausdorff_upper_bound, c.triangle_distance_bounds[t]);
  }
}

//! η of the normalised function: tolerances::flow_normalized_eta_relative times the median of
//! |∇E| (in double) over the vertices of M; 0 when that median is not positive and finite.
double normalization_eta(const CompiledSystem& system, const std::vector<Point3>& points) {
  std::vector<double> lengths;
  lengths.reserve(points.size());
  for (const Point3& p : points) {
    const double at[3] = {p.x(), p.y(), p.z()};
    double values[4];
    system.values<double>(at, nullptr, values);
    const double length = std::sqrt(values[1] * values[1] + values[2] * values[2] + values[3] * values[3]);
    if (std::isfinite(length)) lengths.push_back(length);
  }
  if (lengths.empty()) return 0;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  const double eta = tolerances::flow_normalized_eta_relative * lengths[lengths.size() / 2];
  return eta > 0 && std::isfinite(eta) ? eta : 0;
}

//! F = E / sqrt(|∇E|² + η²), exactly (η as the rational nearest its double).  Throws
//! InvalidInput when F exceeds Surface's size limits (a large E, whose gradient squared is larger).
Surface normalized_function(const Surface& surface, double eta) {
  GiNaC::ex squared_gradient = GiNaC::numeric(0);
  for (const GiNaC::ex& g : surface.gradient()) squared_gradient += GiNaC::pow(g, 2);
  const GiNaC::ex F = surface.E() * GiNaC::pow(squared_gradient + GiNaC::numeric(eta) * GiNaC::numeric(eta),
                                               GiNaC::numeric(-1, 2));
  return Surface(F, "E/sqrt(|grad E|^2+eta^2)");
}

void record(const Verdict& v, FlowCertificate& c) {
  c.status = v.status;
  c.reason = v.reason;
  c.location = v.location;
}

}  // namespace

namespace {

//! Steps 2–5 again with the normalised function F = E/sqrt(|∇E|² + η²), after E's flow failed with
//! `with_e` (file comment): rethrows with_e if it does not depend on the function (or η = 0), then
//! tries F's flow with the tube ±ε′ and, if that fails on a condition that depends on the tube,
//! with the one-sided tube.  Throws the last Verdict, its reason naming every attempt.
void prove_with_normalized(const Verdict& with_e, const FlowProof& proof, const FlowInput& in,
                           std::optional<SolveResult>& solved, FlowCertificate& c) {
  const Surface& surface = in.surface;
  const Box3& box = in.box;
  const FlowCertificateOptions& options = in.options;
  const double eta = normalization_eta(proof.system(), in.points);
  if (with_e.status != FlowCertificateStatus::undecided || !with_e.depends_on_function || eta == 0) throw with_e;
  std::optional<Surface> F;
  try {
    F.emplace(normalized_function(surface, eta));
  } catch (const InvalidInput& too_large) {
    throw Verdict{with_e.status, with_e.reason + " (the normalised function was not tried: " + too_large.what() + ")",
                  with_e.location};
  }
  c.reason_with_E = with_e.reason;
  c.function = FlowFunction::normalized;
  c.eta = eta;
  // F's flow with the tube ±ε′, then, if a condition that depends on the function and the tube
  // fails, with the one-sided tube.
  const auto attempt = [&](bool one_sided) {
    FlowProof normalized(*F, box, options, c, tolerances::flow_normalized_box_budget,
                         tolerances::flow_normalized_box_rounds);
    normalized.compose_from(proof.system(), eta, F->normalization_exponent());
    if (one_sided) normalized.make_one_sided();
    try {
      prove_with(normalized, in, solved, c);
      c.box_rounds = normalized.rounds();
    } catch (const Verdict&) {
      c.box_rounds = normalized.rounds();
      throw;
    }
  };
  const std::string with_e_text = "with E: " + with_e.reason + "; with E/sqrt(|grad E|^2+eta^2): ";
  try {
    attempt(false);
  } catch (const Verdict& with_f) {
    const std::optional<P3> at = with_f.location ? with_f.location : with_e.location;
    if (with_f.status != FlowCertificateStatus::undecided || !with_f.depends_on_function || !with_f.depends_on_tube)
      throw Verdict{with_f.status, with_e_text + with_f.reason, at};
    try {
      attempt(true);
    } catch (const Verdict& one_sided) {
      throw Verdict{one_sided.status,
                    with_e_text + with_f.reason + "; with it and a one-sided tube: " + one_sided.reason,
                    one_sided.location ? one_sided.location : at};
    }
  }
}

}  // namespace

FlowCertificate certify_gradient_flow(const std::vector<Point3>& points,
                                      const std::vector<std::array<std::size_t, 3>>& triangles,
                                      const Surface& surface, const Box3& box, const FlowCertificateOptions& options) {
  const auto start = Clock::now();
  FlowCertificate c;
  c.seed = options.seed;
  c.box_diagonal = box.diagonal();
  c.hausdorff_upper_bound = std::numeric_limits<double>::infinity();
  check_soup(points, triangles);
  try {
    if (!options.surface_validated) (void)validate_input(surface, box);
    // 1. A closed orientable 2-manifold, or a proof that M is not Σ's kind of surface: the
    //    validation above proved Σ a closed (orientable) level set of a regular value inside B.
    const MeshReport report = check_mesh(points, triangles);
    if (!report.manifold || !report.orientable)
      throw Verdict{FlowCertificateStatus::refuted,
                    std::string("the mesh is not a closed orientable 2-manifold (") +
                        (report.closed ? "" : "it has boundary edges; ") + std::to_string(report.nonmanifold_edges) +
                        " non-manifold edges, " + std::to_string(report.nonmanifold_vertices) +
                        " non-manifold vertices) while the surface is one (E is certified non-zero on the box's "
                        "boundary and its gradient non-zero on the surface)",
                    std::nullopt};
    const Orientation orientation = orient(triangles);
    c.mesh_components = orientation.components;
    const FlowInput in{points, triangles, orientation, surface, box, options};
    std::optional<SolveResult> solved;

    // 2–5 with the flow of E; then, if that fails on a condition that depends on the function,
    // with the flow of the normalised function F (file comment).
    FlowProof proof(surface, box, options, c, tolerances::flow_box_budget, 1);
    try {
      prove_with(proof, in, solved, c);
    } catch (const Verdict& with_e) {
      prove_with_normalized(with_e, proof, in, solved, c);
    }
  } catch (const Verdict& v) {
    record(v, c);
  } catch (const Stopped&) {
    c.status = FlowCertificateStatus::undecided;
    c.reason = c.interrupted ? "interrupted by a signal" : "stopped by the time limit";
  } catch (const RunStopped& stopped) {
    c.interrupted = stopped.reason() == StopReason::interrupted;
    c.time_limited = stopped.reason() == StopReason::time_limit;
    c.status = FlowCertificateStatus::undecided;
    c.reason = stopped.what();
  }
  c.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return c;
}

nlohmann::json to_json(const FlowCertificate& c, bool per_triangle) {
  std::ostringstream status;
  status << c.status;
  nlohmann::json j;
  j["status"] = status.str();
  j["reason"] = c.reason;
  j["location"] = c.location ? nlohmann::json(*c.location) : nlohmann::json(nullptr);
  j["epsilon"] = c.epsilon;
  j["tube"] = c.tube;
  j["tube_lower"] = c.tube_lower;
  j["tube_upper"] = c.tube_upper;
  j["one_sided_tube"] = c.one_sided_tube;
  j["min_gradient"] = c.min_gradient;
  j["function"] = c.function == FlowFunction::E ? "E" : "E/sqrt(|grad E|^2+eta^2)";
  j["eta"] = c.eta;
  j["reason_with_E"] = c.reason_with_E;
  const bool bounded = c.status == FlowCertificateStatus::certified;
  j["hausdorff_upper_bound"] = bounded ? nlohmann::json(c.hausdorff_upper_bound) : nlohmann::json(nullptr);
  j["hausdorff_relative"] =
      bounded && c.box_diagonal > 0 ? nlohmann::json(c.hausdorff_upper_bound / c.box_diagonal) : nlohmann::json(nullptr);
  j["mesh_components"] = c.mesh_components;
  j["critical_points"] = c.critical_points;
  j["triangle_pieces"] = c.triangle_pieces;
  j["boxes"] = c.boxes;
  j["box_rounds"] = c.box_rounds;
  j["interrupted"] = c.interrupted;
  j["time_limited"] = c.time_limited;
  j["seed"] = c.seed;
  j["seconds"] = c.seconds;
  if (per_triangle) j["triangle_distance_bounds"] = c.triangle_distance_bounds;
  return j;
}

}  // namespace delmesh
