// Input validation by interval subdivision.  The soundness argument for every dropped box is in
// the header comment; this file follows it step by step.
#include "meshing/inputs/input_validation.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "common/errors.h"
#include "common/run_limits.h"
#include "common/tolerances.h"
#include "solvers/detail/interval_box.h"
#include "solvers/krawczyk.h"
#include "symbolic/compiled_system.h"
#include "symbolic/scalar_traits.h"

namespace delmesh {

namespace {

using Point = std::array<double, 3>;
using Box = std::array<Interval, 3>;

const std::vector<GiNaC::symbol>& unknowns() {
  static const std::vector<GiNaC::symbol> xyz{coordinate_x(), coordinate_y(), coordinate_z()};
  return xyz;
}

// {E, ∂xE, ∂yE, ∂zE}: its values are E and ∇E, rows 1–3 of its Jacobian the Hessian of E.
CompiledSystem gradient_system(const Surface& surface) {
  const auto& g = surface.gradient();
  return CompiledSystem(std::vector<GiNaC::ex>{surface.E(), g[0], g[1], g[2]}, unknowns(), {}, false,
                        PolynomialFormBuild::never);
}

bool finite(const Interval& a) { return std::isfinite(a.inf()) && std::isfinite(a.sup()); }

// A double in [a.inf(), a.sup()] near its centre.
double centre(const Interval& a) { return std::min(std::max(0.5 * a.inf() + 0.5 * a.sup(), a.inf()), a.sup()); }

std::string point_text(const Point& p) {
  std::ostringstream s;
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

std::string face_name(int axis, bool upper, const Box3& box) {
  std::ostringstream s;
  s << "xyz"[axis] << " = " << (upper ? box.hi[axis] : box.lo[axis]);
  return s.str();
}

// A box of doubles as an enclosure over T: Interval (under a RoundingGuard) or MpfiInterval (at
// the precision of the current MpfiPrecisionScope, constants of E enclosed at that precision).
template <class T>
T enclose(double lo, double hi);
template <>
Interval enclose<Interval>(double lo, double hi) { return Interval(lo, hi); }
template <>
MpfiInterval enclose<MpfiInterval>(double lo, double hi) { return detail::to_mpfi(lo, hi); }

bool finite(const MpfiInterval& a) { return detail::is_finite(detail::to_interval(a)); }
// A double near the centre of a (finite or not).
double centre_of(const Interval& a) { return centre(a); }
double centre_of(const MpfiInterval& a) { return centre(detail::to_interval(a)); }

// The gradient system over a box (or face rectangle) B: values v and Jacobian j over B, values vc
// at the centre c, and the enclosures d of B − c.
template <class T>
struct BoxEnclosures {
  T v[4], j[12], vc[4];
  std::array<T, 3> d;
  Point c{};
};

// Step 1 of the header's proof with the natural enclosure alone (the cheapest test).
template <class T>
bool natural_excludes_e(const CompiledSystem& system, const std::array<T, 3>& b) {
  T v[4];
  system.values<T>(b.data(), nullptr, v);
  return certainly_nonzero(v[0]);
}

// Step 1 of the header's proof: true iff the natural and mean-value enclosures of E over B
// together exclude 0 (two enclosures of one number: their intersection excludes 0 iff one of
// them does).  Fills `out` for gradient_nonzero.  `bounds` are B's bounds (lo, hi per axis).
template <class T>
bool mean_value_excludes_e(const CompiledSystem& system, const std::array<T, 3>& b, const double* bounds,
                           BoxEnclosures<T>& out) {
  std::array<T, 3> c;
  for (int i = 0; i < 3; ++i) {
    out.c[i] = std::min(std::max(0.5 * bounds[2 * i] + 0.5 * bounds[2 * i + 1], bounds[2 * i]), bounds[2 * i + 1]);
    c[i] = enclose<T>(out.c[i], out.c[i]);
    out.d[i] = b[i] - c[i];
  }
  system.values_and_jacobian<T>(b.data(), nullptr, out.v, out.j);
  system.values<T>(c.data(), nullptr, out.vc);
  if (!(finite(out.vc[0]) && finite(out.v[1]) && finite(out.v[2]) && finite(out.v[3])))
    return certainly_nonzero(out.v[0]);  // the mean-value form needs E C¹ on B
  T mean_value = out.vc[0];
  for (int i = 0; i < 3; ++i) mean_value += out.v[1 + i] * out.d[i];
  return certainly_nonzero(out.v[0]) || certainly_nonzero(mean_value);
}

// Step 2 of the header's proof: true iff ⟨∇E, g⟩ ≠ 0 on B is proved for g one of the axis vectors
// or g ≈ ∇E(c).  Uses the enclosures of mean_value_excludes_e.
template <class T>
bool gradient_nonzero(const BoxEnclosures<T>& e) {
  const T* grad = e.v + 1;      // ∇E(B)
  const T* hess = e.j + 3;      // H(B), row-major, rows 1–3 of the Jacobian
  const T* grad_c = e.vc + 1;   // ∇E(c)
  // The mean-value form needs E C² on B: finite enclosures of ∇E(c) and of the Hessian.
  bool c2 = true;
  for (int i = 0; i < 3; ++i) c2 = c2 && finite(grad_c[i]);
  for (int i = 0; i < 9; ++i) c2 = c2 && finite(hess[i]);
  const auto directional = [&](const std::array<double, 3>& g) {
    T natural(0), mean_value(0);
    for (int i = 0; i < 3; ++i) natural += grad[i] * g[i];
    if (!c2) return certainly_nonzero(natural);
    for (int i = 0; i < 3; ++i) mean_value += grad_c[i] * g[i];
    for (int k = 0; k < 3; ++k) {
      T hg(0);
      for (int i = 0; i < 3; ++i) hg += hess[3 * i + k] * g[i];
      mean_value += hg * e.d[k];
    }
    return certainly_nonzero(natural) || certainly_nonzero(mean_value);
  };
  std::array<double, 3> g{};
  bool usable = false;  // g finite and non-zero
  for (int i = 0; i < 3; ++i) {
    g[i] = centre_of(grad_c[i]);
    usable = usable || g[i] != 0;
  }
  for (int i = 0; i < 3; ++i) usable = usable && std::isfinite(g[i]);
  if (usable && directional(g)) return true;
  for (int k = 0; k < 3; ++k) {
    std::array<double, 3> axis{};
    axis[k] = 1;
    if (directional(axis)) return true;
  }
  return false;
}

// Steps 1 and 2 on the box of `bounds` (lo, hi per axis) over T: true iff the box holds no
// singular point of Σ.
template <class T>
bool box_is_regular(const CompiledSystem& system, const std::array<double, 6>& bounds) {
  std::array<T, 3> b;
  for (int k = 0; k < 3; ++k) b[k] = enclose<T>(bounds[2 * k], bounds[2 * k + 1]);
  BoxEnclosures<T> e;
  return natural_excludes_e(system, b) || mean_value_excludes_e(system, b, bounds.data(), e) || gradient_nonzero(e);
}

// ---- escalation: an undecided box again in MPFI (header: "Escalation") ----

// True iff the box of `bounds` is proved free of singular points of Σ by the tests of
// box_is_regular over MPFI at one of tolerances::validation_mpfi_precisions_bits, bisecting (its
// widest side, while the double midpoint splits it) within `budget` boxes, which it decreases.
bool regular_in_mpfi(const CompiledSystem& system, const std::array<double, 6>& bounds, std::size_t& budget) {
  for (const int bits : tolerances::validation_mpfi_precisions_bits) {
    detail::MpfiPrecisionScope precision(bits);
    std::vector<std::array<double, 6>> stack{bounds};
    while (!stack.empty()) {
      RunLimits::current().check("validating the surface");
      if (budget == 0) return false;
      --budget;
      const auto box = stack.back();
      stack.pop_back();
      if (box_is_regular<MpfiInterval>(system, box)) continue;
      int side = 0;
      for (int k = 1; k < 3; ++k)
        if (box[2 * k + 1] - box[2 * k] > box[2 * side + 1] - box[2 * side]) side = k;
      const double split = 0.5 * (box[2 * side] + box[2 * side + 1]);
      if (!(split > box[2 * side] && split < box[2 * side + 1])) break;  // try a higher precision
      auto lower = box, upper = box;
      lower[2 * side + 1] = split;
      upper[2 * side] = split;
      stack.push_back(upper);
      stack.push_back(lower);
    }
    if (stack.empty()) return true;
  }
  return false;
}

// ---- evidence of a singular point near an undecided box (header: "Undecided boxes ...") ----

struct Scales {
  double E = 1, gradient = 1;  // largest |E| and ‖∇E‖∞ on the 3 × 3 × 3 grid of the domain
};

Scales domain_scales(const CompiledSystem& system, const Box3& box) {
  Scales s{0, 0};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c) {
        const int idx[3] = {a, b, c};
        Point p;
        for (int k = 0; k < 3; ++k) p[k] = box.lo[k] + 0.5 * idx[k] * (box.hi[k] - box.lo[k]);
        double v[4];
        system.values<double>(p.data(), nullptr, v);
        if (std::isfinite(v[0])) s.E = std::max(s.E, std::abs(v[0]));
        for (int k = 1; k < 4; ++k)
          if (std::isfinite(v[k])) s.gradient = std::max(s.gradient, std::abs(v[k]));
      }
  if (!(s.E > 0)) s.E = 1;
  if (!(s.gradient > 0)) s.gradient = 1;
  return s;
}

// Damped Gauss–Newton (Levenberg–Marquardt, in double) on the overdetermined system
// (E/scale.E, ∇E/scale.gradient) = 0 from p.  Returns the best point reached.
Point gauss_newton(const CompiledSystem& system, const Scales& scale, Point p) {
  const auto residual = [&](const Point& x, double* r, double* jac) {
    double v[4], j[12];
    system.values_and_jacobian<double>(x.data(), nullptr, v, j);
    for (int i = 0; i < 4; ++i) {
      const double w = i == 0 ? 1 / scale.E : 1 / scale.gradient;
      r[i] = v[i] * w;
      if (jac)
        for (int k = 0; k < 3; ++k) jac[3 * i + k] = j[3 * i + k] * w;
    }
    double n = 0;
    for (int i = 0; i < 4; ++i) n += r[i] * r[i];
    return std::isfinite(n) ? n : std::numeric_limits<double>::infinity();
  };
  // Marquardt's damping: start at 1e-3, divide by 4 after a step that lowers the residual,
  // multiply by 8 after one that does not (a rejected step leaves p unchanged).
  double r[4], jac[12];
  double norm = residual(p, r, jac);
  double mu = 1e-3;
  for (int it = 0; it < tolerances::singular_evidence_iterations && norm > 0 && std::isfinite(norm); ++it) {
    // (JᵀJ + μ diag(JᵀJ)) δ = −Jᵀr, solved by Gaussian elimination with partial pivoting.
    double a[3][4];
    for (int k = 0; k < 3; ++k) {
      for (int l = 0; l < 3; ++l) {
        a[k][l] = 0;
        for (int i = 0; i < 4; ++i) a[k][l] += jac[3 * i + k] * jac[3 * i + l];
      }
      a[k][3] = 0;
      for (int i = 0; i < 4; ++i) a[k][3] -= jac[3 * i + k] * r[i];
    }
    for (int k = 0; k < 3; ++k) a[k][k] += mu * a[k][k] + std::numeric_limits<double>::min();
    bool solved = true;
    for (int k = 0; k < 3 && solved; ++k) {
      int pivot = k;
      for (int l = k + 1; l < 3; ++l)
        if (std::abs(a[l][k]) > std::abs(a[pivot][k])) pivot = l;
      std::swap(a[k], a[pivot]);
      if (!(std::abs(a[k][k]) > 0)) solved = false;
      for (int l = k + 1; l < 3 && solved; ++l) {
        const double f = a[l][k] / a[k][k];
        for (int m = k; m < 4; ++m) a[l][m] -= f * a[k][m];
      }
    }
    if (!solved) break;
    Point delta;
    for (int k = 2; k >= 0; --k) {
      double s = a[k][3];
      for (int l = k + 1; l < 3; ++l) s -= a[k][l] * delta[l];
      delta[k] = s / a[k][k];
    }
    Point trial;
    for (int k = 0; k < 3; ++k) trial[k] = p[k] + delta[k];
    if (trial == p) break;
    double rt[4], jt[12];
    const double nt = residual(trial, rt, jt);
    if (nt < norm) {
      p = trial;
      norm = nt;
      std::copy(rt, rt + 4, r);
      std::copy(jt, jt + 12, jac);
      mu *= 0.25;
    } else {
      mu *= 8;
    }
  }
  return p;
}

// ---- proof of a singular point (header: "Singular only with a proof") ----

// The exact rational value of a finite double.
GiNaC::numeric exact_rational(double v) {
  int exponent = 0;
  const double mantissa = std::frexp(v, &exponent);  // v = mantissa · 2^exponent, 1/2 ≤ |mantissa| < 1
  return GiNaC::numeric(static_cast<long>(std::ldexp(mantissa, 53))) * GiNaC::numeric(2).power(exponent - 53);
}

// The exact value of f at the rational point q, if it is a rational number (no floating-point
// number, no undefined operation, no unevaluated function).
std::optional<GiNaC::numeric> exact_value(const GiNaC::ex& f, const std::array<GiNaC::numeric, 3>& q) {
  try {
    GiNaC::exmap at;
    for (int k = 0; k < 3; ++k) at[unknowns()[k]] = q[k];
    const GiNaC::ex value = f.subs(at, GiNaC::subs_options::no_pattern);
    if (!GiNaC::is_a<GiNaC::numeric>(value) || !GiNaC::ex_to<GiNaC::numeric>(value).is_rational()) return std::nullopt;
    return GiNaC::ex_to<GiNaC::numeric>(value);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// At most 80 characters of an expression, for a message.
std::string printable_factor(const GiNaC::ex& f) {
  std::ostringstream s;
  s << f;
  std::string text = s.str();
  if (text.size() > 80) text = text.substr(0, 77) + "...";
  return text;
}

bool in_box(const std::array<GiNaC::numeric, 3>& q, const Box3& box) {
  for (int k = 0; k < 3; ++k)
    if (q[k] < exact_rational(box.lo[k]) || q[k] > exact_rational(box.hi[k])) return false;
  return true;
}

std::string rational_point_text(const std::array<GiNaC::numeric, 3>& q) {
  std::ostringstream s;
  s << "(" << q[0] << ", " << q[1] << ", " << q[2] << ")";
  return s.str();
}

// A proof that Σ has a singular point in the box, or "": either a rational point of the box near
// one of `near` at which E and ∇E evaluate to exactly 0 (the points themselves and their
// coordinates rounded to 0 … tolerances::singular_proof_decimal_places decimal places and to
// 0 … tolerances::singular_proof_binary_places binary places are tried), or, for a polynomial E,
// a non-constant common factor g of E, ∂xE, ∂yE, ∂zE that takes both signs at rational points of
// the box (the 27 points of its 3 × 3 × 3 grid and `near`): on the segment between them g has a
// zero, at which E and its three derivatives, all multiples of g, vanish.
std::string singular_proof(const Surface& surface, const Box3& box, const std::vector<Point>& near) {
  const GiNaC::ex& E = surface.E();
  const auto& g = surface.gradient();
  const auto vanishes_at = [&](const std::array<GiNaC::numeric, 3>& q) {
    if (!in_box(q, box)) return false;
    for (const GiNaC::ex* f : {&E, &g[0], &g[1], &g[2]}) {
      const auto v = exact_value(*f, q);
      if (!v || !v->is_zero()) return false;
    }
    return true;
  };
  for (const Point& p : near) {
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) continue;
    std::vector<std::array<GiNaC::numeric, 3>> candidates;
    candidates.push_back({exact_rational(p[0]), exact_rational(p[1]), exact_rational(p[2])});
    const auto add_rounded = [&](int base, int places) {
      std::array<GiNaC::numeric, 3> q;
      const GiNaC::numeric unit = GiNaC::numeric(base).power(places);
      for (int k = 0; k < 3; ++k) {
        // std::round: independent of the rounding mode (a RoundingGuard may be alive).
        const double scaled = std::round(p[k] * std::pow(static_cast<double>(base), places));
        if (!(std::abs(scaled) < 0x1p53)) return;
        q[k] = GiNaC::numeric(static_cast<long>(scaled)) / unit;
      }
      candidates.push_back(q);
    };
    for (int places = 0; places <= tolerances::singular_proof_decimal_places; ++places) add_rounded(10, places);
    for (int places = 1; places <= tolerances::singular_proof_binary_places; ++places) add_rounded(2, places);
    for (const auto& q : candidates)
      if (vanishes_at(q))
        return " at " + rational_point_text(q) + ": E and its gradient evaluate to exactly 0 there (rational arithmetic)";
  }
  if (!surface.is_polynomial()) return "";
  try {
    GiNaC::ex common = E.expand();
    for (const GiNaC::ex& d : g) common = GiNaC::gcd(common, d.expand());
    if (GiNaC::is_a<GiNaC::numeric>(common)) return "";
    std::vector<std::array<GiNaC::numeric, 3>> points;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c) {
          const int idx[3] = {a, b, c};
          std::array<GiNaC::numeric, 3> q;
          for (int k = 0; k < 3; ++k)
            q[k] = exact_rational(box.lo[k]) + GiNaC::numeric(idx[k], 2) * (exact_rational(box.hi[k]) - exact_rational(box.lo[k]));
          points.push_back(q);
        }
    for (const Point& p : near)
      if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
        points.push_back({exact_rational(p[0]), exact_rational(p[1]), exact_rational(p[2])});
    const std::array<GiNaC::numeric, 3>* negative = nullptr;
    const std::array<GiNaC::numeric, 3>* positive = nullptr;
    for (const auto& q : points) {
      if (!in_box(q, box)) continue;
      const auto v = exact_value(common, q);
      if (!v) continue;
      if (v->is_zero()) return " at " + rational_point_text(q) + ": the common factor " + printable_factor(common) +
                               " of E and its gradient vanishes there (rational arithmetic)";
      (v->is_positive() ? positive : negative) = &q;
    }
    if (positive && negative)
      return ": E and its gradient have the common factor " + printable_factor(common) + ", which changes sign between " +
             rational_point_text(*negative) + " and " + rational_point_text(*positive) +
             " (rational arithmetic): E and its gradient vanish where it does";
  } catch (const std::exception&) {
  }
  return "";
}

struct Evidence {
  bool singular = false;  // proved: detail is the proof
  Point where{};
  std::string detail;     // the proof, or what was found instead
};

// Whether singular_proof() proves a singular point of Σ from the points `near`; if so, the proof
// is e's detail.
bool proved_singular(const Surface& surface, const Box3& domain, const std::vector<Point>& near, Evidence& e) {
  const std::string proof = singular_proof(surface, domain, near);
  if (proof.empty()) return false;
  e.singular = true;
  e.detail = proof;
  return true;
}

// Krawczyk steps on ∇E = 0 from the box x that holds its unique zero, while they shrink it by
// the refinement ratio.
void refine_critical_box(const CompiledSystem& gradient_only, std::vector<Interval>& x) {
  for (int it = 0; it < tolerances::root_refinement_iterations; ++it) {
    const KrawczykResult next = krawczyk_test(gradient_only, {}, x);
    if (next.outcome != KrawczykOutcome::unique_root) break;
    double before = 0, after = 0;
    for (int i = 0; i < 3; ++i) {
      before = std::max(before, x[i].sup() - x[i].inf());
      after = std::max(after, next.contracted[i].sup() - next.contracted[i].inf());
    }
    x = next.contracted;
    if (!(after < tolerances::root_refinement_shrink_ratio * before)) break;
  }
}

// What E on the tight box x of the only critical point within r of p says: off Σ (E ≠ 0), or,
// with E ∋ 0 and narrow, a singular point if singular_proof() proves one.  False when E on x
// decides neither.
bool critical_point_verdict(const CompiledSystem& system, const Surface& surface, const Box3& domain,
                            const Scales& scale, const Point& p, double r, const std::vector<Interval>& x,
                            Evidence& e) {
  Interval v[4];
  system.values<Interval>(x.data(), nullptr, v);
  for (int i = 0; i < 3; ++i) e.where[i] = centre(x[i]);
  std::ostringstream s;
  if (certainly_nonzero(v[0])) {
    s << " (Krawczyk certifies that the only critical point of E within " << r << " of " << point_text(p)
      << ", the point nearest to a singular one found near it, lies off the surface, at "
      << point_text(e.where) << " where |E| >= " << std::min(std::abs(v[0].inf()), std::abs(v[0].sup())) << ")";
    e.detail = s.str();
    return true;
  }
  if (finite(v[0]) && v[0].sup() - v[0].inf() <= tolerances::singular_evidence_relative_residual * scale.E) {
    if (proved_singular(surface, domain, {e.where, p}, e)) return true;
    s << " (Krawczyk certifies a critical point of E within " << r << " of " << point_text(e.where)
      << ", at which |E| <= " << std::max(std::abs(v[0].inf()), std::abs(v[0].sup()))
      << "; that it lies on the surface is not proved)";
    e.detail = s.str();
    return true;
  }
  return false;
}

// A critical point certified by Krawczyk on ∇E = 0 in p ± r (r = w, w/16, w/16², ...: interval
// overestimation of the Hessian may need r far below w), refined to a tight box X.  It is the
// only critical point in p ± r, so E(X) decides: E ∋ 0 on a tight X is evidence of a singular
// point, E ≠ 0 on X proves that there is none in p ± r.  False when no attempt decided.
bool critical_point_evidence(const CompiledSystem& system, const CompiledSystem& gradient_only, const Surface& surface,
                             const Box3& domain, const Scales& scale, const Point& p, double w, Evidence& e) {
  double r = w;
  for (int attempt = 0; attempt < tolerances::singular_evidence_krawczyk_attempts; ++attempt, r /= 16) {
    RoundingGuard guard;
    std::vector<Interval> x(3);
    for (int k = 0; k < 3; ++k) x[k] = Interval(p[k]) + Interval(-r, r);
    KrawczykResult k = krawczyk_test(gradient_only, {}, x);
    if (k.outcome == KrawczykOutcome::no_root) {  // ∇E ≠ 0 on p ± r: no singular point at p
      std::ostringstream s;
      s << " (Krawczyk proves that grad E has no zero within " << r << " of " << point_text(p)
        << ", the point nearest to a singular one found near it)";
      e.detail = s.str();
      return true;
    }
    if (k.outcome == KrawczykOutcome::unique_root) {
      x = k.contracted;
      refine_critical_box(gradient_only, x);
      return critical_point_verdict(system, surface, domain, scale, p, r, x, e);
    }
  }
  return false;
}

// A degenerate singular point: (E, ∇E) vanish at p to within rho relative to their scales; proved
// by singular_proof(), or noted in e's detail.
void residual_evidence(const CompiledSystem& system, const Surface& surface, const Box3& domain, const Scales& scale,
                       const Point& p, Evidence& e) {
  const double rho = tolerances::singular_evidence_relative_residual;
  double v[4];
  system.values<double>(p.data(), nullptr, v);
  const double gradient = std::max({std::abs(v[1]), std::abs(v[2]), std::abs(v[3])});
  if (!(std::abs(v[0]) <= rho * scale.E && gradient <= rho * scale.gradient)) return;
  e.where = p;
  if (proved_singular(surface, domain, {p}, e)) return;
  std::ostringstream s;
  s << " (near " << point_text(p) << " |E| = " << std::abs(v[0]) << " and |grad E| = " << gradient
    << ", relative to their scales " << scale.E << " and " << scale.gradient
    << " over the box; that both vanish there is not proved)";
  e.detail = s.str();
}

// Looks for a singular point of Σ near the undecided box b (header: "Undecided boxes ...").
Evidence singular_evidence(const CompiledSystem& system, std::optional<CompiledSystem>& gradient_only,
                           const Surface& surface, const Box3& domain, const Scales& scale, const Box& b,
                           bool prove_anyway) {
  Evidence e;
  double w = 0;
  for (int k = 0; k < 3; ++k) {
    e.where[k] = centre(b[k]);
    w = std::max(w, b[k].sup() - b[k].inf());
  }
  const Point p = gauss_newton(system, scale, e.where);
  // Whatever the residuals (Gauss–Newton approaches a degenerate singular point slowly), a proof
  // from the box's centre or p costs little on the first few boxes and is a proof wherever found.
  if (prove_anyway && proved_singular(surface, domain, {e.where, p}, e)) return e;
  for (int k = 0; k < 3; ++k)
    if (!(p[k] >= b[k].inf() - w && p[k] <= b[k].sup() + w)) return e;
  if (!gradient_only) {
    const auto& g = surface.gradient();
    gradient_only.emplace(std::vector<GiNaC::ex>{g[0], g[1], g[2]}, unknowns(), std::vector<GiNaC::symbol>{});
  }
  if (critical_point_evidence(system, *gradient_only, surface, domain, scale, p, w, e)) return e;
  residual_evidence(system, surface, domain, scale, p, e);
  return e;
}

std::size_t check_box_faces(const CompiledSystem& system, const Box3& box) {
  std::size_t examined = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const double fixed = side ? box.hi[axis] : box.lo[axis];
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;
      struct Rect { double u0, u1, v0, v1; int depth; };
      std::vector<Rect> stack{{box.lo[i], box.hi[i], box.lo[j], box.hi[j], 0}};
      bool positive = false, negative = false, undecided = false;
      std::size_t budget = tolerances::mesher_box_budget_global;
      while (!stack.empty()) {
        RunLimits::current().check("validating the surface");
        const Rect r = stack.back();
        stack.pop_back();
        ++examined;
        // E at the rectangle's centre (double) records the signs met on the face.
        Point c{};
        c[axis] = fixed;
        c[i] = 0.5 * (r.u0 + r.u1);
        c[j] = 0.5 * (r.v0 + r.v1);
        double values[4];
        system.values<double>(c.data(), nullptr, values);
        if (values[0] > 0) positive = true;
        if (values[0] < 0) negative = true;
        if (values[0] == 0 || (positive && negative)) {
          throw InvalidInput("the surface meets the boundary of the box on the face " +
                             face_name(axis, side, box) + "; enlarge the box so that it contains Σ strictly inside");
        }
        bool excluded = false;
        {
          RoundingGuard guard;
          std::array<double, 6> bounds{};
          bounds[2 * axis] = bounds[2 * axis + 1] = fixed;
          bounds[2 * i] = r.u0, bounds[2 * i + 1] = r.u1;
          bounds[2 * j] = r.v0, bounds[2 * j + 1] = r.v1;
          Box x;
          for (int k = 0; k < 3; ++k) x[k] = Interval(bounds[2 * k], bounds[2 * k + 1]);
          BoxEnclosures<Interval> e;
          excluded = natural_excludes_e(system, x) || mean_value_excludes_e(system, x, bounds.data(), e);
        }
        if (excluded) continue;
        if (r.depth >= tolerances::box_face_max_depth || budget == 0) {
          undecided = true;
          continue;
        }
        --budget;
        const double um = 0.5 * (r.u0 + r.u1), vm = 0.5 * (r.v0 + r.v1);
        stack.push_back({r.u0, um, r.v0, vm, r.depth + 1});
        stack.push_back({um, r.u1, r.v0, vm, r.depth + 1});
        stack.push_back({r.u0, um, vm, r.v1, r.depth + 1});
        stack.push_back({um, r.u1, vm, r.v1, r.depth + 1});
      }
      if (undecided)
        throw InvalidInput("cannot certify that the surface stays away from the face " +
                           face_name(axis, side, box) + " of the box; enlarge the box");
    }
  return examined;
}

// The volume of a box given by its bounds (lo, hi per coordinate).
double bounds_volume(const std::array<double, 6>& b) { return (b[1] - b[0]) * (b[3] - b[2]) * (b[5] - b[4]); }

// What check_regular()'s bisection left: the boxes it could not decide, and why it stopped.
struct RegularitySearch {
  std::vector<std::array<double, 6>> stack;  // the boxes not examined
  std::vector<Box> undecided;
  std::vector<std::array<double, 6>> undecided_bounds;
  std::string first_note;  // what singular_evidence found near the first undecided box
  std::size_t examined = 0;
  bool budget_exhausted = false;
  std::size_t rounds = 1;
  double domain_volume = 0;
  double unexplored = 0;  // the stack's volume when the budget was last checked
};

// The bisection of the domain into boxes on which ∇E ≠ 0 on Σ is proved (box_is_regular()),
// looking for evidence of a singular point on the boxes that stay undecided.  The budget grows by
// rounds while each round decides volume (tolerances::validation_box_rounds).
class RegularityBisection {
 public:
  RegularityBisection(const CompiledSystem& system, const Surface& surface, const Box3& box, const Scales& scale)
      : system_(system), surface_(surface), box_(box), scale_(scale) {
    double domain_width = 0;
    for (int k = 0; k < 3; ++k) domain_width = std::max(domain_width, box.hi[k] - box.lo[k]);
    min_width_ = tolerances::validation_min_box_relative_width * domain_width;
    deep_min_width_ = tolerances::validation_deep_min_box_relative_width * domain_width;
    s_.stack = {{box.lo[0], box.hi[0], box.lo[1], box.hi[1], box.lo[2], box.hi[2]}};
    s_.domain_volume = bounds_volume(s_.stack.front());
    s_.unexplored = unexplored_before_ = s_.domain_volume;
  }

  // The width below which a box is bisected only within the deep budget.
  double deep_min_width() const { return deep_min_width_; }

  // Examines the boxes until none is left or the budget runs out.
  RegularitySearch run() {
    while (!s_.stack.empty()) {
      RunLimits::current().check("validating the surface");
      if (s_.examined >= s_.rounds * tolerances::mesher_box_budget_global && !next_round()) {
        s_.budget_exhausted = true;
        break;
      }
      const auto bounds = s_.stack.back();
      s_.stack.pop_back();
      ++s_.examined;
      examine(bounds);
    }
    return std::move(s_);
  }

 private:
  // Whether the budget grows by another round: while rounds are left and the last one decided
  // volume (the stack's volume shrank).
  bool next_round() {
    s_.unexplored = 0;
    for (const auto& b : s_.stack) s_.unexplored += bounds_volume(b);
    if (s_.rounds < tolerances::validation_box_rounds && s_.unexplored < unexplored_before_) {
      ++s_.rounds;
      unexplored_before_ = s_.unexplored;
      return true;
    }
    return false;
  }

  // Drops a box proved regular; otherwise bisects it across its widest side, or keeps it
  // undecided once it is too narrow (or does not split).
  void examine(const std::array<double, 6>& bounds) {
    Box b;
    bool dropped = false;
    {
      RoundingGuard guard;
      for (int k = 0; k < 3; ++k) b[k] = Interval(bounds[2 * k], bounds[2 * k + 1]);
      dropped = box_is_regular<Interval>(system_, bounds);
    }
    if (dropped) return;
    int side = 0;
    for (int k = 1; k < 3; ++k)
      if (bounds[2 * k + 1] - bounds[2 * k] > bounds[2 * side + 1] - bounds[2 * side]) side = k;
    const double lo = bounds[2 * side], hi = bounds[2 * side + 1], split = 0.5 * (lo + hi);
    const bool splittable = split > lo && split < hi;
    if (hi - lo < min_width_ || !splittable) {
      // Evidence is looked for once, on the boxes that have just crossed min_width; below it a
      // box without evidence is bisected on, down to deep_min_width, within the deep budget.
      if (hi - lo >= 0.5 * min_width_ || !splittable) look_for_evidence(b);
      if (!splittable || hi - lo < deep_min_width_ || deep_boxes_ >= tolerances::validation_deep_box_budget) {
        s_.undecided.push_back(b);
        s_.undecided_bounds.push_back(bounds);
        return;
      }
      ++deep_boxes_;
    }
    auto lower = bounds, upper = bounds;
    lower[2 * side + 1] = split;
    upper[2 * side] = split;
    s_.stack.push_back(upper);
    s_.stack.push_back(lower);
  }

  // singular_evidence() near b: throws InvalidInput with a proof of a singular point; keeps the
  // note of what it found near the first undecided box.
  void look_for_evidence(const Box& b) {
    const Evidence evidence = singular_evidence(system_, gradient_only_, surface_, box_, scale_, b,
                                                looked_at_++ < tolerances::singular_proof_boxes_without_evidence);
    if (evidence.singular) throw InvalidInput("the surface is singular: the gradient of E vanishes on it" + evidence.detail);
    if (s_.undecided.empty() && !evidence.detail.empty()) s_.first_note = evidence.detail;
  }

  const CompiledSystem& system_;
  const Surface& surface_;
  const Box3& box_;
  const Scales& scale_;
  std::optional<CompiledSystem> gradient_only_;
  double min_width_ = 0, deep_min_width_ = 0;
  std::size_t deep_boxes_ = 0;
  std::size_t looked_at_ = 0;  // boxes singular_evidence looked at
  double unexplored_before_ = 0;  // the stack's volume when the round began
  RegularitySearch s_;
};

// Escalation (header): the undecided boxes again in MPFI, within validation_mpfi_box_budget.  A
// box on which the double enclosures overflow stays undecided: the mesher computes in double
// precision, so the domain is too large for it whatever MPFI proves.
void retry_in_mpfi(const CompiledSystem& system, const Surface& surface, RegularitySearch& search) {
  std::size_t mpfi_budget = tolerances::validation_mpfi_box_budget;
  std::vector<Box> still;
  for (std::size_t i = 0; i < search.undecided.size(); ++i) {
    Interval v[4];
    {
      RoundingGuard guard;
      system.values<Interval>(search.undecided[i].data(), nullptr, v);
    }
    const bool overflows = surface.is_polynomial() && !(finite(v[0]) && finite(v[1]) && finite(v[2]) && finite(v[3]));
    if (overflows || mpfi_budget == 0 || !regular_in_mpfi(system, search.undecided_bounds[i], mpfi_budget))
      still.push_back(search.undecided[i]);
  }
  search.undecided.swap(still);
}

// How small |∇E| may be near the first undecided box, whose centre is `where`: its value at the
// point of smallest (E, ∇E) residual found from there (an upper bound on its minimum; no positive
// lower bound is proved), and whether E or ∇E is not finite on the box.
void describe_first_undecided(std::ostream& s, const CompiledSystem& system, const Surface& surface,
                              const Scales& scale, const Box& first, const Point& where) {
  double width = 0;
  for (int k = 0; k < 3; ++k) width = std::max(width, first[k].sup() - first[k].inf());
  const Point p = gauss_newton(system, scale, where);
  bool near = true;
  for (int k = 0; k < 3; ++k) near = near && std::abs(p[k] - where[k]) <= width;
  const Point at = near ? p : where;
  double values[4];
  system.values<double>(at.data(), nullptr, values);
  const double gradient = std::sqrt(values[1] * values[1] + values[2] * values[2] + values[3] * values[3]);
  if (std::isfinite(gradient) && std::isfinite(values[0]))
    s << "; |grad E| may be as small as " << gradient << " there (its value at " << point_text(at)
      << ", where |E| = " << std::abs(values[0]) << ")";
  Interval v[4];
  {
    RoundingGuard guard;
    system.values<Interval>(first.data(), nullptr, v);
  }
  if (!(finite(v[0]) && finite(v[1]) && finite(v[2]) && finite(v[3]))) {
    // A polynomial has no pole: an infinite enclosure there is an overflow of double precision.
    if (surface.is_polynomial())
      s << " (E or its gradient overflows double precision there: the box is too large for E; rescale the "
           "coordinates or shrink the box)";
    else
      s << " (E or its gradient is undefined, unbounded or beyond double precision there)";
  }
}

// check_regular()'s error: why the search stopped, and where it left boxes undecided.
std::string irregularity_message(const CompiledSystem& system, const Surface& surface, const Scales& scale,
                                 const RegularitySearch& search, double deep_min_width) {
  const auto& undecided = search.undecided;
  Point where{};
  if (!undecided.empty())
    for (int k = 0; k < 3; ++k) where[k] = centre(undecided.front()[k]);
  std::ostringstream s;
  s << "cannot certify that the gradient of E is non-zero on the surface: ";
  if (search.budget_exhausted)
    s << "the budget of " << search.rounds << " × " << tolerances::mesher_box_budget_global << " boxes ran out with "
      << search.stack.size() << " boxes unexplored (" << std::setprecision(3)
      << 100 * search.unexplored / search.domain_volume << std::setprecision(6) << "% of the box's volume"
      << (search.rounds < tolerances::validation_box_rounds ? ", no less than after the round before" : "") << ") and "
      << undecided.size() << " undecided";
  else
    s << undecided.size() << " boxes stay undecided (bisected down to width " << deep_min_width << " or the budget of "
      << tolerances::validation_deep_box_budget << " narrow boxes, then in MPFI at up to "
      << tolerances::validation_mpfi_precisions_bits.back() << " bits within " << tolerances::validation_mpfi_box_budget
      << " boxes)";
  if (!undecided.empty()) {
    s << ", the first near " << point_text(where) << ", with no singular point proved near them";
    describe_first_undecided(s, system, surface, scale, undecided.front(), where);
    s << search.first_note;
  } else if (!search.stack.empty()) {
    const auto& u = search.stack.back();
    s << ", the next near " << point_text({0.5 * (u[0] + u[1]), 0.5 * (u[2] + u[3]), 0.5 * (u[4] + u[5])});
  }
  return s.str();
}

std::size_t check_regular(const CompiledSystem& system, const Surface& surface, const Box3& box) {
  const Scales scale = domain_scales(system, box);
  RegularityBisection bisection(system, surface, box, scale);
  RegularitySearch search = bisection.run();
  if (!search.budget_exhausted) retry_in_mpfi(system, surface, search);
  if (search.undecided.empty() && !search.budget_exhausted) return search.examined;
  throw InvalidInput(irregularity_message(system, surface, scale, search, bisection.deep_min_width()));
}

}  // namespace

std::size_t validate_box_faces(const Surface& surface, const Box3& box) {
  return check_box_faces(gradient_system(surface), box);
}

std::size_t validate_regular(const Surface& surface, const Box3& box) {
  return check_regular(gradient_system(surface), surface, box);
}

ValidationReport validate_input(const Surface& surface, const Box3& box) {
  const auto start = std::chrono::steady_clock::now();
  const CompiledSystem system = gradient_system(surface);
  ValidationReport report;
  report.face_boxes = check_box_faces(system, box);
  report.regular_boxes = check_regular(system, surface, box);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace delmesh
