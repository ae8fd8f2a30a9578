#include "solvers/gradient_cone.h"

#include <algorithm>
#include <cstdint>

#include "common/errors.h"
#include "symbolic/scalar_traits.h"
#include "symbolic/scalar_types.h"

namespace delmesh {

namespace {

// ⟨g, v⟩ for an interval vector g and a point vector v of ℝ³.
Interval inner(const Interval* g, const std::array<double, 3>& v) { return g[0] * v[0] + g[1] * v[1] + g[2] * v[2]; }

}  // namespace

AffineChart AffineChart::identity() {
  AffineChart chart;
  chart.columns = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  return chart;
}

GradientConeResult prove_gradient_cone(const CompiledSystem& E, const AffineChart& chart, const Domain& domain,
                                       const std::array<double, 3>& w, std::size_t box_budget) {
  const std::size_t n = domain.dimension();
  if (chart.columns.size() != n || n < 1 || n > 3)
    throw PreconditionViolation("prove_gradient_cone: the chart's columns must match the domain's dimension");
  if (E.n_equations() != 1 || E.n_unknowns() != 3 || E.n_parameters() != 0)
    throw PreconditionViolation("prove_gradient_cone: E must be one equation in (x, y, z) without parameters");

  RoundingGuard guard;
  GradientConeResult result;
  const bool with_hessians = E.has_hessians();
  // A box with whether it is known to lie inside P (then so do its halves: classify() is not
  // asked again), and the half-spaces not yet known to contain it (classify()'s mask).
  struct Box {
    std::array<Interval, 3> u;
    bool inside = false;
    std::uint64_t active = 0;
  };
  std::vector<Box> stack(1);
  stack.reserve(64);
  stack[0].active = all_half_spaces_active(domain);
  for (std::size_t j = 0; j < n; ++j) stack[0].u[j] = Interval(domain.box.bounds[j][0], domain.box.bounds[j][1]);
  // The world enclosure of chart points: origin + Σ_j u_j c_j, with u_j an interval or a point.
  auto to_world = [&](const Interval* u, Interval* x) {
    for (int k = 0; k < 3; ++k) {
      x[k] = Interval(chart.origin[k]);
      for (std::size_t j = 0; j < n; ++j) x[k] += u[j] * chart.columns[j][k];
    }
  };
  while (!stack.empty()) {
    const Box box = stack.back();
    stack.pop_back();
    if (result.boxes >= box_budget) return result;
    ++result.boxes;
    const auto& u = box.u;
    std::uint64_t active = box.active;
    const DomainSide side = box.inside ? DomainSide::inside : classify(domain, u.data(), active);
    if (side == DomainSide::outside) continue;  // (i)
    Interval x[3], value, gradient[3];
    to_world(u.data(), x);
    E.values_and_jacobian<Interval>(x, nullptr, &value, gradient);
    // (iii) first: on most boxes that meet Σ the functional is what decides; then (ii)'s
    // natural form.
    if (certainly_nonzero(inner(gradient, w)) || certainly_nonzero(value)) continue;
    // (ii) mean-value form around the box centre.
    Interval centre[3], centre_world[3], centre_value, centre_gradient[3];
    for (std::size_t j = 0; j < n; ++j) centre[j] = Interval(CGAL::to_double(u[j]));
    to_world(centre, centre_world);
    if (with_hessians)
      E.values_and_jacobian<Interval>(centre_world, nullptr, &centre_value, centre_gradient);
    else
      E.values<Interval>(centre_world, nullptr, &centre_value);
    Interval mean_value = centre_value;
    for (std::size_t j = 0; j < n; ++j) mean_value += inner(gradient, chart.columns[j]) * (u[j] - centre[j]);
    if (certainly_nonzero(mean_value)) continue;
    // (iii′) the functional's mean-value form, on a box that may meet Σ.
    if (with_hessians) {
      Interval hessian[9], hessian_w[3];  // H(X) and H(X) w, the functional's gradient
      E.hessians<Interval>(x, nullptr, hessian);
      for (int k = 0; k < 3; ++k) hessian_w[k] = inner(hessian + 3 * k, w);
      Interval mean_functional = inner(centre_gradient, w);
      for (std::size_t j = 0; j < n; ++j) mean_functional += inner(hessian_w, chart.columns[j]) * (u[j] - centre[j]);
      if (certainly_nonzero(mean_functional)) continue;
    }
    // Bisect along the widest side; a side that no longer splits ends the attempt.
    std::size_t widest = 0;
    for (std::size_t j = 1; j < n; ++j)
      if (u[j].sup() - u[j].inf() > u[widest].sup() - u[widest].inf()) widest = j;
    const double lo = u[widest].inf(), hi = u[widest].sup(), mid = 0.5 * (lo + hi);
    if (!(lo < mid && mid < hi)) return result;
    Box left{u, side == DomainSide::inside, active}, right = left;
    left.u[widest] = Interval(lo, mid);
    right.u[widest] = Interval(mid, hi);
    stack.push_back(right);
    stack.push_back(left);
  }
  result.proved = true;
  return result;
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
