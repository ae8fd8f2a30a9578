#pragma once
//! \file krawczyk.h
//! The Krawczyk operator K(X) = m − Y f(m) + (I − Y J(X))(X − m), Y ≈ J(m)⁻¹, for a square system.
//! Theorem (Krawczyk; Moore): if K(X) ⊂ int(X) then X contains exactly one zero of f, and if
//! K(X) ∩ X = ∅ then X contains no zero.  Evaluated with rigorous Interval (or MPFI) arithmetic.

#include <vector>

#include "common/enum_names.h"
#include "symbolic/compiled_system.h"

namespace delmesh {

//! What one Krawczyk step proved about the box X.
enum class KrawczykOutcome {
  unique_root,  //!< K(X) ⊂ int X: X contains exactly one zero of f
  no_root,      //!< f(X) ∌ 0 or K(X) ∩ X = ∅: X contains no zero of f
  inconclusive  //!< neither (or J(m) singular, or NaN bounds)
};
constexpr auto enum_names(KrawczykOutcome) {
  return name_table<KrawczykOutcome>("KrawczykOutcome", {{KrawczykOutcome::unique_root, "unique_root"},
                                                         {KrawczykOutcome::no_root, "no_root"},
                                                         {KrawczykOutcome::inconclusive, "inconclusive"}});
}
inline std::ostream& operator<<(std::ostream& out, KrawczykOutcome outcome) { return write_enum(out, outcome); }

struct [[nodiscard]] KrawczykResult {
  KrawczykOutcome outcome = KrawczykOutcome::inconclusive;
  std::vector<Interval> contracted;  //!< K(X) ∩ X (valid when not no_root)
};

//! One Krawczyk step on the box X = `box`: m = midpoint of X, Y = (midpoint of the enclosure of
//! J(m))⁻¹ in double, K = m − Y f(m) + (I − Y J(X))(X − m) in Interval arithmetic.
//! unique_root: K ⊂ int X, so X (and K ∩ X) contains exactly one zero of f; no_root: some
//! f_i(X) excludes 0 or K ∩ X = ∅; inconclusive otherwise, and whenever J(m) is singular (Y does
//! not exist) or an enclosure has NaN bounds.  `contracted` = K ∩ X contains every zero of f in X.
//! Precondition: system is square (n equations, n unknowns), box.size() == n with finite
//! bounds, parameters has system.n_parameters() entries, a RoundingGuard is alive.  Violations
//! of all but the last throw PreconditionViolation.
KrawczykResult krawczyk_test(const CompiledSystem& system, const std::vector<double>& parameters,
                             const std::vector<Interval>& box);

//! The same test in MPFI arithmetic at `precision_bits` (≥ 53, else PreconditionViolation; the
//! MPFI default precision is set for the duration of the call by a detail::MpfiPrecisionScope,
//! which holds the process-wide MPFI precision lock: concurrent calls from several threads are
//! safe and serialized);
//! Y is still a double matrix.  Returns the contracted box rounded outward to double intervals.
//! Does not require a RoundingGuard.
KrawczykResult krawczyk_test_mpfi(const CompiledSystem& system, const std::vector<double>& parameters,
                                  const std::vector<Interval>& box, int precision_bits);

}  // namespace delmesh
