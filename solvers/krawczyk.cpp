#include "solvers/krawczyk.h"

#include <string>

#include "common/errors.h"
#include "solvers/detail/interval_box.h"
#include "solvers/detail/krawczyk_core.h"
#include "symbolic/scalar_traits.h"

namespace delmesh {

std::ostream& operator<<(std::ostream& out, KrawczykOutcome outcome) {
  switch (outcome) {
    case KrawczykOutcome::unique_root: return out << "unique_root";
    case KrawczykOutcome::no_root: return out << "no_root";
    case KrawczykOutcome::inconclusive: return out << "inconclusive";
  }
  return out << "KrawczykOutcome(" << static_cast<int>(outcome) << ")";
}

namespace {

void check_arguments(const CompiledSystem& system, const std::vector<double>& parameters,
                     const std::vector<Interval>& box) {
  if (system.n_equations() != system.n_unknowns())
    throw InvalidInput("krawczyk_test: the system is not square (" + std::to_string(system.n_equations()) +
                       " equations, " + std::to_string(system.n_unknowns()) + " unknowns)");
  if (box.size() != system.n_unknowns())
    throw InvalidInput("krawczyk_test: box has " + std::to_string(box.size()) + " sides, the system " +
                       std::to_string(system.n_unknowns()) + " unknowns");
  if (parameters.size() != system.n_parameters())
    throw InvalidInput("krawczyk_test: " + std::to_string(parameters.size()) + " parameters given, the system has " +
                       std::to_string(system.n_parameters()));
  for (const Interval& side : box)
    if (!detail::is_finite(side)) throw InvalidInput("krawczyk_test: the box is not finite");
}

}  // namespace

KrawczykResult krawczyk_test(const CompiledSystem& system, const std::vector<double>& parameters,
                             const std::vector<Interval>& box) {
  check_arguments(system, parameters, box);
  const std::size_t n = box.size();
  std::vector<Interval> p(parameters.begin(), parameters.end()), mid(n), fm(n), jm(n * n), fx(n), jx(n * n), k(n);
  std::vector<double> jmid(n * n), y(n * n);
  for (std::size_t i = 0; i < n; ++i) mid[i] = Interval(detail::midpoint(box[i]));
  system.values_and_jacobian(mid.data(), p.data(), fm.data(), jm.data());
  system.values_and_jacobian(box.data(), p.data(), fx.data(), jx.data());
  KrawczykResult result;
  result.contracted = box;
  for (std::size_t i = 0; i < n; ++i)
    if (certainly_nonzero(fx[i])) {
      result.outcome = KrawczykOutcome::no_root;
      return result;
    }
  for (std::size_t i = 0; i < n * n; ++i) jmid[i] = detail::midpoint(jm[i]);
  if (!detail::invert_matrix(n, jmid.data(), y.data())) return result;  // singular J(m): inconclusive
  detail::krawczyk_image(n, box.data(), mid.data(), fm.data(), jx.data(), y.data(), k.data());
  result.outcome = detail::krawczyk_compare(n, k.data(), box.data(), result.contracted.data());
  return result;
}

KrawczykResult krawczyk_test_mpfi(const CompiledSystem& system, const std::vector<double>& parameters,
                                  const std::vector<Interval>& box, int precision_bits) {
  check_arguments(system, parameters, box);
  if (precision_bits < 53) throw InvalidInput("krawczyk_test_mpfi: precision below 53 bits");
  RoundingGuard guard;  // the double Interval bookkeeping below
  const std::size_t n = box.size();
  detail::MpfiPrecisionScope scope(precision_bits);
  std::vector<MpfiInterval> p(parameters.size()), x(n), mid(n), fm(n), jm(n * n), fx(n), jx(n * n), k(n);
  for (std::size_t i = 0; i < parameters.size(); ++i) p[i] = detail::to_mpfi(parameters[i], parameters[i]);
  std::vector<Interval> mid_double(n), k_double(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = detail::to_mpfi(box[i]);
    const double m = detail::midpoint(box[i]);
    mid[i] = detail::to_mpfi(m, m);
  }
  system.values_and_jacobian(mid.data(), p.data(), fm.data(), jm.data());
  system.values_and_jacobian(x.data(), p.data(), fx.data(), jx.data());
  KrawczykResult result;
  result.contracted = box;
  for (std::size_t i = 0; i < n; ++i)
    if (certainly_nonzero(fx[i])) {
      result.outcome = KrawczykOutcome::no_root;
      return result;
    }
  std::vector<double> jmid(n * n), y(n * n);
  for (std::size_t i = 0; i < n * n; ++i) jmid[i] = detail::midpoint(detail::to_interval(jm[i]));
  if (!detail::invert_matrix(n, jmid.data(), y.data())) return result;
  detail::krawczyk_image(n, x.data(), mid.data(), fm.data(), jx.data(), y.data(), k.data());
  for (std::size_t i = 0; i < n; ++i) k_double[i] = detail::to_interval(k[i]);
  result.outcome = detail::krawczyk_compare(n, k_double.data(), box.data(), result.contracted.data());
  return result;
}

}  // namespace delmesh
