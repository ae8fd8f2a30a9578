#include "solvers/univariate_isolator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/detail/bernstein.h"
#include "solvers/detail/deadline.h"
#include "solvers/detail/interval_box.h"
#include "solvers/detail/solve_progress.h"
#include "symbolic/scalar_traits.h"

namespace delmesh {

namespace {

using detail::midpoint;

//! Split points tried, in order: a split point at which the value cannot be proved nonzero
//! (a root on the split) would leave both halves undecidable.
constexpr double split_ratios[] = {0.5, 0.4375, 0.5625, 0.375, 0.625};

// Interval sign of a value: +1, −1, or 0 (not certain, including NaN bounds).
inline int certain_sign(const Interval& a) { return a.inf() > 0 ? 1 : (a.sup() < 0 ? -1 : 0); }
inline int certain_sign(const MpfiInterval& a) { return certain_sign(detail::to_interval(a)); }

//! Marks an end point whose certain sign has not been evaluated yet.
constexpr int unknown_sign = 2;

//! E(p + t v) over the compiled surface_line system (any E).
struct LineSystemEvaluator {
  const CompiledSystem& line;
  const Interval* parameters;   // 6 point intervals
  const double* parameters_d;   // 6 doubles
  Interval value(const Interval& t) const {
    Interval out;
    line.values(&t, parameters, &out);
    return out;
  }
  void value_and_derivative(const Interval& t, Interval& f, Interval& df) const {
    line.values_and_jacobian(&t, parameters, &f, &df);
  }
  void value_and_derivative(double t, double& f, double& df) const {
    line.values_and_jacobian(&t, parameters_d, &f, &df);
  }
};

//! E(p + t v) and dE/dt over the compiled surface_line system in MPFI at the current default
//! precision (any E; p and v are exact at every precision).  Construct, use and destroy it inside
//! one detail::MpfiPrecisionScope.
class MpfiLineEvaluator {
 public:
  MpfiLineEvaluator(const CompiledSystem& line, const double* parameters) : line_(line) {
    for (int i = 0; i < 6; ++i) p_[i] = detail::to_mpfi(parameters[i], parameters[i]);
  }
  //! The certain sign of E(p + t v) at the point t, or 0.
  int sign_at(double t) {
    t_ = detail::to_mpfi(t, t);
    line_.values(&t_, p_, &f_);
    return certain_sign(f_);
  }
  //! True when E has no zero on [a, b]: the natural enclosure of E over [a, b], or the mean-value
  //! form E(m) + E'([a, b]) ([a, b] − m) at m ∈ [a, b], excludes 0.  Also returns whether the
  //! enclosure of E' over [a, b] excludes 0 (E strictly monotone there).
  bool excludes(double a, double b, double m, bool& monotone) {
    t_ = detail::to_mpfi(a, b);
    line_.values_and_jacobian(&t_, p_, &f_, &df_);
    monotone = certainly_nonzero(df_);
    if (certainly_nonzero(f_)) return true;
    const MpfiInterval x = t_;
    t_ = detail::to_mpfi(m, m);
    line_.values(&t_, p_, &f_);
    f_ += df_ * (x - t_);
    return certainly_nonzero(f_);
  }

 private:
  const CompiledSystem& line_;
  MpfiInterval p_[6], t_, f_, df_;
};

//! E(p + t v) = Σ c_k t^k from the enclosed coefficients (polynomial E).
struct PolynomialEvaluator {
  int degree;
  const Interval* c;    // enclosures
  const double* c_mid;  // their midpoints, for Newton steps
  Interval value(const Interval& t) const { return detail::horner(degree, c, t); }
  void value_and_derivative(const Interval& t, Interval& f, Interval& df) const {
    f = detail::horner(degree, c, t);
    df = detail::horner_derivative(degree, c, t);
  }
  void value_and_derivative(double t, double& f, double& df) const {
    double a = c_mid[degree], da = 0;
    for (int k = degree - 1; k >= 0; --k) {
      da = da * t + a;
      a = a * t + c_mid[k];
    }
    f = a, df = da;
  }
};

//! [a, b] contains exactly one zero: sign change with certain signs at a and b and a derivative
//! enclosure over [a, b] excluding 0.
//! With known_unique (the caller knows that an interval containing [a, b] holds exactly one
//! zero), the sign change alone suffices.
template <class Evaluator>
bool certify_interval(const Evaluator& e, double a, double b, bool known_unique = false) {
  if (!(a < b)) return false;
  const int sa = certain_sign(e.value(Interval(a))), sb = certain_sign(e.value(Interval(b)));
  if (sa == 0 || sb == 0 || sa == sb) return false;
  if (known_unique) return true;
  Interval f, df;
  e.value_and_derivative(Interval(a, b), f, df);
  return certainly_nonzero(df);
}

//! A tight certified interval around the unique zero known to lie in [lo, hi] (E has exactly
//! one zero there, proved by the caller, and changes sign): safeguarded Newton steps in double
//! (bisection of the bracket when a step leaves it), then growing intervals [x − r, x + r] ∩
//! [lo, hi] until one has a certain sign change (it then holds that unique zero).  Returns false
//! if none has.
template <class Evaluator>
bool refine_root(const Evaluator& e, double lo, double hi, double x, double scale, double& out_lo, double& out_hi) {
  double a = lo, b = hi, fa, dfa;
  e.value_and_derivative(a, fa, dfa);
  for (int it = 0; it < tolerances::univariate_newton_iterations; ++it) {
    double f, df;
    e.value_and_derivative(x, f, df);
    if (f == 0) break;
    if ((f < 0) == (fa < 0))
      a = x, fa = f;
    else
      b = x;
    double next = x - f / df;
    if (!(next > a && next < b)) next = 0.5 * a + 0.5 * b;
    const double tolerance = tolerances::univariate_newton_relative_tolerance * scale;
    const bool done = std::abs(next - x) <= tolerance || b - a <= tolerance;
    x = next;
    if (done) break;
  }
  // Growing intervals around x, clipped to [lo, hi] (a root within r of an end of the isolating
  // interval is still bracketed: the clipped end keeps a certain sign).
  double r = tolerances::univariate_root_relative_radius * std::max(std::abs(x), scale);
  {
    // Start near the radius at which |E| exceeds the width of its enclosure: 2 w(E(x)) / |E'(x)|.
    double f, df;
    e.value_and_derivative(x, f, df);
    const double from_width = 2 * detail::width(e.value(Interval(x))) / std::abs(df);
    if (std::isfinite(from_width)) r = std::max(r, from_width);
  }
  for (int attempt = 0; attempt < tolerances::univariate_certify_attempts;
       ++attempt, r *= tolerances::univariate_certify_growth) {
    const double a = std::max(-(r - x), lo), b = std::min(x + r, hi);  // outward under upward rounding
    if (certify_interval(e, a, b, true)) {
      out_lo = a, out_hi = b;
      return true;
    }
    if (a == lo && b == hi) break;
  }
  return false;
}

//! An interval of relative width w (to t1 − t0) that could be neither excluded nor certified is
//! not subdivided further when it is narrower than singular_box_relative_width and the derivative
//! may vanish on it (not monotone), or narrower than min_box_relative_width.
bool is_leaf(double w, bool monotone) {
  return (!monotone && w < tolerances::singular_box_relative_width) || w < tolerances::min_box_relative_width;
}

//! The interval Bernstein coefficients b_0..b_d of a node are limited by rounding, not by the
//! node's size, when their widest enclosure exceeds univariate_precision_limited_ratio times
//! their largest magnitude: de Casteljau subdivision averages the enclosures and does not shrink
//! them, so no subnode could decide what this node cannot.
bool precision_limited(int d, const Interval* b) {
  double widest = 0, largest = 0;  // max(sup, −inf) = max(|inf|, |sup|) as inf ≤ sup
  for (int i = 0; i <= d; ++i) {
    const double lo = b[i].inf(), hi = b[i].sup();
    widest = std::max(widest, hi - lo);
    largest = std::max(largest, std::max(hi, -lo));
  }
  return widest > tolerances::univariate_precision_limited_ratio * largest;
}

//! The reason such a leaf is undecided: boundary_root if a zero may lie at t0 or t1 (boundary),
//! else precision if it is monotone, else singular_root.
UndecidedReason leaf_reason(bool boundary, bool monotone) {
  return boundary ? UndecidedReason::boundary_root
                  : monotone ? UndecidedReason::precision : UndecidedReason::singular_root;
}

struct Leaf {
  double lo, hi;  // t
  UndecidedReason reason;
  bool escalated = false;  // MPFI already failed on a region containing it: not retried
};

//! A certified interval [lo, hi] of t: exactly one zero, strictly inside (certain nonzero signs at
//! the ends or at the ends of its isolating interval).  monotone: E' is proved nonzero on all of
//! [lo, hi] (then two such intervals that meet hold the same zero: E is strictly monotone on
//! their union).
struct Found {
  double lo, hi;
  bool monotone;
};

//! Outcome of an MPFI escalation of an undecided interval.
enum class Escalation {
  decided,    //!< every zero in it is certified (possibly none); the interval is not undecided any more
  undecided,  //!< no precision decided it; it keeps its reason
  timed_out   //!< the time budget ran out first
};

//! Only leaves that rounding left undecided are escalated: precision (monotone, undecidable at the
//! minimal width) and boundary_root (an end value's enclosure contains 0).  A singular_root leaf
//! (E and E' both not excludable on an interval narrower than singular_box_relative_width) is a
//! tangency or near-tangency — the mesher's candidate witness — and is not; neither is a budget
//! region.
bool escalatable(UndecidedReason reason) {
  return reason == UndecidedReason::precision || reason == UndecidedReason::boundary_root;
}

//! A node of the Bernstein work list: the range [sa, sb] ⊆ [0, 1] of s, t = t0 + s (t1 − t0).
struct BernsteinNode {
  double sa, sb;
};

//! The per-thread buffers of the Bernstein subdivision, kept between solves (no allocation per
//! call; calls do not nest): the coefficients of E(p + t v), the work list (a stack) and the
//! Bernstein coefficients of its nodes, nodes[k]'s at pool[k · block, (k + 1) · block), and the
//! scratch space of de Casteljau's algorithm.
struct BernsteinBuffers {
  std::vector<Interval> c, pool, scratch, left, right;
  std::vector<double> c_mid;
  std::vector<BernsteinNode> nodes;
};

//! One Bernstein subdivision of a polynomial E of degree d on [t0, t1]: its evaluator, its
//! buffers, and the map from s to t = t0 + s h, h = t1 − t0.
struct BernsteinRun {
  int d;
  std::size_t block;  // d + 1 coefficients per node
  BernsteinBuffers& buffers;
  PolynomialEvaluator eval;
  double t0, t1;
  Interval h;
  //! An enclosure of t(s) (s carries ≤ 1 ulp of representation error).
  Interval t_of(double s) const {
    const double e = 0x1p-52;
    return Interval(t0) + h * Interval(s == 0 ? 0.0 : s - e, s == 1 ? 1.0 : s + e);
  }
  //! [lo, hi] ⊆ [t0, t1] containing t([sa, sb]); the ends of the segment are exact.
  void t_outer(double sa, double sb, double& lo, double& hi) const {
    lo = std::max(t0, t_of(sa).inf());
    hi = std::min(t1, t_of(sb).sup());
    if (sa == 0) lo = t0;
    if (sb == 1) hi = t1;
  }
};

//! The certain signs of Bernstein coefficients b_0..b_d: all positive, all negative, all certain,
//! and the number of sign changes among the certain ones.
struct BernsteinSigns {
  bool all_positive = true, all_negative = true, all_certain = true;
  int variations = 0;
};

BernsteinSigns bernstein_signs(int d, const Interval* b) {
  BernsteinSigns signs;
  int last = 0;
  for (int i = 0; i <= d; ++i) {
    const int s = certain_sign(b[i]);
    signs.all_positive = signs.all_positive && s > 0;
    signs.all_negative = signs.all_negative && s < 0;
    if (s == 0) {
      signs.all_certain = false;
    } else {
      if (last != 0 && s != last) ++signs.variations;
      last = s;
    }
  }
  return signs;
}

//! True when the Bernstein coefficients d (b_{i+1} − b_i) of the derivative have one certain
//! sign (d ≥ 1): E is strictly monotone on the node.
bool bernstein_monotone(int d, const Interval* b) {
  bool increasing = d > 0, decreasing = d > 0;
  for (int i = 0; i < d; ++i) {
    const int s = certain_sign(b[i + 1] - b[i]);
    increasing = increasing && s > 0;
    decreasing = decreasing && s < 0;
  }
  return increasing || decreasing;
}

class Isolation {
 public:
  Isolation(const CompiledSystem& line, const std::array<double, 3>& p, const std::array<double, 3>& v, double t0,
            double t1, const UnivariateOptions& options, std::chrono::steady_clock::time_point start)
      : line_(line),
        t0_(t0),
        t1_(t1),
        options_(options),
        deadline_(start, options.time_limit_seconds),
        found_(found_buffer()) {
    found_.clear();
    for (int i = 0; i < 3; ++i) parameters_[i] = p[i], parameters_[i + 3] = v[i];
    for (int i = 0; i < 6; ++i) parameter_intervals_[i] = Interval(parameters_[i]);
    scale_ = t1 - t0;
  }

  SolveResult run(const LinePolynomial* polynomial) {
    if (polynomial && polynomial->degree() <= detail::max_bernstein_degree)
      run_bernstein(*polynomial);
    else
      run_newton(t0_, t1_);
    return finish();
  }

 private:
  static std::vector<Found>& found_buffer() {
    static thread_local std::vector<Found> buffer;
    return buffer;
  }

  //! Whether the solve may take one more node off a work list, counting it as a box: not once the
  //! solve has stopped, nor after the deadline (time_limit) or beyond the box budget (box_limit);
  //! the node is then left on the list, unexplored.
  bool may_take_node() {
    if (progress_.stopped()) return false;
    if (deadline_.expired()) {
      progress_.stop(SolveStatus::time_limit);
      return false;
    }
    if (++counters_.boxes > options_.box_budget) {
      progress_.stop(SolveStatus::box_limit);
      return false;
    }
    return true;
  }

  // ---- polynomial E: Bernstein subdivision ----
  static BernsteinBuffers& bernstein_buffers() {
    static thread_local BernsteinBuffers buffers;
    return buffers;
  }

  //! Isolates the zeros of a polynomial E on [t0, t1] by subdividing its Bernstein coefficients:
  //! start_bernstein() makes the first node, each node of the work list is examined by
  //! bernstein_step() until the list is empty or the solve stops; nodes left then are undecided
  //! (unexplored).
  void run_bernstein(const LinePolynomial& polynomial) {
    const BernsteinRun run = start_bernstein(polynomial, bernstein_buffers());
    std::vector<BernsteinNode>& nodes = run.buffers.nodes;
    // The first node, [t0, t1], is tried on the coefficients before their Bernstein form.
    if (!may_take_node()) {
      leaves_.push_back({t0_, t1_, progress_.unexplored_reason(), false});
      return;
    }
    if (decided_on_segment(run)) return;
    to_bernstein(run);
    bernstein_step(run, {0.0, 1.0}, 0);
    while (!nodes.empty() && may_take_node()) {
      const BernsteinNode node = nodes.back();
      const std::size_t top = nodes.size() - 1;
      nodes.pop_back();
      bernstein_step(run, node, top);
    }
    for (const BernsteinNode& node : nodes) {
      double lo, hi;
      run.t_outer(node.sa, node.sb, lo, hi);
      leaves_.push_back({lo, hi, progress_.unexplored_reason(), false});
    }
    nodes.clear();
  }

  //! The coefficients c_k of E(p + t v) = Σ c_k t^k (enclosures and their midpoints), and the
  //! empty work list.
  BernsteinRun start_bernstein(const LinePolynomial& polynomial, BernsteinBuffers& buffers) const {
    const int d = polynomial.degree();
    const std::size_t block = static_cast<std::size_t>(d) + 1;
    std::vector<Interval>& c = buffers.c;
    c.resize(block), buffers.c_mid.resize(block), buffers.scratch.resize(block), buffers.left.resize(block),
        buffers.right.resize(block);
    polynomial.coefficients(parameters_, c.data());
    for (int k = 0; k <= d; ++k) buffers.c_mid[k] = midpoint(c[k]);
    const BernsteinRun run{d, block, buffers, {d, c.data(), buffers.c_mid.data()}, t0_, t1_,
                           Interval(t1_) - Interval(t0_)};
    buffers.nodes.clear();
    buffers.pool.resize(block * 64);
    return run;
  }

  //! The Bernstein coefficients of E on [t0, t1], those of the node [0, 1], at the start of the pool.
  static void to_bernstein(const BernsteinRun& run) {
    BernsteinBuffers& buffers = run.buffers;
    detail::bernstein_from_monomial(run.d, buffers.c.data(), run.t0, run.h, buffers.pool.data(), buffers.scratch.data());
  }

  //! Decides the whole segment [t0, t1] from the monomial coefficients, when one of three tests
  //! settles it, without their Bernstein form (which then is not computed).  With T = [t0, t1],
  //! m its midpoint and E, E′ the Horner enclosures of E(p + t v) and its derivative in t:
  //!  - 0 ∉ E(T), or 0 ∉ E(m) + E′(T)(T − m) (the mean-value theorem): no zero on T;
  //!  - 0 ∉ E′(T) (E strictly monotone on T) and E(t0), E(t1) of certain signs: no zero if the
  //!    signs agree, else exactly one (intermediate value theorem), isolated as a node of the
  //!    Bernstein subdivision is (isolated()).
  //! Each is a proof, like the Bernstein tests it replaces on this node; when none applies the
  //! node goes to bernstein_step().  Where the node's Bernstein coefficients would decide it as
  //! well, the answer is the same: no zero, or the one zero isolated() certifies from [t0, t1].
  bool decided_on_segment(const BernsteinRun& run) {
    const Interval T(t0_, t1_);
    Interval f, df;
    run.eval.value_and_derivative(T, f, df);
    const double m = midpoint(T);
    if (certainly_nonzero(f) || certainly_nonzero(run.eval.value(Interval(m)) + df * (T - Interval(m)))) {
      ++counters_.exclusions;
      return true;
    }
    if (!certainly_nonzero(df)) return false;
    const int s0 = certain_sign(run.eval.value(Interval(t0_))), s1 = certain_sign(run.eval.value(Interval(t1_)));
    if (s0 == 0 || s1 == 0) return false;
    if (s0 == s1)
      ++counters_.exclusions;
    else
      isolated(run, 0.0, 1.0, true);
    return true;
  }

  //! One node of run_bernstein(), its Bernstein coefficients b at pool[top · block]: excluded (every
  //! b_i of one certain sign, or E monotone with one certain sign at both ends), isolated (one
  //! sign variation among b_i all of certain sign, or E monotone with a sign change), handed to
  //! run_newton() when rounding limits the coefficients, undecided when it is a leaf (is_leaf()),
  //! or split (split_bernstein_node()).
  void bernstein_step(const BernsteinRun& run, const BernsteinNode& node, std::size_t top) {
    const int d = run.d;
    const Interval* b = run.buffers.pool.data() + top * run.block;
    const BernsteinSigns signs = bernstein_signs(d, b);
    if (signs.all_positive || signs.all_negative) {
      ++counters_.exclusions;
      return;
    }
    const double w = node.sb - node.sa;
    const int s_left = certain_sign(b[0]), s_right = certain_sign(b[d]);
    if (signs.all_certain && signs.variations == 1) {
      isolated(run, node.sa, node.sb, false);
      return;
    }
    const bool monotone = bernstein_monotone(d, b);
    if (monotone && s_left != 0 && s_right != 0) {
      if (s_left == s_right) {
        ++counters_.exclusions;
      } else {
        isolated(run, node.sa, node.sb, true);
      }
      return;
    }
    if (precision_limited(d, b)) {
      // Subdividing the coefficients further cannot help.  The compiled expression is often far
      // better conditioned than the expanded coefficients (a product of factors, say): isolate
      // the node's range by interval Newton on it, which escalates to MPFI what it cannot
      // decide either.
      double lo, hi;
      run.t_outer(node.sa, node.sb, lo, hi);
      run_newton(lo, hi);
      return;
    }
    const bool boundary = (node.sa == 0 && s_left == 0) || (node.sb == 1 && s_right == 0);
    if (is_leaf(w, monotone)) {
      double lo, hi;
      run.t_outer(node.sa, node.sb, lo, hi);
      undecided_leaf(lo, hi, leaf_reason(boundary, monotone));
      return;
    }
    split_bernstein_node(run, node, top);
  }

  //! Splits the node at sa + λ (sb − sa), λ the first of split_ratios at which the value is
  //! certainly nonzero (else the last), and pushes the right half, then the left half.
  static void split_bernstein_node(const BernsteinRun& run, const BernsteinNode& node, std::size_t top) {
    const int d = run.d;
    BernsteinBuffers& buffers = run.buffers;
    const Interval* b = buffers.pool.data() + top * run.block;
    double lambda = split_ratios[0];
    for (double candidate : split_ratios) {
      lambda = candidate;
      detail::de_casteljau(d, b, lambda, buffers.left.data(), buffers.right.data(), buffers.scratch.data());
      if (certainly_nonzero(buffers.left[d])) break;
    }
    const double sm = node.sa + lambda * (node.sb - node.sa);
    std::vector<Interval>& pool = buffers.pool;
    if (pool.size() < (top + 2) * run.block) pool.resize(2 * (top + 2) * run.block);
    std::copy(buffers.right.begin(), buffers.right.end(), pool.begin() + top * run.block);
    std::copy(buffers.left.begin(), buffers.left.end(), pool.begin() + (top + 1) * run.block);
    buffers.nodes.push_back({sm, node.sb});
    buffers.nodes.push_back({node.sa, sm});
  }

  //! The node [sa, sb] holds exactly one zero; monotone: E is proved monotone on it.
  void isolated(const BernsteinRun& run, double sa, double sb, bool monotone) {
    // The unique root lies in (t(sa), t(sb)); [inner_lo, inner_hi] is inside that range.
    const double inner_lo = sa == 0 ? t0_ : run.t_of(sa).sup();
    const double inner_hi = sb == 1 ? t1_ : run.t_of(sb).inf();
    double lo, hi;
    if (inner_lo < inner_hi &&
        refine_root(run.eval, inner_lo, inner_hi, midpoint(Interval(inner_lo, inner_hi)), scale_, lo, hi)) {
      certified(lo, hi, monotone);
      return;
    }
    // Rigorous but not tight: keep the isolating interval as a certified box when its outer
    // enclosure still proves a single root (sign change and monotone), else report it undecided.
    run.t_outer(sa, sb, lo, hi);
    if (certify_interval(run.eval, lo, hi))  // proves E' ≠ 0 on [lo, hi]
      certified(lo, hi, true);
    else
      undecided_leaf(lo, hi, UndecidedReason::precision);
  }

  // ---- any E: interval Newton and bisection on the compiled line system ----
  //! An interval [a, b] of run_newton's work list, with the certain signs of E at a and b (or
  //! unknown_sign until they are needed: a sign is evaluated once and handed to the subintervals
  //! that share the point).
  struct NewtonNode {
    double a, b;
    int sa, sb;
  };

  int sign_at(const LineSystemEvaluator& eval, double t) const { return certain_sign(eval.value(Interval(t))); }

  //! Isolates the zeros in [lo, hi] ⊆ [t0, t1] (the whole segment, or a Bernstein node's range):
  //! each interval of the work list is examined by newton_step() until the list is empty or the
  //! solve stops; intervals left then are undecided (unexplored).
  void run_newton(double lo, double hi) {
    const LineSystemEvaluator eval{line_, parameter_intervals_, parameters_};
    static thread_local std::vector<NewtonNode> nodes;
    nodes.clear();
    nodes.push_back({lo, hi, unknown_sign, unknown_sign});
    while (!nodes.empty() && may_take_node()) {
      NewtonNode node = nodes.back();
      nodes.pop_back();
      if (!newton_step(eval, node, nodes)) break;
    }
    for (const NewtonNode& node : nodes) leaves_.push_back({node.a, node.b, progress_.unexplored_reason(), false});
    nodes.clear();
  }

  //! One interval T = [a, b] of run_newton(): excluded (E(T), the mean-value form or interval
  //! Newton proves no zero; E monotone with the same certain sign at both ends), certified (E
  //! monotone with a sign change), contracted by interval Newton (queued again), or handed to
  //! split_or_settle().  False when the solve must stop (node queued again).
  bool newton_step(const LineSystemEvaluator& eval, NewtonNode node, std::vector<NewtonNode>& nodes) {
    const Interval T(node.a, node.b);
    Interval f, df;
    eval.value_and_derivative(T, f, df);
    if (certainly_nonzero(f)) {
      ++counters_.exclusions;
      return true;
    }
    if (node.sa == unknown_sign) node.sa = sign_at(eval, node.a);
    if (node.sb == unknown_sign) node.sb = sign_at(eval, node.b);
    const int sa = node.sa, sb = node.sb;
    const bool monotone = certainly_nonzero(df);
    if (monotone && sa != 0 && sb != 0) {
      if (sa == sb) {
        ++counters_.exclusions;
      } else {
        double lo, hi;
        if (refine_root(eval, node.a, node.b, midpoint(T), scale_, lo, hi))
          certified(lo, hi, true);  // inside [a, b], where E' ≠ 0
        else
          undecided_leaf(node.a, node.b, UndecidedReason::precision);
      }
      return true;
    }
    // Mean-value form over T: E(m) + E'(T) (T − m).
    const double m = midpoint(T);
    const Interval fm = eval.value(Interval(m));
    const Interval mean_value = fm + df * (T - Interval(m));
    if (certainly_nonzero(mean_value)) {
      ++counters_.exclusions;
      return true;
    }
    if (monotone) {
      // Interval Newton: every zero in T lies in m − f(m)/f'(T).
      const Interval n = Interval(m) - fm / df;
      if (detail::is_finite(n)) {
        if (detail::disjoint(n, T)) {
          ++counters_.exclusions;
          return true;
        }
        const Interval c = detail::intersection(n, T);
        if (detail::width(c) < tolerances::krawczyk_contraction_ratio * detail::width(T) && c.inf() < c.sup()) {
          nodes.push_back({c.inf(), c.sup(), c.inf() == node.a ? sa : unknown_sign,
                           c.sup() == node.b ? sb : unknown_sign});
          return true;
        }
      }
    }
    return split_or_settle(eval, node, fm, mean_value, monotone, nodes);
  }

  //! An interval of newton_step() still open (fm ∋ E(midpoint), mean_value its mean-value form,
  //! monotone: E' ≠ 0 on it): escalated to MPFI (once per region) where rounding limits what
  //! doubles decide; then, a leaf (is_leaf()) is undecided, any other interval is split (at a
  //! point with a certain sign of E if one of split_ratios gives one).  False when the escalation
  //! ran out of time (node queued again, the solve stopped).
  bool split_or_settle(const LineSystemEvaluator& eval, const NewtonNode& node, const Interval& fm,
                       const Interval& mean_value, bool monotone, std::vector<NewtonNode>& nodes) {
    const Interval T(node.a, node.b);
    const int sa = node.sa, sb = node.sb;
    const double w = (node.b - node.a) / scale_;
    const bool boundary = (node.a == t0_ && sa == 0) || (node.b == t1_ && sb == 0);
    const bool leaf = is_leaf(w, monotone);
    // Split, avoiding a split point at which the value is not certainly nonzero.
    double split = midpoint(T);
    int s_split = unknown_sign;
    for (double ratio : split_ratios) {
      if (leaf) break;
      split = node.a + ratio * (node.b - node.a);
      if (split <= node.a || split >= node.b) split = midpoint(T);
      s_split = sign_at(eval, split);
      if (s_split != 0) break;
    }
    // Rounding, not T's width, limits what doubles can decide on T when the value at one point
    // is nearly as uncertain as the mean-value form over all of T, or when no candidate split
    // point has a certain sign: T is escalated to MPFI now (once per region).
    const bool rounding_limited =
        detail::width(fm) > tolerances::univariate_precision_limited_ratio * detail::width(mean_value) ||
        s_split == 0;
    if (rounding_limited && !inside_failed(node.a, node.b)) {
      const Escalation outcome = escalate(node.a, node.b);
      if (outcome == Escalation::decided) return true;
      if (outcome == Escalation::timed_out) {
        nodes.push_back(node);
        progress_.stop(SolveStatus::time_limit);
        return false;
      }
      failed_.push_back({node.a, node.b});
    }
    if (leaf) {
      undecided_leaf(node.a, node.b, leaf_reason(boundary, monotone), inside_failed(node.a, node.b));
      return true;
    }
    nodes.push_back({split, node.b, s_split, sb});
    nodes.push_back({node.a, split, sa, s_split});
    return true;
  }

  // ---- MPFI escalation of undecided intervals ----

  //! [a, b] lies in a subinterval whose MPFI escalation failed: its pieces are not escalated
  //! again.
  bool inside_failed(double a, double b) const {
    for (const auto& f : failed_)
      if (f.first <= a && b <= f.second) return true;
    return false;
  }

  //! Re-examines [lo, hi] (undecided in double intervals) in MPFI at each escalation precision
  //! in turn; on success its zeros are certified (counted once per precision tried).  Rare: kept
  //! out of the double loops' code (cold).
  [[gnu::cold]] Escalation escalate(double lo, double hi) {
    for (int bits : tolerances::escalation_precisions) {
      ++counters_.precision_escalations;
      std::vector<Found> fresh;
      const Escalation outcome = mpfi_pass(lo, hi, bits, fresh);
      if (outcome == Escalation::timed_out) return outcome;
      if (outcome == Escalation::decided) {
        for (const Found& f : fresh) certified(f.lo, f.hi, f.monotone);
        return outcome;
      }
    }
    return Escalation::undecided;
  }

  //! Depth-first subdivision of [lo, hi] at `bits` with exclusion (natural or mean-value
  //! enclosure of E excluding 0, or E monotone with equal certain end signs) and certification (E
  //! monotone with opposite certain end signs, then narrowed by bisection on certain signs).
  //! Abandoned (undecided) at the first undecided piece that is narrower than the escalation
  //! width (or whose midpoint is not strictly inside it), or, if E' may vanish on it, narrower
  //! than the singular width; or after the escalation budget.  Then nothing of it is kept.
  Escalation mpfi_pass(double lo, double hi, int bits, std::vector<Found>& fresh) {
    detail::MpfiPrecisionScope scope(bits);
    MpfiLineEvaluator e(line_, parameters_);  // destroyed before the scope
    struct Piece {
      double a, b;
      int sa, sb;
    };
    std::vector<Piece> pieces{{lo, hi, unknown_sign, unknown_sign}};
    const double min_width = tolerances::univariate_escalation_min_relative_width * scale_;
    const double singular_width = tolerances::singular_box_relative_width * scale_;
    std::size_t visited = 0;
    while (!pieces.empty()) {
      if (deadline_.expired()) return Escalation::timed_out;
      if (++visited > tolerances::univariate_escalation_box_budget) return Escalation::undecided;
      Piece q = pieces.back();
      pieces.pop_back();
      const double m = midpoint(Interval(q.a, q.b));
      bool monotone = false;
      if (e.excludes(q.a, q.b, m, monotone)) {
        ++counters_.exclusions;
        continue;
      }
      if (q.sa == unknown_sign) q.sa = e.sign_at(q.a);
      if (q.sb == unknown_sign) q.sb = e.sign_at(q.b);
      if (monotone && q.sa != 0 && q.sb != 0) {
        if (q.sa == q.sb) {
          ++counters_.exclusions;
        } else {
          narrow(e, q.a, q.b, q.sa);
          fresh.push_back({q.a, q.b, true});
        }
        continue;
      }
      // A piece where E' may vanish, narrower than the singular width, is a (near-)double root:
      // it stays singular_root (the double pass's rule), MPFI does not try to split it.
      if (!monotone && q.b - q.a < singular_width) return Escalation::undecided;
      if (q.b - q.a < min_width || !(m > q.a && m < q.b)) return Escalation::undecided;
      // Split, avoiding a split point at which the sign is not certain.
      double split = m;
      int s_split = 0;
      for (double ratio : split_ratios) {
        split = q.a + ratio * (q.b - q.a);
        if (!(split > q.a && split < q.b)) split = m;
        s_split = e.sign_at(split);
        if (s_split != 0) break;
      }
      pieces.push_back({split, q.b, s_split, q.sb});
      pieces.push_back({q.a, split, q.sa, s_split});
    }
    return Escalation::decided;
  }

  //! [a, b] holds exactly one zero, E is monotone on it, sa is E's certain sign at a (and −sa at
  //! b): halves it, keeping the half with a certain sign change, until it is as tight as
  //! refine_root's intervals or a midpoint's sign is not certain.
  void narrow(MpfiLineEvaluator& e, double& a, double& b, int sa) const {
    const double target = 2 * tolerances::univariate_root_relative_radius * std::max(std::abs(a), scale_);
    while (b - a > target) {
      const double m = midpoint(Interval(a, b));
      if (!(m > a && m < b)) break;
      const int s = e.sign_at(m);
      if (s == 0) break;
      (s == sa ? a : b) = m;
    }
  }

  //! Escalates every leaf that more precision may decide; a decided leaf is removed.  Leaves left
  //! when the time budget runs out get reason budget (their MPFI examination did not happen).
  void escalate_leaves(std::vector<Leaf>& leaves) {
    std::vector<Leaf> kept;
    for (Leaf leaf : leaves) {
      if (escalatable(leaf.reason) && !leaf.escalated) {
        const Escalation outcome = escalate(leaf.lo, leaf.hi);
        if (outcome == Escalation::decided) continue;
        if (outcome == Escalation::timed_out) {
          leaf.reason = UndecidedReason::budget;
          if (!progress_.stopped()) progress_.stop(SolveStatus::time_limit);
        }
      }
      kept.push_back(leaf);
    }
    leaves.swap(kept);
  }

  //! Certified intervals from different sources (double isolation, MPFI escalation of adjacent
  //! regions whose outward-rounded ranges share a few ulps) may hold the same zero.  Two that meet
  //! and are both monotone do (E is strictly monotone on their connected union): the second is
  //! dropped.  Two that touch only at an end point hold different zeros (each zero is strictly
  //! inside its interval).  Two that overlap by more than a point without both being monotone
  //! cannot be told apart (the isolation's construction excludes this; kept as a safeguard): both
  //! are replaced by one undecided interval (precision) covering them.
  void deduplicate(std::vector<Leaf>& leaves) {
    std::sort(found_.begin(), found_.end(), [](const Found& a, const Found& b) { return a.lo < b.lo; });
    std::size_t kept = 0;  // found_[0, kept) is the deduplicated prefix
    for (std::size_t i = 0; i < found_.size(); ++i) {
      const Found f = found_[i];
      if (kept > 0 && found_[kept - 1].hi >= f.lo) {
        const Found& last = found_[kept - 1];
        if (last.monotone && f.monotone) continue;  // the same zero, already held by `last`
        if (last.hi > f.lo) {
          leaves.push_back({last.lo, std::max(last.hi, f.hi), UndecidedReason::precision, true});
          --kept;
          continue;
        }
      }
      found_[kept++] = f;
    }
    found_.resize(kept);
  }

  // ---- bookkeeping ----
  void certified(double lo, double hi, bool monotone) {
    ++counters_.krawczyk_successes;
    found_.push_back({lo, hi, monotone});
  }

  void undecided_leaf(double lo, double hi, UndecidedReason reason, bool escalated = false) {
    leaves_.push_back({lo, hi, reason, escalated});
    if (reason == UndecidedReason::singular_root || reason == UndecidedReason::boundary_root ||
        reason == UndecidedReason::precision)
      progress_.count_unresolved();
  }

  SolveResult finish() {
    SolveResult result;
    // Undecided leaves: sorted, adjacent ones with the same reason merged into one region.
    std::sort(leaves_.begin(), leaves_.end(), [](const Leaf& a, const Leaf& b) { return a.lo < b.lo; });
    std::vector<Leaf> merged;
    for (const Leaf& leaf : leaves_) {
      Leaf l = leaf;
      if (progress_.non_isolated()) l.reason = UndecidedReason::non_isolated;
      if (!merged.empty() && merged.back().reason == l.reason && merged.back().hi >= l.lo) {
        merged.back().hi = std::max(merged.back().hi, l.hi);
        merged.back().escalated = merged.back().escalated && l.escalated;
      } else
        merged.push_back(l);
    }
    if (!progress_.non_isolated()) escalate_leaves(merged);
    deduplicate(merged);
    std::sort(merged.begin(), merged.end(), [](const Leaf& a, const Leaf& b) { return a.lo < b.lo; });
    for (const Leaf& leaf : merged) {
      UndecidedBox box;
      box.box.bounds = {{leaf.lo, leaf.hi}};
      box.reason = leaf.reason;
      const double t = 0.5 * leaf.lo + 0.5 * leaf.hi;
      line_.world_point(&t, parameters_, box.world.data());
      result.undecided.push_back(std::move(box));
    }
    result.roots.reserve(found_.size());
    for (const Found& f : found_) {
      CertifiedRoot root;
      root.box.bounds = {{f.lo, f.hi}};
      const double t = 0.5 * f.lo + 0.5 * f.hi;
      root.midpoint = {t};
      line_.world_point(&t, parameters_, root.world.data());
      result.roots.push_back(std::move(root));
    }
    result.counters = counters_;
    result.status = progress_.status(!result.undecided.empty());
    return result;
  }

  const CompiledSystem& line_;
  double t0_, t1_, scale_;
  UnivariateOptions options_;
  detail::Deadline deadline_;
  double parameters_[6];             // (p, v) as given
  Interval parameter_intervals_[6];  // the same as point intervals
  std::vector<Found>& found_;        // a per-thread buffer (no allocation per call; calls do not nest)
  std::vector<std::pair<double, double>> failed_;  // escalations that failed (see inside_failed)
  std::vector<Leaf> leaves_;
  SolverCounters counters_;
  detail::SolveProgress progress_;
};

}  // namespace

SolveResult isolate_line_roots(const CompiledSystem& line, const LinePolynomial* polynomial,
                               const std::array<double, 3>& p, const std::array<double, 3>& v, double t0,
                               double t1, const UnivariateOptions& options) {
  if (line.n_unknowns() != 1 || line.n_equations() != 1 || line.n_parameters() != 6)
    throw PreconditionViolation("isolate_line_roots: expected the surface_line system (1 unknown t, 1 equation, "
                                "6 parameters p, v); got " + std::to_string(line.n_unknowns()) + " unknowns, " +
                                std::to_string(line.n_equations()) + " equations, " +
                                std::to_string(line.n_parameters()) + " parameters");
  if (!std::isfinite(t0) || !std::isfinite(t1) || !(t0 < t1))
    throw PreconditionViolation("isolate_line_roots: need finite t0 < t1");
  bool finite = true, nonzero = false;
  for (int i = 0; i < 3; ++i) {
    finite = finite && std::isfinite(p[i]) && std::isfinite(v[i]);
    nonzero = nonzero || v[i] != 0;
  }
  if (!finite || !nonzero) throw PreconditionViolation("isolate_line_roots: p and v must be finite and v non-zero");
  if (!(options.time_limit_seconds >= 0) || !std::isfinite(options.time_limit_seconds))
    throw PreconditionViolation("isolate_line_roots: time_limit_seconds must be finite and >= 0");
  const auto start = options.start ? *options.start : std::chrono::steady_clock::now();
  RoundingGuard guard;
  Isolation isolation(line, p, v, t0, t1, options, start);
  SolveResult result = isolation.run(polynomial);
  result.counters.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace delmesh
