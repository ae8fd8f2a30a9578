#include "solvers/detail/homotopy_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Dense>

#include "common/tolerances.h"

namespace delmesh::detail {

std::ostream& operator<<(std::ostream& out, PathOutcome outcome) {
  switch (outcome) {
    case PathOutcome::finite: return out << "finite";
    case PathOutcome::singular: return out << "singular";
    case PathOutcome::diverging: return out << "diverging";
    case PathOutcome::failed: return out << "failed";
  }
  return out << "PathOutcome(" << static_cast<int>(outcome) << ")";
}

TrackerSettings TrackerSettings::defaults() {
  namespace tol = tolerances;
  return {tol::homotopy_initial_step,        tol::homotopy_max_step,
          tol::homotopy_min_step,            tol::homotopy_corrector_tolerance,
          tol::homotopy_corrector_trust,     tol::homotopy_corrector_iterations,
          tol::homotopy_divergence_norm,     tol::homotopy_endgame_start,
          tol::homotopy_singular_condition,  tol::homotopy_max_steps_per_path};
}

TrackerSettings TrackerSettings::stricter() const {
  TrackerSettings s = *this;
  s.initial_step /= 10;
  s.max_step /= 10;
  s.corrector_trust /= 10;
  s.max_steps *= 4;
  return s;
}

HomotopyTracker::HomotopyTracker(const CompiledSystem& f, std::vector<int> degrees,
                                 std::vector<Complex> parameters, Complex gamma, std::vector<Complex> patch)
    : f_(f), degrees_(std::move(degrees)), parameters_(std::move(parameters)), gamma_(gamma),
      patch_(std::move(patch)) {}

namespace {

//! The tracking loop for systems of at most MaxN unknowns (Eigen::Dynamic: any n).  Fixed maximal
//! sizes keep every vector and matrix on the stack.
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

  PathTracker(const CompiledSystem& f, const std::vector<int>& degrees, const std::vector<Complex>& parameters,
              Complex gamma, const std::vector<Complex>& patch)
      : f_(f), degrees_(degrees), parameters_(parameters), gamma_(gamma), patch_(patch),
        n_(static_cast<int>(degrees.size())), values_(n_), jacobian_(static_cast<std::size_t>(n_) * n_) {}

  PathEndpoint track(const std::vector<Complex>& start, const TrackerSettings& settings) {
    PathEndpoint end;
    Vec X(n_ + 1);
    X[0] = 1;
    for (int i = 0; i < n_; ++i) X[i + 1] = start[i];
    Complex on_patch = 0;
    for (int j = 0; j <= n_; ++j) on_patch += patch_[j] * X[j];
    X /= on_patch;
    double s = 0, h = settings.initial_step;
    int successes = 0;
    bool stuck = false;
    while (s < 1) {
      if (end.steps + end.rejections >= settings.max_steps) {
        stuck = true;
        break;
      }
      h = std::min(h, 1 - s);
      const bool last = h >= 1 - s;
      const double s_new = last ? 1.0 : s + h;
      Vec next(n_ + 1);
      if (predict(X, s, s_new - s, next) && correct(next, s_new, settings)) {
        X = next;
        s = s_new;
        ++end.steps;
        if (++successes >= 2) {
          h = std::min(2 * h, settings.max_step);
          successes = 0;
        }
        if (s >= settings.endgame_start && at_infinity(X, settings)) {
          end.outcome = PathOutcome::diverging;
          end.s = s;
          end.point = affine(X);
          return end;
        }
      } else {
        ++end.rejections;
        successes = 0;
        h /= 2;
        if (h < settings.min_step) {
          stuck = true;
          break;
        }
      }
    }
    end.s = s;
    if (stuck && s < settings.endgame_start) {
      end.outcome = PathOutcome::failed;
      end.point = affine(X);
      return end;
    }
    endgame(X, stuck, settings, end);
    return end;
  }

 private:
  template <class V>
  static double norm(const V& v) {
    return v.cwiseAbs().maxCoeff();
  }
  template <class V>
  static bool finite(const V& v) {
    return v.allFinite();
  }

  bool at_infinity(const Vec& X, const TrackerSettings& settings) const {
    return std::abs(X[0]) * settings.divergence_norm < norm(X);
  }
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

  //! H, H_X and H_s at (X, s), the last row being the patch ⟨c, X⟩ − 1.
  void evaluate(const Vec& X, double s, Vec& H, Mat& HX, Vec& Hs) {
    const Complex X0 = X[0];
    AffineVec u(n_), fv;
    AffineMat fj;
    for (int j = 0; j < n_; ++j) u[j] = X[j + 1] / X0;
    evaluate_f(u, fv, fj);
    H.resize(n_ + 1);
    Hs.resize(n_ + 1);
    HX.setZero(n_ + 1, n_ + 1);
    const Complex a = (1 - s) * gamma_;
    for (int i = 0; i < n_; ++i) {
      const int d = degrees_[i];
      const Complex x0_power = std::pow(X0, d - 1), xi_power = std::pow(X[i + 1], d - 1);
      const Complex fh = x0_power * X0 * fv[i];
      const Complex gh = xi_power * X[i + 1] - x0_power * X0;
      Complex euler = static_cast<double>(d) * fv[i];
      for (int j = 0; j < n_; ++j) {
        euler -= u[j] * fj(i, j);
        HX(i, j + 1) = s * x0_power * fj(i, j);
      }
      HX(i, 0) = s * x0_power * euler - a * static_cast<double>(d) * x0_power;
      HX(i, i + 1) += a * static_cast<double>(d) * xi_power;
      H[i] = a * gh + s * fh;
      Hs[i] = fh - gamma_ * gh;
    }
    Complex on_patch = -1.0;
    for (int j = 0; j <= n_; ++j) {
      on_patch += patch_[j] * X[j];
      HX(n_, j) = patch_[j];
    }
    H[n_] = on_patch;
    Hs[n_] = 0;
  }

  //! dX/ds = −H_X⁻¹ H_s.
  bool velocity(const Vec& X, double s, Vec& v) {
    Vec H, Hs;
    Mat HX;
    evaluate(X, s, H, HX, Hs);
    Eigen::PartialPivLU<Mat> lu(HX);
    v = -lu.solve(Hs);
    return finite(v);
  }

  //! Classical Runge–Kutta step of length h from (X, s).
  bool predict(const Vec& X, double s, double h, Vec& out) {
    Vec k1, k2, k3, k4;
    if (!velocity(X, s, k1)) return false;
    if (!velocity(X + (h / 2) * k1, s + h / 2, k2)) return false;
    if (!velocity(X + (h / 2) * k2, s + h / 2, k3)) return false;
    if (!velocity(X + h * k3, s + h, k4)) return false;
    out = X + (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
    return finite(out);
  }

  //! Newton on H(·, s) from X; true if it converges within the settings' iterations.
  bool correct(Vec& X, double s, const TrackerSettings& settings) {
    Vec H, Hs;
    Mat HX;
    for (int k = 0; k < settings.corrector_iterations; ++k) {
      evaluate(X, s, H, HX, Hs);
      if (!finite(H) || !HX.allFinite()) return false;
      Eigen::PartialPivLU<Mat> lu(HX);
      const Vec delta = -lu.solve(H);
      if (!finite(delta)) return false;
      X += delta;
      const double scale = norm(X), size = norm(delta);
      if (k == 0 && size > settings.corrector_trust * scale) return false;
      if (size <= settings.corrector_tolerance * scale) return true;
    }
    return false;
  }

  //! 2-norm condition number σ_max / σ_min of J (∞ if σ_min = 0).  Rows are not equilibrated:
  //! at a singular point of Σ a Jacobian row can vanish up to round-off, and scaling it to unit
  //! length would hide exactly the singularity this must detect.
  double condition(const AffineMat& J) const {
    if (!J.allFinite()) return std::numeric_limits<double>::infinity();
    Eigen::JacobiSVD<AffineMat> svd(J);
    const auto& sigma = svd.singularValues();
    const double smallest = sigma[n_ - 1];
    return smallest > 0 ? sigma[0] / smallest : std::numeric_limits<double>::infinity();
  }

  //! At (or near) s = 1: a point at infinity is diverging; otherwise Newton on f itself in the
  //! affine chart, then classify by conditioning.  Newton may not carry the point far from where
  //! the path ended (that would be a jump to another root).
  void endgame(const Vec& X, bool stuck, const TrackerSettings& settings, PathEndpoint& end) {
    // A regular zero converges quadratically; a singular one only linearly, hence the budget.
    constexpr int newton_budget = 60;
    constexpr double eps = std::numeric_limits<double>::epsilon();
    constexpr double max_travel = 1e-3;  // relative to 1 + ‖u‖: farther is not this path's end
    end.point = affine(X);
    if (!finite(X) || X[0] == Complex(0) || at_infinity(X, settings)) {
      end.outcome = PathOutcome::diverging;
      return;
    }
    AffineVec u0(n_), fv;
    AffineMat fj;
    for (int j = 0; j < n_; ++j) u0[j] = end.point[j];
    AffineVec u = u0;
    double last = std::numeric_limits<double>::infinity();
    bool converged = false;
    for (int k = 0; k < newton_budget; ++k) {
      evaluate_f(u, fv, fj);
      Eigen::PartialPivLU<AffineMat> lu(fj);
      const AffineVec delta = -lu.solve(fv);
      if (!finite(delta)) break;
      const double size = norm(delta);
      if (size > last && k > 2) break;  // round-off level reached, or running away
      const AffineVec next = u + delta;
      if (norm(AffineVec(next - u0)) > max_travel * (1 + norm(u0))) break;
      u = next;
      last = size;
      if (size <= 4 * eps * (1 + norm(u))) {
        converged = true;
        break;
      }
    }
    evaluate_f(u, fv, fj);
    end.point.assign(u.data(), u.data() + n_);
    end.last_correction = last;
    end.condition = condition(fj);
    if (stuck && !converged && norm(u) > std::sqrt(settings.divergence_norm)) {
      end.outcome = PathOutcome::diverging;
    } else if (end.condition > settings.singular_condition || (stuck && !converged)) {
      end.outcome = PathOutcome::singular;
    } else {
      end.outcome = PathOutcome::finite;
    }
  }

  const CompiledSystem& f_;
  const std::vector<int>& degrees_;
  const std::vector<Complex>& parameters_;
  Complex gamma_;
  const std::vector<Complex>& patch_;
  int n_;
  std::vector<Complex> values_, jacobian_;
};

}  // namespace

PathEndpoint HomotopyTracker::track(const std::vector<Complex>& start, const TrackerSettings& settings) const {
  switch (degrees_.size()) {
    case 1: return PathTracker<1>(f_, degrees_, parameters_, gamma_, patch_).track(start, settings);
    case 2: return PathTracker<2>(f_, degrees_, parameters_, gamma_, patch_).track(start, settings);
    case 3: return PathTracker<3>(f_, degrees_, parameters_, gamma_, patch_).track(start, settings);
    default: return PathTracker<Eigen::Dynamic>(f_, degrees_, parameters_, gamma_, patch_).track(start, settings);
  }
}

}  // namespace delmesh::detail
