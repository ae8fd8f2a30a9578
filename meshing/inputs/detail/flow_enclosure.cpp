#include "meshing/inputs/detail/flow_enclosure.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "symbolic/surface.h"

namespace delmesh::detail {

Interval meet(const Interval& a, const Interval& b) {
  if (!finite(b)) return a;
  if (!finite(a)) return b;
  const double lo = std::max(a.inf(), b.inf()), hi = std::min(a.sup(), b.sup());
  return lo <= hi ? Interval(lo, hi) : a;
}

double magnitude(const Interval& a) {
  return finite(a) ? std::max(std::abs(a.inf()), std::abs(a.sup())) : std::numeric_limits<double>::infinity();
}

P3 centre_of(const IBox& x) {
  P3 c;
  for (int k = 0; k < 3; ++k) c[k] = std::min(std::max(0.5 * x[k].inf() + 0.5 * x[k].sup(), x[k].inf()), x[k].sup());
  return c;
}

double width_of(const IBox& x) {
  double w = 0;
  for (int k = 0; k < 3; ++k) w = std::max(w, x[k].sup() - x[k].inf());
  return w;
}

CompiledSystem compile_value_and_gradient(const GiNaC::ex& E, const std::array<GiNaC::ex, 3>& gradient) {
  return CompiledSystem(std::vector<GiNaC::ex>{E, gradient[0], gradient[1], gradient[2]},
                        {coordinate_x(), coordinate_y(), coordinate_z()}, {}, false, PolynomialFormBuild::never);
}

Enclosure::Enclosure(const CompiledSystem& system, const IBox& x) {
  c = centre_of(x);
  IBox at;
  for (int k = 0; k < 3; ++k) {
    at[k] = Interval(c[k]);
    d[k] = x[k] - at[k];
  }
  system.values_and_jacobian<Interval>(x.data(), nullptr, v, j);
  system.values<Interval>(at.data(), nullptr, vc);
  c2 = true;
  for (const Interval& a : v) c2 = c2 && finite(a);
  for (const Interval& a : j) c2 = c2 && finite(a);
  for (const Interval& a : vc) c2 = c2 && finite(a);
}

Interval Enclosure::value() const {
  if (!c2) return v[0];
  Interval mv = vc[0];
  for (int i = 0; i < 3; ++i) mv += v[1 + i] * d[i];
  return meet(v[0], mv);
}

Interval Enclosure::directional(const IBox& w) const {
  Interval natural(0);
  for (int i = 0; i < 3; ++i) natural += v[1 + i] * w[i];
  if (!c2) return natural;
  Interval mv(0);
  for (int i = 0; i < 3; ++i) mv += vc[1 + i] * w[i];
  for (int k = 0; k < 3; ++k) {
    Interval hw(0);
    for (int i = 0; i < 3; ++i) hw += hessian(i, k) * w[i];
    mv += hw * d[k];
  }
  return meet(natural, mv);
}

Interval Enclosure::value_on_hull(const std::array<IBox, 3>& corners) const {
  if (!c2) return v[0];
  // The affine term is affine in x, so its range over the hull is spanned by the corners.
  Interval affine;
  for (int i = 0; i < 3; ++i) {
    Interval at_corner(0);
    for (int k = 0; k < 3; ++k) at_corner += vc[1 + k] * (corners[i][k] - Interval(c[k]));
    affine = i == 0 ? at_corner
                    : Interval(std::min(affine.inf(), at_corner.inf()), std::max(affine.sup(), at_corner.sup()));
  }
  Interval quadratic(0);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) quadratic += hessian(i, k) * d[i] * d[k];
  return meet(v[0], vc[0] + affine + Interval(0.5) * quadratic);
}

namespace {

//! The best lower bound of |∇f| over the enclosure's box from |⟨∇f, g⟩|/‖g‖ for g = `first` (if
//! `use_first`) and for the three axes; Enc::directional encloses ⟨∇f, w⟩.
template <class Enc>
double gradient_lower_bound_along(const Enc& en, const P3& first, bool use_first, double enough) {
  double best = 0;
  const auto try_direction = [&](const P3& g) {
    const IBox w = interval_point(g);
    const Interval s = en.directional(w);
    if (!certainly_nonzero(s) || !finite(s)) return;
    const Interval norm = CGAL::sqrt(CGAL::square(w[0]) + CGAL::square(w[1]) + CGAL::square(w[2]));
    const Interval lower = Interval(std::min(std::abs(s.inf()), std::abs(s.sup()))) / norm;
    best = std::max(best, lower.inf());
  };
  if (use_first) try_direction(first);
  for (int k = 0; k < 3 && !(best > 0 && best >= enough); ++k) {
    P3 axis{};
    axis[k] = 1;
    try_direction(axis);
  }
  return best;
}

double midpoint(const Interval& a) { return finite(a) ? 0.5 * a.inf() + 0.5 * a.sup() : 0; }

}  // namespace

double gradient_lower_bound(const Enclosure& en, double enough) {
  P3 g{};
  bool usable = false;
  for (int i = 0; i < 3; ++i) {
    g[i] = midpoint(en.vc[1 + i]);
    usable = usable || g[i] != 0;
  }
  return gradient_lower_bound_along(en, g, usable, enough);
}

NormalizedEnclosure::NormalizedEnclosure(const CompiledSystem& system_of_E, const IBox& x, double eta)
    : eta(eta), e(system_of_E, x) {
  const Interval eta_squared = CGAL::square(Interval(eta));
  Interval q = eta_squared, q_centre = eta_squared;
  for (int i = 0; i < 3; ++i) {
    gradient[i] = e.v[1 + i];
    if (e.c2) {
      Interval mv = e.vc[1 + i];
      for (int k = 0; k < 3; ++k) mv += e.hessian(i, k) * e.d[k];
      gradient[i] = meet(gradient[i], mv);
    }
    q += CGAL::square(gradient[i]);
    q_centre += CGAL::square(e.vc[1 + i]);
  }
  s = Interval(1) / CGAL::sqrt(q);
  s_centre = Interval(1) / CGAL::sqrt(q_centre);
  usable = e.c2 && eta > 0 && finite(s) && finite(s_centre);
  for (int i = 0; i < 3; ++i) usable = usable && finite(gradient[i]);
}

Interval NormalizedEnclosure::value() const {
  if (!usable) return Interval::largest();
  return e.value() * s;
}

Interval NormalizedEnclosure::value_at_centre() const {
  if (!usable) return Interval::largest();
  return e.vc[0] * s_centre;
}

Interval NormalizedEnclosure::directional(const IBox& w) const {
  if (!usable) return Interval::largest();
  // ⟨H ∇E, w⟩ = Σ_i w_i Σ_k H_ik ∂_k E.
  Interval hgw(0);
  for (int i = 0; i < 3; ++i) {
    Interval row(0);
    for (int k = 0; k < 3; ++k) row += e.hessian(i, k) * gradient[k];
    hgw += row * w[i];
  }
  // s ⟨∇E, w⟩ by its monotonicity in a and b (header).
  const Interval a = e.directional(w);
  const Interval w2 = CGAL::square(w[0]) + CGAL::square(w[1]) + CGAL::square(w[2]);
  Interval b = CGAL::square(Interval(eta));
  for (int i = 0; i < 3; ++i) b += CGAL::square(gradient[i] - a * w[i] / w2);
  Interval first = s * a;
  if (finite(a) && finite(b) && finite(w2) && w2.inf() > 0 && b.inf() > 0) {
    const auto at = [&](double a_end, double b_end) {
      const Interval ai(a_end);
      return ai / CGAL::sqrt(CGAL::square(ai) / w2 + Interval(b_end));
    };
    const Interval lo = at(a.inf(), a.inf() >= 0 ? b.sup() : b.inf());
    const Interval hi = at(a.sup(), a.sup() >= 0 ? b.inf() : b.sup());
    first = meet(first, Interval(lo.inf(), hi.sup()));
  }
  return first - value() * CGAL::square(s) * hgw;
}

P3 NormalizedEnclosure::centre_gradient(const CompiledSystem& system_of_E) const {
  P3 g{};
  if (!usable) return g;
  double v[4], j[12];
  system_of_E.values_and_jacobian<double>(e.c.data(), nullptr, v, j);
  const double s_c = 1 / std::sqrt(v[1] * v[1] + v[2] * v[2] + v[3] * v[3] + eta * eta);
  for (int i = 0; i < 3; ++i) {
    double hg = 0;
    for (int k = 0; k < 3; ++k) hg += j[3 * (1 + i) + k] * v[1 + k];
    g[i] = s_c * v[1 + i] - v[0] * s_c * s_c * s_c * hg;
  }
  for (double& a : g)
    if (!std::isfinite(a)) a = 0;
  return g;
}

double gradient_lower_bound(const NormalizedEnclosure& en, const P3& g, double enough) {
  return gradient_lower_bound_along(en, g, en.usable && (g[0] != 0 || g[1] != 0 || g[2] != 0), enough);
}

std::array<TrianglePiece, 4> TrianglePiece::children() const {
  const auto mid = [&](int i, int j) {
    return std::array<double, 2>{0.5 * (uv[i][0] + uv[j][0]), 0.5 * (uv[i][1] + uv[j][1])};
  };
  const auto m01 = mid(0, 1), m12 = mid(1, 2), m20 = mid(2, 0);
  return {TrianglePiece{{{uv[0], m01, m20}}, depth + 1}, TrianglePiece{{{m01, uv[1], m12}}, depth + 1},
          TrianglePiece{{{m20, m12, uv[2]}}, depth + 1}, TrianglePiece{{{m12, m20, m01}}, depth + 1}};
}

EnclosedTriangle::EnclosedTriangle(const P3& a, const P3& b, const P3& c) {
  const IBox ia = interval_point(a), ib = interval_point(b), ic = interval_point(c);
  a_ = ia;
  for (int k = 0; k < 3; ++k) {
    ab_[k] = ib[k] - ia[k];
    ac_[k] = ic[k] - ia[k];
  }
  normal_ = {ab_[1] * ac_[2] - ab_[2] * ac_[1], ab_[2] * ac_[0] - ab_[0] * ac_[2], ab_[0] * ac_[1] - ab_[1] * ac_[0]};
}

void EnclosedTriangle::corners(const TrianglePiece& piece, std::array<IBox, 3>& corner, IBox& box) const {
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      corner[i][k] = a_[k] + Interval(piece.uv[i][0]) * ab_[k] + Interval(piece.uv[i][1]) * ac_[k];
      box[k] = i == 0 ? corner[i][k]
                      : Interval(std::min(box[k].inf(), corner[i][k].inf()), std::max(box[k].sup(), corner[i][k].sup()));
    }
}

double centroid_value(const CompiledSystem& system, const std::array<IBox, 3>& corner) {
  P3 centroid{};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) centroid[k] += (0.5 * corner[i][k].inf() + 0.5 * corner[i][k].sup()) / 3;
  double values[4];
  system.values<double>(centroid.data(), nullptr, values);
  return values[0];
}

}  // namespace delmesh::detail
