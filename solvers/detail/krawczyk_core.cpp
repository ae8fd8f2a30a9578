#include "solvers/detail/krawczyk_core.h"

#include <cmath>

#include <Eigen/Dense>

#include "solvers/detail/interval_box.h"

namespace delmesh::detail {

bool invert_matrix(std::size_t n, const double* a, double* inverse) {
  if (n == 1) {
    inverse[0] = 1.0 / a[0];
    return a[0] != 0 && std::isfinite(inverse[0]);
  }
  if (n == 2) {
    const double det = a[0] * a[3] - a[1] * a[2];
    if (det == 0 || !std::isfinite(det)) return false;
    inverse[0] = a[3] / det, inverse[1] = -a[1] / det;
    inverse[2] = -a[2] / det, inverse[3] = a[0] / det;
  } else if (n == 3) {
    const double c00 = a[4] * a[8] - a[5] * a[7], c01 = a[5] * a[6] - a[3] * a[8], c02 = a[3] * a[7] - a[4] * a[6];
    const double det = a[0] * c00 + a[1] * c01 + a[2] * c02;
    if (det == 0 || !std::isfinite(det)) return false;
    const double r = 1.0 / det;
    inverse[0] = c00 * r, inverse[1] = (a[2] * a[7] - a[1] * a[8]) * r, inverse[2] = (a[1] * a[5] - a[2] * a[4]) * r;
    inverse[3] = c01 * r, inverse[4] = (a[0] * a[8] - a[2] * a[6]) * r, inverse[5] = (a[2] * a[3] - a[0] * a[5]) * r;
    inverse[6] = c02 * r, inverse[7] = (a[1] * a[6] - a[0] * a[7]) * r, inverse[8] = (a[0] * a[4] - a[1] * a[3]) * r;
  } else {
    using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    const Eigen::Map<const Matrix> A(a, static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    if (!A.allFinite()) return false;
    Eigen::FullPivLU<Matrix> lu(A);
    if (!lu.isInvertible()) return false;
    Eigen::Map<Matrix>(inverse, static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n)) = lu.inverse();
  }
  for (std::size_t i = 0; i < n * n; ++i)
    if (!std::isfinite(inverse[i])) return false;
  return true;
}

KrawczykOutcome krawczyk_compare(std::size_t n, const Interval* k, const Interval* x, Interval* contracted) {
  bool unique = true;
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isnan(k[i].inf()) && !std::isnan(k[i].sup()) && disjoint(k[i], x[i])) return KrawczykOutcome::no_root;
    if (!strictly_inside(k[i], x[i])) unique = false;
  }
  for (std::size_t i = 0; i < n; ++i)
    contracted[i] = is_finite(k[i]) ? intersection(k[i], x[i]) : x[i];
  return unique ? KrawczykOutcome::unique_root : KrawczykOutcome::inconclusive;
}

}  // namespace delmesh::detail
