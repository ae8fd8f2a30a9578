#include "symbolic/detail/straight_line_program.h"

#include <algorithm>
#include <atomic>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>

#include "common/errors.h"
#include "common/run_limits.h"
#include "symbolic/complex_interval.h"

namespace delmesh::detail {

namespace {

std::string to_text(const GiNaC::ex& e) {
  std::ostringstream os;
  os << e;
  return os.str();
}

[[noreturn]] void unsupported(const GiNaC::ex& e, const std::string& why) {
  throw PreconditionViolation("cannot compile '" + to_text(e) + "': " + why);
}

//! True for the opcodes whose operand b is a register (for pow, b is the exponent).
bool is_binary(OpCode op) {
  return op == OpCode::add || op == OpCode::sub || op == OpCode::mul || op == OpCode::div || op == OpCode::scale;
}

std::atomic<std::uint64_t> next_serial{1};

//! A value during compilation: an input, a constant or an instruction result, by index.  The
//! register number is fixed only once the number of constants is known.
enum class Kind : int { input = 0, constant = 1, instruction = 2 };
int make_ref(Kind kind, int index) { return index * 3 + static_cast<int>(kind); }
Kind ref_kind(int ref) { return static_cast<Kind>(ref % 3); }
int ref_index(int ref) { return ref / 3; }


std::uint64_t mix(std::uint64_t h, std::uint64_t v) {  // splitmix64 finaliser of h ⊕ v
  std::uint64_t z = h ^ (v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2));
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
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

  //! The register holding the value of e.
  int compile(const GiNaC::ex& e) {
    const SignedRef v = signed_value(e);
    return v.negated ? emit(OpCode::neg, v.ref) : v.ref;
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
      if (is_binary(ins.op)) ins.b = reg(ins.b);
    }
    for (int ref : output_refs) program_.outputs_.push_back(reg(ref));
  }

 private:
  //! value = (negated ? −1 : 1) · register[ref].  Sums are compiled up to sign in one canonical
  //! orientation, so that s and −s (which GiNaC may produce in either form, depending on its
  //! term order) share one computation; the sign travels outwards through products and odd
  //! powers and becomes a subtraction in sums.  Negation is exact in every scalar type, so this
  //! changes no rounding.
  struct SignedRef {
    int ref;
    bool negated;
  };

  SignedRef signed_value(const GiNaC::ex& e) {
    if (share_) {
      const auto it = memo_.find(e);
      if (it != memo_.end()) return it->second;
    }
    const SignedRef v = signed_value_uncached(e);
    if (share_) memo_.emplace(e, v);
    return v;
  }

  SignedRef signed_value_uncached(const GiNaC::ex& e) {
    using namespace GiNaC;
    // A node costs hash-table work; the strided test of the limits adds nothing measurable.
    limits_.check("compiling the expression");
    if (is_a<symbol>(e)) {
      const auto it = symbols_.find(e);
      if (it == symbols_.end())
        unsupported(e, "the symbol is neither an unknown nor a parameter of the system");
      return {it->second, false};
    }
    if (is_a<numeric>(e)) {
      const numeric& q = ex_to<numeric>(e);
      if (!q.is_rational()) unsupported(e, "only exact real rational numbers can be compiled");
      return {rational_constant(abs(q)), q.is_negative()};
    }
    if (is_a<constant>(e)) {
      if (e.is_equal(Pi)) return {pi_constant(), false};
      unsupported(e, "the only supported named constant is Pi");
    }
    if (is_a<add>(e)) return compile_add(e, canonical(e).negative);
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
      return {emit(op, compile(e.op(0))), false};
    }
    unsupported(e, "unsupported kind of expression");
  }

  //! A constant register holding q ≥ 0 (shared between equal constants when sharing).
  int rational_constant(const GiNaC::numeric& q) {
    if (share_) {
      const auto it = constant_refs_.find(q);
      if (it != constant_refs_.end()) return it->second;
    }
    const std::string text = to_text(q.numer()) + "/" + to_text(q.denom());
    program_.constants_.push_back(Constant{Rational(text), false});
    const int ref = make_ref(Kind::constant, static_cast<int>(program_.constants_.size() - 1));
    if (share_) constant_refs_.emplace(q, ref);
    return ref;
  }

  int pi_constant() {
    program_.constants_.push_back(Constant{Rational(0), true});
    return make_ref(Kind::constant, static_cast<int>(program_.constants_.size() - 1));
  }

  //! The canonical form of an expression up to sign, independent of the run.  GiNaC orders the
  //! operands of sums and products by hash values seeded with type_info addresses, which change
  //! from run to run (ASLR), and picks the sign of a sum under an even power accordingly.  The
  //! compiler instead visits operands sorted by `hash` and orients every sum by it, so the program
  //! (and every rounding it performs) is the same in every run.  value(e) = ±M(e) where M(e) is
  //! the canonical magnitude identified by `hash`, and `negative` gives the sign.
  struct Canon {
    std::uint64_t hash;
    bool negative;
  };

  Canon canonical(const GiNaC::ex& e) {
    using namespace GiNaC;
    const auto it = canon_.find(e);
    if (it != canon_.end()) return it->second;
    Canon c{0, false};
    const auto signed_hash = [](const Canon& x, bool flip) { return mix(x.hash, (x.negative != flip) ? 2 : 1); };
    if (is_a<symbol>(e)) {
      const auto s = symbols_.find(e);
      c.hash = mix(1, s == symbols_.end() ? std::hash<std::string>()(ex_to<symbol>(e).get_name()) : s->second + 1);
    } else if (is_a<numeric>(e)) {
      const numeric& q = ex_to<numeric>(e);
      c.negative = q.is_real() && q.is_negative();
      c.hash = mix(2, std::hash<std::string>()(to_text(c.negative ? ex(-q) : e)));
    } else if (is_a<add>(e)) {
      std::vector<Canon> terms;
      for (std::size_t i = 0; i < e.nops(); ++i) terms.push_back(canonical(e.op(i)));
      std::uint64_t h[2];
      for (int flip = 0; flip < 2; ++flip) {
        std::vector<std::uint64_t> keys;
        for (const Canon& t : terms) keys.push_back(signed_hash(t, flip));
        std::sort(keys.begin(), keys.end());
        h[flip] = 3;
        for (std::uint64_t k : keys) h[flip] = mix(h[flip], k);
      }
      c.negative = h[1] < h[0];  // orient the sum by the smaller hash
      c.hash = h[c.negative ? 1 : 0];
    } else if (is_a<mul>(e)) {
      std::vector<std::uint64_t> keys;
      for (std::size_t i = 0; i < e.nops(); ++i) {
        const Canon f = canonical(e.op(i));
        c.negative ^= f.negative;
        const bool unit = is_a<numeric>(e.op(i)) && abs(ex_to<numeric>(e.op(i))).is_equal(numeric(1));
        if (!unit) keys.push_back(f.hash);  // −x is x up to sign
      }
      std::sort(keys.begin(), keys.end());
      if (keys.size() == 1) {
        c.hash = keys[0];
      } else {
        c.hash = 4;
        for (std::uint64_t k : keys) c.hash = mix(c.hash, k);
      }
    } else if (is_a<power>(e)) {
      const Canon b = canonical(e.op(0));
      const ex& k = e.op(1);
      const bool integer = is_a<numeric>(k) && ex_to<numeric>(k).is_integer();
      const Canon exponent = canonical(k);
      c.hash = mix(mix(5, integer ? b.hash : signed_hash(b, false)), exponent.hash ^ (exponent.negative ? 7 : 0));
      c.negative = integer && b.negative && ex_to<numeric>(k).is_odd();
    } else {
      c.hash = is_a<function>(e) ? mix(6, std::hash<std::string>()(ex_to<function>(e).get_name()))
                                 : mix(7, std::hash<std::string>()(to_text(e)));
      for (std::size_t i = 0; i < e.nops(); ++i) c.hash = mix(c.hash, signed_hash(canonical(e.op(i)), false));
    }
    canon_.emplace(e, c);
    return c;
  }

  //! The operands of a sum or product in canonical order.
  std::vector<GiNaC::ex> sorted_operands(const GiNaC::ex& e) {
    std::vector<std::pair<std::uint64_t, GiNaC::ex>> keyed;
    for (std::size_t i = 0; i < e.nops(); ++i) keyed.emplace_back(canonical(e.op(i)).hash, e.op(i));
    std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<GiNaC::ex> out;
    for (auto& k : keyed) out.push_back(k.second);
    return out;
  }

  //! Σ terms as a chain of additions and subtractions (positive terms first); with flip, the
  //! chain computes −Σ terms and the result is marked negated.
  SignedRef compile_add(const GiNaC::ex& e, bool flip) {
    std::vector<SignedRef> terms;
    for (const GiNaC::ex& t : sorted_operands(e)) {
      SignedRef v = signed_value(t);
      v.negated ^= flip;
      terms.push_back(v);
    }
    int acc = -1;
    for (const SignedRef& t : terms)
      if (!t.negated) acc = acc < 0 ? t.ref : emit(OpCode::add, acc, t.ref);
    if (acc < 0) {  // every term negative: −(Σ |terms|)
      for (const SignedRef& t : terms) acc = acc < 0 ? t.ref : emit(OpCode::add, acc, t.ref);
      return {acc, !flip};
    }
    for (const SignedRef& t : terms)
      if (t.negated) acc = emit(OpCode::sub, acc, t.ref);
    return {acc, flip};
  }

  //! ± (|coefficient| · Π numerator factors) / Π denominator factors.
  SignedRef compile_mul(const GiNaC::ex& e) {
    using namespace GiNaC;
    bool negated = false;
    int numerator = -1, denominator = -1, coefficient = -1;
    for (const ex& f : sorted_operands(e)) {
      SignedRef v;
      bool in_denominator = false;
      if (is_a<numeric>(f) && ex_to<numeric>(f).is_rational()) {
        const numeric& q = ex_to<numeric>(f);
        negated ^= q.is_negative();
        if (!abs(q).is_equal(numeric(1))) coefficient = rational_constant(abs(q));
        continue;
      }
      if (is_a<power>(f) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_negative()) {
        v = signed_value(pow(f.op(0), -f.op(1)));
        in_denominator = true;
      } else {
        v = signed_value(f);
      }
      negated ^= v.negated;
      int& chain = in_denominator ? denominator : numerator;
      chain = chain < 0 ? v.ref : emit(OpCode::mul, chain, v.ref);
    }
    if (coefficient >= 0) numerator = numerator < 0 ? coefficient : emit(OpCode::mul, coefficient, numerator);
    int result;
    if (numerator < 0)
      result = denominator < 0 ? rational_constant(numeric(1)) : emit(OpCode::inv, denominator);
    else
      result = denominator < 0 ? numerator : emit(OpCode::div, numerator, denominator);
    return {result, negated};
  }

  //! base^n for an integer n ≠ 0 given the compiled base.
  int integer_power(int base, long n) {
    const long m = n < 0 ? -n : n;
    if (m > (1L << 30)) throw PreconditionViolation("straight-line program: exponent too large");
    int r = base;
    if (m == 2) r = emit(OpCode::square, base);
    else if (m > 2) r = emit(OpCode::pow, base, static_cast<int>(m));
    return n < 0 ? emit(OpCode::inv, r) : r;
  }

  SignedRef compile_power(const GiNaC::ex& base, const GiNaC::ex& exponent, const GiNaC::ex& e) {
    using namespace GiNaC;
    if (!is_a<numeric>(exponent)) unsupported(e, "the exponent must be an integer or half an odd integer");
    const numeric& k = ex_to<numeric>(exponent);
    if (k.is_integer()) {
      if (k.is_zero()) return {rational_constant(numeric(1)), false};
      if (!k.is_pos_integer()) {  // negative: share base^|k| with other occurrences
        const SignedRef v = signed_value(pow(base, -exponent));
        return {emit(OpCode::inv, v.ref), v.negated};
      }
      if (k > numeric(1L << 30)) unsupported(e, "exponent too large");
      const long n = k.to_long();
      const SignedRef b = signed_value(base);  // (−b)ⁿ = ±bⁿ
      return {integer_power(b.ref, n), b.negated && (n % 2 == 1)};
    }
    const numeric twice = k * 2;
    if (twice.is_integer()) {  // k = p/2 with p odd: sqrt(base)^p
      if (twice > numeric(1L << 30) || twice < numeric(-(1L << 30))) unsupported(e, "exponent too large");
      const int s = emit(OpCode::sqrt, compile(base));
      return {integer_power(s, twice.to_long()), false};
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
  const RunLimits& limits_ = RunLimits::current();
  std::unordered_map<GiNaC::ex, int, std::hash<GiNaC::ex>, GiNaC::ex_is_equal> symbols_;
  std::unordered_map<GiNaC::ex, SignedRef, std::hash<GiNaC::ex>, GiNaC::ex_is_equal> memo_;
  std::unordered_map<GiNaC::ex, Canon, std::hash<GiNaC::ex>, GiNaC::ex_is_equal> canon_;
  std::map<GiNaC::numeric, int, GiNaC::ex_is_less> constant_refs_;
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
  mark_scalings();
  schedule();
}

void StraightLineProgram::mark_scalings() {
  const std::int32_t first = static_cast<std::int32_t>(n_inputs_);
  const std::int32_t end = first + static_cast<std::int32_t>(constants_.size());
  auto exact_constant = [&](std::int32_t reg) {
    if (reg < first || reg >= end) return false;
    const Interval& c = constants_interval_[reg - first];
    return c.inf() == c.sup() && c.inf() != 0;
  };
  for (Instruction& ins : code_) {
    if (ins.op != OpCode::mul) continue;
    if (exact_constant(ins.a)) std::swap(ins.a, ins.b);
    if (exact_constant(ins.b)) ins.op = OpCode::scale;
  }
}

void StraightLineProgram::schedule() {
  // Kahn's algorithm; among the ready instructions prefer the opcode of the previous one, else the
  // opcode with the most ready instructions (ties: the smaller opcode).  Deterministic.
  const std::size_t n = code_.size();
  const std::int32_t base = static_cast<std::int32_t>(n_inputs_ + constants_.size());
  constexpr int n_ops = static_cast<int>(OpCode::scale) + 1;
  std::vector<int> pending(n, 0);
  std::vector<std::vector<std::int32_t>> users(n);
  std::vector<std::deque<std::int32_t>> ready(n_ops);
  for (std::size_t i = 0; i < n; ++i) {
    const Instruction& ins = code_[i];
    std::int32_t deps[2] = {ins.a, is_binary(ins.op) ? ins.b : -1};
    if (deps[1] == deps[0]) deps[1] = -1;
    for (std::int32_t d : deps)
      if (d >= base) {
        ++pending[i];
        users[d - base].push_back(static_cast<std::int32_t>(i));
      }
    if (pending[i] == 0) ready[static_cast<int>(ins.op)].push_back(static_cast<std::int32_t>(i));
  }
  std::vector<std::int32_t> order, position(n);
  order.reserve(n);
  int current = -1;
  while (order.size() < n) {
    if (current < 0 || ready[current].empty()) {
      current = 0;
      for (int op = 1; op < n_ops; ++op)
        if (ready[op].size() > ready[current].size()) current = op;
    }
    const std::int32_t i = ready[current].front();
    ready[current].pop_front();
    position[i] = static_cast<std::int32_t>(order.size());
    order.push_back(i);
    for (std::int32_t u : users[i])
      if (--pending[u] == 0) ready[static_cast<int>(code_[u].op)].push_back(u);
  }
  const auto renumber = [&](std::int32_t reg) { return reg >= base ? base + position[reg - base] : reg; };
  std::vector<Instruction> code;
  code.reserve(n);
  for (std::int32_t i : order) {
    Instruction ins = code_[i];
    ins.a = renumber(ins.a);
    if (is_binary(ins.op)) ins.b = renumber(ins.b);
    code.push_back(ins);
  }
  code_ = std::move(code);
  for (std::int32_t& reg : outputs_) reg = renumber(reg);
  blocks_.clear();
  for (std::uint32_t k = 0; k < n; ++k) {
    if (blocks_.empty() || blocks_.back().op != code_[k].op) blocks_.push_back(Block{code_[k].op, k, k});
    blocks_.back().end = k + 1;
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
  const std::size_t n_in_first = std::min(n_first, n_inputs_);
  for (std::size_t i = 0; i < n_in_first; ++i) Tr::assign(r[i], in_first[i]);
  for (std::size_t i = n_in_first; i < n_inputs_; ++i) Tr::assign(r[i], in_rest[i - n_first]);

  T* const out = r + n_inputs_ + n_c;
  const Instruction* const code = code_.data();
  for (const Block& block : blocks_) {
    const std::uint32_t begin = block.begin, end = block.end;
#define DELMESH_SLP_RUN(STATEMENT)                     \
  for (std::uint32_t k = begin; k < end; ++k) {        \
    const Instruction& ins = code[k];                  \
    STATEMENT;                                         \
  }                                                    \
  break;
    switch (block.op) {
      case OpCode::add: DELMESH_SLP_RUN(Tr::add(out[k], r[ins.a], r[ins.b]))
      case OpCode::sub: DELMESH_SLP_RUN(Tr::sub(out[k], r[ins.a], r[ins.b]))
      case OpCode::mul: DELMESH_SLP_RUN(Tr::mul(out[k], r[ins.a], r[ins.b]))
      case OpCode::div: DELMESH_SLP_RUN(Tr::div(out[k], r[ins.a], r[ins.b]))
      case OpCode::neg: DELMESH_SLP_RUN(Tr::neg(out[k], r[ins.a]))
      case OpCode::inv: DELMESH_SLP_RUN(Tr::inv(out[k], r[ins.a]))
      case OpCode::square: DELMESH_SLP_RUN(Tr::square(out[k], r[ins.a]))
      case OpCode::pow: DELMESH_SLP_RUN(Tr::pow(out[k], r[ins.a], ins.b))
      case OpCode::exp: DELMESH_SLP_RUN(Tr::exp(out[k], r[ins.a]))
      case OpCode::log: DELMESH_SLP_RUN(Tr::log(out[k], r[ins.a]))
      case OpCode::sqrt: DELMESH_SLP_RUN(Tr::sqrt(out[k], r[ins.a]))
      case OpCode::sin: DELMESH_SLP_RUN(Tr::sin(out[k], r[ins.a]))
      case OpCode::cos: DELMESH_SLP_RUN(Tr::cos(out[k], r[ins.a]))
      case OpCode::scale:
        // Interval multiplies by the double itself (see the header).
        if constexpr (std::is_same_v<T, Interval>) {
          DELMESH_SLP_RUN(out[k] = r[ins.b].inf() * r[ins.a])
        } else {
          DELMESH_SLP_RUN(Tr::mul(out[k], r[ins.a], r[ins.b]))
        }
    }
#undef DELMESH_SLP_RUN
  }
  const std::int32_t* const output = outputs_.data();
  const std::size_t n_outputs = outputs_.size(), n_first_outputs = std::min(n_out_first, n_outputs);
  for (std::size_t j = 0; j < n_first_outputs; ++j) out_first[j] = r[output[j]];
  for (std::size_t j = n_first_outputs; j < n_outputs; ++j) out_rest[j - n_out_first] = r[output[j]];
}

bool StraightLineProgram::is_polynomial_program() const {
  for (const Instruction& ins : code_) {
    switch (ins.op) {
      case OpCode::add:
      case OpCode::sub:
      case OpCode::mul:
      case OpCode::scale:
      case OpCode::neg:
      case OpCode::square: break;
      case OpCode::pow:
        if (ins.b < 0) return false;
        break;
      default: return false;
    }
  }
  return true;
}

std::optional<int> StraightLineProgram::degree_bound(std::size_t n_variables) const {
  if (!is_polynomial_program()) return std::nullopt;
  constexpr long saturated = std::numeric_limits<int>::max();
  const std::size_t first = n_inputs_ + constants_.size();
  std::vector<long> degree(first + code_.size(), 0);
  for (std::size_t j = 0; j < std::min(n_variables, n_inputs_); ++j) degree[j] = 1;
  for (std::size_t k = 0; k < code_.size(); ++k) {
    const Instruction& ins = code_[k];
    const long a = degree[ins.a];
    long d = a;  // neg
    switch (ins.op) {
      case OpCode::add:
      case OpCode::sub: d = std::max(a, degree[ins.b]); break;
      case OpCode::mul:
      case OpCode::scale: d = a + degree[ins.b]; break;
      case OpCode::square: d = 2 * a; break;
      case OpCode::pow: d = a * ins.b; break;
      default: break;
    }
    degree[first + k] = std::min(d, saturated);
  }
  return static_cast<int>(*std::max_element(degree.begin(), degree.end()));
}

namespace {

//! c = a·b truncated after t^(n−1), where a_i = 0 for i > da and b_i = 0 for i > db (da, db < n);
//! returns the degree bound of c, min(da + db, n − 1).  Only the coefficients up to it are
//! written (c must not alias a or b; its higher coefficients are left as they are).  The products
//! with a known zero factor are skipped: each sum then adds the same nonzero products in the same
//! order as the full convolution, and adding an exact zero changes no bound.
template <class T>
std::size_t multiply_truncated(const T* a, std::size_t da, const T* b, std::size_t db, std::size_t n, T* c) {
  const std::size_t dc = std::min(da + db, n - 1);
  for (std::size_t k = 0; k <= dc; ++k) {
    const std::size_t lo = k > db ? k - db : 0, hi = std::min(k, da);
    T sum = a[lo] * b[k - lo];
    for (std::size_t i = lo + 1; i <= hi; ++i) sum += a[i] * b[k - i];
    c[k] = sum;
  }
  return dc;
}

//! out = a^e truncated after t^(n−1) (a of degree bound da), by square-and-multiply on truncated
//! series, out starting as the series 1; `power` and `product` are scratch of n coefficients.
//! Returns out's degree bound.
template <class T>
std::size_t power_truncated(const T* a, std::size_t da, std::int32_t e, std::size_t n, T* power, T* product, T* out) {
  out[0] = T(1);
  std::size_t d = 0;
  std::copy(a, a + da + 1, power);
  std::size_t dp = da;
  for (; e > 0; e >>= 1) {
    if (e & 1) {
      d = multiply_truncated(out, d, power, dp, n, product);
      std::copy(product, product + d + 1, out);
    }
    if (e > 1) {
      dp = multiply_truncated(power, dp, power, dp, n, product);
      std::copy(product, product + dp + 1, power);
    }
  }
  return d;
}

//! One instruction of a polynomial program on series truncated after t^(n−1): writes its
//! register `out` up to its degree bound d, from the registers (n coefficients each) and their
//! degree bounds; `power` and `product` are scratch of n coefficients.  False for an instruction
//! that is not polynomial.
template <class T>
bool series_instruction(const Instruction& ins, const T* registers, const std::size_t* degree, std::size_t n,
                        T* power, T* product, T* out, std::size_t& d) {
  auto reg = [&](std::int32_t i) { return registers + static_cast<std::size_t>(i) * n; };
  const T* a = reg(ins.a);
  const std::size_t da = degree[ins.a];
  switch (ins.op) {
    case OpCode::add:
    case OpCode::sub: {
      const T* b = reg(ins.b);
      d = std::max(da, degree[ins.b]);
      if (ins.op == OpCode::add)
        for (std::size_t i = 0; i <= d; ++i) out[i] = a[i] + b[i];
      else
        for (std::size_t i = 0; i <= d; ++i) out[i] = a[i] - b[i];
      return true;
    }
    case OpCode::neg:
      d = da;
      for (std::size_t i = 0; i <= d; ++i) out[i] = -a[i];
      return true;
    case OpCode::mul:
    case OpCode::scale: d = multiply_truncated(a, da, reg(ins.b), degree[ins.b], n, out); return true;
    case OpCode::square: d = multiply_truncated(a, da, a, da, n, out); return true;
    case OpCode::pow: d = power_truncated(a, da, ins.b, n, power, product, out); return true;
    default: return false;  // excluded by is_polynomial_program()
  }
}

}  // namespace

template <class T>
bool StraightLineProgram::evaluate_along_line(const T* point, const T* direction, int order, T* outputs) const {
  if (order < 0 || !is_polynomial_program()) return false;
  const std::size_t n = static_cast<std::size_t>(order) + 1;
  const std::size_t n_c = constants_.size();
  const std::size_t n_registers = n_inputs_ + n_c + code_.size();
  // degree[r] bounds the degree in t of register r: 1 for an input, 0 for a constant, and what
  // the instruction makes of its operands' bounds (capped at the order); every coefficient above
  // it is zero, so it is not computed (an addition reads the shorter operand's zeros).
  // The bounds depend on the program and the order only, and every instruction writes all the
  // coefficients of its register up to the bound and none above it, before any later one reads
  // them.  So the zeros above the bounds, once written, stay: the registers are zeroed only when
  // the program or the order differs from this thread's previous call.
  thread_local std::vector<T> registers, power, product;
  thread_local std::vector<std::size_t> degree;
  thread_local std::uint64_t zeroed_for_program = 0;
  thread_local std::size_t zeroed_for_order = 0;
  if (zeroed_for_program != serial_ || zeroed_for_order != n || registers.size() != n_registers * n) {
    registers.assign(n_registers * n, T(0));
    zeroed_for_program = serial_;
    zeroed_for_order = n;
  }
  degree.assign(n_registers, 0);
  power.resize(n);
  product.resize(n);
  auto reg = [&](std::int32_t i) { return registers.data() + static_cast<std::size_t>(i) * n; };
  for (std::size_t i = 0; i < n_inputs_; ++i) {
    reg(static_cast<std::int32_t>(i))[0] = point[i];
    if (n > 1) {
      reg(static_cast<std::int32_t>(i))[1] = direction[i];
      degree[i] = 1;
    }
  }
  thread_local std::vector<T> constant_values;
  constant_values.resize(n_c);
  load_constants(constant_values.data());
  for (std::size_t k = 0; k < n_c; ++k) reg(static_cast<std::int32_t>(n_inputs_ + k))[0] = constant_values[k];
  const std::int32_t first = static_cast<std::int32_t>(n_inputs_ + n_c);
  for (std::size_t k = 0; k < code_.size(); ++k) {
    T* out = reg(first + static_cast<std::int32_t>(k));
    if (!series_instruction(code_[k], registers.data(), degree.data(), n, power.data(), product.data(), out,
                            degree[n_inputs_ + n_c + k]))
      return false;
  }
  for (std::size_t j = 0; j < outputs_.size(); ++j) std::copy(reg(outputs_[j]), reg(outputs_[j]) + n, outputs + j * n);
  return true;
}

template bool StraightLineProgram::evaluate_along_line<double>(const double*, const double*, int, double*) const;
template bool StraightLineProgram::evaluate_along_line<Interval>(const Interval*, const Interval*, int,
                                                                 Interval*) const;

#define DELMESH_DEFINE_SLP_EVALUATE(T)                                                                   \
  template void StraightLineProgram::evaluate<T>(const T*, std::size_t, const T*, T*, std::size_t, T*) \
      const;
DELMESH_DEFINE_SLP_EVALUATE(double)
DELMESH_DEFINE_SLP_EVALUATE(Interval)
DELMESH_DEFINE_SLP_EVALUATE(MpfrReal)
DELMESH_DEFINE_SLP_EVALUATE(MpfiInterval)
DELMESH_DEFINE_SLP_EVALUATE(Complex)
DELMESH_DEFINE_SLP_EVALUATE(ComplexInterval)
#undef DELMESH_DEFINE_SLP_EVALUATE

}  // namespace delmesh::detail
