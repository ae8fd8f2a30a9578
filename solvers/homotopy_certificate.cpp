#include "solvers/homotopy_certificate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <queue>
#include <string>

#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/detail/complex_krawczyk.h"

namespace delmesh {

namespace tol = tolerances;
using detail::ComplexBox;
using detail::HomotopyMap;
using Clock = std::chrono::steady_clock;

namespace {

//! A barrier box C: real part [lo_i − μ, hi_i + μ], imaginary part [−μ, μ], around the real box
//! ∏ [lo_i, hi_i].
struct BarrierBox {
  std::vector<double> re_lo, re_hi;
  double margin = 0;

  BarrierBox(const std::vector<std::array<double, 2>>& real_box, double mu) : margin(mu) {
    for (const auto& [lo, hi] : real_box) {
      re_lo.push_back(lo - mu);
      re_hi.push_back(hi + mu);
    }
  }
  std::size_t dimension() const { return re_lo.size(); }

  //! Signed ∞-norm distance of u to ∂C on R^{2n}: positive inside C, negative outside.
  double clearance(const std::vector<Complex>& u) const {
    double inside = std::numeric_limits<double>::infinity(), outside = 0;
    for (std::size_t i = 0; i < dimension(); ++i) {
      for (const double d : {u[i].real() - re_lo[i], re_hi[i] - u[i].real(), u[i].imag() + margin, margin - u[i].imag()}) {
        inside = std::min(inside, d);
        outside = std::max(outside, -d);
      }
    }
    return inside >= 0 ? inside : -outside;
  }

  //! The box lies in the open box C.
  bool contains(const ComplexBox& box) const {
    for (std::size_t i = 0; i < dimension(); ++i)
      if (!(box[i].re.inf() > re_lo[i] && box[i].re.sup() < re_hi[i] && box[i].im.inf() > -margin &&
            box[i].im.sup() < margin))
        return false;
    return true;
  }

  //! The box misses the closure of C.
  bool misses(const ComplexBox& box) const {
    for (std::size_t i = 0; i < dimension(); ++i)
      if (box[i].re.sup() < re_lo[i] || box[i].re.inf() > re_hi[i] || box[i].im.sup() < -margin ||
          box[i].im.inf() > margin)
        return true;
    return false;
  }

  //! The 4n faces of ∂C: C with one real coordinate (Re u_i or Im u_i) fixed to a bound.
  std::vector<ComplexBox> faces() const {
    std::vector<ComplexBox> all;
    ComplexBox whole;
    for (std::size_t i = 0; i < dimension(); ++i)
      whole.emplace_back(Interval(re_lo[i], re_hi[i]), Interval(-margin, margin));
    for (std::size_t i = 0; i < dimension(); ++i) {
      for (const double re : {re_lo[i], re_hi[i]}) {
        ComplexBox face = whole;
        face[i].re = Interval(re);
        all.push_back(face);
      }
      for (const double im : {-margin, margin}) {
        ComplexBox face = whole;
        face[i].im = Interval(im);
        all.push_back(face);
      }
    }
    return all;
  }
};

double widest_side(const std::vector<std::array<double, 2>>& box) {
  double w = 0;
  for (const auto& [lo, hi] : box) w = std::max(w, hi - lo);
  return w;
}

//! μ: the first candidate margin with enough clearance from the proposed zeros, else the best.
double choose_margin(const std::vector<std::array<double, 2>>& real_box,
                     const std::vector<std::vector<Complex>>& proposed) {
  double best = 0, best_clearance = -std::numeric_limits<double>::infinity();
  for (const double m : tol::homotopy_barrier_margins) {
    const double mu = m * widest_side(real_box);
    const BarrierBox c(real_box, mu);
    double clearance = std::numeric_limits<double>::infinity();
    for (const auto& z : proposed) {
      bool finite = true;
      for (const Complex& x : z) finite = finite && std::isfinite(x.real()) && std::isfinite(x.imag());
      if (finite) clearance = std::min(clearance, std::abs(c.clearance(z)));
    }
    if (clearance >= tol::homotopy_barrier_clearance * mu) return mu;
    if (clearance / mu > best_clearance) {
      best_clearance = clearance / mu;
      best = mu;
    }
  }
  return best;
}

//! A face box of a barrier, with mig|f_i| and mag|g_i| of the i of largest ratio, and that ratio.
struct FaceBox {
  ComplexBox box;
  double ratio = 0;
  double mig_f = 0, mag_g = 0;
};

double mig(const Interval& a) { return a.inf() > 0 ? a.inf() : a.sup() < 0 ? -a.sup() : 0.0; }
double mag(const Interval& a) { return std::max(std::abs(a.inf()), std::abs(a.sup())); }

//! The best (i, mig|f_i|, mag|g_i|) of a face box from the enclosures f and g.  Needs a live
//! RoundingGuard (so the upper bound of |g_i| rounds up).
void best_ratio(const ComplexBox& f, const ComplexBox& g, FaceBox& out) {
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double lower = std::max(mig(f[i].re), mig(f[i].im));  // |z| ≥ max(|Re z|, |Im z|)
    const double ar = mag(g[i].re), ai = mag(g[i].im);
    const double upper = std::sqrt(ar * ar + ai * ai);            // rounded upward
    if (!(lower > 0) || !std::isfinite(upper)) continue;
    const double ratio = upper > 0 ? lower / upper : std::numeric_limits<double>::infinity();
    if (ratio > out.ratio) {
      out.ratio = ratio;
      out.mig_f = lower;
      out.mag_g = upper;
    }
  }
}

//! Evaluates a face box: the natural enclosure of f, and the mean-value form when the natural one
//! does not reach `needed`.  Needs a live RoundingGuard.
FaceBox evaluate_face(const HomotopyMap& map, ComplexBox box, double needed) {
  ComplexBox f, g;
  detail::enclose_f_and_g(map, box, f, g);
  FaceBox out;
  best_ratio(f, g, out);
  if (out.ratio < needed) {
    detail::enclose_f_centred(map, box, f);
    best_ratio(f, g, out);
  }
  out.box = std::move(box);
  return out;
}

//! Bisects the widest free real coordinate of a face box (a fixed coordinate has width 0).
std::pair<ComplexBox, ComplexBox> bisect(const ComplexBox& box) {
  std::size_t best = 0;
  bool imaginary = false;
  double widest = -1;
  for (std::size_t i = 0; i < box.size(); ++i) {
    if (box[i].re.sup() - box[i].re.inf() > widest) {
      widest = box[i].re.sup() - box[i].re.inf();
      best = i;
      imaginary = false;
    }
    if (box[i].im.sup() - box[i].im.inf() > widest) {
      widest = box[i].im.sup() - box[i].im.inf();
      best = i;
      imaginary = true;
    }
  }
  ComplexBox a = box, b = box;
  const Interval& side = imaginary ? box[best].im : box[best].re;
  const double mid = 0.5 * side.inf() + 0.5 * side.sup();
  (imaginary ? a[best].im : a[best].re) = Interval(side.inf(), mid);
  (imaginary ? b[best].im : b[best].re) = Interval(mid, side.sup());
  return {a, b};
}

bool passed(const std::optional<Clock::time_point>& deadline) { return deadline && Clock::now() >= *deadline; }

//! (B) on ∂C for the fixed t_e: bisects the face boxes, depth first, until every one satisfies
//! (1 − t_e) mig|f_i| > t_e mag|g_i| for some i (decided in interval arithmetic) or `budget` boxes
//! were evaluated.  Counts the boxes in the certificate.
bool prove_barrier(const HomotopyProblem& problem, const BarrierBox& c, double t_e, std::size_t budget,
                   HomotopyCertificate& certificate) {
  const HomotopyMap f_and_g{problem.f, problem.parameters, problem.degrees, problem.gamma, 0.0};
  const Interval t(t_e);
  const double needed = t_e / (1 - t_e);  // a box below this ratio (rounded) is bisected
  RoundingGuard guard;
  const auto settled = [&](const FaceBox& box) {
    return box.ratio >= needed &&
           ((Interval(1.0) - t) * Interval(box.mig_f) - t * Interval(box.mag_g)).inf() > 0;
  };
  std::vector<FaceBox> open;  // a stack: depth first, so a hopeless face does not spread
  std::size_t used = 0;
  for (ComplexBox& face : c.faces()) {
    open.push_back(evaluate_face(f_and_g, std::move(face), needed));
    ++used;
  }
  while (!open.empty()) {
    FaceBox box = std::move(open.back());
    open.pop_back();
    if (settled(box)) continue;
    if (used + 2 > budget) {
      certificate.barrier_boxes += used;
      return false;
    }
    auto [a, b] = bisect(box.box);
    open.push_back(evaluate_face(f_and_g, std::move(a), needed));
    open.push_back(evaluate_face(f_and_g, std::move(b), needed));
    used += 2;
  }
  certificate.barrier_boxes += used;
  return true;
}

//! (I): the D zeros of H_{t_e}, certified and pairwise disjoint, into `boxes`.
bool prove_intermediate_zeros(
    const HomotopyProblem& problem, std::size_t start_count,
    const std::function<std::optional<std::vector<Complex>>(std::size_t, double)>& point_at,
    std::vector<ComplexBox>& boxes, HomotopyCertificate& certificate,
    const std::optional<Clock::time_point>& deadline) {
  const HomotopyMap map{problem.f, problem.parameters, problem.degrees, problem.gamma, certificate.t_barrier};
  for (std::size_t j = 0; j < start_count; ++j) {
    if (passed(deadline)) {
      certificate.status = HomotopyCertificateStatus::out_of_time;
      return false;
    }
    const std::optional<std::vector<Complex>> point = point_at(j, certificate.t_barrier);
    if (!point) {
      certificate.status = passed(deadline) ? HomotopyCertificateStatus::out_of_time
                                            : HomotopyCertificateStatus::intermediate_path_failed;
      return false;
    }
    ComplexBox box;
    if (!detail::certify_complex_zero(map, *point, box)) {
      certificate.status = HomotopyCertificateStatus::intermediate_not_certified;
      return false;
    }
    for (const ComplexBox& other : boxes)
      if (detail::boxes_meet(box, other)) {
        certificate.status = HomotopyCertificateStatus::intermediate_not_distinct;
        return false;
      }
    boxes.push_back(std::move(box));
  }
  return true;
}

//! k for the barrier box c: how many of the zeros at t_e lie in c; nothing if one straddles ∂c.
std::optional<std::size_t> count_inside(const BarrierBox& c, const std::vector<ComplexBox>& zeros) {
  std::size_t k = 0;
  for (const ComplexBox& box : zeros) {
    if (c.contains(box))
      ++k;
    else if (!c.misses(box))
      return std::nullopt;
  }
  return k;
}

//! A box symmetric about the reals that contains `box` and holds exactly one zero of f (so the
//! zero in `box` is real): boxes of half-width r in every part around the centre of Re box, r at
//! least the extent of `box` and homotopy_certify_radius · (1 + |Re|), growing by
//! homotopy_certify_growth, at most homotopy_certify_attempts of them.
std::optional<ComplexBox> symmetric_certified_box(const HomotopyMap& f, const ComplexBox& box) {
  double radius = 0;
  for (const auto& x : box)
    radius = std::max({radius, 0.5 * (x.re.sup() - x.re.inf()), std::abs(x.im.inf()), std::abs(x.im.sup()),
                       tol::homotopy_certify_radius * (1 + mag(x.re))});
  for (int attempt = 0; attempt < tol::homotopy_certify_attempts; ++attempt, radius *= tol::homotopy_certify_growth) {
    ComplexBox symmetric;
    for (const auto& x : box) {
      const double c = 0.5 * x.re.inf() + 0.5 * x.re.sup();
      symmetric.emplace_back(Interval(std::min(c - radius, x.re.inf()), std::max(c + radius, x.re.sup())),
                             Interval(-radius, radius));
    }
    if (detail::complex_krawczyk_test(f, symmetric).outcome == KrawczykOutcome::unique_root) return symmetric;
  }
  return std::nullopt;
}

//! The zeros of f proposed, certified by Krawczyk and without repetitions (two certified boxes
//! that meet hold one zero when their hull holds exactly one; false if that is not proved).
bool certify_proposed_zeros(const HomotopyMap& f, const std::vector<std::vector<Complex>>& proposed,
                            std::vector<ComplexBox>& zeros) {
  for (const auto& z : proposed) {
    ComplexBox box;
    if (!detail::certify_complex_zero(f, z, box)) continue;
    bool known = false;
    for (const ComplexBox& other : zeros) {
      if (!detail::boxes_meet(box, other)) continue;
      ComplexBox hull(box.size());
      for (std::size_t i = 0; i < box.size(); ++i)
        hull[i] = ComplexInterval(Interval(std::min(box[i].re.inf(), other[i].re.inf()),
                                           std::max(box[i].re.sup(), other[i].re.sup())),
                                  Interval(std::min(box[i].im.inf(), other[i].im.inf()),
                                           std::max(box[i].im.sup(), other[i].im.sup())));
      if (detail::complex_krawczyk_test(f, hull).outcome != KrawczykOutcome::unique_root) return false;
      known = true;
    }
    if (!known) zeros.push_back(std::move(box));
  }
  return true;
}

//! The real classification of the zeros of f that lie in some barrier box (the others are not
//! needed: every real root of the domain lies in some barrier box).
bool classify_zeros(const HomotopyMap& f, const std::vector<ComplexBox>& zeros, const std::vector<BarrierBox>& barriers,
                    HomotopyCertificate& certificate) {
  for (const ComplexBox& box : zeros) {
    if (std::none_of(barriers.begin(), barriers.end(), [&](const BarrierBox& c) { return c.contains(box); })) continue;
    const bool not_real =
        std::any_of(box.begin(), box.end(), [](const ComplexInterval& x) { return certainly_nonzero(x.im); });
    if (not_real) {
      ++certificate.nonreal_zeros;
      continue;
    }
    std::optional<ComplexBox> symmetric = symmetric_certified_box(f, box);
    if (!symmetric) {
      certificate.status = HomotopyCertificateStatus::real_not_decided;
      return false;
    }
    std::vector<Interval> real;
    for (const auto& x : *symmetric) real.push_back(x.re);
    certificate.real_zeros.push_back(std::move(real));
  }
  return true;
}

}  // namespace

HomotopyCertificate certify_homotopy(
    const HomotopyProblem& problem, std::size_t start_count,
    const std::function<std::optional<std::vector<Complex>>(std::size_t, double)>& point_at,
    const std::vector<std::vector<Complex>>& proposed_zeros, std::optional<Clock::time_point> deadline) {
  const std::size_t n = problem.degrees.size();
  if (n == 0 || problem.f.n_unknowns() != n || problem.f.n_equations() != n || problem.domain.dimension() != n)
    throw PreconditionViolation("certify_homotopy: the system, its degrees and the domain differ in dimension");
  std::size_t bezout = 1;
  for (int d : problem.degrees) bezout *= static_cast<std::size_t>(std::max(d, 1));
  if (start_count != bezout)
    throw PreconditionViolation("certify_homotopy: " + std::to_string(start_count) + " paths, Bézout number " +
                                std::to_string(bezout));
  HomotopyCertificate certificate;
  certificate.t_barrier = tol::homotopy_barrier_t;
  const HomotopyMap f{problem.f, problem.parameters, problem.degrees, problem.gamma, 0.0};

  // A failure that concerns the whole solve leaves the whole domain unproved.
  const auto nothing_proved = [&](HomotopyCertificateStatus status) {
    certificate.status = status;
    certificate.pieces.clear();
    certificate.real_zeros.clear();
    certificate.nonreal_zeros = 0;
    certificate.unproved = {problem.domain.box.bounds};
    return certificate;
  };
  // (I) once, and f's proposed zeros certified once
  std::vector<ComplexBox> intermediate, zeros;
  if (!prove_intermediate_zeros(problem, start_count, point_at, intermediate, certificate, deadline))
    return nothing_proved(certificate.status);
  if (!certify_proposed_zeros(f, proposed_zeros, zeros))
    return nothing_proved(HomotopyCertificateStatus::zeros_not_certified);
  // The domain's box is covered by pieces, each with its barrier box: a piece whose barrier or
  // counts are not proved is bisected along its widest side (breadth first, so that every region
  // that fails shrinks alike), up to homotopy_barrier_max_pieces; the rest stays unproved.
  std::deque<std::vector<std::array<double, 2>>> pieces = {problem.domain.box.bounds};
  std::vector<BarrierBox> proved;
  std::size_t budget_left = tol::homotopy_barrier_box_budget;
  HomotopyCertificateStatus first_failure = HomotopyCertificateStatus::proved;
  while (!pieces.empty()) {
    if (passed(deadline)) return nothing_proved(HomotopyCertificateStatus::out_of_time);
    std::vector<std::array<double, 2>> piece = std::move(pieces.front());
    pieces.pop_front();
    const BarrierBox c(piece, choose_margin(piece, proposed_zeros));
    HomotopyCertificateStatus failure = HomotopyCertificateStatus::proved;
    const std::size_t before = certificate.barrier_boxes;
    const std::optional<std::size_t> k = count_inside(c, intermediate);
    if (!k) {
      failure = HomotopyCertificateStatus::intermediate_straddles;
    } else if (budget_left == 0 || !prove_barrier(problem, c, certificate.t_barrier,
                                                  std::min(budget_left, tol::homotopy_barrier_piece_budget),
                                                  certificate)) {
      failure = HomotopyCertificateStatus::barrier_not_proved;
    } else if (static_cast<std::size_t>(std::count_if(zeros.begin(), zeros.end(), [&](const ComplexBox& z) {
                 return c.contains(z);
               })) != *k) {
      failure = HomotopyCertificateStatus::zeros_not_certified;
    }
    budget_left -= std::min(budget_left, certificate.barrier_boxes - before);
    if (failure == HomotopyCertificateStatus::proved) {
      certificate.zeros_inside += *k;
      certificate.pieces.push_back(BarrierPiece{piece, c.margin});
      proved.push_back(c);
      continue;
    }
    if (proved.size() + certificate.unproved.size() + pieces.size() + 2 > tol::homotopy_barrier_max_pieces ||
        budget_left == 0) {
      if (first_failure == HomotopyCertificateStatus::proved) first_failure = failure;
      certificate.unproved.push_back(std::move(piece));
      continue;
    }
    std::size_t widest = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (piece[i][1] - piece[i][0] > piece[widest][1] - piece[widest][0]) widest = i;
    const double mid = 0.5 * piece[widest][0] + 0.5 * piece[widest][1];
    std::vector<std::array<double, 2>> high = piece;
    piece[widest][1] = mid;
    high[widest][0] = mid;
    pieces.push_back(std::move(piece));
    pieces.push_back(std::move(high));
  }
  if (!classify_zeros(f, zeros, proved, certificate)) return nothing_proved(certificate.status);
  certificate.status = first_failure;
  return certificate;
}

}  // namespace delmesh
