#pragma once
//! \file exact_rational.h
//! Test support: the exact rational value of a double, for comparing floating-point and interval
//! results with exact GiNaC arithmetic.

#include <cmath>

#include <ginac/ginac.h>

namespace delmesh::testing {

//! The exact rational value of a finite double d = m · 2^(e − 53), m an integer.
inline GiNaC::numeric exact(double d) {
  int e = 0;
  const double mantissa = std::frexp(d, &e);  // |mantissa| ∈ [1/2, 1)
  const auto m = static_cast<long>(std::ldexp(mantissa, 53));
  return GiNaC::numeric(m) * GiNaC::numeric(2).power(GiNaC::numeric(e - 53));
}

}  // namespace delmesh::testing
