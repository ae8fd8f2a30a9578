#include "solvers/subdivision_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/detail/interval_box.h"
#include "solvers/detail/krawczyk_core.h"
#include "solvers/krawczyk.h"
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

class Subdivision {
 public:
  Subdivision(const CompiledSystem& system, const std::vector<double>& parameters, const Domain& domain,
              const SubdivisionOptions& options)
      : system_(system),
        params_d_(parameters),
        params_(parameters.begin(), parameters.end()),
        domain_(domain),
        options_(options),
        n_(system.n_unknowns()),
        m_(system.n_equations()),
        exclusion_(options.exclusion_mode),
        start_(std::chrono::steady_clock::now()) {
    const double scale = domain.scale();
    singular_width_ = tolerances::singular_box_relative_width * scale;
    min_width_ = tolerances::min_box_relative_width * scale;
  }

  SolveResult run() {
    Box root;
    for (std::size_t i = 0; i < n_; ++i) root.x[i] = Interval(domain_.box.bounds[i][0], domain_.box.bounds[i][1]);
    work_.push_back(root);
    std::size_t since_clock = 0;
    while (!work_.empty() && !stopped_) {
      const Box box = work_.back();
      work_.pop_back();
      if (counters_.boxes >= options_.box_budget) {
        work_.push_back(box);
        stop(SolveStatus::box_limit);
        break;
      }
      if (options_.time_limit_seconds > 0 && ++since_clock >= 16) {
        since_clock = 0;
        if (elapsed() > options_.time_limit_seconds) {
          work_.push_back(box);
          stop(SolveStatus::time_limit);
          break;
        }
      }
      ++counters_.boxes;
      process(box);
    }
    return finish();
  }

 private:
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
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

  void process(Box X) {
    if (outside_polytope(X)) {
      ++counters_.exclusions;
      return;
    }
    Interval f[max_equations];
    system_.values(X.x, params_.data(), f);
    for (std::size_t i = 0; i < m_; ++i)
      if (certainly_nonzero(f[i])) {
        ++counters_.exclusions;
        return;
      }
    const Box Xp = exclusion_ ? X : inflated(X);
    Interval mid[max_unknowns], fm[max_equations], jm[max_equations * max_unknowns], fx[max_equations],
        jx[max_equations * max_unknowns];
    for (std::size_t i = 0; i < n_; ++i) mid[i] = Interval(midpoint(X.x[i]));
    system_.values_and_jacobian(mid, params_.data(), fm, jm);
    system_.values_and_jacobian(Xp.x, params_.data(), fx, jx);
    // Mean-value form over X with the Jacobian enclosure over Xp ⊇ X.  When the enclosure of
    // f at the single point m is not much tighter than the mean-value enclosure over the whole
    // box, rounding (cancellation) rather than the box size limits what doubles can decide:
    // bisecting further would not help, so the box is escalated to MPFI.
    bool precision_limited = false;
    for (std::size_t i = 0; i < m_; ++i) {
      Interval acc = fm[i];
      for (std::size_t j = 0; j < n_; ++j) acc += jx[i * n_ + j] * (X.x[j] - mid[j]);
      if (certainly_nonzero(acc)) {
        ++counters_.exclusions;
        return;
      }
      precision_limited = precision_limited || width(fm[i]) > tolerances::precision_limited_ratio * width(acc);
    }
    bool escalated = false;
    if (precision_limited) {
      if (escalate(X)) return;
      escalated = true;
    }
    if (!exclusion_) {
      Interval contracted[max_unknowns];
      KrawczykOutcome outcome;
      if (krawczyk(Xp.x, mid, fm, jm, jx, contracted, outcome)) {
        if (outcome == KrawczykOutcome::no_root) {
          ++counters_.exclusions;
          return;
        }
        if (outcome == KrawczykOutcome::unique_root) {
          ++counters_.krawczyk_successes;
          Box R;
          std::copy(contracted, contracted + n_, R.x);
          handle_root(Xp, R);
          return;
        }
        // Every zero in X lies in K ∩ X.
        double before = 0, after = 0;
        detail::widest_side(X.x, n_, &before);
        for (std::size_t i = 0; i < n_; ++i) {
          if (detail::disjoint(contracted[i], X.x[i])) {
            ++counters_.exclusions;
            return;
          }
          X.x[i] = detail::intersection(contracted[i], X.x[i]);
        }
        detail::widest_side(X.x, n_, &after);
        if (after < tolerances::krawczyk_contraction_ratio * before && after >= min_width_) {
          work_.push_back(X);
          return;
        }
      }
    }
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
    work_.push_back(hi);
    work_.push_back(lo);
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
        std::vector<MpfiInterval> x(n_), p(params_d_.size()), mid(n_), f(m_), fm(m_), jx(m_ * n_), jm(m_ * n_);
        for (std::size_t i = 0; i < params_d_.size(); ++i) p[i] = detail::to_mpfi(params_d_[i], params_d_[i]);
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
        for (std::size_t i = 0; i < m_; ++i) {
          MpfiInterval acc = fm[i];
          for (std::size_t j = 0; j < n_; ++j) acc += jx[i * n_ + j] * (x[j] - mid[j]);
          if (certainly_nonzero(acc)) {
            ++counters_.exclusions;
            return true;
          }
        }
      }
      if (exclusion_) continue;
      const std::vector<Interval> box(Xp.x, Xp.x + n_);
      const KrawczykResult k = krawczyk_test_mpfi(system_, params_d_, box, bits);
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
      system_.values_and_jacobian(mid, params_.data(), fm, jm);
      system_.values_and_jacobian(X.x, params_.data(), fx, jx);
      KrawczykOutcome outcome;
      return krawczyk(X.x, mid, fm, jm, jx, K.x, outcome) && outcome != KrawczykOutcome::no_root;
    });
  }

  //! shrink() with Krawczyk steps in MPFI at `bits` (for roots only MPFI could certify).
  void refine_mpfi(Box& R, int bits) const {
    shrink(R, [this, bits](const Box& X, Box& K) {
      const KrawczykResult k = krawczyk_test_mpfi(system_, params_d_, std::vector<Interval>(X.x, X.x + n_), bits);
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
          const KrawczykResult k = krawczyk_test_mpfi(system_, params_d_, std::vector<Interval>(R.x, R.x + n_), bits);
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
    if (system_.has_world_point()) system_.world_point(u, params_d_.data(), out.data());
  }

  void add_undecided(const Box& X, UndecidedReason reason) {
    undecided_.push_back({X, reason});
    if (++unresolved_ > tolerances::non_isolated_box_count) stop(SolveStatus::non_isolated);
  }

  void stop(SolveStatus status) {
    stopped_ = true;
    status_ = status;
  }

  SolveResult finish() {
    SolveResult result;
    const bool non_isolated = stopped_ && status_ == SolveStatus::non_isolated;
    for (const Box& b : work_)
      undecided_.push_back({b, non_isolated ? UndecidedReason::non_isolated : UndecidedReason::budget});
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
    result.status = stopped_ ? status_ : (result.undecided.empty() ? SolveStatus::complete : SolveStatus::undecided);
    return result;
  }

  const CompiledSystem& system_;
  const std::vector<double>& params_d_;
  std::vector<Interval> params_;
  const Domain& domain_;
  SubdivisionOptions options_;
  std::size_t n_, m_;
  bool exclusion_;
  std::chrono::steady_clock::time_point start_;
  double singular_width_ = 0, min_width_ = 0;
  std::vector<Box> work_;
  std::vector<Found> found_;
  std::vector<CertifiedRoot> roots_;
  std::vector<std::pair<Box, UndecidedReason>> undecided_;
  SolverCounters counters_;
  std::size_t unresolved_ = 0;
  bool stopped_ = false;
  SolveStatus status_ = SolveStatus::complete;
};

}  // namespace

SolveResult solve_subdivision(const CompiledSystem& system, const std::vector<double>& parameters,
                              const Domain& domain, const SubdivisionOptions& options) {
  domain.validate();
  const std::size_t n = system.n_unknowns(), m = system.n_equations();
  if (n != domain.dimension() || n < 2 || n > max_unknowns)
    throw InvalidInput("solve_subdivision: the system has " + std::to_string(n) + " unknowns, the domain " +
                       std::to_string(domain.dimension()) + " dimensions; both must be 2 or 3");
  if (parameters.size() != system.n_parameters())
    throw InvalidInput("solve_subdivision: " + std::to_string(parameters.size()) + " parameters given, the system has " +
                       std::to_string(system.n_parameters()));
  if (options.exclusion_mode ? (m < n || m > max_equations) : m != n)
    throw InvalidInput("solve_subdivision: " + std::to_string(m) + " equations in " + std::to_string(n) +
                       " unknowns (square systems, or m ≥ n in exclusion mode)");
  for (double p : parameters)
    if (!std::isfinite(p)) throw InvalidInput("solve_subdivision: a parameter is not finite");
  RoundingGuard guard;
  Subdivision solver(system, parameters, domain, options);
  return solver.run();
}

}  // namespace delmesh
