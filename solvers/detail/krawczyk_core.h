#pragma once
//! \file krawczyk_core.h
//! The Krawczyk operator on already evaluated quantities (internal; shared by krawczyk.cpp and
//! the subdivision solver, which reuses the evaluations it made for exclusion).

#include <cstddef>

#include "solvers/krawczyk.h"
#include "symbolic/scalar_types.h"

namespace delmesh::detail {

//! inverse = a⁻¹ for the row-major n × n matrix a (cofactors for n ≤ 3, Eigen's full-pivot LU
//! above).  Returns false if a is singular or an entry of a or of the inverse is not finite.
bool invert_matrix(std::size_t n, const double* a, double* inverse);

//! K = m − Y f(m) + (I − Y J)(X − m), entry-wise in T's interval arithmetic, where x is the box X,
//! mid the point m ∈ X (as point intervals), fm an enclosure of f(m), jx an enclosure of the
//! Jacobian over X (row-major), y the (exact double) preconditioner.  k must not alias inputs.
template <class T>
void krawczyk_image(std::size_t n, const T* x, const T* mid, const T* fm, const T* jx, const double* y, T* k) {
  for (std::size_t i = 0; i < n; ++i) {
    T acc = mid[i];
    for (std::size_t j = 0; j < n; ++j) acc -= T(y[i * n + j]) * fm[j];
    for (std::size_t j = 0; j < n; ++j) {
      T c(i == j ? 1.0 : 0.0);
      for (std::size_t l = 0; l < n; ++l) c -= T(y[i * n + l]) * jx[l * n + j];
      acc += c * (x[j] - mid[j]);
    }
    k[i] = acc;
  }
}

//! Compares K with X: no_root if K_i ∩ X_i = ∅ for some i, unique_root if K ⊂ int X, else
//! inconclusive.  contracted = K ∩ X unless no_root (then untouched).  NaN or infinite bounds
//! never prove anything.
KrawczykOutcome krawczyk_compare(std::size_t n, const Interval* k, const Interval* x, Interval* contracted);

}  // namespace delmesh::detail
