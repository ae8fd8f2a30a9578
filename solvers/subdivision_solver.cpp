#include "solvers/subdivision_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/detail/deadline.h"
#include "solvers/detail/interval_box.h"
#include "solvers/detail/krawczyk_core.h"
#include "solvers/detail/mean_value.h"
#include "solvers/detail/solve_progress.h"
#include "solvers/detail/taylor_form.h"
#include "solvers/krawczyk.h"
#include "symbolic/polynomial_form.h"
#include "symbolic/scalar_traits.h"

namespace delmesh {

namespace {

using detail::midpoint;
using detail::width;

constexpr std::size_t max_unknowns = 3;
constexpr std::size_t max_equations = 6;

struct Box {
  Interval x[max_unknowns];
};

//! A work item: the box x and, for a polynomial system solved with Taylor forms, the affine map
//! x_k = centre_k + radius_k s_k from the cube s ∈ [−1, 1]^n onto the exact box (centre and radius
//! enclose the exact values; x is their outward image) and the Taylor coefficients of every
//! equation in s, concatenated as in PolynomialForm.  Without coefficients the box is examined
//! through the compiled expressions alone.
struct Item {
  Box x;
  Interval centre[max_unknowns], radius[max_unknowns];
  std::vector<Interval> taylor;
};

//! A certified root: U is the box in which it is the unique zero, R a tight box containing it.
struct Found {
  Box uniqueness, tight;
};

//! The interval determinant of an n × n row-major interval matrix, n ∈ {2, 3}.
Interval determinant(std::size_t n, const Interval* a) {
  if (n == 2) return a[0] * a[3] - a[1] * a[2];
  return a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
         a[2] * (a[3] * a[7] - a[4] * a[6]);
}

bool use_taylor_forms(const CompiledSystem& system, TaylorForms choice) {
  if (!system.polynomial_form() || choice == TaylorForms::never) return false;
  return choice == TaylorForms::always || system.taylor_forms_pay();
}

class Subdivision {
 public:
  Subdivision(const CompiledSystem& system, const std::vector<double>& parameters, const Domain& domain,
              const SubdivisionOptions& options)
      : system_(system),
        parameters_(parameters),
        parameter_intervals_(parameters.begin(), parameters.end()),
        domain_(domain),
        options_(options),
        n_(system.n_unknowns()),
        m_(system.n_equations()),
        exclusion_(options.exclusion_mode),
        start_(std::chrono::steady_clock::now()),
        deadline_(start_, options.time_limit_seconds) {
    form_ = use_taylor_forms(system, options.taylor_forms) ? system.polynomial_form() : nullptr;
    if (form_) {
      int degree = 0;
      for (std::size_t i = 0; i < m_; ++i) degree = std::max(degree, form_->basis(i).degree());
      cube_powers_ = detail::radius_powers(1, degree);
      inflated_powers_ = detail::radius_powers(1 + 2 * tolerances::krawczyk_inflation, degree);
    }
    const double scale = domain.scale();
    const double relative = options.singular_relative_width > 0 ? options.singular_relative_width
                            : exclusion_                       ? tolerances::exclusion_singular_box_relative_width
                                                               : tolerances::singular_box_relative_width;
    singular_width_ = relative * scale;
    min_width_ = tolerances::min_box_relative_width * scale;
  }

  SolveResult run() {
    Box root;
    for (std::size_t i = 0; i < n_; ++i) root.x[i] = Interval(domain_.box.bounds[i][0], domain_.box.bounds[i][1]);
    if (form_)
      work_.push_back(taylor_root(root));
    else
      push(root);
    while (!work_.empty() && !progress_.stopped()) {
      Item item = std::move(work_.back());
      work_.pop_back();
      if (counters_.boxes >= options_.box_budget) {
        work_.push_back(std::move(item));
        progress_.stop(SolveStatus::box_limit);
        break;
      }
      if (deadline_.expired()) {
        work_.push_back(std::move(item));
        progress_.stop(SolveStatus::time_limit);
        break;
      }
      ++counters_.boxes;
      if (item.taylor.empty())
        process(item.x);
      else
        process_taylor(item);
    }
    return finish();
  }

 private:
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  void push(const Box& b) {
    work_.emplace_back();
    work_.back().x = b;
  }

  //! The Taylor item of the domain box: the monomial coefficients at the parameters, re-centred
  //! on the box's midpoint and scaled to its half-widths (rounded up, so that the cube's image
  //! contains the box).
  Item taylor_root(const Box& box) const {
    Item item;
    item.taylor.resize(form_->n_coefficients());
    form_->coefficients(parameter_intervals_.data(), item.taylor.data());
    for (std::size_t k = 0; k < n_; ++k) {
      const double c = midpoint(box.x[k]);
      const double r = std::max(box.x[k].sup() - c, c - box.x[k].inf());  // rounded up under the guard
      item.centre[k] = Interval(c);
      item.radius[k] = Interval(r);
      for (std::size_t i = 0; i < m_; ++i)
        detail::substitute_affine(form_->basis(i), k, item.centre[k], item.radius[k], coefficients(item, i));
    }
    set_box(item);
    return item;
  }

  Interval* coefficients(Item& item, std::size_t i) const { return item.taylor.data() + form_->offset(i); }
  const Interval* coefficients(const Item& item, std::size_t i) const { return item.taylor.data() + form_->offset(i); }

  void set_box(Item& item) const {
    for (std::size_t k = 0; k < n_; ++k) item.x.x[k] = item.centre[k] + item.radius[k] * Interval(-1, 1);
  }

  //! Restricts the item to s_axis ∈ μ + ρ[−1, 1] (exact doubles μ, ρ).
  void restrict_item(Item& item, std::size_t axis, double mu, double rho) const {
    const Interval m(mu), r(rho);
    for (std::size_t i = 0; i < m_; ++i) detail::substitute_affine(form_->basis(i), axis, m, r, coefficients(item, i));
    item.centre[axis] += item.radius[axis] * m;
    item.radius[axis] *= r;
  }

  //! jx (row-major m × n) ⊇ {∂g_i/∂s_k (s) : s ∈ [−ρ, ρ]^n} (`powers` holds ρ^j): the Taylor
  //! gradient intersected with the compiled Jacobian over the world image of the cube, times the
  //! radii.  The expressions as written (factored, nested: sums of squares) often give the
  //! tighter Jacobian, the expanded Taylor form the tighter one for dense polynomials; both
  //! enclose it.
  void cube_jacobian(const Item& item, const std::vector<Interval>& powers, Interval* jx) const {
    for (std::size_t i = 0; i < m_; ++i)
      detail::gradient_on_cube(form_->basis(i), coefficients(item, i), powers.data(), jx + i * n_);
    const Interval cube(-powers[1].sup(), powers[1].sup());
    Interval world[max_unknowns], values[max_equations], jacobian[max_equations * max_unknowns];
    for (std::size_t k = 0; k < n_; ++k) world[k] = item.centre[k] + item.radius[k] * cube;
    system_.values_and_jacobian(world, parameter_intervals_.data(), values, jacobian);
    for (std::size_t i = 0; i < m_; ++i)
      for (std::size_t k = 0; k < n_; ++k) {
        const Interval scaled = jacobian[i * n_ + k] * item.radius[k];
        Interval& entry = jx[i * n_ + k];
        if (detail::is_finite(scaled) && !detail::disjoint(scaled, entry)) entry = detail::intersection(scaled, entry);
      }
  }

  //! Restricts the item to the half s_axis·side ≥ 0 of its cube (side = ±1).
  void halve_item(Item& item, std::size_t axis, int side) const {
    for (std::size_t i = 0; i < m_; ++i) detail::bisect_axis(form_->basis(i), axis, side, coefficients(item, i));
    item.centre[axis] += item.radius[axis] * Interval(0.5 * side);
    item.radius[axis] *= Interval(0.5);
  }

  //! One box of a polynomial system in Taylor form (the cube coordinates s ∈ [−1, 1]^n):
  //! exclusion by the domain, by the Taylor range of each equation, and by the mean-value form
  //! g(0) + J(cube)·s; then (square systems) a Krawczyk step on the inflated cube — no zero →
  //! excluded; a strong contraction → the contracted box, re-centred; otherwise the widest side
  //! (in world coordinates) is bisected.  Boxes that need the world coordinates — a unique zero
  //! to certify, refine and de-duplicate, a box narrower than the singular width, ranges limited
  //! by rounding (MPFI escalation) — go to process().
  void process_taylor(Item& item) {
    const Box& X = item.x;
    if (outside_polytope(X) || outside_domain_box(X)) {
      ++counters_.exclusions;
      return;
    }
    bool precision_limited = false;
    for (std::size_t i = 0; i < m_; ++i) {
      const Interval* a = coefficients(item, i);
      const Interval range = detail::range_on_cube(form_->basis(i), a, cube_powers_.data());
      if (certainly_nonzero(range)) {
        ++counters_.exclusions;
        return;
      }
      precision_limited = precision_limited || width(a[0]) > tolerances::precision_limited_ratio * width(range);
    }
    double w = 0;
    const std::size_t side = detail::widest_side(X.x, n_, &w);
    if (precision_limited || w < singular_width_) {
      process(X);
      return;
    }
    // Over-determined systems: the Jacobian over the cube itself; square ones: over the inflated
    // cube, for Krawczyk (ε-inflation as in process()).
    const std::vector<Interval>& powers = exclusion_ ? cube_powers_ : inflated_powers_;
    Interval fm[max_equations], jm[max_equations * max_unknowns], jx[max_equations * max_unknowns];
    cube_jacobian(item, powers, jx);
    for (std::size_t i = 0; i < m_; ++i) {
      const MonomialBasis& basis = form_->basis(i);
      const Interval* a = coefficients(item, i);
      fm[i] = a[0];
      for (std::size_t k = 0; k < n_; ++k) jm[i * n_ + k] = basis.degree() >= 1 ? a[basis.linear(k)] : Interval(0);
    }
    // the mean-value form on the cube: s ∈ [−1, 1]^n around its centre 0
    Interval offset[max_unknowns], enclosure[max_equations];
    std::fill(offset, offset + n_, Interval(-1, 1));
    if (detail::mean_value_excludes(m_, n_, fm, jx, offset, enclosure)) {
      ++counters_.exclusions;
      return;
    }
    if (!exclusion_ && krawczyk_on_cube(item, fm, jm, jx, w)) return;
    // Bisect the widest side (in world coordinates).
    Item hi = item;
    halve_item(item, side, -1);
    halve_item(hi, side, 1);
    set_box(item);
    set_box(hi);
    work_.push_back(std::move(hi));
    work_.push_back(std::move(item));
  }

  //! The Krawczyk step of process_taylor() on the inflated cube B (midpoint 0, g(0) ∈ fm,
  //! J(0) ∈ jm, J(B) ⊆ jx); w is the widest world side of the item.  True when it disposed of
  //! the item (excluded, handed to process() with a unique zero, or contracted and re-queued).
  bool krawczyk_on_cube(Item& item, const Interval* fm, const Interval* jm, const Interval* jx, double w) {
    Interval cube[max_unknowns], zero[max_unknowns], contracted[max_unknowns];
    for (std::size_t k = 0; k < n_; ++k) {
      cube[k] = Interval(-inflated_powers_[1].sup(), inflated_powers_[1].sup());
      zero[k] = Interval(0);
    }
    KrawczykOutcome outcome;
    if (!krawczyk(cube, zero, fm, jm, jx, contracted, outcome)) return false;
    if (outcome == KrawczykOutcome::no_root) {
      ++counters_.exclusions;
      return true;
    }
    if (outcome == KrawczykOutcome::unique_root) {
      // Proved in the cube coordinates; certified, refined and de-duplicated in world
      // coordinates by the compiled expressions.
      process(item.x);
      return true;
    }
    // Every zero in the cube lies in K ∩ [−1, 1]^n.
    const Interval unit(-1, 1);
    double widest = 0;
    for (std::size_t k = 0; k < n_; ++k) {
      if (detail::disjoint(contracted[k], unit)) {
        ++counters_.exclusions;
        return true;
      }
      contracted[k] = detail::intersection(contracted[k], unit);
      widest = std::max(widest, width(contracted[k]) * item.radius[k].sup());
    }
    if (!(widest < tolerances::krawczyk_contraction_ratio * w)) return false;
    for (std::size_t k = 0; k < n_; ++k) {
      const double mu = midpoint(contracted[k]);
      const double rho = std::max(contracted[k].sup() - mu, mu - contracted[k].inf());  // rounded up
      if (mu != 0 || rho != 1) restrict_item(item, k, mu, rho);
    }
    set_box(item);
    work_.push_back(std::move(item));
    return true;
  }

  bool outside_domain_box(const Box& b) const {
    for (std::size_t k = 0; k < n_; ++k)
      if (b.x[k].inf() > domain_.box.bounds[k][1] || b.x[k].sup() < domain_.box.bounds[k][0]) return true;
    return false;
  }

  bool outside_polytope(const Box& b) const {
    for (const HalfSpace& h : domain_.half_spaces)
      if (detail::half_space_excess(h.normal.data(), h.offset, b.x, n_).inf() > 0) return true;
    return false;
  }

  Box inflated(const Box& b) const {
    Box out;
    // The floor keeps sides that contraction made (nearly) points from staying points: K ⊂ int X'
    // needs X' to have an interior.
    for (std::size_t i = 0; i < n_; ++i)
      out.x[i] = detail::inflate(b.x[i], tolerances::krawczyk_inflation * std::max(width(b.x[i]), min_width_));
    return out;
  }

  //! One box in world coordinates: exclusion by the polytope, by the interval values of f and by
  //! the mean-value form; escalation to MPFI where rounding rather than the box size limits what
  //! doubles decide; then (square systems) a Krawczyk step on the inflated box (krawczyk_in_box());
  //! a box still open is bisected, or reported undecided when too small (settle_or_bisect()).
  void process(Box X) {
    if (outside_polytope(X)) {
      ++counters_.exclusions;
      return;
    }
    Interval f[max_equations];
    system_.values(X.x, parameter_intervals_.data(), f);
    for (std::size_t i = 0; i < m_; ++i)
      if (certainly_nonzero(f[i])) {
        ++counters_.exclusions;
        return;
      }
    const Box Xp = exclusion_ ? X : inflated(X);
    Interval mid[max_unknowns], fm[max_equations], jm[max_equations * max_unknowns], fx[max_equations],
        jx[max_equations * max_unknowns];
    for (std::size_t i = 0; i < n_; ++i) mid[i] = Interval(midpoint(X.x[i]));
    system_.values_and_jacobian(mid, parameter_intervals_.data(), fm, jm);
    system_.values_and_jacobian(Xp.x, parameter_intervals_.data(), fx, jx);
    // Mean-value form over X with the Jacobian enclosure over Xp ⊇ X.  When the enclosure of
    // f at the single point m is not much tighter than the mean-value enclosure over the whole
    // box, rounding (cancellation) rather than the box size limits what doubles can decide:
    // bisecting further would not help, so the box is escalated to MPFI.
    Interval offset[max_unknowns], enclosure[max_equations];
    for (std::size_t j = 0; j < n_; ++j) offset[j] = X.x[j] - mid[j];
    if (detail::mean_value_excludes(m_, n_, fm, jx, offset, enclosure)) {
      ++counters_.exclusions;
      return;
    }
    bool precision_limited = false;
    for (std::size_t i = 0; i < m_; ++i)
      precision_limited = precision_limited || width(fm[i]) > tolerances::precision_limited_ratio * width(enclosure[i]);
    bool escalated = false;
    if (precision_limited) {
      if (escalate(X)) return;
      escalated = true;
    }
    if (!exclusion_ && krawczyk_in_box(X, Xp, mid, fm, jm, jx)) return;
    settle_or_bisect(X, fx, jx, escalated);
  }

  //! The Krawczyk step of process() on Xp ⊇ X (mid, fm ∋ f(mid), jm ∋ J(mid), jx ⊇ J(Xp)).  True
  //! when it disposed of the box: no zero, a unique zero (certified), or every zero in K ∩ X and
  //! that box enough smaller to be queued again.  Otherwise X is narrowed to K ∩ X when the step
  //! proved anything, and is left to settle_or_bisect().
  bool krawczyk_in_box(Box& X, const Box& Xp, const Interval* mid, const Interval* fm, const Interval* jm,
                       const Interval* jx) {
    Interval contracted[max_unknowns];
    KrawczykOutcome outcome;
    if (!krawczyk(Xp.x, mid, fm, jm, jx, contracted, outcome)) return false;
    if (outcome == KrawczykOutcome::no_root) {
      ++counters_.exclusions;
      return true;
    }
    if (outcome == KrawczykOutcome::unique_root) {
      ++counters_.krawczyk_successes;
      Box R;
      std::copy(contracted, contracted + n_, R.x);
      handle_root(Xp, R);
      return true;
    }
    // Every zero in X lies in K ∩ X.
    double before = 0, after = 0;
    detail::widest_side(X.x, n_, &before);
    for (std::size_t i = 0; i < n_; ++i) {
      if (detail::disjoint(contracted[i], X.x[i])) {
        ++counters_.exclusions;
        return true;
      }
      X.x[i] = detail::intersection(contracted[i], X.x[i]);
    }
    detail::widest_side(X.x, n_, &after);
    if (after < tolerances::krawczyk_contraction_ratio * before && after >= min_width_) {
      push(X);
      return true;
    }
    return false;
  }

  //! A box of process() that is still open (fx ⊇ f(Xp), jx ⊇ J(Xp); escalated: MPFI has already
  //! examined it).  Narrower than the singular width and, for a square system, with a Jacobian
  //! determinant not proved non-zero (or narrower than the minimum width): escalated to MPFI, else
  //! undecided (singular_root where a zero may be singular, else precision).  Otherwise its widest
  //! side is bisected (undecided with precision if the midpoint does not split it).
  void settle_or_bisect(const Box& X, const Interval* fx, const Interval* jx, bool escalated) {
    double w = 0;
    const std::size_t side = detail::widest_side(X.x, n_, &w);
    // The interval Jacobian determinant over Xp is needed only on the smallest boxes.
    const bool singular = w < singular_width_ && (exclusion_ || !certainly_nonzero(determinant(n_, jx)));
    if (w < singular_width_ && (singular || w < min_width_)) {
      if (!escalated && escalate(X)) return;
      bool all_zero = true;
      for (std::size_t i = 0; i < m_; ++i) all_zero = all_zero && !certainly_nonzero(fx[i]);
      const UndecidedReason reason =
          (exclusion_ ? all_zero : singular) ? UndecidedReason::singular_root : UndecidedReason::precision;
      add_undecided(X, reason);
      return;
    }
    // Bisect the widest side.
    const double split = midpoint(X.x[side]);
    if (!(split > X.x[side].inf() && split < X.x[side].sup())) {
      if (!escalated && escalate(X)) return;
      add_undecided(X, UndecidedReason::precision);
      return;
    }
    Box lo = X, hi = X;
    lo.x[side] = Interval(X.x[side].inf(), split);
    hi.x[side] = Interval(split, X.x[side].sup());
    push(hi);
    push(lo);
  }

  //! One Krawczyk step on the box B (double intervals) from the evaluations mid (a point m ∈ B),
  //! fm ∋ f(m), jm ∋ J(m) and jx ⊇ J(B).  False when J(m) has no double inverse (nothing proved);
  //! otherwise `outcome` as krawczyk_compare and, unless no_root, contracted = K(B) ∩ B.
  bool krawczyk(const Interval* B, const Interval* mid, const Interval* fm, const Interval* jm, const Interval* jx,
                Interval* contracted, KrawczykOutcome& outcome) const {
    double jmid[max_unknowns * max_unknowns], y[max_unknowns * max_unknowns];
    for (std::size_t i = 0; i < n_ * n_; ++i) jmid[i] = midpoint(jm[i]);
    if (!detail::invert_matrix(n_, jmid, y)) return false;
    Interval k[max_unknowns];
    detail::krawczyk_image(n_, B, mid, fm, jx, y, k);
    outcome = detail::krawczyk_compare(n_, k, B, contracted);
    return true;
  }

  //! Re-examines X in MPFI at the escalation precisions: exclusion, then (square systems)
  //! Krawczyk on the inflated box.  True when X was decided.
  bool escalate(const Box& X) {
    ++counters_.precision_escalations;
    const Box Xp = inflated(X);
    for (int bits : tolerances::escalation_precisions) {
      {
        detail::MpfiPrecisionScope scope(bits);
        std::vector<MpfiInterval> x(n_), p(parameters_.size()), mid(n_), f(m_), fm(m_), jx(m_ * n_), jm(m_ * n_);
        for (std::size_t i = 0; i < parameters_.size(); ++i) p[i] = detail::to_mpfi(parameters_[i], parameters_[i]);
        for (std::size_t i = 0; i < n_; ++i) {
          x[i] = detail::to_mpfi(X.x[i]);
          const double c = midpoint(X.x[i]);
          mid[i] = detail::to_mpfi(c, c);
        }
        system_.values(x.data(), p.data(), f.data());
        for (std::size_t i = 0; i < m_; ++i)
          if (certainly_nonzero(f[i])) {
            ++counters_.exclusions;
            return true;
          }
        system_.values_and_jacobian(mid.data(), p.data(), fm.data(), jm.data());
        system_.values_and_jacobian(x.data(), p.data(), f.data(), jx.data());
        std::vector<MpfiInterval> offset(n_), enclosure(m_);
        for (std::size_t j = 0; j < n_; ++j) offset[j] = x[j] - mid[j];
        if (detail::mean_value_excludes(m_, n_, fm.data(), jx.data(), offset.data(), enclosure.data())) {
          ++counters_.exclusions;
          return true;
        }
      }
      if (exclusion_) continue;
      const std::vector<Interval> box(Xp.x, Xp.x + n_);
      const KrawczykResult k = krawczyk_test_mpfi(system_, parameters_, box, bits);
      if (k.outcome == KrawczykOutcome::no_root) {
        ++counters_.exclusions;
        return true;
      }
      if (k.outcome == KrawczykOutcome::unique_root) {
        ++counters_.krawczyk_successes;
        Box R;
        std::copy(k.contracted.begin(), k.contracted.end(), R.x);
        handle_root(Xp, R, bits);
        return true;
      }
    }
    return false;
  }

  //! Shrinks R (which contains a zero) by Krawczyk iteration, at most root_refinement_iterations
  //! steps, until a step leaves its widest side at ≥ root_refinement_shrink_ratio times before.  step(R, K) performs one Krawczyk
  //! step on R and stores K ∩ R in K; it returns false when the step proved nothing usable.
  template <class Step>
  void shrink(Box& R, const Step& step) const {
    for (int it = 0; it < tolerances::root_refinement_iterations; ++it) {
      Box K;
      if (!step(R, K)) return;
      double before = 0, after = 0;
      detail::widest_side(R.x, n_, &before);
      detail::widest_side(K.x, n_, &after);
      std::copy(K.x, K.x + n_, R.x);
      if (!(after < tolerances::root_refinement_shrink_ratio * before)) return;
    }
  }

  //! shrink() with Krawczyk steps in double intervals.
  void refine(Box& R) const {
    shrink(R, [this](const Box& X, Box& K) {
      Interval mid[max_unknowns], fm[max_equations], jm[max_equations * max_unknowns], fx[max_equations],
          jx[max_equations * max_unknowns];
      for (std::size_t i = 0; i < n_; ++i) mid[i] = Interval(midpoint(X.x[i]));
      system_.values_and_jacobian(mid, parameter_intervals_.data(), fm, jm);
      system_.values_and_jacobian(X.x, parameter_intervals_.data(), fx, jx);
      KrawczykOutcome outcome;
      return krawczyk(X.x, mid, fm, jm, jx, K.x, outcome) && outcome != KrawczykOutcome::no_root;
    });
  }

  //! shrink() with Krawczyk steps in MPFI at `bits` (for roots only MPFI could certify).
  void refine_mpfi(Box& R, int bits) const {
    shrink(R, [this, bits](const Box& X, Box& K) {
      const KrawczykResult k = krawczyk_test_mpfi(system_, parameters_, std::vector<Interval>(X.x, X.x + n_), bits);
      std::copy(k.contracted.begin(), k.contracted.end(), K.x);
      return k.outcome != KrawczykOutcome::no_root;
    });
  }

  static bool box_inside(const Box& a, const Box& b, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
      if (!detail::inside(a.x[i], b.x[i])) return false;
    return true;
  }

  //! A unique zero in U, known to lie in R ⊂ U.  mpfi_bits > 0: certified only in MPFI.
  void handle_root(const Box& U, Box R, int mpfi_bits = 0) {
    refine(R);
    if (mpfi_bits > 0) refine_mpfi(R, mpfi_bits);
    for (const Found& f : found_)
      if (box_inside(R, f.uniqueness, n_) || box_inside(f.tight, U, n_)) return;  // the same zero
    found_.push_back({U, R});
    DomainSide side = classify(domain_, R.x);
    if (side == DomainSide::boundary) {
      // Try to separate the root from the face at higher precision.
      for (int bits : tolerances::escalation_precisions) {
        ++counters_.precision_escalations;
        for (int it = 0; it < tolerances::boundary_separation_iterations && side == DomainSide::boundary; ++it) {
          const KrawczykResult k = krawczyk_test_mpfi(system_, parameters_, std::vector<Interval>(R.x, R.x + n_), bits);
          if (k.outcome == KrawczykOutcome::no_root) break;
          std::copy(k.contracted.begin(), k.contracted.end(), R.x);
          side = classify(domain_, R.x);
        }
        if (side != DomainSide::boundary) break;
      }
    }
    if (side == DomainSide::outside) {
      ++counters_.roots_outside;
      return;
    }
    if (side == DomainSide::boundary) {
      undecided_.push_back({R, UndecidedReason::boundary_root});
      return;
    }
    CertifiedRoot root;
    root.box.bounds.resize(n_);
    root.midpoint.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      root.box.bounds[i] = {R.x[i].inf(), R.x[i].sup()};
      root.midpoint[i] = midpoint(R.x[i]);
    }
    world(root.midpoint.data(), root.world);
    root.inside_domain = true;
    roots_.push_back(std::move(root));
  }

  //! The world point of the unknowns, or (0, 0, 0) for a system without one (CompiledSystem
  //! built from bare expressions in fewer than three unknowns).
  void world(const double* u, std::array<double, 3>& out) const {
    if (system_.has_world_point()) system_.world_point(u, parameters_.data(), out.data());
  }

  void add_undecided(const Box& X, UndecidedReason reason) {
    undecided_.push_back({X, reason});
    progress_.count_unresolved();
  }

  SolveResult finish() {
    SolveResult result;
    const bool non_isolated = progress_.non_isolated();
    for (const Item& item : work_) undecided_.push_back({item.x, progress_.unexplored_reason()});
    work_.clear();
    for (const auto& [box, reason] : undecided_) {
      UndecidedBox u;
      u.box.bounds.resize(n_);
      double centre[max_unknowns];
      for (std::size_t i = 0; i < n_; ++i) {
        u.box.bounds[i] = {box.x[i].inf(), box.x[i].sup()};
        centre[i] = midpoint(box.x[i]);
      }
      u.reason = non_isolated && reason != UndecidedReason::boundary_root ? UndecidedReason::non_isolated : reason;
      world(centre, u.world);
      result.undecided.push_back(std::move(u));
    }
    result.roots = std::move(roots_);
    result.counters = counters_;
    result.counters.seconds = elapsed();
    result.status = progress_.status(!result.undecided.empty());
    return result;
  }

  const CompiledSystem& system_;
  const std::vector<double>& parameters_;      // as given
  std::vector<Interval> parameter_intervals_;  // the same as point intervals
  const Domain& domain_;
  SubdivisionOptions options_;
  std::size_t n_, m_;
  bool exclusion_;
  std::chrono::steady_clock::time_point start_;
  detail::Deadline deadline_;
  double singular_width_ = 0, min_width_ = 0;
  const PolynomialForm* form_ = nullptr;
  std::vector<Interval> cube_powers_, inflated_powers_;  // ρ^j for ρ = 1 and the inflated ρ
  std::vector<Item> work_;
  std::vector<Found> found_;
  std::vector<CertifiedRoot> roots_;
  std::vector<std::pair<Box, UndecidedReason>> undecided_;
  SolverCounters counters_;
  detail::SolveProgress progress_;
};

}  // namespace

SolveResult solve_subdivision(const CompiledSystem& system, const std::vector<double>& parameters,
                              const Domain& domain, const SubdivisionOptions& options) {
  domain.validate();
  const std::size_t n = system.n_unknowns(), m = system.n_equations();
  if (n != domain.dimension() || n < 2 || n > max_unknowns)
    throw PreconditionViolation("solve_subdivision: the system has " + std::to_string(n) + " unknowns, the domain " +
                                std::to_string(domain.dimension()) + " dimensions; both must be 2 or 3");
  if (parameters.size() != system.n_parameters())
    throw PreconditionViolation("solve_subdivision: " + std::to_string(parameters.size()) +
                                " parameters given, the system has " + std::to_string(system.n_parameters()));
  if (options.exclusion_mode ? (m < n || m > max_equations) : m != n)
    throw PreconditionViolation("solve_subdivision: " + std::to_string(m) + " equations in " + std::to_string(n) +
                                " unknowns (square systems, or m ≥ n in exclusion mode)");
  for (double p : parameters)
    if (!std::isfinite(p)) throw PreconditionViolation("solve_subdivision: a parameter is not finite");
  RoundingGuard guard;
  Subdivision solver(system, parameters, domain, options);
  return solver.run();
}

void refine_singular_regions(const CompiledSystem& system, const std::vector<double>& parameters,
                             const Domain& domain, SolveResult& result, SubdivisionOptions options) {
  const bool open = result.status == SolveStatus::undecided || result.status == SolveStatus::non_isolated;
  if (!open || options.exclusion_mode) return;
  const double width = tolerances::refined_singular_box_relative_width * domain.scale();
  options.box_budget = tolerances::singular_refinement_box_budget;
  // A root is already in the result when its box and the box of a root there nest: each box
  // holds exactly one root, so the inner box's root is the outer box's.
  auto contains = [](const SolverBox& outer, const SolverBox& inner) {
    for (std::size_t i = 0; i < outer.bounds.size(); ++i)
      if (!(outer.bounds[i][0] <= inner.bounds[i][0] && inner.bounds[i][1] <= outer.bounds[i][1])) return false;
    return true;
  };
  auto known = [&](const CertifiedRoot& r) {
    for (const CertifiedRoot& k : result.roots)
      if (contains(k.box, r.box) || contains(r.box, k.box)) return true;
    return false;
  };
  // The solves share what is left of the caller's time limit.
  const auto start = std::chrono::steady_clock::now();
  const double time_limit = options.time_limit_seconds;
  auto out_of_time = [&] {
    if (time_limit <= 0) return false;
    const double left = time_limit - std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    options.time_limit_seconds = left;
    return !(left > 0);
  };
  auto proper = [](const SolverBox& box) {
    return std::all_of(box.bounds.begin(), box.bounds.end(), [](const std::array<double, 2>& side) {
      return std::isfinite(side[0]) && std::isfinite(side[1]) && side[0] < side[1];
    });
  };
  std::vector<UndecidedBox> kept;
  // Once one region stays undecided, the solve holds a true singular root or a curve of
  // solutions, whose other regions would cost the budget each and stay undecided too: they are
  // kept as they are.
  bool gave_up = false;
  for (UndecidedBox& region : result.undecided) {
    const bool singular = region.reason == UndecidedReason::singular_root || region.reason == UndecidedReason::non_isolated;
    if (!singular || gave_up || !proper(region.box) || out_of_time()) {
      kept.push_back(std::move(region));
      continue;
    }
    Domain part{region.box, domain.half_spaces};
    options.singular_relative_width = width / part.scale();
    SolveResult again = solve_subdivision(system, parameters, part, options);
    result.counters += again.counters;
    if (again.status != SolveStatus::complete) {
      kept.push_back(std::move(region));
      gave_up = true;
      continue;
    }
    for (CertifiedRoot& r : again.roots)
      if (!known(r)) result.roots.push_back(std::move(r));
  }
  result.undecided = std::move(kept);
  if (result.undecided.empty()) result.status = SolveStatus::complete;
}

}  // namespace delmesh
