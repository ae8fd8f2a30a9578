// Input validation by interval subdivision.  The soundness argument for every dropped box is in
// the header comment; this file follows it step by step.
#include "meshing/input_validation.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "common/errors.h"
#include "common/tolerances.h"
#include "solvers/krawczyk.h"
#include "symbolic/compiled_system.h"
#include "symbolic/scalar_traits.h"

namespace delmesh {

namespace {

using Point = std::array<double, 3>;
using Box = std::array<Interval, 3>;

const std::vector<GiNaC::symbol>& unknowns() {
  static const std::vector<GiNaC::symbol> xyz{coordinate_x(), coordinate_y(), coordinate_z()};
  return xyz;
}

// {E, ∂xE, ∂yE, ∂zE}: its values are E and ∇E, rows 1–3 of its Jacobian the Hessian of E.
CompiledSystem gradient_system(const Surface& surface) {
  const auto& g = surface.gradient();
  return CompiledSystem(std::vector<GiNaC::ex>{surface.E(), g[0], g[1], g[2]}, unknowns(), {});
}

bool finite(const Interval& a) { return std::isfinite(a.inf()) && std::isfinite(a.sup()); }

// a and b both enclose the same real number v.  True iff a ∩ b excludes 0 (then v ≠ 0).
bool excludes_zero(const Interval& a, const Interval& b) {
  if (certainly_nonzero(a) || certainly_nonzero(b)) return true;
  if (!finite(a) || !finite(b)) return false;
  return std::max(a.inf(), b.inf()) > 0 || std::min(a.sup(), b.sup()) < 0;
}

// A double in [a.inf(), a.sup()] near its centre.
double centre(const Interval& a) { return std::min(std::max(0.5 * a.inf() + 0.5 * a.sup(), a.inf()), a.sup()); }

std::string point_text(const Point& p) {
  std::ostringstream s;
  s << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return s.str();
}

std::string face_name(int axis, bool upper, const Box3& box) {
  std::ostringstream s;
  s << "xyz"[axis] << " = " << (upper ? box.hi[axis] : box.lo[axis]);
  return s.str();
}

// The gradient system over a box (or face rectangle) B: values v and Jacobian j over B, values vc
// at the centre c, and the enclosures d of B − c.
struct BoxEnclosures {
  Interval v[4], j[12], vc[4];
  Box d;
  Point c{};
};

// Step 1 of the header's proof with the natural enclosure alone (the cheapest test).
bool natural_excludes_e(const CompiledSystem& system, const Box& b) {
  Interval v[4];
  system.values<Interval>(b.data(), nullptr, v);
  return certainly_nonzero(v[0]);
}

// Step 1 of the header's proof: true iff the natural and mean-value enclosures of E over B
// together exclude 0.  Fills `out` for gradient_nonzero.
bool mean_value_excludes_e(const CompiledSystem& system, const Box& b, BoxEnclosures& out) {
  Box c;
  for (int i = 0; i < 3; ++i) {
    out.c[i] = centre(b[i]);
    c[i] = Interval(out.c[i]);
    out.d[i] = b[i] - c[i];
  }
  system.values_and_jacobian<Interval>(b.data(), nullptr, out.v, out.j);
  system.values<Interval>(c.data(), nullptr, out.vc);
  if (!(finite(out.vc[0]) && finite(out.v[1]) && finite(out.v[2]) && finite(out.v[3])))
    return certainly_nonzero(out.v[0]);  // the mean-value form needs E C¹ on B
  Interval mean_value = out.vc[0];
  for (int i = 0; i < 3; ++i) mean_value += out.v[1 + i] * out.d[i];
  return excludes_zero(out.v[0], mean_value);
}

// Step 2 of the header's proof: true iff ⟨∇E, g⟩ ≠ 0 on B is proved for g one of the axis vectors
// or g ≈ ∇E(c).  Uses the enclosures of mean_value_excludes_e.
bool gradient_nonzero(const BoxEnclosures& e) {
  const Interval* grad = e.v + 1;      // ∇E(B)
  const Interval* hess = e.j + 3;      // H(B), row-major, rows 1–3 of the Jacobian
  const Interval* grad_c = e.vc + 1;   // ∇E(c)
  // The mean-value form needs E C² on B: finite enclosures of ∇E(c) and of the Hessian.
  bool c2 = true;
  for (int i = 0; i < 3; ++i) c2 = c2 && finite(grad_c[i]);
  for (int i = 0; i < 9; ++i) c2 = c2 && finite(hess[i]);
  const auto directional = [&](const std::array<double, 3>& g) {
    Interval natural(0), mean_value(0);
    for (int i = 0; i < 3; ++i) natural += grad[i] * g[i];
    if (!c2) return certainly_nonzero(natural);
    for (int i = 0; i < 3; ++i) mean_value += grad_c[i] * g[i];
    for (int k = 0; k < 3; ++k) {
      Interval hg(0);
      for (int i = 0; i < 3; ++i) hg += hess[3 * i + k] * g[i];
      mean_value += hg * e.d[k];
    }
    return excludes_zero(natural, mean_value);
  };
  std::array<double, 3> g{};
  bool usable = false;  // g finite and non-zero
  for (int i = 0; i < 3; ++i) {
    g[i] = centre(grad_c[i]);
    usable = usable || g[i] != 0;
  }
  for (int i = 0; i < 3; ++i) usable = usable && std::isfinite(g[i]);
  if (usable && directional(g)) return true;
  for (int k = 0; k < 3; ++k) {
    std::array<double, 3> axis{};
    axis[k] = 1;
    if (directional(axis)) return true;
  }
  return false;
}

// ---- evidence of a singular point near an undecided box (header: "Undecided boxes ...") ----

struct Scales {
  double E = 1, gradient = 1;  // largest |E| and ‖∇E‖∞ on the 3 × 3 × 3 grid of the domain
};

Scales domain_scales(const CompiledSystem& system, const Box3& box) {
  Scales s{0, 0};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c) {
        const int idx[3] = {a, b, c};
        Point p;
        for (int k = 0; k < 3; ++k) p[k] = box.lo[k] + 0.5 * idx[k] * (box.hi[k] - box.lo[k]);
        double v[4];
        system.values<double>(p.data(), nullptr, v);
        if (std::isfinite(v[0])) s.E = std::max(s.E, std::abs(v[0]));
        for (int k = 1; k < 4; ++k)
          if (std::isfinite(v[k])) s.gradient = std::max(s.gradient, std::abs(v[k]));
      }
  if (!(s.E > 0)) s.E = 1;
  if (!(s.gradient > 0)) s.gradient = 1;
  return s;
}

// Damped Gauss–Newton (Levenberg–Marquardt, in double) on the overdetermined system
// (E/scale.E, ∇E/scale.gradient) = 0 from p.  Returns the best point reached.
Point gauss_newton(const CompiledSystem& system, const Scales& scale, Point p) {
  const auto residual = [&](const Point& x, double* r, double* jac) {
    double v[4], j[12];
    system.values_and_jacobian<double>(x.data(), nullptr, v, j);
    for (int i = 0; i < 4; ++i) {
      const double w = i == 0 ? 1 / scale.E : 1 / scale.gradient;
      r[i] = v[i] * w;
      if (jac)
        for (int k = 0; k < 3; ++k) jac[3 * i + k] = j[3 * i + k] * w;
    }
    double n = 0;
    for (int i = 0; i < 4; ++i) n += r[i] * r[i];
    return std::isfinite(n) ? n : std::numeric_limits<double>::infinity();
  };
  // Marquardt's damping: start at 1e-3, divide by 4 after a step that lowers the residual,
  // multiply by 8 after one that does not (a rejected step leaves p unchanged).
  double r[4], jac[12];
  double norm = residual(p, r, jac);
  double mu = 1e-3;
  for (int it = 0; it < tolerances::singular_evidence_iterations && norm > 0 && std::isfinite(norm); ++it) {
    // (JᵀJ + μ diag(JᵀJ)) δ = −Jᵀr, solved by Gaussian elimination with partial pivoting.
    double a[3][4];
    for (int k = 0; k < 3; ++k) {
      for (int l = 0; l < 3; ++l) {
        a[k][l] = 0;
        for (int i = 0; i < 4; ++i) a[k][l] += jac[3 * i + k] * jac[3 * i + l];
      }
      a[k][3] = 0;
      for (int i = 0; i < 4; ++i) a[k][3] -= jac[3 * i + k] * r[i];
    }
    for (int k = 0; k < 3; ++k) a[k][k] += mu * a[k][k] + std::numeric_limits<double>::min();
    bool solved = true;
    for (int k = 0; k < 3 && solved; ++k) {
      int pivot = k;
      for (int l = k + 1; l < 3; ++l)
        if (std::abs(a[l][k]) > std::abs(a[pivot][k])) pivot = l;
      std::swap(a[k], a[pivot]);
      if (!(std::abs(a[k][k]) > 0)) solved = false;
      for (int l = k + 1; l < 3 && solved; ++l) {
        const double f = a[l][k] / a[k][k];
        for (int m = k; m < 4; ++m) a[l][m] -= f * a[k][m];
      }
    }
    if (!solved) break;
    Point delta;
    for (int k = 2; k >= 0; --k) {
      double s = a[k][3];
      for (int l = k + 1; l < 3; ++l) s -= a[k][l] * delta[l];
      delta[k] = s / a[k][k];
    }
    Point trial;
    for (int k = 0; k < 3; ++k) trial[k] = p[k] + delta[k];
    if (trial == p) break;
    double rt[4], jt[12];
    const double nt = residual(trial, rt, jt);
    if (nt < norm) {
      p = trial;
      norm = nt;
      std::copy(rt, rt + 4, r);
      std::copy(jt, jt + 12, jac);
      mu *= 0.25;
    } else {
      mu *= 8;
    }
  }
  return p;
}

struct Evidence {
  bool singular = false;
  Point where{};
  std::string detail;  // why singular, or what was found instead
};

// Looks for a singular point of Σ near the undecided box b (header: "Undecided boxes ...").
Evidence singular_evidence(const CompiledSystem& system, std::optional<CompiledSystem>& gradient_only,
                           const Surface& surface, const Scales& scale, const Box& b) {
  const double rho = tolerances::singular_evidence_relative_residual;
  Evidence e;
  double w = 0;
  for (int k = 0; k < 3; ++k) {
    e.where[k] = centre(b[k]);
    w = std::max(w, b[k].sup() - b[k].inf());
  }
  const Point p = gauss_newton(system, scale, e.where);
  for (int k = 0; k < 3; ++k)
    if (!(p[k] >= b[k].inf() - w && p[k] <= b[k].sup() + w)) return e;

  // A critical point certified by Krawczyk on ∇E = 0 in p ± r (r = w, w/16, w/16², ...: interval
  // overestimation of the Hessian may need r far below w), refined to a tight box X.  It is the
  // only critical point in p ± r, so E(X) decides: E ∋ 0 on a tight X is evidence of a singular
  // point, E ≠ 0 on X proves that there is none in p ± r.
  if (!gradient_only) {
    const auto& g = surface.gradient();
    gradient_only.emplace(std::vector<GiNaC::ex>{g[0], g[1], g[2]}, unknowns(), std::vector<GiNaC::symbol>{});
  }
  double r = w;
  for (int attempt = 0; attempt < tolerances::singular_evidence_krawczyk_attempts; ++attempt, r /= 16) {
    RoundingGuard guard;
    std::vector<Interval> x(3);
    for (int k = 0; k < 3; ++k) x[k] = Interval(p[k]) + Interval(-r, r);
    KrawczykResult k = krawczyk_test(*gradient_only, {}, x);
    if (k.outcome == KrawczykOutcome::no_root) {  // ∇E ≠ 0 on p ± r: no singular point at p
      std::ostringstream s;
      s << " (Krawczyk proves that grad E has no zero within " << r << " of " << point_text(p)
        << ", the point nearest to a singular one found near it)";
      e.detail = s.str();
      return e;
    }
    if (k.outcome == KrawczykOutcome::unique_root) {
      x = k.contracted;
      for (int it = 0; it < tolerances::root_refinement_iterations; ++it) {
        const KrawczykResult next = krawczyk_test(*gradient_only, {}, x);
        if (next.outcome != KrawczykOutcome::unique_root) break;
        double before = 0, after = 0;
        for (int i = 0; i < 3; ++i) {
          before = std::max(before, x[i].sup() - x[i].inf());
          after = std::max(after, next.contracted[i].sup() - next.contracted[i].inf());
        }
        x = next.contracted;
        if (!(after < tolerances::root_refinement_shrink_ratio * before)) break;
      }
      Interval v[4];
      system.values<Interval>(x.data(), nullptr, v);
      for (int i = 0; i < 3; ++i) e.where[i] = centre(x[i]);
      std::ostringstream s;
      if (certainly_nonzero(v[0])) {
        s << " (Krawczyk certifies that the only critical point of E within " << r << " of " << point_text(p)
          << ", the point nearest to a singular one found near it, lies off the surface, at "
          << point_text(e.where) << " where |E| >= " << std::min(std::abs(v[0].inf()), std::abs(v[0].sup())) << ")";
        e.detail = s.str();
        return e;
      }
      if (finite(v[0]) && v[0].sup() - v[0].inf() <= rho * scale.E) {
        s << "; Krawczyk certifies a critical point of E there, at which |E| <= "
          << std::max(std::abs(v[0].inf()), std::abs(v[0].sup()));
        e.singular = true;
        e.detail = s.str();
        return e;
      }
      break;
    }
  }

  // A degenerate singular point: (E, ∇E) vanish at p to within rho relative to their scales.
  double v[4];
  system.values<double>(p.data(), nullptr, v);
  const double gradient = std::max({std::abs(v[1]), std::abs(v[2]), std::abs(v[3])});
  if (std::abs(v[0]) <= rho * scale.E && gradient <= rho * scale.gradient) {
    e.singular = true;
    e.where = p;
    std::ostringstream s;
    s << "; there |E| = " << std::abs(v[0]) << " and |grad E| = " << gradient
      << ", relative to their scales " << scale.E << " and " << scale.gradient << " over the box";
    e.detail = s.str();
  }
  return e;
}

std::size_t check_box_faces(const CompiledSystem& system, const Box3& box) {
  std::size_t examined = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const double fixed = side ? box.hi[axis] : box.lo[axis];
      const int i = (axis + 1) % 3, j = (axis + 2) % 3;
      struct Rect { double u0, u1, v0, v1; int depth; };
      std::vector<Rect> stack{{box.lo[i], box.hi[i], box.lo[j], box.hi[j], 0}};
      bool positive = false, negative = false, undecided = false;
      std::size_t budget = tolerances::mesher_box_budget_global;
      while (!stack.empty()) {
        const Rect r = stack.back();
        stack.pop_back();
        ++examined;
        // E at the rectangle's centre (double) records the signs met on the face.
        Point c{};
        c[axis] = fixed;
        c[i] = 0.5 * (r.u0 + r.u1);
        c[j] = 0.5 * (r.v0 + r.v1);
        double values[4];
        system.values<double>(c.data(), nullptr, values);
        if (values[0] > 0) positive = true;
        if (values[0] < 0) negative = true;
        if (values[0] == 0 || (positive && negative)) {
          throw InvalidInput("the surface meets the boundary of the box on the face " +
                             face_name(axis, side, box) + "; enlarge the box so that it contains Σ strictly inside");
        }
        bool excluded = false;
        {
          RoundingGuard guard;
          Box x;
          x[axis] = Interval(fixed);
          x[i] = Interval(r.u0, r.u1);
          x[j] = Interval(r.v0, r.v1);
          BoxEnclosures e;
          excluded = natural_excludes_e(system, x) || mean_value_excludes_e(system, x, e);
        }
        if (excluded) continue;
        if (r.depth >= tolerances::box_face_max_depth || budget == 0) {
          undecided = true;
          continue;
        }
        --budget;
        const double um = 0.5 * (r.u0 + r.u1), vm = 0.5 * (r.v0 + r.v1);
        stack.push_back({r.u0, um, r.v0, vm, r.depth + 1});
        stack.push_back({um, r.u1, r.v0, vm, r.depth + 1});
        stack.push_back({r.u0, um, vm, r.v1, r.depth + 1});
        stack.push_back({um, r.u1, vm, r.v1, r.depth + 1});
      }
      if (undecided)
        throw InvalidInput("cannot certify that the surface stays away from the face " +
                           face_name(axis, side, box) + " of the box; enlarge the box");
    }
  return examined;
}

std::size_t check_regular(const CompiledSystem& system, const Surface& surface, const Box3& box) {
  double domain_width = 0;
  for (int k = 0; k < 3; ++k) domain_width = std::max(domain_width, box.hi[k] - box.lo[k]);
  const double min_width = tolerances::validation_min_box_relative_width * domain_width;
  const double deep_min_width = validation_deep_min_box_relative_width * domain_width;
  std::size_t deep_boxes = 0;
  const Scales scale = domain_scales(system, box);
  std::optional<CompiledSystem> gradient_only;

  std::vector<std::array<double, 6>> stack{{box.lo[0], box.hi[0], box.lo[1], box.hi[1], box.lo[2], box.hi[2]}};
  std::vector<Box> undecided;
  std::string first_note;  // what singular_evidence found near the first undecided box
  std::size_t examined = 0;
  bool budget_exhausted = false;
  while (!stack.empty()) {
    if (examined >= tolerances::mesher_box_budget_global) {
      budget_exhausted = true;
      break;
    }
    const auto bounds = stack.back();
    stack.pop_back();
    ++examined;
    Box b;
    bool dropped = false;
    {
      RoundingGuard guard;
      for (int k = 0; k < 3; ++k) b[k] = Interval(bounds[2 * k], bounds[2 * k + 1]);
      BoxEnclosures e;
      dropped = natural_excludes_e(system, b) || mean_value_excludes_e(system, b, e) || gradient_nonzero(e);
    }
    if (dropped) continue;
    int side = 0;
    for (int k = 1; k < 3; ++k)
      if (bounds[2 * k + 1] - bounds[2 * k] > bounds[2 * side + 1] - bounds[2 * side]) side = k;
    const double lo = bounds[2 * side], hi = bounds[2 * side + 1], split = 0.5 * (lo + hi);
    const bool splittable = split > lo && split < hi;
    if (hi - lo < min_width || !splittable) {
      // Evidence is looked for once, on the boxes that have just crossed min_width; below it a
      // box without evidence is bisected on, down to deep_min_width, within the deep budget.
      if (hi - lo >= 0.5 * min_width || !splittable) {
        const Evidence evidence = singular_evidence(system, gradient_only, surface, scale, b);
        if (evidence.singular)
          throw InvalidInput("the surface is singular: the gradient of E vanishes on it near " +
                             point_text(evidence.where) + evidence.detail);
        if (undecided.empty() && !evidence.detail.empty()) first_note = evidence.detail;
      }
      if (!splittable || hi - lo < deep_min_width || deep_boxes >= validation_deep_box_budget) {
        undecided.push_back(b);
        continue;
      }
      ++deep_boxes;
    }
    auto lower = bounds, upper = bounds;
    lower[2 * side + 1] = split;
    upper[2 * side] = split;
    stack.push_back(upper);
    stack.push_back(lower);
  }
  if (undecided.empty() && !budget_exhausted) return examined;

  Point where{};
  if (!undecided.empty())
    for (int k = 0; k < 3; ++k) where[k] = centre(undecided.front()[k]);
  std::ostringstream s;
  s << "cannot certify that the gradient of E is non-zero on the surface: ";
  if (budget_exhausted)
    s << "the budget of " << tolerances::mesher_box_budget_global << " boxes ran out with " << stack.size()
      << " boxes unexplored and " << undecided.size() << " undecided";
  else
    s << undecided.size() << " boxes stay undecided (bisected down to width " << deep_min_width << " or the budget of " << validation_deep_box_budget << " narrow boxes)";
  if (!undecided.empty()) {
    s << ", the first near " << point_text(where) << ", with no singular point found near them";
    Interval v[4];
    {
      RoundingGuard guard;
      system.values<Interval>(undecided.front().data(), nullptr, v);
    }
    if (!(finite(v[0]) && finite(v[1]) && finite(v[2]) && finite(v[3]))) {
      // A polynomial has no pole: an infinite enclosure there is an overflow of double precision.
      if (surface.is_polynomial())
        s << " (E or its gradient overflows double precision there: the box is too large for E; rescale the "
             "coordinates or shrink the box)";
      else
        s << " (E or its gradient is undefined, unbounded or beyond double precision there)";
    }
    s << first_note;
  } else if (!stack.empty()) {
    const auto& u = stack.back();
    s << ", the next near " << point_text({0.5 * (u[0] + u[1]), 0.5 * (u[2] + u[3]), 0.5 * (u[4] + u[5])});
  }
  throw InvalidInput(s.str());
}

}  // namespace

std::size_t validate_box_faces(const Surface& surface, const Box3& box) {
  return check_box_faces(gradient_system(surface), box);
}

std::size_t validate_regular(const Surface& surface, const Box3& box) {
  return check_regular(gradient_system(surface), surface, box);
}

ValidationReport validate_input(const Surface& surface, const Box3& box) {
  const auto start = std::chrono::steady_clock::now();
  const CompiledSystem system = gradient_system(surface);
  ValidationReport report;
  report.face_boxes = check_box_faces(system, box);
  report.regular_boxes = check_regular(system, surface, box);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace delmesh
