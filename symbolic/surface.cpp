#include "symbolic/surface.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "common/errors.h"
#include "common/run_limits.h"

namespace delmesh {

const GiNaC::symbol& coordinate_x() {
  static const GiNaC::symbol x("x");
  return x;
}
const GiNaC::symbol& coordinate_y() {
  static const GiNaC::symbol y("y");
  return y;
}
const GiNaC::symbol& coordinate_z() {
  static const GiNaC::symbol z("z");
  return z;
}
GiNaC::lst coordinates() { return GiNaC::lst{coordinate_x(), coordinate_y(), coordinate_z()}; }

// ---------------------------------------------------------------------------------------------
// Box3
// ---------------------------------------------------------------------------------------------

Box3 Box3::cube(double h) {
  if (!(h > 0)) throw PreconditionViolation("Box3::cube: the half width must be positive");
  Box3 b;
  b.lo = {-h, -h, -h};
  b.hi = {h, h, h};
  return b;
}

Box3 Box3::parse(const std::string& text) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(text);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!text.empty() && text.back() == ',') fields.emplace_back();
  if (fields.size() != 6)
    throw InvalidInput("box \"" + text + "\": expected 6 comma-separated numbers x0,x1,y0,y1,z0,z1, got " +
                       std::to_string(fields.size()));
  double values[6];
  for (int i = 0; i < 6; ++i) {
    const std::string& f = fields[i];
    const std::string field_name = "box \"" + text + "\": field " + std::to_string(i + 1) + " \"" + f + "\"";
    std::size_t start = 0;
    while (start < f.size() && std::isspace(static_cast<unsigned char>(f[start]))) ++start;
    char* end = nullptr;
    errno = 0;
    values[i] = start < f.size() ? std::strtod(f.c_str() + start, &end) : 0;
    const bool range_error = errno == ERANGE;
    bool ok = start < f.size() && end != f.c_str() + start;
    if (ok)
      for (const char* k = end; *k != '\0'; ++k)
        if (!std::isspace(static_cast<unsigned char>(*k))) ok = false;
    if (ok && range_error && std::isinf(values[i]))
      throw InvalidInput(field_name + " is not a finite number: it overflows double precision (magnitude above "
                         "1.7976931348623157e308)");
    if (!ok || !std::isfinite(values[i])) throw InvalidInput(field_name + " is not a finite number");
    // A nonzero coordinate must be a normal double: a subnormal one (or one that underflows to 0)
    // has lost precision, and a side that small cannot be subdivided or evaluated on.
    if (range_error || (values[i] != 0 && std::abs(values[i]) < min_coordinate))
      throw InvalidInput(field_name + " is too small: a nonzero box coordinate must be at least " +
                         "2.2250738585072014e-308 in magnitude (the smallest normal double); write 0 for 0");
  }
  Box3 box;
  static const char* names = "xyz";
  for (int i = 0; i < 3; ++i) {
    box.lo[i] = values[2 * i];
    box.hi[i] = values[2 * i + 1];
    if (!(box.lo[i] < box.hi[i]))
      throw InvalidInput("box \"" + text + "\": empty range for " + names[i] + " (need " + names[i] +
                         "0 < " + names[i] + "1)");
    if (!std::isfinite(box.hi[i] - box.lo[i]))
      throw InvalidInput("box \"" + text + "\": too large: the width " + names[i] + "1 - " + names[i] +
                         "0 overflows double precision; rescale the coordinates");
  }
  if (!std::isfinite(box.diagonal()))
    throw InvalidInput("box \"" + text + "\": too large: the square of its diagonal overflows double precision "
                       "(widths up to about 1e154); rescale the coordinates");
  return box;
}

bool Box3::contains(const std::array<double, 3>& p) const {
  for (int i = 0; i < 3; ++i)
    if (!(lo[i] <= p[i] && p[i] <= hi[i])) return false;
  return true;
}

double Box3::diagonal() const {
  double s = 0;
  for (int i = 0; i < 3; ++i) s += (hi[i] - lo[i]) * (hi[i] - lo[i]);
  return std::sqrt(s);
}

// ---------------------------------------------------------------------------------------------
// Parsing
// ---------------------------------------------------------------------------------------------

namespace {

constexpr long kMaxDecimalExponent = Surface::max_decimal_exponent;
constexpr long kMaxPower = Surface::max_power;

//! The exact rational value of a decimal literal "123", "0.16", ".5", "1.5e-3", "2E4".
GiNaC::numeric decimal_to_rational(const std::string& literal) {
  std::string digits;
  long scale = 0;  // value = digits * 10^scale
  std::size_t i = 0;
  bool seen_point = false;
  for (; i < literal.size(); ++i) {
    char c = literal[i];
    if (std::isdigit(static_cast<unsigned char>(c))) {
      digits += c;
      if (seen_point) --scale;
    } else if (c == '.' && !seen_point) {
      seen_point = true;
    } else {
      break;
    }
  }
  if (i < literal.size()) {
    if (literal[i] != 'e' && literal[i] != 'E')
      throw InvalidInput("malformed number \"" + literal + "\"");
    ++i;
    std::string exponent;
    if (i < literal.size() && (literal[i] == '+' || literal[i] == '-')) exponent += literal[i++];
    for (; i < literal.size() && std::isdigit(static_cast<unsigned char>(literal[i])); ++i) exponent += literal[i];
    if (i != literal.size() || exponent.empty() || exponent == "+" || exponent == "-")
      throw InvalidInput("malformed number \"" + literal + "\"");
    if (exponent.size() > 6 || std::abs(std::stol(exponent)) > kMaxDecimalExponent)
      throw InvalidInput("number \"" + literal + "\": decimal exponent out of range (|e| <= " +
                         std::to_string(kMaxDecimalExponent) + ")");
    scale += std::stol(exponent);
  }
  if (digits.empty()) throw InvalidInput("malformed number \"" + literal + "\"");
  GiNaC::numeric value(digits.c_str());  // an exact integer
  GiNaC::numeric ten(10);
  return scale >= 0 ? value * ten.power(GiNaC::numeric(scale)) : value / ten.power(GiNaC::numeric(-scale));
}

const char* const kAllowedFunctions[] = {"exp", "sqrt", "sin", "cos", "log"};
const char* const kAllowedSymbols = "x, y, z, Pi (alias pi)";

bool is_allowed_function(const std::string& name) {
  for (const char* f : kAllowedFunctions)
    if (name == f) return true;
  return false;
}

//! For a function that is not C² (abs, min, max, sign, floor, ceil, in the spellings of C, GiNaC
//! and sympy's str()): why it is refused and the smooth blend to write instead, e.g. "is not
//! smooth: E must be C² (use …)"; "" for any other name.
std::string non_smooth_reason(const std::string& name) {
  const std::string small_c = ", with a small c > 0)";
  if (name == "abs" || name == "Abs" || name == "fabs")
    return "is not smooth: E must be C² (use a smooth blend, e.g. sqrt(x^2+c^2) for |x|" + small_c;
  if (name == "min" || name == "Min" || name == "fmin")
    return "is not smooth: E must be C² (use a smooth blend, e.g. (a+b-sqrt((a-b)^2+c^2))/2 for min(a,b)" + small_c;
  if (name == "max" || name == "Max" || name == "fmax")
    return "is not smooth: E must be C² (use a smooth blend, e.g. (a+b+sqrt((a-b)^2+c^2))/2 for max(a,b)" + small_c;
  if (name == "sign" || name == "csgn" || name == "step" || name == "Heaviside")
    return "is not continuous: E must be C² (use a smooth blend, e.g. x/sqrt(x^2+c^2) for sign(x)" + small_c;
  if (name == "floor" || name == "ceil" || name == "ceiling" || name == "round")
    return "is not continuous: E must be C² (write E without it)";
  return "";
}

//! The two spellings of the power operator: '^' and '**' (Python's, which sympy's str() prints).
bool is_power(const std::string& op) { return op == "^" || op == "**"; }

enum class TokenKind { number, identifier, op, lparen, rparen, end };
struct Token {
  TokenKind kind;
  std::string text;
  std::size_t position;  // 1-based column in the original text
};

//! The text for a message: itself when short, else its beginning and its length (an error stays
//! one readable line).
std::string abbreviated(const std::string& text) {
  constexpr std::size_t shown = 60;
  if (text.size() <= shown) return "\"" + text + "\"";
  return "\"" + text.substr(0, shown) + "...\" (" + std::to_string(text.size()) + " characters)";
}

std::string where(const std::string& text, std::size_t position) {
  return "at position " + std::to_string(position) + " of " + abbreviated(text);
}

std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  const std::size_t n = text.size();
  auto is_digit = [&](std::size_t k) { return k < n && std::isdigit(static_cast<unsigned char>(text[k])); };
  while (i < n) {
    const char c = text[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
      continue;
    }
    const std::size_t start = i;
    if (is_digit(i) || (c == '.' && is_digit(i + 1))) {
      while (is_digit(i)) ++i;
      if (i < n && text[i] == '.') {
        ++i;
        while (is_digit(i)) ++i;
      }
      if (i < n && (text[i] == 'e' || text[i] == 'E')) {
        std::size_t k = i + 1;
        if (k < n && (text[k] == '+' || text[k] == '-')) ++k;
        if (!is_digit(k))
          throw InvalidInput("malformed number \"" + text.substr(start, k - start + (k < n ? 1 : 0)) + "\" " +
                             where(text, start + 1));
        i = k;
        while (is_digit(i)) ++i;
      }
      tokens.push_back({TokenKind::number, text.substr(start, i - start), start + 1});
    } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      while (i < n && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) ++i;
      tokens.push_back({TokenKind::identifier, text.substr(start, i - start), start + 1});
      // A call of a function that is not C² is refused here, before its arguments (min(x, y)
      // has a comma) can stop the tokenizer with a less helpful message.
      std::size_t k = i;
      while (k < n && std::isspace(static_cast<unsigned char>(text[k]))) ++k;
      const std::string reason = non_smooth_reason(tokens.back().text);
      if (k < n && text[k] == '(' && !reason.empty())
        throw InvalidInput(tokens.back().text + " " + where(text, start + 1) + " " + reason);
    } else if (c == '*' && i + 1 < n && text[i + 1] == '*') {
      tokens.push_back({TokenKind::op, "**", start + 1});
      i += 2;
    } else if (c == '+' || c == '-' || c == '*' || c == '/' || c == '^') {
      tokens.push_back({TokenKind::op, std::string(1, c), start + 1});
      ++i;
    } else if (c == '(') {
      tokens.push_back({TokenKind::lparen, "(", start + 1});
      ++i;
    } else if (c == ')') {
      tokens.push_back({TokenKind::rparen, ")", start + 1});
      ++i;
    } else {
      throw InvalidInput(std::string("unexpected character '") + c + "' " + where(text, start + 1) +
                         "; allowed: numbers, x y z, Pi, exp sqrt sin cos log, + - * / ^ (or **) and parentheses");
    }
  }
  tokens.push_back({TokenKind::end, "", n + 1});
  return tokens;
}

//! A recognizer of the accepted grammar over the token list.  GiNaC's parser builds the
//! expression; this pass only exists to give errors with positions (GiNaC reports none) and to
//! reject constructs GiNaC accepts with surprising meaning:
//!   expression := unary (binop unary)*        binop ∈ { + - * / }
//!   unary      := [+|-] factor                only at the start of an expression
//!   factor     := primary [ power exponent ]  power ∈ { ^ ** } (a^b^c is rejected as ambiguous)
//!   exponent   := number | '(' [+|-] exponent ')'    an integer
//!   primary    := number | x | y | z | Pi | pi | f '(' expression ')' | '(' expression ')'
//! GiNaC parses a sign after a binary operator as applying to the rest of the expression
//! ("2*-x+y" becomes 2*(-x+y)), so a sign directly after an operator is rejected.
class Recognizer {
 public:
  Recognizer(const std::string& text, const std::vector<Token>& tokens) : text_(text), tokens_(tokens) {}

  void run() {
    if (tokens_.front().kind == TokenKind::end) throw InvalidInput("empty expression");
    expression();
    if (peek().kind != TokenKind::end) fail("unexpected '" + peek().text + "'", peek());
  }

 private:
  const Token& peek() const { return tokens_[at_]; }
  const Token& next() { return tokens_[at_++]; }
  [[noreturn]] void fail(const std::string& what, const Token& token) const {
    if (token.kind == TokenKind::end)
      throw InvalidInput("syntax error: " + what + " at the end of " + abbreviated(text_));
    throw InvalidInput("syntax error: " + what + " " + where(text_, token.position));
  }
  static std::string describe(const Token& t) { return t.kind == TokenKind::end ? "end of input" : "'" + t.text + "'"; }

  //! Entered at every '(' (of a parenthesis, a function call or an exponent): the recursion, and
  //! GiNaC's recursive algorithms later, stay within Surface::max_nesting levels.
  void open(const Token& t) {
    if (++depth_ > Surface::max_nesting)
      fail("parentheses nested more than " + std::to_string(Surface::max_nesting) + " deep", t);
  }

  void expression() {
    if (peek().kind == TokenKind::op && (peek().text == "+" || peek().text == "-")) next();
    factor();
    while (peek().kind == TokenKind::op) {
      const Token& op = next();
      if (is_power(op.text)) fail("a" + op.text + "b" + op.text + "c is ambiguous, use parentheses; '" + op.text + "'", op);
      if (peek().kind == TokenKind::op && (peek().text == "+" || peek().text == "-"))
        fail("sign '" + peek().text + "' directly after operator '" + op.text +
                 "' (write it in parentheses, e.g. x*(-y))",
             peek());
      factor();
    }
  }

  void factor() {
    primary();
    if (peek().kind == TokenKind::op && is_power(peek().text)) exponent(next().text, 0);
  }

  //! The exponent after the power operator `power` ("^" or "**", as written, for the messages).
  void exponent(const std::string& power, int depth) {
    const Token& t = next();
    if (t.kind == TokenKind::lparen) {
      open(t);
      if (peek().kind == TokenKind::op && (peek().text == "+" || peek().text == "-")) next();
      exponent(power, depth + 1);
      const Token& close = next();
      if (close.kind != TokenKind::rparen) fail("non-integer power: expected ')' after the exponent, got " + describe(close), close);
      --depth_;
      return;
    }
    if (t.kind == TokenKind::number) {
      GiNaC::numeric value = decimal_to_rational(t.text);
      if (!value.is_integer()) fail("non-integer power '" + power + t.text + "'", t);
      if (GiNaC::abs(value) > kMaxPower)
        fail("power '" + power + t.text + "' too large (at most " + std::to_string(kMaxPower) + ")", t);
      return;
    }
    if (t.kind == TokenKind::op && (t.text == "+" || t.text == "-"))
      fail("sign after '" + power + "' must be in parentheses, e.g. x" + power + "(-2); got '" + t.text + "'", t);
    if (t.kind == TokenKind::op) fail("expected an integer exponent after '" + power + "', got '" + t.text + "'", t);
    fail("non-integer power: the exponent must be an integer literal, got " + describe(t), t);
  }

  void primary() {
    const Token& t = next();
    switch (t.kind) {
      case TokenKind::number:
        return;
      case TokenKind::identifier:
        if (t.text == "x" || t.text == "y" || t.text == "z" || t.text == "Pi" || t.text == "pi") {
          if (peek().kind == TokenKind::lparen) fail("'" + t.text + "' is not a function", t);
          return;
        }
        if (is_allowed_function(t.text)) {
          const Token& paren = next();
          if (paren.kind != TokenKind::lparen) fail("expected '(' after function '" + t.text + "'", paren);
          open(paren);
          expression();
          const Token& close = next();
          if (close.kind != TokenKind::rparen)
            fail("expected ')' closing '" + t.text + "(' (one argument), got " + describe(close), close);
          --depth_;
          return;
        }
        if (peek().kind == TokenKind::lparen)
          throw InvalidInput("unknown function '" + t.text + "' " + where(text_, t.position) +
                             "; allowed: exp, sqrt, sin, cos, log");
        throw InvalidInput("unknown symbol '" + t.text + "' " + where(text_, t.position) + "; allowed: " +
                           kAllowedSymbols);
      case TokenKind::lparen: {
        open(t);
        expression();
        const Token& close = next();
        if (close.kind != TokenKind::rparen) fail("expected ')', got " + describe(close), close);
        --depth_;
        return;
      }
      default:
        fail("unexpected " + describe(t), t);
    }
  }

  const std::string& text_;
  const std::vector<Token>& tokens_;
  std::size_t at_ = 0;
  std::size_t depth_ = 0;
};

std::string print(const GiNaC::ex& e) {
  std::ostringstream out;
  out << e;
  return out.str();
}

//! Replaces every floating-point numeric by the exact rational of the shortest decimal text that
//! reads back as the same double (numeric(0.1) becomes 1/10).
GiNaC::ex rationalize_floats(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) {
    const auto& n = GiNaC::ex_to<GiNaC::numeric>(e);
    if (!n.is_real()) return e;  // rejected by validate()
    if (n.is_rational()) return e;
    // The shortest decimal text that reads back as the same double: numeric(0.1) becomes 1/10.
    const double value = n.to_double();
    if (!std::isfinite(value)) throw InvalidInput("non-finite constant " + print(e));
    char text[64];
    for (int digits = 1; digits <= 17; ++digits) {
      std::snprintf(text, sizeof text, "%.*e", digits - 1, std::fabs(value));
      if (std::strtod(text, nullptr) == std::fabs(value)) break;
    }
    GiNaC::numeric r = decimal_to_rational(text);
    return value < 0 ? GiNaC::ex(-r) : GiNaC::ex(r);
  }
  if (e.nops() == 0) return e;
  return e.map([](const GiNaC::ex& sub) { return rationalize_floats(sub); });
}

//! Throws InvalidInput unless e is a real-valued expression in x, y, z built from rationals, Pi,
//! + - * /, integer powers, square roots and exp sin cos log.
void validate(const GiNaC::ex& e, const std::string& text) {
  using namespace GiNaC;
  const std::string in = " in " + abbreviated(text);
  if (is_a<numeric>(e)) {
    const auto& n = ex_to<numeric>(e);
    if (!n.is_real()) throw InvalidInput("complex value " + print(e) + in + " (E must be real)");
    if (!n.is_rational()) throw InvalidInput("non-rational constant " + print(e) + in);
    return;
  }
  if (is_a<symbol>(e)) {
    if (e.is_equal(coordinate_x()) || e.is_equal(coordinate_y()) || e.is_equal(coordinate_z())) return;
    throw InvalidInput("unknown symbol '" + print(e) + "'" + in + "; allowed: " + kAllowedSymbols);
  }
  if (is_a<constant>(e)) {
    if (e.is_equal(Pi)) return;
    throw InvalidInput("unknown constant '" + print(e) + "'" + in + "; allowed: Pi");
  }
  if (is_a<power>(e)) {
    const ex exponent = e.op(1);
    bool ok = is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_rational() &&
              (ex_to<numeric>(exponent) * 2).is_integer();  // integer, or half-integer from sqrt
    if (!ok) throw InvalidInput("non-integer power '" + print(e) + "'" + in);
    validate(e.op(0), text);
    return;
  }
  if (is_a<function>(e)) {
    const std::string name = ex_to<function>(e).get_name();
    if (!non_smooth_reason(name).empty()) throw InvalidInput(name + in + " " + non_smooth_reason(name));
    if (name != "exp" && name != "sin" && name != "cos" && name != "log")
      throw InvalidInput("unknown function '" + name + "'" + in + "; allowed: exp, sqrt, sin, cos, log");
    validate(e.op(0), text);
    return;
  }
  if (is_a<add>(e) || is_a<mul>(e)) {
    for (std::size_t i = 0; i < e.nops(); ++i) validate(e.op(i), text);
    return;
  }
  throw InvalidInput("unsupported expression '" + print(e) + "'" + in);
}

//! True iff every numeric in e is rational and e uses no constants, functions or non-integer powers.
bool has_only_rational_polynomial_parts(const GiNaC::ex& e) {
  using namespace GiNaC;
  if (is_a<numeric>(e)) return ex_to<numeric>(e).is_rational();
  if (is_a<symbol>(e)) return true;
  if (is_a<constant>(e) || is_a<function>(e)) return false;
  if (is_a<power>(e)) {
    const ex exponent = e.op(1);
    if (!is_a<numeric>(exponent) || !ex_to<numeric>(exponent).is_nonneg_integer()) return false;
    return has_only_rational_polynomial_parts(e.op(0));
  }
  for (std::size_t i = 0; i < e.nops(); ++i)
    if (!has_only_rational_polynomial_parts(e.op(i))) return false;
  return true;
}

//! Bounds on the total degree of e in x, y, z and on the number of terms of e.expand() once each
//! symbol is replaced by a sum of `symbol_terms` terms, each its own variable (upper bounds where
//! e is a polynomial; a negative power counts like a positive one), computed from the expression
//! tree without expanding: a sum adds the term counts, a product multiplies them, an n-th power
//! of t terms has at most C(t + |n| − 1, |n|) (the monomials of degree |n| in t symbols); and a
//! polynomial of degree d in the k symbols of a subexpression has at most C(d + k·symbol_terms,
//! k·symbol_terms) terms.  Function arguments are bounded separately (a function value counts as
//! one term of degree 0).  Counts saturate at `cap`, and so do degrees.
struct SizeBound {
  double degree = 0;
  double terms = 1;
  std::set<std::string> symbols;  //!< the symbols of the subexpression
};

SizeBound size_bound(const GiNaC::ex& e, double cap, double symbol_terms) {
  using namespace GiNaC;
  const auto monomials = [cap](double symbols, double degree) {  // C(symbols + degree − 1, degree)
    double c = 1;
    for (double k = 1; k <= degree && c <= cap; ++k) c = c * (symbols - 1 + k) / k;
    return std::min(c, cap + 1);
  };
  const auto clamp = [cap, symbol_terms](SizeBound b) {
    const double variables = symbol_terms * static_cast<double>(b.symbols.size());
    double c = 1;  // C(degree + variables, variables)
    for (double k = 1; k <= variables && c <= cap; ++k) c = c * (b.degree + k) / k;
    b.degree = std::min(b.degree, cap + 1);
    b.terms = std::min({b.terms, cap + 1, std::max(1.0, c)});
    return b;
  };
  if (is_a<symbol>(e)) return {1, symbol_terms, {ex_to<symbol>(e).get_name()}};
  if (is_a<numeric>(e) || is_a<constant>(e)) return {0, 1, {}};
  if (is_a<function>(e)) {
    for (std::size_t i = 0; i < e.nops(); ++i) (void)size_bound(e.op(i), cap, symbol_terms);
    return {0, 1, {}};
  }
  if (is_a<power>(e)) {
    SizeBound base = size_bound(e.op(0), cap, symbol_terms);
    const ex exponent = e.op(1);
    double n = 1;
    if (is_a<numeric>(exponent)) n = std::ceil(std::abs(ex_to<numeric>(exponent).to_double()));
    return clamp({base.degree * n, monomials(base.terms, n), std::move(base.symbols)});
  }
  const bool sum = is_a<add>(e), product = is_a<mul>(e);
  SizeBound b{0, sum ? 0.0 : 1.0, {}};
  for (std::size_t i = 0; i < e.nops(); ++i) {
    SizeBound t = size_bound(e.op(i), cap, symbol_terms);
    if (sum) {
      b.degree = std::max(b.degree, t.degree);
      b.terms += t.terms;
    } else if (product) {
      b.degree += t.degree;
      b.terms *= t.terms;
    } else {
      b.degree = t.degree;
      b.terms = t.terms;
    }
    b.symbols.insert(t.symbols.begin(), t.symbols.end());
  }
  return sum || product ? clamp(std::move(b)) : b;
}

//! Throws InvalidInput if E's degree bound exceeds Surface::max_degree, or if its expansion, or
//! the expansion of E(p + t v) along a general line (each coordinate replaced by the sum of the
//! two products p_i and t·v_i: what symbolic/line_polynomial.h expands for a polynomial E), may
//! have more than Surface::max_expanded_terms terms (size_bound), before anything is expanded.
void check_size(const GiNaC::ex& E, const std::string& text) {
  const double cap = static_cast<double>(std::max<std::size_t>(Surface::max_degree, Surface::max_expanded_terms));
  SizeBound b = size_bound(E, cap, 1);
  const SizeBound along_line = size_bound(E, cap, 2);
  b.terms = std::max(b.terms, along_line.terms);
  if (b.degree > Surface::max_degree)
    throw InvalidInput("expression " + abbreviated(text) + " has degree up to " +
                       (b.degree > cap ? std::string("more than ") + std::to_string(Surface::max_degree) : std::to_string(static_cast<long>(b.degree))) +
                       " in x, y, z (at most " + std::to_string(Surface::max_degree) + ")");
  if (b.terms > Surface::max_expanded_terms)
    throw InvalidInput("expression " + abbreviated(text) + " is too large: expanded it may have more than " +
                       std::to_string(Surface::max_expanded_terms) + " terms; simplify it or lower its degree");
}

//! The size of e written out as a tree: every node counted at each of its uses.  `sizes` memoizes
//! it per shared node, so the cost is that of the expression's DAG.  Saturates at 1e300.
double tree_size(const GiNaC::ex& e, std::unordered_map<const GiNaC::basic*, double>& sizes) {
  const GiNaC::basic* node = &GiNaC::ex_to<GiNaC::basic>(e);
  const auto found = sizes.find(node);
  if (found != sizes.end()) return found->second;
  double size = 1;
  for (std::size_t i = 0; i < e.nops(); ++i) size = std::min(size + tree_size(e.op(i), sizes), 1e300);
  sizes.emplace(node, size);
  return size;
}

//! Throws InvalidInput if the Hessian of E, estimated from the tree sizes of E and ∇E, exceeds
//! Surface::max_derivative_tree_size and Surface::max_derivative_growth times E's size.
void check_derivative_size(const GiNaC::ex& E, const std::array<GiNaC::ex, 3>& gradient, const std::string& text) {
  std::unordered_map<const GiNaC::basic*, double> sizes;
  const double e = tree_size(E, sizes);
  double g = 0;
  for (const auto& d : gradient) g += tree_size(d, sizes);
  const double estimate = g / e * g;
  const double limit = std::max(Surface::max_derivative_tree_size, Surface::max_derivative_growth * e);
  if (estimate > limit) {
    std::ostringstream s;
    s.precision(2);
    s << "expression " << abbreviated(text) << " is too large to differentiate: its second derivatives would "
      << "have about " << estimate << " operations written out (at most " << limit
      << "); simplify it, e.g. use fewer factors in a product";
    throw InvalidInput(s.str());
  }
}

GiNaC::ex parse_text(const std::string& text) {
  if (text.size() > Surface::max_length)
    throw InvalidInput("expression too long: " + std::to_string(text.size()) + " characters (at most " +
                       std::to_string(Surface::max_length) + ")");
  const std::vector<Token> tokens = tokenize(text);
  Recognizer(text, tokens).run();

  // Rebuild the text with every decimal literal replaced by its exact rational "(n/d)", so that
  // GiNaC never sees a floating-point number.
  std::string exact;
  for (const Token& t : tokens) {
    if (t.kind == TokenKind::end) break;
    if (t.kind == TokenKind::number) {
      exact += "(" + print(decimal_to_rational(t.text)) + ")";
    } else if (t.kind == TokenKind::op && is_power(t.text)) {
      exact += '^';
    } else {
      exact += t.text;
    }
    exact += ' ';
  }

  GiNaC::symtab table;
  table["x"] = coordinate_x();
  table["y"] = coordinate_y();
  table["z"] = coordinate_z();
  table["Pi"] = GiNaC::Pi;
  table["pi"] = GiNaC::Pi;
  GiNaC::parser reader(table, /*strict=*/true);
  try {
    return reader(exact);
  } catch (const GiNaC::parse_error& error) {
    std::string message = error.what();
    const std::size_t colon = message.find(": ", message.find("column"));
    if (colon != std::string::npos) message = message.substr(colon + 2);
    const std::size_t newline = message.find('\n');
    if (newline != std::string::npos) message.resize(newline);
    throw InvalidInput("syntax error in " + abbreviated(text) + ": " + message);
  } catch (const std::exception& error) {
    if (std::string(error.what()).find("division by zero") != std::string::npos)
      throw InvalidInput("division by zero in " + abbreviated(text) + ": a divisor is identically 0");
    throw InvalidInput("cannot parse " + abbreviated(text) + ": " + error.what());
  }
}

}  // namespace

Surface Surface::parse(const std::string& text) { return Surface(parse_text(text), text); }

Surface::Surface(GiNaC::ex E, std::string text) {
  E_ = rationalize_floats(E);
  text_ = text.empty() ? print(E_) : std::move(text);
  validate(E_, text_);
  check_size(E_, text_);
  const GiNaC::symbol& x = coordinate_x();
  const GiNaC::symbol& y = coordinate_y();
  const GiNaC::symbol& z = coordinate_z();
  if (!E_.has(x) && !E_.has(y) && !E_.has(z))
    throw InvalidInput("constant expression " + abbreviated(text_) + " (= " + print(E_) +
                       ") does not define a surface; E must depend on x, y or z");

  // Each GiNaC call runs to its end; the command's limits are tested between them.
  const RunLimits& limits = RunLimits::current();
  const GiNaC::symbol* xyz[3] = {&x, &y, &z};
  for (int i = 0; i < 3; ++i) {
    limits.check("differentiating the expression", true);
    gradient_[i] = E_.diff(*xyz[i]);
  }
  check_derivative_size(E_, gradient_, text_);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (j >= i) limits.check("differentiating the expression", true);
      hessian_(i, j) = (j < i) ? hessian_(j, i) : gradient_[i].diff(*xyz[j]);
    }
  limits.check("expanding the expression", true);

  // Only a polynomial is expanded (check_size bounds its terms); a product of n non-polynomial
  // factors such as (2 + sin x) would expand to 2^n terms.
  const bool polynomial_in_xyz = E_.is_polynomial(coordinates());
  const GiNaC::ex expanded = polynomial_in_xyz ? E_.expand() : E_;
  polynomial_ = polynomial_in_xyz && has_only_rational_polynomial_parts(expanded);
  if (polynomial_) {
    // Total degree: the degree in s of E(s x, s y, s z).
    GiNaC::symbol s("s");
    GiNaC::ex scaled = E_.subs(GiNaC::lst{x == s * x, y == s * y, z == s * z}).expand();
    degree_ = scaled.degree(s);
  }
  normalize_constant_factor(expanded);
}

namespace {

//! The product of the numeric factors of a product (the number itself for a number; 1 for any
//! other expression).
GiNaC::numeric numeric_factor(const GiNaC::ex& e) {
  using namespace GiNaC;
  if (is_a<numeric>(e)) return ex_to<numeric>(e);
  numeric c = 1;
  if (is_a<mul>(e))
    for (std::size_t i = 0; i < e.nops(); ++i)
      if (is_a<numeric>(e.op(i))) c *= ex_to<numeric>(e.op(i));
  return c;
}

}  // namespace

void Surface::normalize_constant_factor(const GiNaC::ex& expanded) {
  using namespace GiNaC;
  numeric largest = 0;
  if (polynomial_ && is_a<add>(expanded)) {
    for (std::size_t i = 0; i < expanded.nops(); ++i) {
      const numeric c = abs(numeric_factor(expanded.op(i)));
      if (c > largest) largest = c;
    }
  } else {
    largest = abs(numeric_factor(polynomial_ ? expanded : E_));
  }
  if (largest.is_zero() || !largest.is_rational()) return;
  // 2^(k − 1) < largest < 2^(k + 1).
  const long k = static_cast<long>(largest.numer().int_length()) - static_cast<long>(largest.denom().int_length());
  if (k >= -max_coefficient_exponent && k <= max_coefficient_exponent) return;
  const ex factor = pow(numeric(2), numeric(-k));
  E_ = E_ * factor;
  for (auto& g : gradient_) g = g * factor;
  for (unsigned i = 0; i < 3; ++i)
    for (unsigned j = 0; j < 3; ++j) hessian_(i, j) = hessian_(i, j) * factor;
  normalization_exponent_ = static_cast<int>(k);
}

double Surface::evaluate(const std::array<double, 3>& p) const {
  GiNaC::ex value;
  try {
    value = E_.subs(GiNaC::lst{coordinate_x() == GiNaC::numeric(p[0]), coordinate_y() == GiNaC::numeric(p[1]),
                               coordinate_z() == GiNaC::numeric(p[2])})
                .evalf();
  } catch (const std::exception&) {  // a pole (1/0, log(0)): E is not defined there
    return std::nan("");
  }
  if (!GiNaC::is_a<GiNaC::numeric>(value)) return std::nan("");
  const auto& n = GiNaC::ex_to<GiNaC::numeric>(value);
  if (!n.is_real()) return std::nan("");
  return n.to_double();
}

}  // namespace delmesh
