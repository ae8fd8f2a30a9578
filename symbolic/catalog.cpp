#include "symbolic/catalog.h"

#include <algorithm>
#include <cmath>

#include "common/errors.h"

namespace delmesh {

namespace {

using Point = std::array<double, 3>;

Box3 box(double x0, double x1, double y0, double y1, double z0, double z1) {
  Box3 b;
  b.lo = {x0, y0, z0};
  b.hi = {x1, y1, z1};
  return b;
}

//! lfs on a torus of core radius R and tube radius r about the z-axis: the medial axis of the
//! surface is the core circle (distance r from every surface point) together with the z-axis
//! (distance ρ = √(x² + y²)), so lfs(p) = min(r, ρ(p)).
std::function<double(const Point&)> torus_lfs(double r) {
  return [r](const Point& p) { return std::min(r, std::hypot(p[0], p[1])); };
}

//! Distance from (u, v) to the filled ellipse {x²/α² + y²/β² ≤ 1}, α ≥ β > 0.  Outside it, the
//! nearest point is (α²u/(t+α²), β²v/(t+β²)) with t > 0 the root of
//! F(t) = (αu/(t+α²))² + (βv/(t+β²))² − 1, which is decreasing; F(α|q|) < 0 brackets it.
double distance_to_filled_ellipse(double u, double v, double alpha, double beta) {
  u = std::fabs(u);
  v = std::fabs(v);
  if ((u / alpha) * (u / alpha) + (v / beta) * (v / beta) <= 1) return 0;
  auto F = [&](double t) {
    const double a = alpha * u / (t + alpha * alpha), b = beta * v / (t + beta * beta);
    return a * a + b * b - 1;
  };
  double lo = 0, hi = alpha * std::hypot(u, v);
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (F(mid) > 0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  const double nx = alpha * alpha * u / (t + alpha * alpha), ny = beta * beta * v / (t + beta * beta);
  return std::hypot(u - nx, v - ny);
}

//! lfs on the ellipsoid x²/a² + y²/b² + z²/c² = 1, a > b > c: the medial axis of the surface is
//! the filled focal ellipse {z = 0, x²/α² + y²/β² ≤ 1} with α = (a²−c²)/a, β = (b²−c²)/b (the
//! outside has an empty medial axis, the surface being convex), so lfs(p) is the distance from p
//! to that planar region.
std::function<double(const Point&)> ellipsoid_lfs(double a, double b, double c) {
  const double alpha = (a * a - c * c) / a, beta = (b * b - c * c) / b;
  return [alpha, beta](const Point& p) {
    return std::hypot(p[2], distance_to_filled_ellipse(p[0], p[1], alpha, beta));
  };
}

std::vector<CatalogEntry> make_catalog() {
  std::vector<CatalogEntry> entries;

  entries.push_back({"sphere", "x^2+y^2+z^2-1", box(-1.5, 1.5, -1.5, 1.5, -1.5, 1.5), 1, {0},
                     "unit sphere; lfs = 1 (medial axis = the centre)",
                     [](const Point&) { return 1.0; }});

  entries.push_back({"ellipsoid", "x^2/2.25+y^2+z^2/0.5625-1", box(-1.75, 1.75, -1.25, 1.25, -1, 1), 1, {0},
                     "ellipsoid with semi-axes 1.5, 1, 0.75; lfs = distance to the filled focal ellipse "
                     "{z = 0, x^2/1.125^2 + y^2/0.4375^2 <= 1}",
                     ellipsoid_lfs(1.5, 1.0, 0.75)});

  entries.push_back({"torus", "(x^2+y^2+z^2+0.84)^2-4*(x^2+y^2)", box(-1.65, 1.65, -1.65, 1.65, -0.65, 0.65), 1,
                     {1},
                     "torus about the z-axis, core radius R = 1, tube radius r = 0.4; lfs = min(r, rho) = 0.4",
                     torus_lfs(0.4)});

  // genus2: Σ = {g² + z² = 1/50} is the double of the planar region D = {|g| ≤ √(1/50)}.  The
  // critical points of g are the saddle (0, 0) with g = 0 and the maxima (±1/√2, 0) with g = 1/4,
  // so for 0 < √(1/50) < 1/4 the set {g ≥ −√(1/50)} is a disc and {g > √(1/50)} two discs in it:
  // D is a disc with two holes and its double has genus 2.  ∇E = (2g∇g, 2z) vanishes on Σ only
  // where ∇g = 0 and g² = 1/50, which never happens.
  entries.push_back({"genus2", "(x^2-x^4-y^2)^2+z^2-0.02", box(-1.3, 1.3, -0.9, 0.9, -0.4, 0.4), 1, {2},
                     "double torus g^2 + z^2 = 1/50 around the figure-eight g = x^2 - x^4 - y^2 = 0 "
                     "(the double of the planar region |g| <= sqrt(1/50), a disc with two holes)",
                     nullptr});

  // chair: genus 3 by a Morse count (a generic height has 1 maximum, 1 minimum and 6 saddles on
  // Σ) and by the Euler characteristic of {E < 0} on grids of 100³ and 250³ cells.  The critical
  // points of E at (±0.612, ±0.612, 0) have E = −1/100 and lie about 0.044 inside Σ: narrow
  // necks, a small lfs there.
  entries.push_back({"chair", "(x^2+y^2+z^2-0.95)^2-0.8*((z-1)^2-2*x^2)*((z+1)^2-2*y^2)",
                     box(-1.6, 1.6, -1.6, 1.6, -1.6, 1.6), 1, {3},
                     "the 'chair' quartic (r^2 - a k^2)^2 - b((z-k)^2 - 2x^2)((z+k)^2 - 2y^2), k = 5, "
                     "a = 0.95, b = 0.8, scaled by 1/5; genus 3 (8 critical points of a generic height: "
                     "max, min, 6 saddles); narrow necks near (+-0.61, +-0.61, 0)",
                     nullptr});

  // tanglecube: genus 5 (Morse count: 16 critical points of a generic height, χ = −8; grid χ of
  // the solid −4).  Critical values of E: 11.8, 5.55, −0.7, −6.95, so 0 is a regular value.
  entries.push_back({"tanglecube", "x^4-5*x^2+y^4-5*y^2+z^4-5*z^2+11.8", box(-3, 3, -3, 3, -3, 3), 1, {5},
                     "the tangle cube x^4 - 5x^2 + y^4 - 5y^2 + z^4 - 5z^2 + 11.8", nullptr});

  // metaball and two_blobs: f = Σ w_i exp(−4|x − c_i|²), E = T − f.  All critical points of f lie
  // in the plane P through the centres, and across P, f(q + s n) = f(q) exp(−4 s²) for q ∈ P; so
  // {f ≥ T} is a thickening of D = {q ∈ P : f(q) ≥ T} and Σ is the double of D.  metaball: all
  // critical values of f are ≥ 0.54 > T = 0.3 (3 maxima, 3 saddles, 1 minimum), so D is a disc
  // and Σ a sphere.  two_blobs: the saddle of f on the line of the centres has f ≈ 0.198 < T < the
  // maxima ≈ 0.9, 1.0, so D is two discs.  Σ ⊂ ⋃ balls(c_i, √(ln(Σ w_i / T) / 4)) ⊂ box.
  entries.push_back({"metaball",
                     "0.3-exp(-4*((x+0.55)^2+(y+0.3)^2+z^2))-exp(-4*((x-0.55)^2+(y+0.35)^2+z^2))"
                     "-0.8*exp(-4*((x-0.05)^2+(y-0.6)^2+(z-0.25)^2))",
                     box(-1.5, 1.5, -1.3, 1.5, -0.9, 1.1), 1, {0},
                     "one blob of three Gaussians exp(-4|x-c_i|^2) (weights 1, 1, 0.8) at level 0.3, as in Fig. 12",
                     nullptr});

  entries.push_back({"two_blobs", "0.3-exp(-4*((x+0.75)^2+y^2+z^2))-0.9*exp(-4*((x-0.75)^2+(y-0.1)^2+z^2))",
                     box(-1.75, 1.75, -1.1, 1.2, -1, 1), 2, {0, 0},
                     "two disjoint blobs: Gaussians exp(-4|x-c_i|^2) (weights 1, 0.9) at level 0.3", nullptr});

  entries.push_back({"thin_handle", "(x^2+y^2+z^2+0.9936)^2-4*(x^2+y^2)", box(-1.3, 1.3, -1.3, 1.3, -0.3, 0.3), 1,
                     {1}, "thin torus about the z-axis, R = 1, r = 0.08; lfs = min(r, rho) = 0.08",
                     torus_lfs(0.08)});

  entries.push_back({"near_sheets", "((x-1.025)^2+y^2+z^2-1)*((x+1.025)^2+y^2+z^2-1)",
                     box(-2.3, 2.3, -1.3, 1.3, -1.3, 1.3), 2, {0, 0},
                     "two unit spheres at (+-1.025, 0, 0) with a gap of 0.05; lfs = min(1, |x|) (medial axis = "
                     "the centres and the bisector plane x = 0)",
                     [](const Point& p) { return std::min(1.0, std::fabs(p[0])); }});
  return entries;
}

}  // namespace

const std::vector<CatalogEntry>& catalog() {
  static const std::vector<CatalogEntry> entries = make_catalog();
  return entries;
}

const CatalogEntry& catalog_entry(const std::string& name) {
  std::string known;
  for (const CatalogEntry& entry : catalog()) {
    if (entry.name == name) return entry;
    known += (known.empty() ? "" : ", ") + entry.name;
  }
  throw InvalidInput("unknown surface '" + name + "'; known surfaces: " + known);
}

}  // namespace delmesh
