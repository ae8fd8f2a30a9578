#include "solvers/homotopy_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>

#include <Eigen/Dense>

#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/detail/homotopy_tracker.h"
#include "solvers/kostlan_system.h"
#include "solvers/krawczyk.h"
#include "solvers/subdivision_solver.h"

namespace delmesh {

namespace tol = tolerances;
using detail::PathEndpoint;
using detail::PathOutcome;

std::vector<int> equation_degrees(const PrimitiveSystem& system) {
  GiNaC::lst unknowns;
  GiNaC::exmap scaled;
  const GiNaC::symbol s("homotopy_scale");
  for (const auto& u : system.unknowns) {
    unknowns.append(u);
    scaled[u] = s * u;
  }
  std::vector<int> degrees;
  for (std::size_t i = 0; i < system.equations.size(); ++i) {
    const GiNaC::ex& equation = system.equations[i];
    if (!equation.is_polynomial(unknowns))
      throw InvalidInput("equation_degrees: equation " + std::to_string(i) + " of " + system.name +
                         " is not polynomial in the unknowns");
    degrees.push_back(equation.subs(scaled).expand().degree(s));
  }
  return degrees;
}

std::size_t bezout_number(const std::vector<int>& degrees) {
  if (degrees.empty()) throw PreconditionViolation("bezout_number: no equations");
  std::size_t product = 1;
  for (int d : degrees) {
    if (d < 1) throw InvalidInput("homotopy: every equation needs degree ≥ 1, got " + std::to_string(d));
    product *= static_cast<std::size_t>(d);
  }
  return product;
}

std::vector<std::vector<Complex>> total_degree_start_solutions(const std::vector<int>& degrees) {
  const std::size_t count = bezout_number(degrees), n = degrees.size();
  std::vector<std::vector<Complex>> starts(count, std::vector<Complex>(n));
  for (std::size_t k = 0; k < count; ++k) {
    std::size_t index = k;  // mixed-radix digits of k, the last unknown varying fastest
    for (std::size_t i = n; i-- > 0;) {
      const auto d = static_cast<std::size_t>(degrees[i]);
      const std::size_t j = index % d;
      index /= d;
      starts[k][i] = std::polar(1.0, 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(d));
    }
  }
  return starts;
}

namespace {

using Clock = std::chrono::steady_clock;

double max_abs(const std::vector<Complex>& u) {
  double m = 0;
  for (const auto& c : u) m = std::max(m, std::abs(c));
  return m;
}
double max_imag(const std::vector<Complex>& u) {
  double m = 0;
  for (const auto& c : u) m = std::max(m, std::abs(c.imag()));
  return m;
}
double distance(const std::vector<Complex>& a, const std::vector<Complex>& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

bool boxes_intersect(const std::vector<Interval>& a, const std::vector<Interval>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].sup() < b[i].inf() || b[i].sup() < a[i].inf()) return false;
  return true;
}
std::vector<Interval> hull(const std::vector<Interval>& a, const std::vector<Interval>& b) {
  std::vector<Interval> h;
  for (std::size_t i = 0; i < a.size(); ++i)
    h.emplace_back(std::min(a[i].inf(), b[i].inf()), std::max(a[i].sup(), b[i].sup()));
  return h;
}
double width(const std::vector<Interval>& box) {
  double w = 0;
  for (const auto& x : box) w = std::max(w, x.sup() - x.inf());
  return w;
}
SolverBox to_solver_box(const std::vector<Interval>& box) {
  SolverBox b;
  for (const auto& x : box) b.bounds.push_back({x.inf(), x.sup()});
  return b;
}

//! Where the (unique) root in `box` lies relative to the domain (the rigorous classify() of domain.h).
DomainSide place(const std::vector<Interval>& box, const Domain& domain) {
  RoundingGuard guard;
  return classify(domain, box.data());
}

struct Certified {
  std::vector<Interval> box;
  std::vector<double> midpoint;
};

//! Newton polish over the reals and Krawczyk certification of real endpoints.
class EndpointCertifier {
 public:
  EndpointCertifier(const CompiledSystem& system, const std::vector<double>& parameters,
                    const std::vector<int>& degrees)
      : system_(system), parameters_(parameters), degrees_(degrees), n_(system.n_unknowns()) {}

  const CompiledSystem& system() const { return system_; }
  const std::vector<double>& parameters() const { return parameters_; }
  const std::vector<int>& degrees() const { return degrees_; }

  //! Newton in double from x; returns the size of the last correction (∞ if it broke down).
  double polish(std::vector<double>& x) const {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    std::vector<double> f(n_), J(n_ * n_);
    Eigen::MatrixXd A(n_, n_);
    Eigen::VectorXd b(n_);
    double last = std::numeric_limits<double>::infinity();
    for (int k = 0; k < tol::homotopy_polish_iterations; ++k) {
      system_.values_and_jacobian<double>(x.data(), parameters_.data(), f.data(), J.data());
      for (std::size_t i = 0; i < n_; ++i) {
        b[i] = -f[i];
        for (std::size_t j = 0; j < n_; ++j) A(i, j) = J[i * n_ + j];
      }
      const Eigen::VectorXd delta = A.partialPivLu().solve(b);
      if (!delta.allFinite()) return std::numeric_limits<double>::infinity();
      double scale = 0;
      for (std::size_t i = 0; i < n_; ++i) {
        x[i] += delta[i];
        scale = std::max(scale, std::abs(x[i]));
      }
      const double size = delta.cwiseAbs().maxCoeff();
      if (size > last && k >= tol::homotopy_newton_noise_after_steps) break;  // round-off level reached
      last = size;
      if (size <= tol::homotopy_newton_converged_ulps * eps * (1 + scale)) break;
    }
    return last;
  }

  //! Krawczyk iteration from a box known to hold a unique root: shrink while it keeps proving.
  std::vector<Interval> contract(std::vector<Interval> box) const {
    RoundingGuard guard;
    for (int k = 0; k < tol::homotopy_contract_iterations; ++k) {
      const KrawczykResult r = krawczyk_test(system_, parameters_, box);
      if (r.outcome != KrawczykOutcome::unique_root || !(width(r.contracted) < width(box))) break;
      box = r.contracted;
    }
    return box;
  }

  bool unique(const std::vector<Interval>& box) const {
    RoundingGuard guard;
    return krawczyk_test(system_, parameters_, box).outcome == KrawczykOutcome::unique_root;
  }

  //! True if the Krawczyk test proves that f has no zero in box.
  bool excludes(const std::vector<Interval>& box) const {
    RoundingGuard guard;
    return krawczyk_test(system_, parameters_, box).outcome == KrawczykOutcome::no_root;
  }

  //! Certifies a root near x (real part of an endpoint).  On failure `tried` is the largest box.
  bool certify(std::vector<double> x, Certified& out, std::vector<Interval>& tried) const {
    const double correction = polish(x);
    double scale = 0;
    for (double c : x) scale = std::max(scale, std::abs(c));
    double radius = tol::homotopy_certify_radius * (1 + scale);
    if (std::isfinite(correction)) radius = std::max(radius, tol::homotopy_correction_box_factor * correction);
    for (int attempt = 0; attempt < tol::homotopy_certify_attempts; ++attempt, radius *= tol::homotopy_certify_growth) {
      std::vector<Interval> box;
      for (double c : x) box.emplace_back(c - radius, c + radius);
      tried = box;
      if (!std::isfinite(radius) || !std::isfinite(scale)) return false;
      KrawczykResult r;
      {
        RoundingGuard guard;
        r = krawczyk_test(system_, parameters_, box);
      }
      if (r.outcome != KrawczykOutcome::unique_root) continue;
      out.box = contract(r.contracted);
      out.midpoint.resize(n_);
      for (std::size_t i = 0; i < n_; ++i) {
        // the polished point when it lies in the certified box, else the box centre
        const double c = x[i];
        out.midpoint[i] = (c >= out.box[i].inf() && c <= out.box[i].sup()) ? c
                                                                              : 0.5 * (out.box[i].inf() + out.box[i].sup());
      }
      return true;
    }
    return false;
  }

  std::array<double, 3> world(const std::vector<double>& u) const {
    std::array<double, 3> xyz{};
    if (system_.has_world_point())
      system_.world_point<double>(u.data(), parameters_.data(), xyz.data());
    else  // no world map (bare equations in fewer than 3 unknowns): the unknowns, zero-padded
      for (std::size_t i = 0; i < std::min<std::size_t>(3, u.size()); ++i) xyz[i] = u[i];
    return xyz;
  }

 private:
  const CompiledSystem& system_;
  const std::vector<double>& parameters_;
  const std::vector<int>& degrees_;
  std::size_t n_;
};

void validate(const CompiledSystem& system, const std::vector<int>& degrees, const std::vector<double>& parameters,
              const Domain& domain) {
  const std::size_t n = system.n_unknowns();
  if (n == 0 || system.n_equations() != n)
    throw PreconditionViolation("solve_homotopy: the system must be square, got " +
                                std::to_string(system.n_equations()) + " equations in " + std::to_string(n) +
                                " unknowns");
  if (degrees.size() != n)
    throw PreconditionViolation("solve_homotopy: " + std::to_string(degrees.size()) + " degrees for " +
                                std::to_string(n) + " equations");
  bezout_number(degrees);  // throws on a degree < 1
  if (parameters.size() != system.n_parameters())
    throw PreconditionViolation("solve_homotopy: " + std::to_string(parameters.size()) +
                                " parameters given, the system has " + std::to_string(system.n_parameters()));
  if (domain.dimension() != n)
    throw PreconditionViolation("solve_homotopy: the domain has dimension " + std::to_string(domain.dimension()) +
                                ", the system " + std::to_string(n) + " unknowns");
  domain.validate();
}

//! Adds `box` to `undecided`, merging it with an overlapping box of the same reason.
void add_undecided(std::vector<UndecidedBox>& undecided, std::vector<Interval> box, UndecidedReason reason,
                   const EndpointCertifier& certifier) {
  for (auto it = undecided.begin(); it != undecided.end(); ++it) {
    if (it->reason != reason) continue;
    std::vector<Interval> other;
    for (const auto& [lo, hi] : it->box.bounds) other.emplace_back(lo, hi);
    if (boxes_intersect(other, box)) {
      box = hull(other, box);
      undecided.erase(it);
      add_undecided(undecided, std::move(box), reason, certifier);
      return;
    }
  }
  UndecidedBox u;
  u.box = to_solver_box(box);
  u.reason = reason;
  std::vector<double> centre;
  for (const auto& x : box) centre.push_back(0.5 * (x.inf() + x.sup()));
  u.world = certifier.world(centre);
  undecided.push_back(std::move(u));
}

std::vector<Interval> domain_box(const Domain& domain) {
  std::vector<Interval> box;
  for (const auto& [lo, hi] : domain.box.bounds) box.emplace_back(lo, hi);
  return box;
}

//! Sorts the endpoints of the paths (solve_homotopy): a real regular endpoint near the domain is
//! certified by Krawczyk or its box is undecided (precision); a near-real one's box is settled by
//! a certified root in it or a proof that it holds none, else undecided; a singular one near the
//! domain and not certainly complex gives an undecided box (singular_root); the others are dropped.
class EndpointSorter {
 public:
  EndpointSorter(const Domain& domain, const EndpointCertifier& certifier, std::size_t n)
      : domain_(domain), certifier_(certifier), n_(n), margin_(tol::homotopy_domain_margin * domain.scale()),
        near_distance_(tol::homotopy_diverging_near_domain * domain.scale()) {}

  //! One endpoint, counted in `statistics`; certified roots go to `certified`, undecided boxes to
  //! `undecided`; a diverging path near the domain is counted (statistics.diverging_near_domain).
  void sort(const PathEndpoint& end, HomotopyStatistics& statistics, std::vector<Certified>& certified,
            std::vector<UndecidedBox>& undecided) const {
    switch (end.outcome) {
      case PathOutcome::finite: ++statistics.finite; break;
      case PathOutcome::singular: ++statistics.singular; break;
      case PathOutcome::diverging: ++statistics.diverging; break;
      case PathOutcome::failed: ++statistics.failed; break;
    }
    if (end.outcome == PathOutcome::failed) return;
    if (end.outcome == PathOutcome::diverging) {
      if (!diverging_near_domain(end.point)) return;
      ++statistics.diverging_near_domain;
      return;
    }
    const double scale = 1 + max_abs(end.point);
    const double imag = max_imag(end.point);
    std::vector<double> x(n_);
    for (std::size_t i = 0; i < n_; ++i) x[i] = end.point[i].real();
    if (end.outcome == PathOutcome::singular) {
      const double radius =
          std::max(tol::homotopy_singular_box_radius * scale,
                   tol::homotopy_correction_box_factor * (std::isfinite(end.last_correction) ? end.last_correction : 0));
      if (imag > std::max(radius, tol::homotopy_near_real * scale)) return;  // certainly not real
      const double box_radius = std::max(radius, tol::homotopy_near_real_box_ratio * imag);
      if (!near_domain(x, box_radius)) return;
      if (imag > std::max(radius, tol::homotopy_real_candidate * scale)) ++statistics.near_real;
      add_undecided(undecided, box_around(x, box_radius), UndecidedReason::singular_root, certifier_);
      return;
    }
    // finite, regular endpoint
    if (imag > tol::homotopy_near_real * scale) return;  // certainly not real
    if (imag <= tol::homotopy_real_candidate * scale) {
      if (!near_domain(x, 0)) return;
      Certified root;
      std::vector<Interval> tried;
      if (certifier_.certify(x, root, tried)) {
        certified.push_back(std::move(root));
      } else if (place(tried, domain_) != DomainSide::outside) {
        add_undecided(undecided, tried, UndecidedReason::precision, certifier_);
      }
      return;
    }
    // Near-real: the real root this endpoint may approximate lies about ‖Im u‖∞ from Re u.  The
    // box there is settled by a root certified in it, or by a proof that it holds none; else it
    // is undecided.  (A root certified elsewhere is a root all the same, and is kept.)
    const double box_radius = std::max(tol::homotopy_certify_radius * scale, tol::homotopy_near_real_box_ratio * imag);
    if (!near_domain(x, box_radius)) return;
    ++statistics.near_real;
    const std::vector<Interval> box = box_around(x, box_radius);
    Certified root;
    std::vector<Interval> tried;
    bool settled = false;
    if (certifier_.certify(x, root, tried)) {
      settled = boxes_intersect(root.box, box);
      certified.push_back(std::move(root));
    }
    if (!settled && !certifier_.excludes(box) && place(box, domain_) != DomainSide::outside)
      add_undecided(undecided, box, UndecidedReason::precision, certifier_);
  }

 private:
  //! x within margin + extra of the domain box.
  bool near_domain(const std::vector<double>& x, double extra) const {
    for (std::size_t i = 0; i < n_; ++i)
      if (x[i] < domain_.box.bounds[i][0] - margin_ - extra || x[i] > domain_.box.bounds[i][1] + margin_ + extra)
        return false;
    return true;
  }

  //! A diverging path is near the domain when its last tracked point u (where it was declared at
  //! infinity) has Re u within near_distance_ of the domain box and ‖Im u‖∞ ≤ near_distance_.
  bool diverging_near_domain(const std::vector<Complex>& u) const {
    for (const auto& c : u)
      if (!std::isfinite(c.real()) || !std::isfinite(c.imag())) return false;
    std::vector<double> x(n_);
    for (std::size_t i = 0; i < n_; ++i) x[i] = u[i].real();
    return max_imag(u) <= near_distance_ && near_domain(x, near_distance_);
  }

  //! The box of half-width `radius` around x.
  static std::vector<Interval> box_around(const std::vector<double>& x, double radius) {
    std::vector<Interval> box;
    for (double c : x) box.emplace_back(c - radius, c + radius);
    return box;
  }

  const Domain& domain_;
  const EndpointCertifier& certifier_;
  std::size_t n_;
  double margin_, near_distance_;
};

//! The paths of one solve from their start solutions, tracked with `settings`; each tracking is
//! counted in the result's counters and the statistics.
class Paths {
 public:
  Paths(const detail::HomotopyTracker& tracker, const detail::TrackerSettings& settings,
        std::vector<std::vector<Complex>> starts, SolveResult& result, HomotopyStatistics& statistics)
      : tracker_(tracker), settings_(settings), starts_(std::move(starts)), result_(result), statistics_(statistics) {}

  //! Tracks every path in order; a path cut off by the deadline is neither an endpoint nor a
  //! failure: the tracking stops there with out_of_time set.
  void track_all() {
    ends.reserve(starts_.size());
    for (const auto& start : starts_) {
      PathEndpoint end = track(start, settings_);
      if (end.stopped) {
        out_of_time = true;
        break;
      }
      ends.push_back(std::move(end));
    }
  }

  //! Two paths at the same regular root: one of them jumped (a regular root is the end of exactly
  //! one path).  Near-singular coincidences (condition above homotopy_cluster_condition) are a
  //! multiple root instead: both become singular.  With `retrack`, both jumpers are tracked again
  //! with stricter settings (unless out of time); without, true if a jump remains.
  bool find_coincidences(bool retrack) {
    bool jumped = false;
    for (std::size_t i = 0; i < ends.size(); ++i)
      for (std::size_t j = i + 1; j < ends.size(); ++j) {
        if (!coincide(ends[i], ends[j])) continue;
        if (std::max(ends[i].condition, ends[j].condition) > tol::homotopy_cluster_condition) {
          ends[i].outcome = ends[j].outcome = PathOutcome::singular;
        } else if (retrack && !out_of_time) {
          for (std::size_t k : {i, j}) {
            PathEndpoint again = track(starts_[k], settings_.stricter());
            if (again.stopped) {
              out_of_time = true;  // keep the first endpoint; the solve reports time_limit
              break;
            }
            ends[k] = std::move(again);
          }
        } else {
          jumped = true;
        }
      }
    return jumped;
  }

  std::vector<PathEndpoint> ends;  //!< the endpoints, in the order of the start solutions
  bool out_of_time = false;        //!< the deadline cut the tracking short

 private:
  PathEndpoint track(const std::vector<Complex>& start, const detail::TrackerSettings& with) {
    PathEndpoint end = tracker_.track(start, with);
    ++result_.counters.paths;
    statistics_.steps += end.steps;
    statistics_.rejections += end.rejections;
    statistics_.max_winding = std::max(statistics_.max_winding, end.winding);
    return end;
  }

  static bool coincide(const PathEndpoint& a, const PathEndpoint& b) {
    return a.outcome == PathOutcome::finite && b.outcome == PathOutcome::finite &&
           distance(a.point, b.point) <= tol::homotopy_duplicate_endpoint * (1 + max_abs(a.point));
  }

  const detail::HomotopyTracker& tracker_;
  const detail::TrackerSettings& settings_;
  std::vector<std::vector<Complex>> starts_;
  SolveResult& result_;
  HomotopyStatistics& statistics_;
};

//! The earlier of options.deadline and the end of options.time_limit_seconds from `started` (a
//! limit beyond half the clock's remaining range is no limit: its end would not be representable).
std::optional<Clock::time_point> solve_deadline(const HomotopyOptions& options, Clock::time_point started) {
  std::optional<Clock::time_point> deadline = options.deadline;
  if (options.time_limit_seconds > 0 &&
      options.time_limit_seconds < 0.5 * std::chrono::duration<double>(Clock::time_point::max() - started).count()) {
    const auto by_limit =
        started + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.time_limit_seconds));
    deadline = deadline ? std::min(*deadline, by_limit) : by_limit;
  }
  return deadline;
}

//! The certified roots without repetitions: intersecting uniqueness boxes whose hull still holds a
//! unique root are the same root (the narrower box is kept); intersecting boxes whose hull does
//! not are a cluster, reported undecided.
std::vector<Certified> distinct_roots(std::vector<Certified> certified, const EndpointCertifier& certifier,
                                      std::vector<UndecidedBox>& undecided) {
  std::sort(certified.begin(), certified.end(),
            [](const Certified& a, const Certified& b) { return a.midpoint < b.midpoint; });
  std::vector<Certified> distinct;
  for (auto& root : certified) {
    bool merged = false;
    for (auto& kept : distinct) {
      if (!boxes_intersect(kept.box, root.box)) continue;
      if (certifier.unique(hull(kept.box, root.box))) {
        if (width(root.box) < width(kept.box)) kept = root;
      } else {
        add_undecided(undecided, hull(kept.box, root.box), UndecidedReason::cluster, certifier);
      }
      merged = true;
      break;
    }
    if (!merged) distinct.push_back(std::move(root));
  }
  return distinct;
}

//! Each distinct certified root by its place in the domain: outside (counted), on its boundary
//! (undecided, boundary_root) or inside (a root of the result).
void place_roots(const std::vector<Certified>& distinct, const Domain& domain, const EndpointCertifier& certifier,
                 SolveResult& result) {
  for (const auto& root : distinct) {
    switch (place(root.box, domain)) {
      case DomainSide::outside: ++result.counters.roots_outside; break;
      case DomainSide::boundary:
        add_undecided(result.undecided, root.box, UndecidedReason::boundary_root, certifier);
        break;
      case DomainSide::inside: {
        CertifiedRoot r;
        r.box = to_solver_box(root.box);
        r.midpoint = root.midpoint;
        r.world = certifier.world(root.midpoint);
        r.inside_domain = true;
        result.roots.push_back(std::move(r));
        ++result.counters.krawczyk_successes;
        break;
      }
    }
  }
}

//! Answers an unproved piece by the subdivision solver: its roots that lie in no proved piece
//! (the certificate has those) and its undecided boxes go to `result`, and the roots of rules 1–5
//! in the piece are dropped (the subdivision's are certified the same way).  False, leaving
//! `result` alone, if the deadline has passed.
template <class InProvedPiece>
bool solve_piece_by_subdivision(const std::vector<std::array<double, 2>>& piece, const Domain& domain,
                                const EndpointCertifier& certifier, std::size_t budget,
                                const std::optional<Clock::time_point>& deadline, const InProvedPiece& in_proved_piece,
                                HomotopySolveResult& result) {
  SubdivisionOptions options;
  options.box_budget = budget;
  if (deadline) {
    const double left = std::chrono::duration<double>(*deadline - Clock::now()).count();
    if (!(left > 0)) return false;
    options.time_limit_seconds = left;
  }
  Domain part = domain;
  part.box.bounds = piece;
  SolveResult answer = solve_subdivision(certifier.system(), certifier.parameters(), part, options);
  const auto in_piece = [&](const std::vector<double>& x) {
    for (std::size_t i = 0; i < x.size(); ++i)
      if (x[i] < piece[i][0] || x[i] > piece[i][1]) return false;
    return true;
  };
  result.roots.erase(std::remove_if(result.roots.begin(), result.roots.end(),
                                    [&](const CertifiedRoot& r) { return in_piece(r.midpoint); }),
                     result.roots.end());
  for (auto& root : answer.roots)
    if (root.inside_domain && !in_proved_piece(root.midpoint)) result.roots.push_back(std::move(root));
  for (auto& box : answer.undecided) result.undecided.push_back(std::move(box));
  return true;
}

//! Runs certify_homotopy() on the tracked paths and rebuilds the result from what it proved: on
//! the proved pieces, the certificate's real zeros placed against the domain; each unproved piece
//! undecided (precision), with the roots of rules 1–5 outside the proved pieces kept.  Nothing is
//! changed when the deadline passed (the caller reports time_limit).
void certify_completeness(const detail::HomotopyTracker& tracker, const detail::TrackerSettings& settings,
                          Complex gamma, const std::vector<PathEndpoint>& ends, const Domain& domain,
                          const EndpointCertifier& certifier, std::size_t subdivision_budget,
                          HomotopySolveResult& result) {
  const std::vector<std::vector<Complex>> starts = total_degree_start_solutions(certifier.degrees());
  std::vector<std::vector<Complex>> proposed;
  for (const auto& end : ends)
    if (end.outcome == PathOutcome::finite || end.outcome == PathOutcome::singular) proposed.push_back(end.point);
  const HomotopyProblem problem{certifier.system(), certifier.parameters(), certifier.degrees(), gamma, domain};
  result.certificate = certify_homotopy(
      problem, starts.size(),
      [&](std::size_t j, double t) { return tracker.point_at(starts[j], t, settings); }, proposed, settings.deadline);
  const HomotopyCertificate& certificate = result.certificate;
  if (certificate.status == HomotopyCertificateStatus::out_of_time) return;
  const auto in_proved_piece = [&](const std::vector<double>& x) {
    return std::any_of(certificate.pieces.begin(), certificate.pieces.end(), [&](const BarrierPiece& piece) {
      for (std::size_t i = 0; i < x.size(); ++i)
        if (x[i] < piece.box[i][0] || x[i] > piece.box[i][1]) return false;
      return true;
    });
  };
  std::vector<CertifiedRoot> kept;
  for (auto& root : result.roots)
    if (!in_proved_piece(root.midpoint)) kept.push_back(std::move(root));
  std::vector<Certified> zeros;
  for (const auto& box : certificate.real_zeros) {
    Certified zero;
    zero.box = box;
    std::vector<double> x;
    for (const auto& side : box) x.push_back(0.5 * (side.inf() + side.sup()));
    certifier.polish(x);
    for (std::size_t i = 0; i < box.size(); ++i)  // the polished point if it stayed in the box
      if (!(x[i] >= box[i].inf() && x[i] <= box[i].sup())) x[i] = 0.5 * (box[i].inf() + box[i].sup());
    zero.midpoint = std::move(x);
    zeros.push_back(std::move(zero));
  }
  result.roots = std::move(kept);
  result.undecided.clear();
  result.counters.roots_outside = 0;
  place_roots(zeros, domain, certifier, result);
  result.counters.krawczyk_successes = result.roots.size();
  for (const auto& piece : certificate.unproved) {
    if (subdivision_budget > 0 && solve_piece_by_subdivision(piece, domain, certifier, subdivision_budget,
                                                             settings.deadline, in_proved_piece, result)) {
      ++result.statistics.pieces_by_subdivision;
      continue;
    }
    std::vector<Interval> box;
    for (const auto& [lo, hi] : piece) box.emplace_back(lo, hi);
    add_undecided(result.undecided, std::move(box), UndecidedReason::precision, certifier);
  }
  std::sort(result.roots.begin(), result.roots.end(),
            [](const CertifiedRoot& a, const CertifiedRoot& b) { return a.midpoint < b.midpoint; });
}

}  // namespace

HomotopySolveResult solve_homotopy(const CompiledSystem& system, const std::vector<int>& degrees,
                                   const std::vector<double>& parameters, const Domain& domain,
                                   const HomotopyOptions& options) {
  validate(system, degrees, parameters, domain);
  const auto started = Clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - started).count(); };
  const std::optional<Clock::time_point> deadline = solve_deadline(options, started);
  const std::size_t n = system.n_unknowns();

  // γ: a unit complex number drawn from the seed (the gamma trick).
  KostlanRng rng(options.seed);
  const Complex gamma = std::polar(1.0, 2.0 * M_PI * rng.uniform());
  // the random affine patch of the projective tracking: a unit complex Gaussian vector
  std::vector<Complex> patch(n + 1);
  double patch_norm = 0;
  for (auto& c : patch) {
    c = Complex(rng.normal(), rng.normal());
    patch_norm += std::norm(c);
  }
  for (auto& c : patch) c /= std::sqrt(patch_norm);
  const std::vector<Complex> complex_parameters(parameters.begin(), parameters.end());
  const detail::HomotopyTracker tracker(system, degrees, complex_parameters, gamma, patch);
  auto settings = detail::TrackerSettings::defaults();
  settings.max_steps = options.max_steps_per_path;
  settings.deadline = deadline;

  HomotopySolveResult result;
  HomotopyStatistics& statistics = result.statistics;
  Paths paths(tracker, settings, total_degree_start_solutions(degrees), result, statistics);
  paths.track_all();
  paths.find_coincidences(true);
  paths.find_coincidences(false);  // a jump left: the certificate decides (it trusts no path)
  const std::vector<PathEndpoint>& ends = paths.ends;
  const bool out_of_time = paths.out_of_time;

  const EndpointCertifier certifier(system, parameters, degrees);
  const EndpointSorter sorter(domain, certifier, n);
  std::vector<Certified> certified;
  for (const auto& end : ends)
    sorter.sort(end, statistics, certified, result.undecided);

  place_roots(distinct_roots(std::move(certified), certifier, result.undecided), domain, certifier, result);
  if (!out_of_time)
    certify_completeness(tracker, settings, gamma, ends, domain, certifier, options.subdivision_budget_for_unproved,
                         result);

  if (out_of_time || result.certificate.status == HomotopyCertificateStatus::out_of_time) {
    add_undecided(result.undecided, domain_box(domain), UndecidedReason::budget, certifier);
    result.status = SolveStatus::time_limit;
  } else {
    result.status = result.undecided.empty() ? SolveStatus::complete : SolveStatus::undecided;
  }
  result.counters.seconds = elapsed();
  return result;
}

}  // namespace delmesh
