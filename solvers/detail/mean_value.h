#pragma once
//! \file mean_value.h
//! Internal: the mean-value exclusion test of the subdivision solver, in double intervals and in
//! MPFI.

#include <cstddef>

#include "symbolic/scalar_traits.h"

namespace delmesh::detail {

//! The mean-value test of m equations in n unknowns on a box X: by the mean-value theorem, for
//! m ∈ X ⊆ X', f_i(X) ⊆ f_i(m) + Σ_j ∂_j f_i(X') · (X_j − m_j).
//! \pre fm[i] ∋ f_i(m); jx (row-major m × n) ⊇ J_f(X'); offset[j] ⊇ X_j − m_j; for Interval, a
//!      live RoundingGuard; for MpfiInterval, an MpfiPrecisionScope.
//! \return true if some equation's enclosure excludes 0 (f has no zero in X); otherwise false,
//!      with the enclosure of every equation in `enclosure` (m values).
template <class I>
bool mean_value_excludes(std::size_t m, std::size_t n, const I* fm, const I* jx, const I* offset, I* enclosure) {
  for (std::size_t i = 0; i < m; ++i) {
    I acc = fm[i];
    for (std::size_t j = 0; j < n; ++j) acc += jx[i * n + j] * offset[j];
    if (certainly_nonzero(acc)) return true;
    enclosure[i] = acc;
  }
  return false;
}

}  // namespace delmesh::detail
