#pragma once
//! \file straight_line_program.h
//! Internal: a vector of GiNaC expressions compiled once into a straight-line program (SLP) and
//! evaluated without GiNaC over the five scalar types of scalar_types.h and ComplexInterval
//! (complex_interval.h), via ScalarTraits.
//!
//! Compilation walks each expression tree as given (nothing is expanded).  With sharing on (the
//! default), equal sub-expressions (GiNaC structural equality) and equal instructions (same
//! opcode and operands) are computed once, across all outputs.  Supported: the input symbols,
//! exact rational constants and π, sums (n-ary → binary chain, negative terms as subtractions),
//! products (with negative powers collected into one division), integer powers (x² as square),
//! half-integer powers (via sqrt), exp, log, sin, cos.  Anything else — a symbol that is not an
//! input, a floating-point or complex number, another constant or function, another exponent —
//! throws PreconditionViolation.  A product by a constant that is exactly a non-zero double is
//! emitted as `scale`, which Interval evaluates as the product by that double (the same enclosure
//! as the product with the point interval, with one vector multiplication instead of four).
//!
//! Register layout of an evaluation: [inputs | constants | one register per instruction].

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <vector>

#include <ginac/ginac.h>

#include "common/enum_names.h"
#include "symbolic/scalar_traits.h"
#include "symbolic/scalar_types.h"

namespace delmesh::detail {

//! scale is a mul whose b is a constant register holding a non-zero rational that is exactly a
//! double (so that Interval may multiply by the double itself, which gives the same enclosure).
enum class OpCode : std::uint8_t { add, sub, mul, div, neg, inv, square, pow, exp, log, sqrt, sin, cos, scale };
constexpr auto enum_names(OpCode) {
  return name_table<OpCode>("OpCode", {{OpCode::add, "add"}, {OpCode::sub, "sub"}, {OpCode::mul, "mul"},
                                       {OpCode::div, "div"}, {OpCode::neg, "neg"}, {OpCode::inv, "inv"},
                                       {OpCode::square, "square"}, {OpCode::pow, "pow"}, {OpCode::exp, "exp"},
                                       {OpCode::log, "log"}, {OpCode::sqrt, "sqrt"}, {OpCode::sin, "sin"},
                                       {OpCode::cos, "cos"}, {OpCode::scale, "scale"}});
}
inline std::ostream& operator<<(std::ostream& out, OpCode op) { return write_enum(out, op); }

//! register[result] = op(register[a], register[b]); for pow, b is the integer exponent.
struct Instruction {
  OpCode op;
  std::int32_t a;
  std::int32_t b;
};

class StraightLineProgram {
 public:
  //! Compiles outputs in the given input symbols (distinct; may be empty).  Throws
  //! PreconditionViolation on an unsupported expression or a duplicated input symbol.
  //! share_subexpressions = false compiles every occurrence separately (for comparisons only).
  StraightLineProgram(const std::vector<GiNaC::ex>& outputs, const std::vector<GiNaC::symbol>& inputs,
                      bool share_subexpressions = true);

  std::size_t n_inputs() const { return n_inputs_; }
  std::size_t n_outputs() const { return outputs_.size(); }
  std::size_t n_constants() const { return constants_.size(); }
  //! Number of arithmetic instructions (inputs and constants not counted).
  std::size_t instruction_count() const { return code_.size(); }
  //! The instructions in execution order; instruction k writes register
  //! n_inputs() + n_constants() + k.
  const std::vector<Instruction>& code() const { return code_; }

  //! outputs[i] = value of output i at the inputs.  Inputs are read from in_first[0, n_first)
  //! followed by in_rest[0, n_inputs − n_first); outputs are written to out_first[0, n_out_first)
  //! followed by out_rest[0, n_outputs − n_out_first).  Pointers to empty ranges may be null.
  //! Interval requires a live RoundingGuard; MpfrReal and MpfiInterval compute at the type's
  //! current default precision.  Uses thread-local scratch registers.
  template <class T>
  void evaluate(const T* in_first, std::size_t n_first, const T* in_rest, T* out_first,
                std::size_t n_out_first, T* out_rest) const;
  //! All inputs contiguous, all outputs contiguous.
  template <class T>
  void evaluate(const T* inputs, T* outputs) const {
    evaluate(inputs, n_inputs_, static_cast<const T*>(nullptr), outputs, outputs_.size(),
             static_cast<T*>(nullptr));
  }

  //! Taylor evaluation along a line.  Input i is the polynomial point[i] + t·direction[i]; every
  //! register holds a polynomial in t truncated after t^order, and output j's coefficients of
  //! t^0 … t^order are written to outputs[j·(order+1) + k].  Truncated power-series arithmetic is
  //! the ring homomorphism R[t] → R[t]/(t^(order+1)), so when every output is a polynomial of
  //! degree ≤ order in t its coefficients are exact whatever the degrees of the intermediate
  //! registers.  Only programs of add, sub, mul, neg, square and pow (non-negative exponent) —
  //! polynomial programs — are supported: returns false, writing nothing, if another opcode occurs.
  //! Instantiated for double and Interval (Interval: needs a live RoundingGuard; each coefficient
  //! then encloses the exact one at the given doubles).  Uses thread-local scratch registers.
  template <class T>
  bool evaluate_along_line(const T* point, const T* direction, int order, T* outputs) const;
  //! Whether evaluate_along_line() supports this program.
  bool is_polynomial_program() const;
  //! For a polynomial program: an upper bound of the total degree of every register, so of every
  //! output, in the first n_variables inputs (the other inputs and the constants have degree 0):
  //! a sum has the larger degree of its terms, a product their sum, a power the multiple.
  //! Saturated at INT_MAX.  Nothing when the program is not polynomial.
  std::optional<int> degree_bound(std::size_t n_variables) const;

 private:
  class Compiler;
  struct Constant {
    Rational value;
    bool is_pi = false;
  };

  std::size_t n_inputs_ = 0;
  std::vector<Constant> constants_;
  std::vector<Instruction> code_;
  struct Block {
    OpCode op;
    std::uint32_t begin, end;  // code_[begin, end) all have opcode op
  };
  std::vector<Block> blocks_;
  std::vector<std::int32_t> outputs_;  // register of each output
  std::uint64_t serial_ = 0;           // unique per program: keys the per-thread constant cache
  // Constants pre-converted for the fixed-precision types.
  std::vector<double> constants_double_;
  std::vector<Interval> constants_interval_;
  std::vector<Complex> constants_complex_;

  template <class T>
  void load_constants(T* registers) const;
  //! Turns each mul by a constant that is exactly a non-zero double into a scale (its operand
  //! first, the constant second).  Needs constants_interval_.
  void mark_scalings();
  //! Reorders code_ (a topological order that groups equal opcodes) and fills blocks_.
  void schedule();
};

#define DELMESH_DECLARE_SLP_EVALUATE(T)                                                         \
  extern template void StraightLineProgram::evaluate<T>(const T*, std::size_t, const T*, T*, \
                                                        std::size_t, T*) const;
DELMESH_DECLARE_SLP_EVALUATE(double)
DELMESH_DECLARE_SLP_EVALUATE(Interval)
DELMESH_DECLARE_SLP_EVALUATE(MpfrReal)
DELMESH_DECLARE_SLP_EVALUATE(MpfiInterval)
DELMESH_DECLARE_SLP_EVALUATE(Complex)
#undef DELMESH_DECLARE_SLP_EVALUATE
extern template bool StraightLineProgram::evaluate_along_line<double>(const double*, const double*, int,
                                                                      double*) const;
extern template bool StraightLineProgram::evaluate_along_line<Interval>(const Interval*, const Interval*, int,
                                                                        Interval*) const;

}  // namespace delmesh::detail
