#pragma once
//! \file scalar_types.h
//! The scalar types every compiled system is evaluated over.  All come from libraries:
//! CGAL's interval arithmetic, Boost.Multiprecision's MPFR and MPFI back ends, std::complex.

#include <complex>

#include <CGAL/Interval_nt.h>
#include <boost/multiprecision/mpfi.hpp>
#include <boost/multiprecision/mpfr.hpp>

namespace delmesh {

//! Double-precision interval.  The unprotected variant: every computation on it must run while a
//! RoundingGuard is alive (CGAL sets the rounding mode upward for the guard's lifetime).
using Interval = CGAL::Interval_nt<false>;
//! The one way delmesh changes the FPU rounding mode (see design notes, "Numerics").
using RoundingGuard = CGAL::Protect_FPU_rounding<true>;

//! MPFR real with precision chosen at run time (boost::multiprecision default precision).
using MpfrReal = boost::multiprecision::mpfr_float;
//! MPFI interval with precision chosen at run time: the escalation type of the solvers.
using MpfiInterval = boost::multiprecision::mpfi_float;

using Complex = std::complex<double>;

}  // namespace delmesh
