#pragma once
//! \file kostlan_system.h
//! Random dense Kostlan polynomials and systems: the coefficient of the monomial u^α (|α| ≤ d)
//! is an independent normal variable with mean 0 and variance the multinomial coefficient
//! d! / ((d − |α|)! α_1! ⋯ α_n!).  This is the O(n+1)-invariant Gaussian ensemble (Kostlan 1993;
//! Shub–Smale), whose expected number of real roots for a square system of degrees d_i is
//! √(d_1 ⋯ d_n); its real roots are spread around the unit ball.  Used as random test systems for
//! cross-checking the subdivision and homotopy solvers and as benchmark inputs.
//!
//! Reproducibility: the generator is std::mt19937_64 (fully specified by the standard) with
//! normals drawn by the Box–Muller transform written here, so a seed gives the same system on every
//! platform and standard library.

#include <cstdint>
#include <ostream>
#include <random>
#include <vector>

#include <ginac/ginac.h>

#include "common/enum_names.h"
#include "solvers/solve_result.h"
#include "symbolic/primitive_system.h"

namespace delmesh {

//! How the Gaussian samples become coefficients.
enum class KostlanCoefficients {
  exact_rational,  //!< the sample rounded to a multiple of 2^-24, as an exact GiNaC rational
  double_rounded   //!< the sample as a double (a GiNaC floating-point numeric)
};
constexpr auto enum_names(KostlanCoefficients) {
  return name_table<KostlanCoefficients>("KostlanCoefficients", {{KostlanCoefficients::exact_rational, "exact_rational"},
                                                                 {KostlanCoefficients::double_rounded, "double_rounded"}});
}
inline std::ostream& operator<<(std::ostream& out, KostlanCoefficients coefficients) { return write_enum(out, coefficients); }

//! A reproducible source of standard normal samples (mt19937_64 + Box–Muller).
class KostlanRng {
 public:
  explicit KostlanRng(std::uint64_t seed) : engine_(seed) {}
  //! A uniform double in (0, 1) built from 53 random bits.
  double uniform();
  //! A standard normal sample N(0, 1).
  double normal();

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0;
};

//! A dense Kostlan polynomial of total degree `degree` ≥ 1 in `variables` (n ≥ 1).  Monomials are
//! drawn in a fixed order (graded, then lexicographic), so the result depends only on the rng state.
//! Throws InvalidInput if degree < 1 (a generator parameter), PreconditionViolation if variables
//! is empty.
GiNaC::ex kostlan_polynomial(const std::vector<GiNaC::symbol>& variables, int degree, KostlanRng& rng,
                             KostlanCoefficients coefficients = KostlanCoefficients::exact_rational);

//! A square random system f_i = Kostlan polynomial of degree degrees[i] in n = degrees.size()
//! unknowns, as a PrimitiveSystem named "kostlan" with no parameters, its exact Jacobian, and world
//! point (u_1, u_2, u_3) (missing coordinates are 0).  Unknowns are the coordinate symbols x, y, z
//! of surface.h when n ≤ 3 (so an equation can also be used as a Surface), else fresh symbols
//! u0, u1, ….  Throws PreconditionViolation if degrees is empty, InvalidInput if a degree is < 1.
PrimitiveSystem kostlan_system(const std::vector<int>& degrees, std::uint64_t seed,
                               KostlanCoefficients coefficients = KostlanCoefficients::exact_rational);

//! The system scaled into `box`: g_i(x) = f_i((x − c) / h) (componentwise), with c the centre and h the half-widths of the box, so the roots of f in [−1, 1]^n become the
//! roots of g in `box`.  Box bounds are converted to exact rationals (doubles are dyadic), so
//! exact coefficients stay exact.  Parameters are carried over unchanged; the Jacobian is
//! re-derived.  Throws PreconditionViolation if box has not n_unknowns() finite non-empty sides.
PrimitiveSystem scale_into_box(const PrimitiveSystem& system, const SolverBox& box);

}  // namespace delmesh
