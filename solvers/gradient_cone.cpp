#include "solvers/gradient_cone.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/detail/interval_box.h"
#include "symbolic/scalar_traits.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

namespace {

// ⟨g, v⟩ for an interval vector g and a point vector v of ℝ³.
Interval inner(const Interval* g, const std::array<double, 3>& v) { return g[0] * v[0] + g[1] * v[1] + g[2] * v[2]; }

// H w for an interval matrix H (rows H_k·) and a point vector w: the gradient of ⟨∇E, w⟩.
void hessian_times(const Interval* hessian, const std::array<double, 3>& w, Interval* out) {
  for (int k = 0; k < 3; ++k) out[k] = inner(hessian + 3 * k, w);
}

// The chart applied to points and covectors.  The identity chart of ℝ³ is read off directly: its
// products with 0 and 1 and its sums with 0 are exact, so the enclosures are the ones the general
// formulas give (for finite intervals), at none of their cost.
class ChartMap {
 public:
  explicit ChartMap(const AffineChart& chart) : chart_(chart) {
    const auto& c = chart.columns;
    identity_ = c.size() == 3 && chart.origin == std::array<double, 3>{0, 0, 0};
    for (std::size_t j = 0; identity_ && j < c.size(); ++j)
      for (std::size_t k = 0; k < 3; ++k) identity_ = identity_ && c[j][k] == (j == k ? 1.0 : 0.0);
  }
  //! ⟨g, c_j⟩: the derivative in u_j of a function whose gradient is enclosed by g.
  Interval along(const Interval* g, std::size_t j) const { return identity_ ? g[j] : inner(g, chart_.columns[j]); }
  //! The same for a point vector g (rounded to nearest).
  double along(const std::array<double, 3>& g, std::size_t j) const {
    if (identity_) return g[j];
    const auto& c = chart_.columns[j];
    return g[0] * c[0] + g[1] * c[1] + g[2] * c[2];
  }
  //! The world enclosure origin + Σ_j u_j c_j of chart points (u_j intervals or points).
  void to_world(const Interval* u, Interval* x) const {
    const std::size_t n = chart_.columns.size();
    for (int k = 0; k < 3; ++k) {
      if (identity_) {
        x[k] = u[k];
        continue;
      }
      x[k] = Interval(chart_.origin[k]);
      for (std::size_t j = 0; j < n; ++j) x[k] += u[j] * chart_.columns[j][k];
    }
  }

 private:
  const AffineChart& chart_;
  bool identity_ = false;
};

// a ∩ b for two enclosures of the same real number (so it is not empty; b if rounding said so).
Interval meet(const Interval& a, const Interval& b) {
  const double lo = std::max(a.inf(), b.inf()), hi = std::min(a.sup(), b.sup());
  return lo <= hi ? Interval(lo, hi) : b;
}

// A lower bound of |⟨g, w⟩| / |g| over a box, from enclosures φ ∌ 0 of ⟨∇E, w⟩ and G of ∇E on
// it (upward rounding: each quotient is taken as an interval and its lower end kept), the larger
// of two bounds that hold for every g ∈ G with ⟨g, w⟩ ∈ φ:
//  - min |φ| / max |G|;
//  - |w| cos θ, θ the angle between g and the line of w: |g × w| = |g| |w| sin θ and
//    |⟨g, w⟩| = |g| |w| cos θ, so tan θ ≤ τ / α with α = min |φ| and τ ≥ |g × w| the norm of the
//    componentwise maxima of the enclosure G × w, and |⟨g, w⟩| / |g| = |w| cos θ
//    ≥ |w| α / √(α² + τ²).
// The first loses the whole variation of |∇E| over the box (min |φ| against max |G|); the second
// only the variation of the direction, which is what a slope bounds.
double box_slope(const Interval& functional, const Interval* gradient, const std::array<double, 3>& w) {
  const double least = functional.inf() > 0 ? functional.inf() : -functional.sup();
  const Interval norm_squared = CGAL::square(gradient[0]) + CGAL::square(gradient[1]) + CGAL::square(gradient[2]);
  const double largest = CGAL::sqrt(norm_squared).sup();
  const double by_norm = (Interval(least) / Interval(largest)).inf();
  Interval across_squared(0);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    across_squared += CGAL::square(gradient[i] * w[j] - gradient[j] * w[i]);
  }
  const Interval alpha(least);
  const Interval w_norm = CGAL::sqrt(CGAL::square(Interval(w[0])) + CGAL::square(Interval(w[1])) + CGAL::square(Interval(w[2])));
  const Interval by_angle =
      Interval(w_norm.inf()) * alpha / CGAL::sqrt(CGAL::square(alpha) + Interval(across_squared.sup()));
  return std::max(by_norm, by_angle.inf());
}

// A guess, in chart coordinates, at a zero of f(u) = (E(x(u)), ⟨∇E(x(u)), w⟩) near the centre c
// of a box: c + δ, δ the least-norm solution of the linearisation f(c) + f′(c) δ = 0, with f′(c)
// from the midpoints of ∇E at c and of H over the box (or of E's row alone when the two rows are
// nearly parallel).  Nothing when neither row is usable.  Only the order in which the halves of a
// box are examined depends on it: it steers a refutation (test (iv)) towards the zero first.
std::optional<std::array<double, 3>> predicted_zero(const ChartMap& chart, std::size_t n,
                                                    const std::array<double, 3>& w, const Interval* centre,
                                                    const Interval& centre_value, const Interval* centre_gradient,
                                                    const Interval* hessian) {
  auto mid = [](const Interval& a) { return 0.5 * (a.inf() + a.sup()); };
  std::array<double, 3> g{}, hw{};
  for (int k = 0; k < 3; ++k) {
    g[k] = mid(centre_gradient[k]);
    hw[k] = mid(hessian[3 * k]) * w[0] + mid(hessian[3 * k + 1]) * w[1] + mid(hessian[3 * k + 2]) * w[2];
  }
  const double r[2] = {mid(centre_value), g[0] * w[0] + g[1] * w[1] + g[2] * w[2]};
  double a[3] = {}, b[3] = {}, aa = 0, ab = 0, bb = 0;
  for (std::size_t j = 0; j < n; ++j) {
    a[j] = chart.along(g, j);
    b[j] = chart.along(hw, j);
    aa += a[j] * a[j], ab += a[j] * b[j], bb += b[j] * b[j];
  }
  const double det = aa * bb - ab * ab;
  double ya = 0, yb = 0;  // δ = −(ya a + yb b)
  if (det > tolerances::cone_guess_parallel_rows * aa * bb) {
    ya = (bb * r[0] - ab * r[1]) / det;
    yb = (aa * r[1] - ab * r[0]) / det;
  } else if (aa > 0) {
    ya = r[0] / aa;
  } else {
    return std::nullopt;
  }
  std::array<double, 3> point{};
  for (std::size_t j = 0; j < n; ++j) point[j] = mid(centre[j]) - (ya * a[j] + yb * b[j]);
  for (std::size_t j = 0; j < n; ++j)
    if (!std::isfinite(point[j])) return std::nullopt;
  return point;
}

// The Krawczyk test for f(u) = (E(x(u)), ⟨∇E(x(u)), w⟩) on a box U in chart coordinates (n = 2
// or 3; x the chart), in the slice u_k = c_k through the centre c along one coordinate k when
// n = 3, the unknowns being the other two.  `centre_value` and `centre_functional` enclose E and
// ⟨∇E, w⟩ at the centre c (a point), `gradient` and `hessian_w` enclose ∇E and H w over the world
// box of U, which holds the slice.  The derivative of f in u_j is (⟨∇E, c_j⟩, ⟨H w, c_j⟩).  With Y
// the slice's box in the two unknowns, y its centre, J the enclosure of f′ on Y and C ≈ (mid J)⁻¹:
//     K = y − C f(y) + (I − C J)(Y − y).
// Every zero of f in Y lies in K, and K ⊂ int Y proves that f has one there (Krawczyk's theorem:
// K ⊆ Y makes y − C f(y) a self-map of Y by the mean-value theorem, whose fixed point is a zero).
class SliceKrawczyk {
 public:
  //! `gradient` and `hessian_w` enclose ∇E and H w over U's world box.
  SliceKrawczyk(const ChartMap& chart, std::size_t n, const Interval* gradient, const Interval* hessian_w) : n_(n) {
    for (std::size_t j = 0; j < n; ++j) {
      J_[0][j] = chart.along(gradient, j);
      J_[1][j] = chart.along(hessian_w, j);
    }
  }

  //! The unknowns of U's slice: in dimension 3 the pair whose 2 × 2 minor of mid J is largest.
  std::array<std::size_t, 2> unknowns() const {
    std::array<std::size_t, 2> pair{0, 1};
    if (n_ == 3) {
      double best = std::abs(minor(0, 1));
      for (const auto& other : {std::array<std::size_t, 2>{0, 2}, std::array<std::size_t, 2>{1, 2}})
        if (std::abs(minor(other[0], other[1])) > best) {
          best = std::abs(minor(other[0], other[1]));
          pair = other;
        }
    }
    return pair;
  }

  //! K on the unknowns `pair`, the centre's value on the other coordinate; nothing if mid J is
  //! singular (or not finite), or, with `only_inside`, when K is not inside the interior of U:
  //! K = N + (I − C J)(Y − y) with N = y − C f(y) and 0 ∈ Y − y, so K ⊇ N, and K ⊄ int Y as soon
  //! as N ⊄ int Y, which is tested first.
  std::optional<std::array<Interval, 3>> image(const std::array<std::size_t, 2>& pair, const std::array<Interval, 3>& u,
                                               const Interval* centre, const Interval& centre_value,
                                               const Interval& centre_functional, bool only_inside = false) const {
    const std::size_t a = pair[0], b = pair[1];
    const double det = minor(a, b);
    if (!(std::abs(det) > 0) || !std::isfinite(det)) return std::nullopt;
    // C = (mid J)⁻¹ (any matrix serves; only its quality matters).
    const double C[2][2] = {{mid(J_[1][b]) / det, -mid(J_[0][b]) / det}, {-mid(J_[1][a]) / det, mid(J_[0][a]) / det}};
    const Interval f[2] = {centre_value, centre_functional};
    Interval newton[2];
    for (int r = 0; r < 2; ++r) {
      newton[r] = centre[pair[r]] - (C[r][0] * f[0] + C[r][1] * f[1]);
      if (only_inside && !(u[pair[r]].inf() < newton[r].inf() && newton[r].sup() < u[pair[r]].sup()))
        return std::nullopt;
    }
    const Interval offset[2] = {u[a] - centre[a], u[b] - centre[b]};
    std::array<Interval, 3> k;
    for (std::size_t j = 0; j < n_; ++j) k[j] = centre[j];
    for (int r = 0; r < 2; ++r) {
      Interval kr = newton[r];
      for (int c = 0; c < 2; ++c) {
        const Interval identity(r == c ? 1.0 : 0.0);
        kr += (identity - (C[r][0] * J_[0][pair[c]] + C[r][1] * J_[1][pair[c]])) * offset[c];
      }
      k[pair[r]] = kr;
    }
    return k;
  }

 private:
  static double mid(const Interval& a) { return 0.5 * (a.inf() + a.sup()); }
  double minor(std::size_t a, std::size_t b) const {
    return mid(J_[0][a]) * mid(J_[1][b]) - mid(J_[0][b]) * mid(J_[1][a]);
  }

  std::size_t n_;
  Interval J_[2][3];  //!< the enclosure of f′ on U: rows ∇E and H w along the chart's columns
};

// The enclosures the Krawczyk test needs on a box U: ∇E and H over U's world box, E and ∇E at
// U's centre c.
struct KrawczykData {
  Interval centre[3], centre_value, centre_gradient[3], derivatives[12];  // ∇E, then H
  const Interval* gradient() const { return derivatives; }
  const Interval* hessian() const { return derivatives + 3; }
};

KrawczykData krawczyk_data(const CompiledSystem& E, const ChartMap& chart, std::size_t n,
                           const std::array<Interval, 3>& u) {
  KrawczykData d;
  Interval x[3], value, centre_world[3];
  chart.to_world(u.data(), x);
  E.values_and_derivatives<Interval>(x, nullptr, &value, d.derivatives);
  for (std::size_t j = 0; j < n; ++j) d.centre[j] = Interval(CGAL::to_double(u[j]));
  chart.to_world(d.centre, centre_world);
  E.values_and_jacobian<Interval>(centre_world, nullptr, &d.centre_value, d.centre_gradient);
  return d;
}

// The world point at the centre of a box `zero` in the slice (unknowns `pair`) that holds a zero
// x* of f, after narrowing the box by Krawczyk steps: each step replaces Y by K(Y) ∩ Y, which
// still holds x* (every zero of f in Y lies in K(Y)), and the steps stop when the box no longer
// shrinks.  So the point is within the final box's world extent of x*.
std::array<double, 3> narrowed_zero(const CompiledSystem& E, const ChartMap& chart, const std::array<double, 3>& w,
                                    std::size_t n, const std::array<std::size_t, 2>& pair,
                                    std::array<Interval, 3> zero) {
  for (int step = 0; step < tolerances::vanishing_point_narrowing_steps; ++step) {
    const KrawczykData d = krawczyk_data(E, chart, n, zero);
    Interval hessian_w[3];
    hessian_times(d.hessian(), w, hessian_w);
    const SliceKrawczyk krawczyk(chart, n, d.gradient(), hessian_w);
    const auto k = krawczyk.image(pair, zero, d.centre, d.centre_value, inner(d.centre_gradient, w));
    if (!k) break;
    std::array<Interval, 3> next = zero;
    bool shrinks = false, meets = true;
    for (std::size_t j : pair) {
      const double lo = std::max(zero[j].inf(), (*k)[j].inf()), hi = std::min(zero[j].sup(), (*k)[j].sup());
      meets = meets && lo <= hi;
      if (!meets) break;
      shrinks = shrinks || lo > zero[j].inf() || hi < zero[j].sup();
      next[j] = Interval(lo, hi);
    }
    if (!meets || !shrinks) break;
    zero = next;
  }
  Interval centre[3], world[3];
  for (std::size_t j = 0; j < n; ++j) centre[j] = Interval(CGAL::to_double(zero[j]));
  chart.to_world(centre, world);
  return {CGAL::to_double(world[0]), CGAL::to_double(world[1]), CGAL::to_double(world[2])};
}

}  // namespace

AffineChart AffineChart::identity() {
  AffineChart chart;
  chart.columns = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  return chart;
}

namespace {

// E and ∇E over one box (and H when E has Hessians), and what the tests derive from them, each
// computed once.
struct BoxEnclosures {
  Interval x[3], value, derivatives[12];  // the world box X, E(X), then ∇E(X) and H(X)
  // H w over the box and ⟨∇E, w⟩ at the centre, computed by (iii′), which every box that reaches
  // (iv) has been through (with Hessians, past the natural form of (iii)).
  Interval hessian_w[3], centre_functional;
  // The centre, and E and ∇E there, computed once a test needs them.
  Interval centre[3], centre_world[3], centre_value, centre_gradient[3];
  bool have_centre = false;
  const Interval* gradient() const { return derivatives; }
  const Interval* hessian() const { return derivatives + 3; }
};

// What (ii) and (iii) decided on a box: it misses Σ, or the functional keeps one sign on it with
// slope bound `bound` (−1: neither).
struct ConeDecision {
  bool misses_surface = false;
  double bound = -1;
  int sign = 0;
};

// prove_gradient_cone() in dimension n = N, with the loops over the chart's coordinates of fixed
// length: the boxes of the cover still to examine, and what the examined ones proved.
template <std::size_t N>
class ConeProver {
 public:
  ConeProver(const CompiledSystem& E, const AffineChart& chart, const Domain& domain, const std::array<double, 3>& w,
             std::size_t box_budget, const SlopeRefinement& refinement)
      : E_(E), map_(chart), domain_(domain), w_(w), box_budget_(box_budget), refinement_(refinement),
        with_hessians_(E.has_hessians()), stack_(1) {
    stack_.reserve(64);
    stack_[0].active = all_half_spaces_active(domain);
    for (std::size_t j = 0; j < n; ++j) stack_[0].u[j] = Interval(domain.box.bounds[j][0], domain.box.bounds[j][1]);
  }

  // Examines the boxes until none is left (the certificate is proved) or the attempt ends.
  GradientConeResult run() {
    while (!stack_.empty()) {
      const Box box = stack_.back();
      stack_.pop_back();
      if (!examine(box)) return result_;
    }
    result_.proved = true;
    result_.slope = refinement_.target > 0 ? slope_ : 0;
    result_.orientation = positive_seen_ == negative_seen_ ? 0 : positive_seen_ ? 1 : -1;
    result_.surface_lo = surface_lo_;
    result_.surface_hi = surface_hi_;
    return result_;
  }

 private:
  static constexpr std::size_t n = N;
  static constexpr double infinity = std::numeric_limits<double>::infinity();

  // A box with whether it is known to lie inside P (then so do its halves: classify() is not
  // asked again), and the half-spaces not yet known to contain it (classify()'s mask).  A
  // refining box is a part of a box that (iii) dropped with slope bound `parent_slope`, split only
  // to raise that bound: it is covered by its parent's decision, so it never fails (when no test
  // drops it, the parent's bound stands for it), and it does not count against box_budget.
  struct Box {
    std::array<Interval, 3> u;
    bool inside = false;
    bool refining = false;
    double parent_slope = 0;
    std::uint64_t active = 0;
  };

  // Runs tests (i)-(iv) on one box and drops or splits it; false when the attempt ends there (the
  // budget is spent, (iv) refuted the certificate, or no side splits).
  bool examine(const Box& box) {
    if (box.refining) {
      ++refining_boxes_;
    } else if (result_.boxes - refining_boxes_ >= box_budget_) {
      return false;
    }
    ++result_.boxes;
    std::uint64_t active = box.active;
    const DomainSide side = box.inside ? DomainSide::inside : classify(domain_, box.u.data(), active);
    if (side == DomainSide::outside) return true;  // (i)
    const bool inside = side == DomainSide::inside;
    BoxEnclosures e;
    enclose(box.u, e);
    if (certainly_nonzero(e.value)) return true;  // (ii), natural form
    const ConeDecision decision = decide(box.u, e);
    if (decision.misses_surface) return true;
    if (decision.bound >= 0) {
      keep_decided(box, inside, active, decision, e);
      return true;
    }
    if (box.refining) {
      slope_ = std::min(slope_, box.parent_slope);  // covered by its parent's decision
      holds_surface(e.x);
      return true;
    }
    std::optional<std::array<double, 3>> towards;
    if (with_hessians_ && e.have_centre && n >= 2) {
      towards = predicted_zero(map_, n, w_, e.centre, e.centre_value, e.centre_gradient, e.hessian());
      if (refutes(box.u, inside, active, e)) return false;
    }
    // A side that no longer splits ends the attempt.
    return split(box, inside, active, false, 0, e.gradient(), towards);
  }

  // E and ∇E over the box, and H with them when E has Hessians (one program: the tests want H on
  // most boxes that (ii) does not drop, and it shares most of its work with ∇E).
  void enclose(const std::array<Interval, 3>& u, BoxEnclosures& e) const {
    map_.to_world(u.data(), e.x);
    if (with_hessians_)
      E_.values_and_derivatives<Interval>(e.x, nullptr, &e.value, e.derivatives);
    else
      E_.values_and_jacobian<Interval>(e.x, nullptr, &e.value, e.derivatives);
  }

  // Tests (ii) by the mean-value form and (iii) on a box that (ii)'s natural form did not drop.
  ConeDecision decide(const std::array<Interval, 3>& u, BoxEnclosures& e) const {
    ConeDecision d;
    const Interval functional = inner(e.gradient(), w_);
    if (certainly_nonzero(functional)) {
      d.bound = refinement_.target > 0 ? box_slope(functional, e.gradient(), w_) : 0;  // (iii), natural form
      d.sign = functional.inf() > 0 ? 1 : -1;
      if (d.bound < refinement_.target && with_hessians_) {
        // A sharper bound from the mean-value forms, unless the box misses Σ.
        if (mean_value_excludes_zero(u, e)) return ConeDecision{true};
        Interval g[3];
        centred_gradient(u, e, g);
        const Interval phi = meet(inner(g, w_), functional);
        if (certainly_nonzero(phi)) d.bound = std::max(d.bound, box_slope(phi, g, w_));
      }
      return d;
    }
    if (mean_value_excludes_zero(u, e)) return ConeDecision{true};  // (ii), mean-value form
    if (with_hessians_) {
      // (iii′) the functional's mean-value form: its gradient is H w.
      hessian_times(e.hessian(), w_, e.hessian_w);
      e.centre_functional = inner(e.centre_gradient, w_);
      Interval mean_functional = e.centre_functional;
      for (std::size_t j = 0; j < n; ++j) mean_functional += map_.along(e.hessian_w, j) * (u[j] - e.centre[j]);
      if (certainly_nonzero(mean_functional)) {
        d.sign = mean_functional.inf() > 0 ? 1 : -1;
        if (refinement_.target > 0) {
          Interval g[3];
          centred_gradient(u, e, g);
          d.bound = box_slope(mean_functional, g, w_);
        } else {
          d.bound = 0;  // no slope asked for
        }
      }
    }
    return d;
  }

  // The centre of the box, and E (and ∇E with Hessians) there, once.
  void at_centre(const std::array<Interval, 3>& u, BoxEnclosures& e) const {
    if (e.have_centre) return;
    for (std::size_t j = 0; j < n; ++j) e.centre[j] = Interval(CGAL::to_double(u[j]));
    map_.to_world(e.centre, e.centre_world);
    if (with_hessians_)
      E_.values_and_jacobian<Interval>(e.centre_world, nullptr, &e.centre_value, e.centre_gradient);
    else
      E_.values<Interval>(e.centre_world, nullptr, &e.centre_value);
    e.have_centre = true;
  }

  // Whether E's mean-value form about the centre excludes 0 from the box.
  bool mean_value_excludes_zero(const std::array<Interval, 3>& u, BoxEnclosures& e) const {
    at_centre(u, e);
    Interval mean_value = e.centre_value;
    for (std::size_t j = 0; j < n; ++j) mean_value += map_.along(e.gradient(), j) * (u[j] - e.centre[j]);
    return certainly_nonzero(mean_value);
  }

  // ∇E on the box by its mean-value form about the centre, met with the natural enclosure.
  void centred_gradient(const std::array<Interval, 3>& u, BoxEnclosures& e, Interval* g) const {
    at_centre(u, e);
    for (int k = 0; k < 3; ++k) {
      Interval gk = e.centre_gradient[k];
      for (std::size_t j = 0; j < n; ++j) gk += map_.along(e.hessian() + 3 * k, j) * (u[j] - e.centre[j]);
      g[k] = meet(gk, e.gradient()[k]);
    }
  }

  // Keeps the slope bound of a box that (iii) dropped, or splits the box into refining halves to
  // raise a bound below the target while the refinement's budget lasts.
  void keep_decided(const Box& box, bool inside, std::uint64_t active, const ConeDecision& decision,
                    const BoxEnclosures& e) {
    (decision.sign > 0 ? positive_seen_ : negative_seen_) = true;
    const double box_bound = std::max(decision.bound, box.refining ? box.parent_slope : 0.0);
    if (box_bound < refinement_.target && refining_created_ + 2 <= refinement_.box_budget &&
        split(box, inside, active, true, box_bound, e.gradient())) {
      refining_created_ += 2;
      return;
    }
    slope_ = std::min(slope_, box_bound);
    holds_surface(e.x);
  }

  // (iv) Whether a zero of the functional on Σ is proved inside P by the Krawczyk test on the
  // box's slice; if so, it is the result's vanishing point.
  bool refutes(const std::array<Interval, 3>& u, bool inside, std::uint64_t active, const BoxEnclosures& e) {
    const SliceKrawczyk krawczyk(map_, n, e.gradient(), e.hessian_w);
    const auto pair = krawczyk.unknowns();
    const auto zero = krawczyk.image(pair, u, e.centre, e.centre_value, e.centre_functional, true);
    bool inside_box = zero.has_value();
    for (std::size_t j : pair)
      inside_box = inside_box && u[j].inf() < (*zero)[j].inf() && (*zero)[j].sup() < u[j].sup();
    if (!inside_box) return false;
    std::uint64_t zero_active = active;
    if (!inside && classify(domain_, zero->data(), zero_active) != DomainSide::inside) return false;
    result_.vanishing_point = narrowed_zero(E_, map_, w_, n, pair, *zero);
    return true;
  }

  // Pushes the halves of `box` (the lower one on top) across the side of largest smear, the
  // width times the largest |∂E/∂u_j| on the box (`gradient` encloses ∇E there), or across the
  // widest side when the smear is not finite or its side no longer splits.  False if no side
  // splits.
  bool split(const Box& box, bool inside, std::uint64_t active, bool refining, double parent_slope,
             const Interval* gradient, const std::optional<std::array<double, 3>>& towards = std::nullopt) {
    const auto& u = box.u;
    auto splits = [&](std::size_t j) {
      const double mid = 0.5 * (u[j].inf() + u[j].sup());
      return u[j].inf() < mid && mid < u[j].sup();
    };
    std::size_t smeared = 0;
    double largest_smear = -1;
    for (std::size_t j = 0; j < n; ++j) {
      const Interval d = map_.along(gradient, j);
      const double smear = detail::width(u[j]) * std::max(std::abs(d.inf()), std::abs(d.sup()));
      if (smear > largest_smear) smeared = j, largest_smear = smear;
    }
    const std::size_t side =
        std::isfinite(largest_smear) && splits(smeared) ? smeared : detail::widest_side(u.data(), n);
    if (!splits(side)) return false;
    const double lo = u[side].inf(), hi = u[side].sup(), mid = 0.5 * (lo + hi);
    Box left{u, inside, refining, parent_slope, active}, right = left;
    left.u[side] = Interval(lo, mid);
    right.u[side] = Interval(mid, hi);
    const bool upper_first = towards && (*towards)[side] > mid;
    stack_.push_back(upper_first ? left : right);
    stack_.push_back(upper_first ? right : left);
    return true;
  }

  // Widens the bounding box of the cover's boxes that may hold points of Σ by a world box.
  void holds_surface(const Interval* x) {
    for (int k = 0; k < 3; ++k) {
      surface_lo_[k] = std::min(surface_lo_[k], x[k].inf());
      surface_hi_[k] = std::max(surface_hi_[k], x[k].sup());
    }
  }

  const CompiledSystem& E_;
  const ChartMap map_;
  const Domain& domain_;
  const std::array<double, 3>& w_;
  const std::size_t box_budget_;
  const SlopeRefinement& refinement_;
  const bool with_hessians_;
  GradientConeResult result_;
  double slope_ = infinity;
  // The bounding box of the world enclosures of the cover's boxes that may hold points of Σ.
  std::array<double, 3> surface_lo_{infinity, infinity, infinity}, surface_hi_{-infinity, -infinity, -infinity};
  std::size_t refining_boxes_ = 0, refining_created_ = 0;
  bool positive_seen_ = false, negative_seen_ = false;  // signs of the functional on boxes (iii) dropped
  std::vector<Box> stack_;
};

// prove_gradient_cone() in dimension N, in the rounding mode interval arithmetic needs.
template <std::size_t N>
GradientConeResult prove_cone_in(const CompiledSystem& E, const AffineChart& chart, const Domain& domain,
                                 const std::array<double, 3>& w, std::size_t box_budget,
                                 const SlopeRefinement& refinement) {
  RoundingGuard guard;
  ConeProver<N> prover(E, chart, domain, w, box_budget, refinement);
  return prover.run();
}

}  // namespace

GradientConeResult prove_gradient_cone(const CompiledSystem& E, const AffineChart& chart, const Domain& domain,
                                       const std::array<double, 3>& w, std::size_t box_budget,
                                       const SlopeRefinement& refinement) {
  const std::size_t n = domain.dimension();
  if (chart.columns.size() != n || n < 1 || n > 3)
    throw PreconditionViolation("prove_gradient_cone: the chart's columns must match the domain's dimension");
  if (E.n_equations() != 1 || E.n_unknowns() != 3 || E.n_parameters() != 0)
    throw PreconditionViolation("prove_gradient_cone: E must be one equation in (x, y, z) without parameters");
  switch (n) {
    case 1: return prove_cone_in<1>(E, chart, domain, w, box_budget, refinement);
    case 2: return prove_cone_in<2>(E, chart, domain, w, box_budget, refinement);
    default: return prove_cone_in<3>(E, chart, domain, w, box_budget, refinement);
  }
}

namespace {

int sign_of(const Interval& v) {
  if (v.inf() > 0) return 1;
  if (v.sup() < 0) return -1;
  return 0;
}

}  // namespace

int gradient_functional_sign(const CompiledSystem& E, const std::array<double, 3>& a, const std::array<double, 3>& b,
                             const std::array<double, 3>& w) {
  RoundingGuard guard;
  Interval x[3], value, gradient[3];
  for (int k = 0; k < 3; ++k) x[k] = Interval(std::min(a[k], b[k]), std::max(a[k], b[k]));
  E.values_and_jacobian<Interval>(x, nullptr, &value, gradient);
  return sign_of(inner(gradient, w));
}

int value_sign(const CompiledSystem& E, const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  RoundingGuard guard;
  Interval box[3], value;
  for (int k = 0; k < 3; ++k) box[k] = Interval(lo[k], hi[k]);
  E.values<Interval>(box, nullptr, &value);
  return sign_of(value);
}

}  // namespace delmesh
