#pragma once
//! \file krawczyk.h
//! The Krawczyk operator K(X) = m − Y f(m) + (I − Y J(X))(X − m), Y ≈ J(m)⁻¹, for a square system.
//! Theorem (Krawczyk; Moore): if K(X) ⊂ int(X) then X contains exactly one zero of f, and if
//! K(X) ∩ X = ∅ then X contains no zero.  Evaluated with rigorous Interval (or MPFI) arithmetic.

#include <vector>

#include "symbolic/compiled_system.h"

namespace delmesh {

enum class KrawczykOutcome { unique_root, no_root, inconclusive };
std::ostream& operator<<(std::ostream& out, KrawczykOutcome outcome);

struct KrawczykResult {
  KrawczykOutcome outcome = KrawczykOutcome::inconclusive;
  std::vector<Interval> contracted;  //!< K(X) ∩ X (valid when not no_root)
};

//! Precondition: system is square (n equations, n unknowns), box.size() == n, parameters has
//! system.n_parameters() entries, a RoundingGuard is alive.
KrawczykResult krawczyk_test(const CompiledSystem& system, const std::vector<double>& parameters,
                             const std::vector<Interval>& box);

//! The same test in MPFI arithmetic at `precision_bits`; returns the contracted box rounded
//! outward to double intervals.
KrawczykResult krawczyk_test_mpfi(const CompiledSystem& system, const std::vector<double>& parameters,
                                  const std::vector<Interval>& box, int precision_bits);

}  // namespace delmesh
