#include "symbolic/detail/straight_line_program.h"

#include <atomic>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>

#include "common/errors.h"

namespace delmesh::detail {

std::ostream& operator<<(std::ostream& os, OpCode op) {
  switch (op) {
    case OpCode::add: return os << "add";
    case OpCode::sub: return os << "sub";
    case OpCode::mul: return os << "mul";
    case OpCode::div: return os << "div";
    case OpCode::neg: return os << "neg";
    case OpCode::inv: return os << "inv";
    case OpCode::square: return os << "square";
    case OpCode::pow: return os << "pow";
    case OpCode::exp: return os << "exp";
    case OpCode::log: return os << "log";
    case OpCode::sqrt: return os << "sqrt";
    case OpCode::sin: return os << "sin";
    case OpCode::cos: return os << "cos";
  }
  return os << "OpCode(" << static_cast<int>(op) << ")";
}

namespace {

std::string to_text(const GiNaC::ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

[[noreturn]] void unsupported(const GiNaC::ex& e, const std::string& why) {
  throw PreconditionViolation("cannot compile '" + to_text(e) + "': " + why);
}

std::atomic<std::uint64_t> next_serial{1};

//! A value during compilation: an input, a constant or an instruction result, by index.  The
//! register number is fixed only once the number of constants is known.
enum class Kind : int { input = 0, constant = 1, instruction = 2 };
int make_ref(Kind kind, int index) { return index * 3 + static_cast<int>(kind); }
Kind ref_kind(int ref) { return static_cast<Kind>(ref % 3); }
int ref_index(int ref) { return ref / 3; }

bool is_negative_term(const GiNaC::ex& t) {
  if (GiNaC::is_a<GiNaC::numeric>(t)) return GiNaC::ex_to<GiNaC::numeric>(t).is_negative();
  if (GiNaC::is_a<GiNaC::mul>(t) && t.nops() > 0) {
    const GiNaC::ex last = t.op(t.nops() - 1);
    return GiNaC::is_a<GiNaC::numeric>(last) && GiNaC::ex_to<GiNaC::numeric>(last).is_negative();
  }
  return false;
}

}  // namespace

class StraightLineProgram::Compiler {
 public:
  Compiler(StraightLineProgram& program, const std::vector<GiNaC::symbol>& inputs, bool share)
      : program_(program), share_(share) {
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      if (!symbols_.emplace(inputs[i], make_ref(Kind::input, static_cast<int>(i))).second)
        throw PreconditionViolation("straight-line program: input symbol '" + inputs[i].get_name() +
                                    "' given twice");
    }
  }

  int compile(const GiNaC::ex& e) {
    if (share_) {
      const auto it = memo_.find(e);
      if (it != memo_.end()) return it->second;
    }
    const int ref = compile_uncached(e);
    if (share_) memo_.emplace(e, ref);
    return ref;
  }

  //! Fixes the register numbers: [inputs | constants | instructions].
  void finish(const std::vector<int>& output_refs) {
    const int n_in = static_cast<int>(program_.n_inputs_);
    const int n_c = static_cast<int>(program_.constants_.size());
    const auto reg = [&](int ref) {
      switch (ref_kind(ref)) {
        case Kind::input: return ref_index(ref);
        case Kind::constant: return n_in + ref_index(ref);
        case Kind::instruction: return n_in + n_c + ref_index(ref);
      }
      return -1;
    };
    for (Instruction& ins : program_.code_) {
      ins.a = reg(ins.a);
      if (ins.op == OpCode::add || ins.op == OpCode::sub || ins.op == OpCode::mul || ins.op == OpCode::div)
        ins.b = reg(ins.b);
    }
    for (int ref : output_refs) program_.outputs_.push_back(reg(ref));
  }

 private:
  int compile_uncached(const GiNaC::ex& e) {
    using namespace GiNaC;
    if (is_a<symbol>(e)) {
      const auto it = symbols_.find(e);
      if (it == symbols_.end())
        unsupported(e, "the symbol is neither an unknown nor a parameter of the system");
      return it->second;
    }
    if (is_a<numeric>(e)) return rational_constant(e);
    if (is_a<constant>(e)) {
      if (e.is_equal(Pi)) return pi_constant();
      unsupported(e, "the only supported named constant is Pi");
    }
    if (is_a<add>(e)) return compile_add(e);
    if (is_a<mul>(e)) return compile_mul(e);
    if (is_a<power>(e)) return compile_power(e.op(0), e.op(1), e);
    if (is_a<function>(e)) {
      const std::string name = ex_to<function>(e).get_name();
      OpCode op;
      if (name == "exp") op = OpCode::exp;
      else if (name == "log") op = OpCode::log;
      else if (name == "sin") op = OpCode::sin;
      else if (name == "cos") op = OpCode::cos;
      else unsupported(e, "the function '" + name + "' is not supported (exp, log, sqrt, sin, cos are)");
      if (e.nops() != 1) unsupported(e, "expected one argument");
      return emit(op, compile(e.op(0)));
    }
    unsupported(e, "unsupported kind of expression");
  }

  int rational_constant(const GiNaC::ex& e) {
    const GiNaC::numeric& q = GiNaC::ex_to<GiNaC::numeric>(e);
    if (!q.is_rational()) unsupported(e, "only exact real rational numbers can be compiled");
    const std::string text = to_text(q.numer()) + "/" + to_text(q.denom());
    program_.constants_.push_back(Constant{Rational(text), false});
    return make_ref(Kind::constant, static_cast<int>(program_.constants_.size() - 1));
  }

  int pi_constant() {
    program_.constants_.push_back(Constant{Rational(0), true});
    return make_ref(Kind::constant, static_cast<int>(program_.constants_.size() - 1));
  }

  int compile_add(const GiNaC::ex& e) {
    int acc = -1;
    std::vector<GiNaC::ex> negatives;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const GiNaC::ex t = e.op(i);
      if (is_negative_term(t)) {
        negatives.push_back(-t);
      } else {
        const int r = compile(t);
        acc = acc < 0 ? r : emit(OpCode::add, acc, r);
      }
    }
    for (const GiNaC::ex& t : negatives) {
      const int r = compile(t);
      acc = acc < 0 ? emit(OpCode::neg, r) : emit(OpCode::sub, acc, r);
    }
    return acc;
  }

  int compile_mul(const GiNaC::ex& e) {
    using namespace GiNaC;
    numeric coefficient(1);
    int numerator = -1, denominator = -1;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex f = e.op(i);
      if (is_a<numeric>(f)) {
        coefficient *= ex_to<numeric>(f);
        continue;
      }
      if (is_a<power>(f) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_negative()) {
        const int r = compile(pow(f.op(0), -f.op(1)));
        denominator = denominator < 0 ? r : emit(OpCode::mul, denominator, r);
        continue;
      }
      const int r = compile(f);
      numerator = numerator < 0 ? r : emit(OpCode::mul, numerator, r);
    }
    if (!coefficient.is_equal(numeric(1)) && !coefficient.is_equal(numeric(-1))) {
      const int c = compile(coefficient.is_negative() ? ex(-coefficient) : ex(coefficient));
      numerator = numerator < 0 ? c : emit(OpCode::mul, c, numerator);
    }
    int result;
    if (numerator < 0)
      result = denominator < 0 ? compile(numeric(1)) : emit(OpCode::inv, denominator);
    else
      result = denominator < 0 ? numerator : emit(OpCode::div, numerator, denominator);
    return coefficient.is_negative() ? emit(OpCode::neg, result) : result;
  }

  //! base^n for an integer n ≠ 0 given the compiled base.
  int integer_power(int base, long n) {
    const long m = n < 0 ? -n : n;
    if (m > 1L << 30) throw PreconditionViolation("straight-line program: exponent too large");
    int r = base;
    if (m == 2) r = emit(OpCode::square, base);
    else if (m > 2) r = emit(OpCode::pow, base, static_cast<int>(m));
    return n < 0 ? emit(OpCode::inv, r) : r;
  }

  int compile_power(const GiNaC::ex& base, const GiNaC::ex& exponent, const GiNaC::ex& e) {
    using namespace GiNaC;
    if (!is_a<numeric>(exponent)) unsupported(e, "the exponent must be an integer or half an odd integer");
    const numeric& k = ex_to<numeric>(exponent);
    if (k.is_integer()) {
      if (!k.is_pos_integer()) {  // negative: share base^|k| with other occurrences
        if (k.is_zero()) return compile(numeric(1));
        return emit(OpCode::inv, compile(pow(base, -exponent)));
      }
      if (!k.is_equal(numeric(k.to_long()))) unsupported(e, "exponent too large");
      return integer_power(compile(base), k.to_long());
    }
    const numeric twice = k * 2;
    if (twice.is_integer()) {  // k = p/2 with p odd: sqrt(base)^p
      const int s = emit(OpCode::sqrt, compile(base));
      return integer_power(s, twice.to_long());
    }
    unsupported(e, "the exponent must be an integer or half an odd integer");
  }

  int emit(OpCode op, int a, int b = 0) {
    if ((op == OpCode::add || op == OpCode::mul) && b < a) std::swap(a, b);
    const auto key = std::make_tuple(static_cast<int>(op), a, b);
    if (share_) {
      const auto it = instructions_.find(key);
      if (it != instructions_.end()) return it->second;
    }
    program_.code_.push_back(Instruction{op, a, b});
    const int ref = make_ref(Kind::instruction, static_cast<int>(program_.code_.size() - 1));
    if (share_) instructions_.emplace(key, ref);
    return ref;
  }

  StraightLineProgram& program_;
  bool share_;
  std::map<GiNaC::ex, int, GiNaC::ex_is_less> symbols_;
  std::map<GiNaC::ex, int, GiNaC::ex_is_less> memo_;
  std::map<std::tuple<int, int, int>, int> instructions_;
};

StraightLineProgram::StraightLineProgram(const std::vector<GiNaC::ex>& outputs,
                                         const std::vector<GiNaC::symbol>& inputs,
                                         bool share_subexpressions)
    : n_inputs_(inputs.size()), serial_(next_serial.fetch_add(1)) {
  Compiler compiler(*this, inputs, share_subexpressions);
  std::vector<int> output_refs;
  output_refs.reserve(outputs.size());
  for (const GiNaC::ex& e : outputs) output_refs.push_back(compiler.compile(e));
  compiler.finish(output_refs);

  for (const Constant& c : constants_) {
    double d;
    Interval i;
    Complex z;
    if (c.is_pi) {
      ScalarTraits<double>::set_pi(d);
      ScalarTraits<Interval>::set_pi(i);
      ScalarTraits<Complex>::set_pi(z);
    } else {
      ScalarTraits<double>::set_rational(d, c.value);
      ScalarTraits<Interval>::set_rational(i, c.value);
      ScalarTraits<Complex>::set_rational(z, c.value);
    }
    constants_double_.push_back(d);
    constants_interval_.push_back(i);
    constants_complex_.push_back(z);
  }
}

template <class T>
void StraightLineProgram::load_constants(T* registers) const {
  if constexpr (std::is_same_v<T, double>) {
    std::copy(constants_double_.begin(), constants_double_.end(), registers);
  } else if constexpr (std::is_same_v<T, Interval>) {
    std::copy(constants_interval_.begin(), constants_interval_.end(), registers);
  } else if constexpr (std::is_same_v<T, Complex>) {
    std::copy(constants_complex_.begin(), constants_complex_.end(), registers);
  } else {
    for (std::size_t k = 0; k < constants_.size(); ++k) {
      if (constants_[k].is_pi)
        ScalarTraits<T>::set_pi(registers[k]);
      else
        ScalarTraits<T>::set_rational(registers[k], constants_[k].value);
    }
  }
}

namespace {
//! Per-thread registers of one scalar type, with the program whose constants they hold.
template <class T>
struct Scratch {
  std::vector<T> registers;
  std::uint64_t program = 0;  // serial of the program whose constants are loaded
  long precision = -1;
};
template <class T>
Scratch<T>& scratch() {
  thread_local Scratch<T> s;
  return s;
}
}  // namespace

template <class T>
void StraightLineProgram::evaluate(const T* in_first, std::size_t n_first, const T* in_rest, T* out_first,
                                   std::size_t n_out_first, T* out_rest) const {
  using Tr = ScalarTraits<T>;
  Scratch<T>& s = scratch<T>();
  const std::size_t n_c = constants_.size();
  const std::size_t total = n_inputs_ + n_c + code_.size();
  const long precision = Tr::precision();
  if (s.registers.size() < total || s.precision != precision) {
    if (s.registers.size() < total) s.registers.resize(total);
    if (precision != 0)
      for (T& r : s.registers) Tr::set_precision(r, precision);
    s.precision = precision;
    s.program = 0;
  }
  T* const r = s.registers.data();
  if (s.program != serial_) {
    load_constants(r + n_inputs_);
    s.program = serial_;
  }
  for (std::size_t i = 0; i < n_inputs_; ++i) Tr::assign(r[i], i < n_first ? in_first[i] : in_rest[i - n_first]);

  T* out = r + n_inputs_ + n_c;
  for (const Instruction& ins : code_) {
    T& o = *out++;
    switch (ins.op) {
      case OpCode::add: Tr::add(o, r[ins.a], r[ins.b]); break;
      case OpCode::sub: Tr::sub(o, r[ins.a], r[ins.b]); break;
      case OpCode::mul: Tr::mul(o, r[ins.a], r[ins.b]); break;
      case OpCode::div: Tr::div(o, r[ins.a], r[ins.b]); break;
      case OpCode::neg: Tr::neg(o, r[ins.a]); break;
      case OpCode::inv: Tr::inv(o, r[ins.a]); break;
      case OpCode::square: Tr::square(o, r[ins.a]); break;
      case OpCode::pow: Tr::pow(o, r[ins.a], ins.b); break;
      case OpCode::exp: Tr::exp(o, r[ins.a]); break;
      case OpCode::log: Tr::log(o, r[ins.a]); break;
      case OpCode::sqrt: Tr::sqrt(o, r[ins.a]); break;
      case OpCode::sin: Tr::sin(o, r[ins.a]); break;
      case OpCode::cos: Tr::cos(o, r[ins.a]); break;
    }
  }
  for (std::size_t j = 0; j < outputs_.size(); ++j) {
    T& target = j < n_out_first ? out_first[j] : out_rest[j - n_out_first];
    target = r[outputs_[j]];
  }
}

#define DELMESH_DEFINE_SLP_EVALUATE(T)                                                                   \
  template void StraightLineProgram::evaluate<T>(const T*, std::size_t, const T*, T*, std::size_t, T*) \
      const;
DELMESH_DEFINE_SLP_EVALUATE(double)
DELMESH_DEFINE_SLP_EVALUATE(Interval)
DELMESH_DEFINE_SLP_EVALUATE(MpfrReal)
DELMESH_DEFINE_SLP_EVALUATE(MpfiInterval)
DELMESH_DEFINE_SLP_EVALUATE(Complex)
#undef DELMESH_DEFINE_SLP_EVALUATE

}  // namespace delmesh::detail
