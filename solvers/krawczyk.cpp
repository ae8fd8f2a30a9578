#include "solvers/krawczyk.h"

#include <string>

#include "common/errors.h"
#include "solvers/detail/interval_box.h"
#include "solvers/detail/krawczyk_core.h"
#include "symbolic/scalar_traits.h"

namespace delmesh {

namespace {

void check_arguments(const CompiledSystem& system, const std::vector<double>& parameters,
                     const std::vector<Interval>& box) {
  if (system.n_equations() != system.n_unknowns())
    throw PreconditionViolation("krawczyk_test: the system is not square (" + std::to_string(system.n_equations()) +
                                " equations, " + std::to_string(system.n_unknowns()) + " unknowns)");
  if (box.size() != system.n_unknowns())
    throw PreconditionViolation("krawczyk_test: box has " + std::to_string(box.size()) + " sides, the system " +
                                std::to_string(system.n_unknowns()) + " unknowns");
  if (parameters.size() != system.n_parameters())
    throw PreconditionViolation("krawczyk_test: " + std::to_string(parameters.size()) +
                                " parameters given, the system has " + std::to_string(system.n_parameters()));
  for (const Interval& side : box)
    if (!detail::is_finite(side)) throw PreconditionViolation("krawczyk_test: the box is not finite");
}

//! Conversions between the double Interval boxes of the interface and the arithmetic T.
template <class T>
T lift(const Interval& a);
template <>
Interval lift<Interval>(const Interval& a) {
  return a;
}
template <>
MpfiInterval lift<MpfiInterval>(const Interval& a) {
  return detail::to_mpfi(a);
}
Interval lower(const Interval& a) { return a; }
Interval lower(const MpfiInterval& a) { return detail::to_interval(a); }

//! krawczyk_test in T's interval arithmetic (Interval under a RoundingGuard, or MPFI at the
//! current default precision); every quantity is rounded outward to double intervals only for
//! the preconditioner and the final comparison.
template <class T>
KrawczykResult krawczyk_step(const CompiledSystem& system, const std::vector<double>& parameters,
                             const std::vector<Interval>& box) {
  const std::size_t n = box.size();
  std::vector<T> p(parameters.size()), x(n), mid(n), fm(n), jm(n * n), fx(n), jx(n * n), k(n);
  for (std::size_t i = 0; i < parameters.size(); ++i) p[i] = lift<T>(Interval(parameters[i]));
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = lift<T>(box[i]);
    mid[i] = lift<T>(Interval(detail::midpoint(box[i])));
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
  for (std::size_t i = 0; i < n * n; ++i) jmid[i] = detail::midpoint(lower(jm[i]));
  if (!detail::invert_matrix(n, jmid.data(), y.data())) return result;  // singular J(m): inconclusive
  detail::krawczyk_image(n, x.data(), mid.data(), fm.data(), jx.data(), y.data(), k.data());
  std::vector<Interval> k_double(n);
  for (std::size_t i = 0; i < n; ++i) k_double[i] = lower(k[i]);
  result.outcome = detail::krawczyk_compare(n, k_double.data(), box.data(), result.contracted.data());
  return result;
}

}  // namespace

KrawczykResult krawczyk_test(const CompiledSystem& system, const std::vector<double>& parameters,
                             const std::vector<Interval>& box) {
  check_arguments(system, parameters, box);
  return krawczyk_step<Interval>(system, parameters, box);
}

KrawczykResult krawczyk_test_mpfi(const CompiledSystem& system, const std::vector<double>& parameters,
                                  const std::vector<Interval>& box, int precision_bits) {
  check_arguments(system, parameters, box);
  if (precision_bits < 53) throw PreconditionViolation("krawczyk_test_mpfi: precision below 53 bits");
  RoundingGuard guard;  // the double Interval bookkeeping
  detail::MpfiPrecisionScope scope(precision_bits);
  return krawczyk_step<MpfiInterval>(system, parameters, box);
}

}  // namespace delmesh
