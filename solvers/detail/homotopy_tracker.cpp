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
                                 std::vector<Complex> parameters, Complex gamma)
    : f_(f), degrees_(std::move(degrees)), parameters_(std::move(parameters)), gamma_(gamma) {}

namespace {

//! The tracking loop for systems of at most MaxN unknowns (Eigen::Dynamic: any n).  Fixed maximal
//! sizes keep every vector and matrix on the stack.
template <int MaxN>
class PathTracker {
 public:
  using Vec = Eigen::Matrix<Complex, Eigen::Dynamic, 1, 0, MaxN, 1>;
  using Mat = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic, 0, MaxN, MaxN>;

  PathTracker(const CompiledSystem& f, const std::vector<int>& degrees, const std::vector<Complex>& parameters,
              Complex gamma)
      : f_(f), degrees_(degrees), parameters_(parameters), gamma_(gamma), n_(static_cast<int>(degrees.size())),
        values_(n_), jacobian_(static_cast<std::size_t>(n_) * n_) {}

  PathEndpoint track(const std::vector<Complex>& start, const TrackerSettings& settings) {
    PathEndpoint end;
    Vec u(n_);
    for (int i = 0; i < n_; ++i) u[i] = start[i];
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
      Vec next(n_);
      if (predict(u, s, s_new - s, next) && correct(next, s_new, settings)) {
        u = next;
        s = s_new;
        ++end.steps;
        if (++successes >= 2) {
          h = std::min(2 * h, settings.max_step);
          successes = 0;
        }
        if (s >= settings.endgame_start && u.cwiseAbs().maxCoeff() > settings.divergence_norm) {
          end.outcome = PathOutcome::diverging;
          end.s = s;
          end.point.assign(u.data(), u.data() + n_);
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
      end.point.assign(u.data(), u.data() + n_);
      return end;
    }
    endgame(u, stuck, settings, end);
    return end;
  }

 private:
  double norm(const Vec& v) const { return v.cwiseAbs().maxCoeff(); }

  //! f and J_f at u into fv, fj.
  void evaluate_f(const Vec& u, Vec& fv, Mat& fj) {
    f_.values_and_jacobian<Complex>(u.data(), parameters_.data(), values_.data(), jacobian_.data());
    fv.resize(n_);
    fj.resize(n_, n_);
    for (int i = 0; i < n_; ++i) {
      fv[i] = values_[i];
      for (int j = 0; j < n_; ++j) fj(i, j) = jacobian_[static_cast<std::size_t>(i) * n_ + j];
    }
  }

  //! H, H_u and H_s at (u, s).
  void evaluate(const Vec& u, double s, Vec& H, Mat& Hu, Vec& Hs) {
    Vec fv;
    Mat fj;
    evaluate_f(u, fv, fj);
    H.resize(n_);
    Hs.resize(n_);
    Hu = s * fj;
    for (int i = 0; i < n_; ++i) {
      const Complex power_minus_one = std::pow(u[i], degrees_[i] - 1);
      const Complex g = power_minus_one * u[i] - 1.0;
      const Complex dg = static_cast<double>(degrees_[i]) * power_minus_one;
      H[i] = (1 - s) * gamma_ * g + s * fv[i];
      Hs[i] = fv[i] - gamma_ * g;
      Hu(i, i) += (1 - s) * gamma_ * dg;
    }
  }

  static bool finite(const Vec& v) { return v.allFinite(); }

  //! du/ds = −H_u⁻¹ H_s.
  bool velocity(const Vec& u, double s, Vec& v) {
    Vec H, Hs;
    Mat Hu;
    evaluate(u, s, H, Hu, Hs);
    Eigen::PartialPivLU<Mat> lu(Hu);
    v = -lu.solve(Hs);
    return finite(v);
  }

  //! Classical Runge–Kutta step of length h from (u, s).
  bool predict(const Vec& u, double s, double h, Vec& out) {
    Vec k1, k2, k3, k4;
    if (!velocity(u, s, k1)) return false;
    if (!velocity(u + (h / 2) * k1, s + h / 2, k2)) return false;
    if (!velocity(u + (h / 2) * k2, s + h / 2, k3)) return false;
    if (!velocity(u + h * k3, s + h, k4)) return false;
    out = u + (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
    return finite(out);
  }

  //! Newton on H(·, s) from u; true if it converges within the settings' iterations.
  bool correct(Vec& u, double s, const TrackerSettings& settings) {
    Vec H, Hs;
    Mat Hu;
    for (int k = 0; k < settings.corrector_iterations; ++k) {
      evaluate(u, s, H, Hu, Hs);
      Eigen::PartialPivLU<Mat> lu(Hu);
      const Vec delta = -lu.solve(H);
      if (!finite(delta)) return false;
      u += delta;
      const double scale = 1 + norm(u), size = norm(delta);
      if (k == 0 && size > settings.corrector_trust * scale) return false;
      if (size <= settings.corrector_tolerance * scale) return true;
    }
    return false;
  }

  //! 2-norm condition number of J with rows scaled to unit length (∞ if a row vanishes).
  double condition(const Mat& J) const {
    Mat scaled = J;
    for (int i = 0; i < n_; ++i) {
      const double r = scaled.row(i).norm();
      if (!(r > 0) || !std::isfinite(r)) return std::numeric_limits<double>::infinity();
      scaled.row(i) /= r;
    }
    Eigen::JacobiSVD<Mat> svd(scaled);
    const auto& sigma = svd.singularValues();
    const double smallest = sigma[n_ - 1];
    return smallest > 0 ? sigma[0] / smallest : std::numeric_limits<double>::infinity();
  }

  //! At (or near) s = 1: Newton on f itself, then classify by norm and conditioning.
  void endgame(Vec u, bool stuck, const TrackerSettings& settings, PathEndpoint& end) {
    // A regular zero converges quadratically; a singular one only linearly, hence the budget.
    constexpr int newton_budget = 60;
    constexpr double eps = std::numeric_limits<double>::epsilon();
    Vec fv;
    Mat fj;
    double last = std::numeric_limits<double>::infinity();
    bool converged = false;
    for (int k = 0; k < newton_budget; ++k) {
      evaluate_f(u, fv, fj);
      Eigen::PartialPivLU<Mat> lu(fj);
      const Vec delta = -lu.solve(fv);
      if (!finite(delta)) break;
      const double size = norm(delta);
      // Stop when Newton stops improving (round-off level) or diverges away.
      if (size > last && k > 2) break;
      u += delta;
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
    const double size = norm(u);
    if (!std::isfinite(size) || size > settings.divergence_norm ||
        (stuck && !converged && size > std::sqrt(settings.divergence_norm))) {
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
  int n_;
  std::vector<Complex> values_, jacobian_;
};

}  // namespace

PathEndpoint HomotopyTracker::track(const std::vector<Complex>& start, const TrackerSettings& settings) const {
  switch (degrees_.size()) {
    case 1: return PathTracker<1>(f_, degrees_, parameters_, gamma_).track(start, settings);
    case 2: return PathTracker<2>(f_, degrees_, parameters_, gamma_).track(start, settings);
    case 3: return PathTracker<3>(f_, degrees_, parameters_, gamma_).track(start, settings);
    default: return PathTracker<Eigen::Dynamic>(f_, degrees_, parameters_, gamma_).track(start, settings);
  }
}

}  // namespace delmesh::detail
