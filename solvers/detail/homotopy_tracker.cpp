#include "solvers/detail/homotopy_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Dense>

#include "common/errors.h"
#include "common/tolerances.h"

namespace delmesh::detail {

TrackerSettings TrackerSettings::defaults() {
  namespace tol = tolerances;
  return {tol::homotopy_initial_step,        tol::homotopy_max_step,
          tol::homotopy_min_step,            tol::homotopy_corrector_tolerance,
          tol::homotopy_corrector_trust,     tol::homotopy_corrector_iterations,
          tol::homotopy_divergence_norm,     tol::homotopy_endgame_start,
          tol::homotopy_singular_condition,  tol::homotopy_max_steps_per_path,
          tol::homotopy_endgame_samples,     tol::homotopy_endgame_ratio,
          tol::homotopy_endgame_tolerance,   tol::homotopy_endgame_max_winding,
          tol::homotopy_endgame_min_t,       tol::homotopy_endgame_closure,
          tol::homotopy_endgame_valuation_stable, tol::homotopy_endgame_valuation_infinity,
          tol::homotopy_endgame_direct_steps,  tol::homotopy_endgame_valuation_max_t,
          tol::homotopy_cluster_condition,    tol::homotopy_singular_endpoint_residual};
}

TrackerSettings TrackerSettings::stricter() const {
  TrackerSettings s = *this;
  s.initial_step /= tolerances::homotopy_retrack_step_divisor;
  s.max_step /= tolerances::homotopy_retrack_step_divisor;
  s.corrector_trust /= tolerances::homotopy_retrack_step_divisor;
  s.max_steps *= tolerances::homotopy_retrack_step_budget_factor;
  return s;
}

HomotopyTracker::HomotopyTracker(const CompiledSystem& f, std::vector<int> degrees,
                                 std::vector<Complex> parameters, Complex gamma, std::vector<Complex> patch)
    : f_(f), degrees_(std::move(degrees)), parameters_(std::move(parameters)), gamma_(gamma),
      patch_(std::move(patch)) {}

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

//! A path in the t-plane parametrised by a real τ ≥ 0: t(τ) = origin + rate·τ (linear), or
//! t(τ) = origin·e^{rate·τ} (exponential: rate = −1 shrinks |t|, rate = i turns around t = 0).
struct TPath {
  Complex origin, rate;
  bool exponential;
  Complex at(double tau) const { return exponential ? origin * std::exp(rate * tau) : origin + rate * tau; }
  Complex derivative(double tau) const { return exponential ? rate * at(tau) : rate; }
};

//! z^k for k ≥ 0 by repeated squaring.
Complex power(Complex z, int k) {
  Complex p = 1.0;
  for (; k > 0; k >>= 1, z *= z)
    if (k & 1) p *= z;
  return p;
}

//! Path tracking and the Cauchy endgame for systems of at most MaxN unknowns (Eigen::Dynamic: any
//! n).  Fixed maximal sizes keep every vector and matrix on the stack.
//!
//! Paths are tracked in homogeneous coordinates X = (X_0, X_1, …, X_n), u = (X_1, …, X_n) / X_0,
//! on the random affine patch ⟨c, X⟩ = 1: the homogenised equations
//! f_i^h(X) = X_0^{d_i} f_i(X/X_0), g_i^h(X) = X_i^{d_i} − X_0^{d_i} keep a path that goes to
//! infinity in u bounded in X (X_0 → 0), so diverging paths neither overflow nor get pulled onto
//! finite roots by the corrector.  f^h and its partial derivatives come from f and J_f at u:
//! ∂f_i^h/∂X_j = X_0^{d_i−1} ∂_j f_i(u) (j ≥ 1), ∂f_i^h/∂X_0 = X_0^{d_i−1}(d_i f_i − Σ_j u_j ∂_j f_i)(u).
template <int MaxN>
class PathTracker {
 public:
  static constexpr int MaxH = MaxN == Eigen::Dynamic ? Eigen::Dynamic : MaxN + 1;
  using Vec = Eigen::Matrix<Complex, Eigen::Dynamic, 1, 0, MaxH, 1>;
  using Mat = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic, 0, MaxH, MaxH>;
  using AffineVec = Eigen::Matrix<Complex, Eigen::Dynamic, 1, 0, MaxN, 1>;
  using AffineMat = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic, 0, MaxN, MaxN>;
  using RealVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, MaxH, 1>;

  PathTracker(const CompiledSystem& f, const std::vector<int>& degrees, const std::vector<Complex>& parameters,
              Complex gamma, const std::vector<Complex>& patch, const TrackerSettings& settings)
      : f_(f), degrees_(degrees), parameters_(parameters), gamma_(gamma), patch_(patch), settings_(settings),
        n_(static_cast<int>(degrees.size())), values_(n_), jacobian_(static_cast<std::size_t>(n_) * n_) {}

  //! The start solution in homogeneous coordinates (1, start), scaled onto the patch.
  Vec on_patch(const std::vector<Complex>& start) const {
    Vec X(n_ + 1);
    X[0] = 1;
    for (int i = 0; i < n_; ++i) X[i + 1] = start[i];
    Complex dot = 0;
    for (int j = 0; j <= n_; ++j) dot += patch_[j] * X[j];
    return X / dot;
  }

  PathEndpoint track(const std::vector<Complex>& start) {
    PathEndpoint end;
    Vec X = on_patch(start);
    // main phase: t = 1 − s, s from 0 to endgame_start
    double h = settings_.initial_step;
    if (!run(TPath{1.0, -1.0, false}, settings_.endgame_start, settings_.max_step, X, h, end, &end.s)) {
      end.outcome = PathOutcome::failed;
      end.point = affine(X);
      return end;
    }
    cauchy_endgame(X, end);
    return end;
  }

  //! HomotopyTracker::point_at().
  std::optional<std::vector<Complex>> point_at(const std::vector<Complex>& start, double t_stop) {
    PathEndpoint end;
    Vec X = on_patch(start);
    // linear in t down to t_0 = 1 − endgame_start (or t_stop if larger), then t = t_0 e^{−τ}
    const double t0 = std::max(t_stop, 1 - settings_.endgame_start);
    double h = settings_.initial_step;
    if (!run(TPath{1.0, -1.0, false}, 1 - t0, settings_.max_step, X, h, end)) return std::nullopt;
    if (t_stop < t0) {
      h = settings_.initial_step;
      if (!run(TPath{t0, -1.0, true}, std::log(t0 / t_stop), settings_.max_step, X, h, end)) return std::nullopt;
    }
    if (!finite(X) || std::abs(X[0]) == 0) return std::nullopt;
    return affine(X);
  }

 private:
  enum class LoopOutcome { closed, diverging, failed };

  template <class V>
  static double norm(const V& v) {
    return v.cwiseAbs().maxCoeff();
  }
  template <class V>
  static bool finite(const V& v) {
    return v.allFinite();
  }

  bool at_infinity(const Vec& X) const { return std::abs(X[0]) * settings_.divergence_norm < norm(X); }
  std::vector<Complex> affine(const Vec& X) const {
    std::vector<Complex> u(n_);
    for (int i = 0; i < n_; ++i) u[i] = X[i + 1] / X[0];
    return u;
  }

  //! f and J_f at the affine point u into fv, fj.
  void evaluate_f(const AffineVec& u, AffineVec& fv, AffineMat& fj) {
    f_.values_and_jacobian<Complex>(u.data(), parameters_.data(), values_.data(), jacobian_.data());
    fv.resize(n_);
    fj.resize(n_, n_);
    for (int i = 0; i < n_; ++i) {
      fv[i] = values_[i];
      for (int j = 0; j < n_; ++j) fj(i, j) = jacobian_[static_cast<std::size_t>(i) * n_ + j];
    }
  }

  //! H, H_X and H_t at (X, t) for H = t γ g^h + (1 − t) f^h, the last row being the patch ⟨c, X⟩ − 1.
  void evaluate(const Vec& X, Complex t, Vec& H, Mat& HX, Vec& Ht) {
    const Complex X0 = X[0];
    AffineVec u(n_), fv;
    AffineMat fj;
    for (int j = 0; j < n_; ++j) u[j] = X[j + 1] / X0;
    evaluate_f(u, fv, fj);
    H.resize(n_ + 1);
    Ht.resize(n_ + 1);
    HX.setZero(n_ + 1, n_ + 1);
    const Complex a = t * gamma_, b = 1.0 - t;
    for (int i = 0; i < n_; ++i) {
      const int d = degrees_[i];
      const Complex x0_power = power(X0, d - 1), xi_power = power(X[i + 1], d - 1);
      const Complex fh = x0_power * X0 * fv[i];
      const Complex gh = xi_power * X[i + 1] - x0_power * X0;
      Complex euler = static_cast<double>(d) * fv[i];
      const Complex b_x0_power = b * x0_power;
      for (int j = 0; j < n_; ++j) {
        euler -= u[j] * fj(i, j);
        HX(i, j + 1) = b_x0_power * fj(i, j);
      }
      HX(i, 0) = b_x0_power * euler - a * static_cast<double>(d) * x0_power;
      HX(i, i + 1) += a * static_cast<double>(d) * xi_power;
      H[i] = a * gh + b * fh;
      Ht[i] = gamma_ * gh - fh;
    }
    Complex on_patch = -1.0;
    for (int j = 0; j <= n_; ++j) {
      on_patch += patch_[j] * X[j];
      HX(n_, j) = patch_[j];
    }
    H[n_] = on_patch;
    Ht[n_] = 0;
  }

  //! dX/dτ = −H_X⁻¹ H_t · dt/dτ along the path.
  bool velocity(const Vec& X, const TPath& path, double tau, Vec& v) {
    Vec H, Ht;
    Mat HX;
    evaluate(X, path.at(tau), H, HX, Ht);
    Eigen::PartialPivLU<Mat> lu(HX);
    v = -lu.solve(Ht) * path.derivative(tau);
    return finite(v);
  }

  //! Classical Runge–Kutta step from τ to τ + h.
  bool predict(const Vec& X, const TPath& path, double tau, double h, Vec& out) {
    Vec k1, k2, k3, k4;
    if (!velocity(X, path, tau, k1)) return false;
    if (!velocity(X + (h / 2) * k1, path, tau + h / 2, k2)) return false;
    if (!velocity(X + (h / 2) * k2, path, tau + h / 2, k3)) return false;
    if (!velocity(X + h * k3, path, tau + h, k4)) return false;
    out = X + (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
    return finite(out);
  }

  //! Newton on H(·, t) from X; true if it converges within the settings' iterations.
  bool correct(Vec& X, Complex t) {
    Vec H, Ht;
    Mat HX;
    for (int k = 0; k < settings_.corrector_iterations; ++k) {
      evaluate(X, t, H, HX, Ht);
      if (!finite(H) || !HX.allFinite()) return false;
      Eigen::PartialPivLU<Mat> lu(HX);
      const Vec delta = -lu.solve(H);
      if (!finite(delta)) return false;
      X += delta;
      const double scale = norm(X), size = norm(delta);
      if (k == 0 && size > settings_.corrector_trust * scale) return false;
      if (size <= settings_.corrector_tolerance * scale) return true;
    }
    return false;
  }

  //! Newton on H(·, t) past the corrector's tolerance, to (near) full double accuracy: the Cauchy
  //! estimate is a mean of these samples and cannot be more accurate than they are.
  void refine(Vec& X, Complex t) {
    Vec H, Ht;
    Mat HX;
    double last = std::numeric_limits<double>::infinity();
    for (int k = 0; k < tolerances::homotopy_refine_iterations; ++k) {
      evaluate(X, t, H, HX, Ht);
      Eigen::PartialPivLU<Mat> lu(HX);
      const Vec delta = -lu.solve(H);
      const double size = norm(delta);
      if (!finite(delta) || size > last) return;
      X += delta;
      last = size;
      if (size <= tolerances::homotopy_refine_converged_ulps * eps * norm(X)) return;
    }
  }

  //! Tracks X along t = path(τ) from τ = 0 to τ = length with adaptive steps of at most max_step
  //! (h: the current step, carried from call to call).  False if a step underflows, the step
  //! budget (settings.max_steps per path, and at most `budget` steps in this call) runs out, or
  //! the settings' deadline has passed (then end.stopped is set); *reached (if given) is the τ
  //! reached.
  bool run(const TPath& path, double length, double max_step, Vec& X, double& h, PathEndpoint& end,
           double* reached = nullptr, std::size_t budget = std::numeric_limits<std::size_t>::max()) {
    const std::size_t limit = std::min(settings_.max_steps, end.steps + end.rejections + std::min(budget, settings_.max_steps));
    double tau = 0;
    int successes = 0;
    bool ok = true;
    while (tau < length) {
      if (end.steps + end.rejections >= limit) {
        ok = false;
        break;
      }
      if (settings_.deadline && std::chrono::steady_clock::now() >= *settings_.deadline) {
        end.stopped = true;
        ok = false;
        break;
      }
      h = std::min(h, max_step);
      const bool last = h >= length - tau;
      const double step = last ? length - tau : h;
      const double tau_new = last ? length : tau + h;
      Vec next(n_ + 1);
      if (predict(X, path, tau, step, next) && correct(next, path.at(tau_new))) {
        X = next;
        tau = tau_new;
        ++end.steps;
        if (++successes >= tolerances::homotopy_step_growth_successes) {
          h = std::min(2 * h, max_step);
          successes = 0;
        }
      } else {
        ++end.rejections;
        successes = 0;
        h = step / 2;
        if (h < settings_.min_step) {
          ok = false;
          break;
        }
      }
    }
    if (reached) *reached = tau;
    return ok;
  }

  //! From X at t = t_k (real): the loops t = t_k e^{iθ}, M samples per loop, until the path closes
  //! up.  closed: c is the winding number, estimate the mean of the c·M samples (the trapezoid
  //! rule for the Cauchy integral) and X is back at θ = 0.  diverging: a sample is at infinity.
  //! failed (no closure within the cap, or a step failed): X is reset to where the loops started
  //! (after unclosed loops the tracked point is on another path).
  LoopOutcome loops(Vec& X, double t, double& h, PathEndpoint& end, int& c, Vec& estimate, double& spread) {
    const int samples = settings_.endgame_samples;
    const double arc = 2 * M_PI / samples;
    const Vec first = X;
    Vec sum = Vec::Zero(n_ + 1);
    spread = 0;
    for (int loop = 1; loop <= settings_.endgame_max_winding; ++loop) {
      double spacing = std::numeric_limits<double>::infinity();
      for (int j = 0; j < samples; ++j) {
        sum += X;
        const Vec previous = X;
        const TPath path{std::polar(t, arc * ((loop - 1) * samples + j)), Complex(0, 1), true};
        if (!run(path, arc, arc, X, h, end)) {
          X = first;
          return LoopOutcome::failed;
        }
        refine(X, path.at(arc));
        if (!finite(X)) {
          X = first;
          return LoopOutcome::failed;
        }
        if (at_infinity(X)) return LoopOutcome::diverging;
        spacing = std::min(spacing, norm(Vec(X - previous)));
        spread = std::max(spread, norm(Vec(X - first)));
      }
      // Closed: back at the first sample, up to a small fraction of the distance between two
      // successive samples (one loop short of closing, the path is on another branch, at least
      // about that distance away) or up to round-off.
      const double gap = norm(Vec(X - first));
      if (gap <= settings_.endgame_closure * spacing || gap <= tolerances::homotopy_loop_closure_ulps * eps * norm(first)) {
        c = loop;
        estimate = sum / static_cast<double>(loop * samples);
        return LoopOutcome::closed;
      }
    }
    X = first;
    return LoopOutcome::failed;
  }

  //! The valuations ν_j = Re(t X_j'(t) / X_j(t)) of the homogeneous coordinates at real t (along a
  //! Puiseux series X_j ~ a_j t^{ν_j}, this tends to ν_j), shifted so that the smallest is 0; a
  //! coordinate below homotopy_valuation_floor ‖X‖∞ gets NaN (too small to estimate).  False if the
  //! velocity is not finite.
  bool valuations(const Vec& X, double t, RealVec& nu) {
    Vec v;
    if (!velocity(X, TPath{t, -1.0, true}, 0, v)) return false;  // v = dX/dτ = −t X'(t)
    const double scale = norm(X);
    nu.resize(n_ + 1);
    double smallest = std::numeric_limits<double>::infinity();
    for (int j = 0; j <= n_; ++j) {
      nu[j] = std::abs(X[j]) > tolerances::homotopy_valuation_floor * scale ? -(v[j] / X[j]).real()
                                                                              : std::numeric_limits<double>::quiet_NaN();
      if (nu[j] < smallest) smallest = nu[j];
    }
    nu.array() -= smallest;
    return true;
  }

  //! The limit of a sequence ν_0, ν_1, ν_2 converging geometrically (Aitken's Δ²), or NaN when
  //! the last two differences do not look geometric with ratio in (0, homotopy_aitken_max_ratio]
  //! (a last difference of at most homotopy_aitken_settled: the last value).
  static double aitken(const double (&h)[3]) {
    const double d1 = h[1] - h[0], d2 = h[2] - h[1];
    if (std::abs(d2) <= tolerances::homotopy_aitken_settled) return h[2];
    const double r = d2 / d1;
    if (!(r > 0 && r <= tolerances::homotopy_aitken_max_ratio)) return std::numeric_limits<double>::quiet_NaN();
    return h[2] + d2 * r / (1 - r);
  }

  //! The valuation estimates of the endgame's levels so far.
  struct ValuationHistory {
    RealVec nu, previous;
    double nu0[3] = {0, 0, 0};  // ν_0 at the last three levels (∞ where X_0 ≈ 0)
    int stable_levels = 0;      // successive levels whose estimates changed by ≤ endgame_valuation_stable
  };

  //! The Cauchy estimates of the endgame's levels so far.
  struct EstimateHistory {
    Vec estimate, previous;
    bool have_previous = false;
    int previous_c = 0;
    double previous_spread = 0;
    bool tried_direct = false;  // the direct finish was tried (it is tried once)
  };

  //! The valuations at X, t_k (level k) added to `history`; false if the velocity is not finite.
  bool update_valuations(const Vec& X, double t, int level, ValuationHistory& history) {
    if (!valuations(X, t, history.nu)) return false;
    double change = std::numeric_limits<double>::infinity();
    if (level > 0) {
      change = 0;
      for (int j = 0; j <= n_; ++j)
        if (!std::isnan(history.nu[j]) && !std::isnan(history.previous[j]))
          change = std::max(change, std::abs(history.nu[j] - history.previous[j]));
    }
    history.previous = history.nu;
    history.stable_levels = change <= settings_.endgame_valuation_stable ? history.stable_levels + 1 : 0;
    history.nu0[0] = history.nu0[1];
    history.nu0[1] = history.nu0[2];
    history.nu0[2] = std::isnan(history.nu[0]) ? std::numeric_limits<double>::infinity() : history.nu[0];
    return true;
  }

  //! The valuation test for infinity: at t_k ≤ endgame_valuation_max_t, estimates stable at three
  //! levels, and ν_0 and its Aitken limit ≥ endgame_valuation_infinity.
  bool diverges_by_valuation(double t, const ValuationHistory& history) const {
    const double v = settings_.endgame_valuation_infinity;
    return t <= settings_.endgame_valuation_max_t && history.stable_levels >= 3 && history.nu0[2] >= v &&
           aitken(history.nu0) >= v;
  }

  //! After the loops around t_k closed with winding number c (estimate and spread in `history`):
  //! with c = 1 the direct finish is tried once; then the estimate is accepted (and classified)
  //! when it agrees with the previous one to endgame_tolerance and, for c > 1, the sheets close in
  //! (spread shrinking, branches_meet()).  True when the endgame has concluded (end filled).
  bool conclude(const Vec& X, double t, int c, double spread, EstimateHistory& history, PathEndpoint& end) {
    if (c == 1 && !history.tried_direct) {  // no branching around |t| ≤ t_k: try to finish directly
      history.tried_direct = true;
      if (direct_finish(X, t, end)) return true;
    }
    if (history.have_previous) {
      const double delta = norm(Vec(history.estimate - history.previous));
      // c > 1: the c sheets must also be closing in on one point, their spread shrinking like
      // t^{1/c}; a spread that does not shrink means the loops still enclose a branch point away
      // from t = 0 (the "estimate" is then a mean of distinct endpoints)
      const bool shrinking =
          c == 1 || (c == history.previous_c &&
                     spread <= 0.5 * (1 + std::pow(settings_.endgame_ratio, 1.0 / c)) * history.previous_spread);
      if (shrinking && delta <= settings_.endgame_tolerance * norm(history.estimate) &&
          (c == 1 || branches_meet(history.estimate))) {
        classify(history.estimate, delta, end);
        return true;
      }
    }
    history.previous = history.estimate;
    history.previous_c = c;
    history.previous_spread = spread;
    history.have_previous = true;
    return false;
  }

  //! The Cauchy endgame from X at t_0 = 1 − endgame_start (see homotopy_tracker.h).  At each level
  //! t_k: refine X, update the valuations (update_valuations()) and test for infinity; where X_0
  //! does not visibly go to 0, try the direct finish once at t_0, and once the valuations have
  //! settled run the loops (loops()) and weigh their estimate (conclude()); then go on to t_{k+1}.
  void cauchy_endgame(Vec X, PathEndpoint& end) {
    const double radial = -std::log(settings_.endgame_ratio);  // τ length from t_k to t_{k+1}
    double t = 1 - settings_.endgame_start;
    double loop_h = 2 * M_PI / settings_.endgame_samples, radial_h = radial;
    ValuationHistory valuation;
    EstimateHistory estimates;
    const auto fail = [&](const Vec& at) {
      end.outcome = PathOutcome::failed;
      end.point = affine(at);
    };
    const auto diverging = [&](const Vec& at) {
      end.outcome = PathOutcome::diverging;
      end.point = affine(at);
    };
    for (int level = 0;; ++level) {
      end.s = 1 - t;
      refine(X, t);
      if (!finite(X)) return fail(X);
      if (at_infinity(X)) return diverging(X);
      if (!update_valuations(X, t, level, valuation)) return fail(X);
      if (diverges_by_valuation(t, valuation)) return diverging(X);
      const bool finite_end = valuation.nu0[2] < settings_.endgame_valuation_infinity;  // X_0 not visibly → 0
      if (finite_end && level == 0 && !estimates.tried_direct) {
        estimates.tried_direct = true;
        if (direct_finish(X, t, end)) return;
      }
      if (finite_end && valuation.stable_levels >= 1) {
        int c = 0;
        double spread = 0;
        switch (loops(X, t, loop_h, end, c, estimates.estimate, spread)) {
          case LoopOutcome::failed:
            if (end.steps + end.rejections >= settings_.max_steps) return fail(X);
            estimates.have_previous = false;  // not closed: not in the endgame's operating zone yet
            break;
          case LoopOutcome::diverging: return diverging(X);
          case LoopOutcome::closed:
            end.winding = c;
            if (!finite(estimates.estimate)) return fail(X);
            if (conclude(X, t, c, spread, estimates, end)) return;
            break;
        }
      }
      const TPath inward{t, -1.0, true};
      if (t * settings_.endgame_ratio < settings_.endgame_min_t)
        return fail(estimates.have_previous ? estimates.estimate : X);
      if (!run(inward, radial, radial, X, radial_h, end)) return fail(X);
      t = inward.at(radial).real();
    }
  }

  //! Newton on f in the affine chart from u0: may not carry the point far from u0 (that would be
  //! a jump to another root).  Returns the last correction (∞ if none was taken).
  double newton(AffineVec& u) {
    // A regular zero converges quadratically; a singular one only linearly, hence the budget.
    constexpr int newton_budget = tolerances::homotopy_endpoint_newton_iterations;
    constexpr double max_travel = tolerances::homotopy_endpoint_newton_travel;
    const AffineVec u0 = u;
    AffineVec fv;
    AffineMat fj;
    double last = std::numeric_limits<double>::infinity();
    for (int k = 0; k < newton_budget; ++k) {
      evaluate_f(u, fv, fj);
      Eigen::PartialPivLU<AffineMat> lu(fj);
      const AffineVec delta = -lu.solve(fv);
      if (!finite(delta)) break;
      const double size = norm(delta);
      if (size > last && k >= tolerances::homotopy_newton_noise_after_steps) break;  // round-off, or running away
      const AffineVec next = u + delta;
      if (norm(AffineVec(next - u0)) > max_travel * (1 + norm(u0))) break;
      u = next;
      last = size;
      if (size <= tolerances::homotopy_newton_converged_ulps * eps * (1 + norm(u))) break;
    }
    return last;
  }

  //! 2-norm condition number σ_max / σ_min of J_f at u (∞ if σ_min = 0).  Rows are not
  //! equilibrated: at a singular point of Σ a Jacobian row can vanish up to round-off, and scaling
  //! it to unit length would hide exactly the singularity this must detect.
  double condition(const AffineVec& u) {
    AffineVec fv;
    AffineMat J;
    evaluate_f(u, fv, J);
    if (!J.allFinite()) return std::numeric_limits<double>::infinity();
    Eigen::JacobiSVD<AffineMat> svd(J);
    const auto& sigma = svd.singularValues();
    const double smallest = sigma[n_ - 1];
    return smallest > 0 ? sigma[0] / smallest : std::numeric_limits<double>::infinity();
  }

  //! ‖J_f(u)⁻¹ f(u)‖∞, the Newton correction at u (∞ if it is not finite): where J_f is well
  //! conditioned, about the distance from u to the nearest zero of f.
  double newton_step(const AffineVec& u) {
    AffineVec fv;
    AffineMat fj;
    evaluate_f(u, fv, fj);
    const AffineVec delta = Eigen::PartialPivLU<AffineMat>(fj).solve(fv);
    return finite(delta) ? norm(delta) : std::numeric_limits<double>::infinity();
  }

  //! What Newton on f finds from an endpoint estimate.
  enum class EndpointTest {
    regular,          //!< a zero of f with a well-conditioned Jacobian
    ill_conditioned,  //!< J_f is ill conditioned there (condition > singular_condition)
    not_a_zero        //!< J_f is well conditioned but the Newton correction is not small: not a zero
  };

  //! Newton on f from u (newton()).  Regular if the Jacobian there is well conditioned and the
  //! Newton correction at the refined point is at most homotopy_endpoint_newton_step (relative to
  //! 1 + ‖u‖∞); then fills end (finite).  The correction is the residual f(u) measured in u, so a
  //! point where Newton stalled, or was stopped from travelling, is not taken for a zero.
  EndpointTest regular_endpoint(AffineVec u, PathEndpoint& end) {
    const double last = newton(u);
    const double kappa = condition(u);
    if (!(kappa <= settings_.singular_condition)) return EndpointTest::ill_conditioned;
    if (!(newton_step(u) <= tolerances::homotopy_endpoint_newton_step * (1 + norm(u))))
      return EndpointTest::not_a_zero;
    end.outcome = PathOutcome::finite;
    end.point.assign(u.data(), u.data() + n_);
    end.condition = kappa;
    end.last_correction = last;
    return EndpointTest::regular;
  }

  //! Tracks the segment from t_k straight to t = 0 (at most endgame_direct_steps steps) and accepts
  //! its end if it is a regular zero of f.  At a regular endpoint this replaces the further levels
  //! of the Cauchy endgame; otherwise (steps fail near a singular endpoint, or the end is ill
  //! conditioned) the endgame goes on from X.
  bool direct_finish(const Vec& X, double t, PathEndpoint& end) {
    Vec Y = X;
    double h = 1;
    if (!run(TPath{t, -t, false}, 1.0, 1.0, Y, h, end, nullptr, settings_.endgame_direct_steps)) return false;
    if (!finite(Y) || at_infinity(Y)) return false;
    const std::vector<Complex> u = affine(Y);
    if (regular_endpoint(Eigen::Map<const AffineVec>(u.data(), n_), end) != EndpointTest::regular) return false;
    end.s = 1;
    return true;
  }

  //! For an estimate X̂ from c > 1 loops: true if X̂ is at infinity or J_f is ill conditioned at it
  //! (condition ≥ cluster_condition), as at a zero where c paths meet.  Loops that still enclose a
  //! branch point away from t = 0, where two paths to distinct regular zeros swap, also close after
  //! c > 1 loops, and their mean (the centroid of those zeros) converges too, but J_f is well
  //! conditioned there: the endgame must then go on to smaller t.
  bool branches_meet(const Vec& estimate) {
    if (at_infinity(estimate)) return true;
    const std::vector<Complex> u = affine(estimate);
    return condition(Eigen::Map<const AffineVec>(u.data(), n_)) >= settings_.cluster_condition;
  }

  //! Classifies a converged Cauchy estimate X̂ (change: the last change of the estimate).
  void classify(const Vec& estimate, double change, PathEndpoint& end) {
    end.point = affine(estimate);
    if (at_infinity(estimate)) {
      end.outcome = PathOutcome::diverging;
      return;
    }
    AffineVec u(n_);
    for (int j = 0; j < n_; ++j) u[j] = end.point[j];
    // u = X'/X_0: an error δ in X̂ is an error of about δ (1 + ‖u‖) / |X_0| in u
    const double accuracy = change * (1 + norm(u)) / std::abs(estimate[0]);
    if (end.winding == 1) {
      switch (regular_endpoint(u, end)) {
        case EndpointTest::regular: return;
        case EndpointTest::not_a_zero:  // the estimates agreed, but not on a zero of f
          end.outcome = PathOutcome::failed;
          end.last_correction = accuracy;
          return;
        case EndpointTest::ill_conditioned: break;
      }
    }
    // c > 1 (a branch point: the endpoint is singular) or an ill-conditioned Jacobian: the Cauchy
    // estimate, more accurate than Newton (only linear at a singular zero), if it is a zero of f
    end.outcome = near_a_zero(u) ? PathOutcome::singular : PathOutcome::failed;
    end.condition = condition(u);
    end.last_correction = accuracy;
  }

  //! The residual test of a singular endpoint estimate u: ‖f(u)‖∞ ≤
  //! settings.singular_residual · (1 + ‖u‖∞) · ‖J_f(u)‖∞ (the operator norm, maximal row
  //! sum).  About the distance to the nearest zero where J_f is singular as well as where it is not.
  bool near_a_zero(const AffineVec& u) {
    AffineVec fv;
    AffineMat fj;
    evaluate_f(u, fv, fj);
    if (!finite(fv) || !fj.allFinite()) return false;
    const double jacobian_norm = fj.cwiseAbs().rowwise().sum().maxCoeff();
    return fv.cwiseAbs().maxCoeff() <= settings_.singular_residual * (1 + norm(u)) * jacobian_norm;
  }

  const CompiledSystem& f_;
  const std::vector<int>& degrees_;
  const std::vector<Complex>& parameters_;
  Complex gamma_;
  const std::vector<Complex>& patch_;
  const TrackerSettings& settings_;
  int n_;
  std::vector<Complex> values_, jacobian_;
};

}  // namespace

std::optional<std::vector<Complex>> HomotopyTracker::point_at(const std::vector<Complex>& start, double t_stop,
                                                               const TrackerSettings& settings) const {
  if (!(t_stop > 0 && t_stop < 1)) throw PreconditionViolation("HomotopyTracker::point_at: t_stop must lie in (0, 1)");
  if (degrees_.size() <= 3)
    return PathTracker<3>(f_, degrees_, parameters_, gamma_, patch_, settings).point_at(start, t_stop);
  return PathTracker<Eigen::Dynamic>(f_, degrees_, parameters_, gamma_, patch_, settings).point_at(start, t_stop);
}

PathEndpoint HomotopyTracker::track(const std::vector<Complex>& start, const TrackerSettings& settings) const {
  // The built-in primitives have at most three unknowns: one stack-sized tracker serves
  // n = 1, 2, 3 (its sizes are dynamic up to the maximum), a heap-sized one anything larger.
  if (degrees_.size() <= 3) return PathTracker<3>(f_, degrees_, parameters_, gamma_, patch_, settings).track(start);
  return PathTracker<Eigen::Dynamic>(f_, degrees_, parameters_, gamma_, patch_, settings).track(start);
}

}  // namespace delmesh::detail
