#include "solvers/detail/interval_box.h"

#include <mpfi.h>
#include <mpfr.h>

namespace delmesh::detail {

namespace {
//! The lock that every MpfiPrecisionScope holds (see interval_box.h: Boost's default precision
//! is one process-wide variable).
std::recursive_mutex& mpfi_precision_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}
}  // namespace

MpfiPrecisionScope::MpfiPrecisionScope(int bits)
    : lock_(mpfi_precision_mutex()),
      old_interval_digits_(MpfiInterval::default_precision()), old_real_digits_(MpfrReal::default_precision()) {
  // Boost expresses precision in decimal digits: the smallest digit count carrying ≥ bits bits.
  const unsigned digits = static_cast<unsigned>(std::ceil(bits * 0.30102999566398120)) + 1;
  MpfiInterval::default_precision(digits);
  MpfrReal::default_precision(digits);
}

MpfiPrecisionScope::~MpfiPrecisionScope() {
  MpfiInterval::default_precision(old_interval_digits_);
  MpfrReal::default_precision(old_real_digits_);
}

MpfiInterval to_mpfi(double lo, double hi) {
  MpfiInterval out;
  mpfi_interv_d(out.backend().data(), lo, hi);
  return out;
}

MpfiInterval to_mpfi(const Interval& a) { return to_mpfi(a.inf(), a.sup()); }

Interval to_interval(const MpfiInterval& a) {
  const double lo = mpfr_get_d(&a.backend().data()->left, MPFR_RNDD);
  const double hi = mpfr_get_d(&a.backend().data()->right, MPFR_RNDU);
  if (std::isnan(lo) || std::isnan(hi)) return Interval::largest();
  return Interval(lo, hi);
}

}  // namespace delmesh::detail
