#include "symbolic/catalog.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "symbolic/compiled_system.h"

using namespace delmesh;

namespace {

using Point = std::array<double, 3>;

//! E and ∇E of an entry compiled over (x, y, z).
CompiledSystem compile_with_gradient(const Surface& s) {
  return CompiledSystem({s.E(), s.gradient()[0], s.gradient()[1], s.gradient()[2]},
                        {coordinate_x(), coordinate_y(), coordinate_z()}, {});
}

double value(const CompiledSystem& f, const Point& p) {
  double out[4];
  f.values(p.data(), static_cast<const double*>(nullptr), out);
  return out[0];
}

Point lerp(const Point& a, const Point& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

std::vector<Point> corners(const Box3& box) {
  std::vector<Point> c;
  for (int i = 0; i < 8; ++i) c.push_back({(i & 1) ? box.hi[0] : box.lo[0], (i & 2) ? box.hi[1] : box.lo[1],
                                           (i & 4) ? box.hi[2] : box.lo[2]});
  return c;
}

//! The grid point of an n³ grid of the box with the smallest E (an inside point when E < 0).
Point deepest_grid_point(const CompiledSystem& f, const Box3& box, int n) {
  Point best{};
  double best_value = INFINITY;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Point p{box.lo[0] + (i + 0.5) * (box.hi[0] - box.lo[0]) / n,
                      box.lo[1] + (j + 0.5) * (box.hi[1] - box.lo[1]) / n,
                      box.lo[2] + (k + 0.5) * (box.hi[2] - box.lo[2]) / n};
        const double v = value(f, p);
        if (v < best_value) best_value = v, best = p;
      }
  return best;
}

//! A point of Σ on the segment [inside, outside] (E < 0 at inside, E > 0 at outside) by bisection.
Point bisect_to_surface(const CompiledSystem& f, Point inside, Point outside) {
  for (int i = 0; i < 80; ++i) {
    const Point mid = lerp(inside, outside, 0.5);
    (value(f, mid) < 0 ? inside : outside) = mid;
  }
  return lerp(inside, outside, 0.5);
}

bool strictly_inside(const Box3& box, const Point& p) {
  for (int i = 0; i < 3; ++i)
    if (!(box.lo[i] < p[i] && p[i] < box.hi[i])) return false;
  return true;
}

//! Interval enclosures of E, ∇E over an axis-aligned box.
std::array<Interval, 4> enclose(const CompiledSystem& f, const Point& lo, const Point& hi) {
  const Interval X[3] = {Interval(lo[0], hi[0]), Interval(lo[1], hi[1]), Interval(lo[2], hi[2])};
  std::array<Interval, 4> out;
  f.values(X, static_cast<const Interval*>(nullptr), out.data());
  return out;
}

bool contains_zero(const Interval& I) { return I.inf() <= 0 && 0 <= I.sup(); }

//! Proves by interval subdivision that no point of [lo, hi] satisfies all of the selected
//! conditions: `positive` ⇒ proves E > 0; otherwise proves {E = 0, ∇E = 0} has no solution.
//! Returns false if the box budget runs out (nothing proved).
bool exclude(const CompiledSystem& f, Point lo, Point hi, bool positive, long& budget) {
  std::vector<std::pair<Point, Point>> stack{{lo, hi}};
  while (!stack.empty()) {
    auto [a, b] = stack.back();
    stack.pop_back();
    if (--budget < 0) return false;
    const std::array<Interval, 4> I = enclose(f, a, b);
    if (positive ? I[0].inf() > 0
                 : (!contains_zero(I[0]) || !contains_zero(I[1]) || !contains_zero(I[2]) || !contains_zero(I[3])))
      continue;
    int axis = 0;
    for (int i = 1; i < 3; ++i)
      if (b[i] - a[i] > b[axis] - a[axis]) axis = i;
    Point mid_hi = b, mid_lo = a;
    mid_hi[axis] = mid_lo[axis] = 0.5 * (a[axis] + b[axis]);
    stack.push_back({a, mid_hi});
    stack.push_back({mid_lo, b});
  }
  return true;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) { parent[find(a)] = find(b); }
};

//! Topology of the solid {E < 0} on an (n+1)³ grid of the box, as a cubical complex (grid points,
//! edges, squares and cubes all of whose corners are inside): the genus of the boundary of each
//! component (genus = 1 − χ(component), valid when the outside is connected), and the number of
//! components of the outside (26-connected).
struct GridTopology {
  std::vector<int> genus;  // sorted
  int outside_components = 0;
};
GridTopology grid_topology(const CompiledSystem& f, const Box3& box, int n) {
  const int m = n + 1;
  const auto id = [m](int i, int j, int k) { return (i * m + j) * m + k; };
  std::vector<char> in(static_cast<std::size_t>(m) * m * m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const Point p{box.lo[0] + i * (box.hi[0] - box.lo[0]) / n, box.lo[1] + j * (box.hi[1] - box.lo[1]) / n,
                      box.lo[2] + k * (box.hi[2] - box.lo[2]) / n};
        in[id(i, j, k)] = value(f, p) < 0;
      }
  const auto inside = [&](int i, int j, int k) { return i < m && j < m && k < m && in[id(i, j, k)]; };
  UnionFind solid(in.size()), outside(in.size());
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const int c = id(i, j, k);
        if (in[c]) {
          if (inside(i + 1, j, k)) solid.unite(c, id(i + 1, j, k));
          if (inside(i, j + 1, k)) solid.unite(c, id(i, j + 1, k));
          if (inside(i, j, k + 1)) solid.unite(c, id(i, j, k + 1));
          continue;
        }
        for (int di = -1; di <= 1; ++di)
          for (int dj = -1; dj <= 1; ++dj)
            for (int dk = -1; dk <= 1; ++dk) {
              const int a = i + di, b = j + dj, e = k + dk;
              if (a < 0 || b < 0 || e < 0 || a >= m || b >= m || e >= m || in[id(a, b, e)]) continue;
              outside.unite(c, id(a, b, e));
            }
      }
  std::map<int, long> chi;
  GridTopology t;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const int c = id(i, j, k);
        if (!in[c]) {
          if (outside.find(c) == c) ++t.outside_components;
          continue;
        }
        long& x = chi[solid.find(c)];
        const bool X = inside(i + 1, j, k), Y = inside(i, j + 1, k), Z = inside(i, j, k + 1);
        const bool XY = X && Y && inside(i + 1, j + 1, k), XZ = X && Z && inside(i + 1, j, k + 1),
                   YZ = Y && Z && inside(i, j + 1, k + 1);
        x += 1 - (X + Y + Z) + (XY + XZ + YZ) - (XY && XZ && YZ && inside(i + 1, j + 1, k + 1));
      }
  for (const auto& [root, x] : chi) t.genus.push_back(static_cast<int>(1 - x));
  std::sort(t.genus.begin(), t.genus.end());
  return t;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(catalog_suite)

BOOST_AUTO_TEST_CASE(names_and_lookup) {
  std::set<std::string> names;
  for (const CatalogEntry& e : catalog()) BOOST_TEST(names.insert(e.name).second);
  for (const char* required : {"sphere", "ellipsoid", "torus", "genus2", "chair", "tanglecube", "metaball",
                               "two_blobs", "thin_handle", "near_sheets"})
    BOOST_TEST(names.count(required) == 1u);
  BOOST_TEST(&catalog_entry("torus") == &catalog_entry("torus"));
  try {
    (void)catalog_entry("donut");
    BOOST_FAIL("no exception");
  } catch (const InvalidInput& error) {
    const std::string message = error.what();
    BOOST_TEST(message.find("'donut'") != std::string::npos);
    for (const std::string& name : names) BOOST_TEST(message.find(name) != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(entries_are_well_formed) {
  for (const CatalogEntry& e : catalog()) {
    BOOST_TEST_CONTEXT(e.name) {
      const Surface s = e.surface();
      BOOST_TEST(!e.description.empty());
      BOOST_TEST(e.components >= 1);
      BOOST_TEST(e.genus_per_component.size() == static_cast<std::size_t>(e.components));
      BOOST_TEST(std::is_sorted(e.genus_per_component.begin(), e.genus_per_component.end()));
      for (int i = 0; i < 3; ++i) BOOST_TEST(e.box.lo[i] < e.box.hi[i]);
      // Outside is E > 0: at the eight corners of the box.
      for (const Point& c : corners(e.box)) BOOST_TEST(s.evaluate(c) > 0);
    }
  }
  BOOST_TEST(!catalog_entry("metaball").surface().is_polynomial());
  BOOST_TEST(catalog_entry("torus").surface().degree() == 4);
}

BOOST_AUTO_TEST_CASE(surface_points_inside_the_box_and_lfs) {
  for (const CatalogEntry& e : catalog()) {
    BOOST_TEST_CONTEXT(e.name) {
      const Surface s = e.surface();
      const CompiledSystem f = compile_with_gradient(s);
      const Point inside = deepest_grid_point(f, e.box, 24);
      BOOST_REQUIRE(value(f, inside) < 0);
      for (const Point& c : corners(e.box)) {
        const Point p = bisect_to_surface(f, inside, c);
        BOOST_TEST(strictly_inside(e.box, p));
        BOOST_TEST(std::fabs(s.evaluate(p)) < 1e-9);
        double grad[4];
        f.values(p.data(), static_cast<const double*>(nullptr), grad);
        BOOST_TEST(std::hypot(grad[1], grad[2], grad[3]) > 1e-3);
        if (e.local_feature_size) {
          const double lfs = e.local_feature_size(p);
          BOOST_TEST(lfs > 0);
          BOOST_TEST(lfs < e.box.diagonal());
        }
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(analytic_local_feature_sizes) {
  BOOST_TEST(catalog_entry("sphere").local_feature_size({0.6, 0, 0.8}) == 1.0);
  BOOST_TEST(catalog_entry("torus").local_feature_size({1.4, 0, 0}) == 0.4);
  BOOST_TEST(catalog_entry("torus").local_feature_size({0, 0.6, 0}) == 0.4);
  BOOST_TEST(catalog_entry("thin_handle").local_feature_size({0, 1.08, 0}) == 0.08);
  const auto& near = catalog_entry("near_sheets");
  BOOST_TEST(near.local_feature_size({0.025, 0, 0}) == 0.025);
  BOOST_TEST(near.local_feature_size({-2.025, 0, 0}) == 1.0);
  BOOST_TEST(near.surface().evaluate({0.025, 0, 0}) == 0.0, boost::test_tools::tolerance(1e-12));

  // Ellipsoid, semi-axes a = 3/2, b = 1, c = 3/4: lfs = c²/a at (±a, 0, 0), c²/b at (0, ±b, 0),
  // c at (0, 0, ±c) (the medial axis is the filled focal ellipse in z = 0).
  const auto& ellipsoid = catalog_entry("ellipsoid");
  const auto lfs = ellipsoid.local_feature_size;
  BOOST_TEST(lfs({1.5, 0, 0}) == 0.375, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(lfs({0, -1, 0}) == 0.5625, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(lfs({0, 0, 0.75}) == 0.75, boost::test_tools::tolerance(1e-12));
  // At any p ∈ Σ with z ≠ 0 the inward normal line meets z = 0 inside the focal ellipse, at the
  // centre of a medial ball touching p; so lfs(p) ≤ that distance.  And lfs ≥ c²/a, the reach.
  const Surface s = ellipsoid.surface();
  for (int i = 1; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      const double theta = M_PI * i / 12, phi = 2 * M_PI * j / 12;
      const Point p{1.5 * std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), 0.75 * std::cos(theta)};
      BOOST_TEST_CONTEXT("p = (" << p[0] << ", " << p[1] << ", " << p[2] << ")") {
        BOOST_TEST(std::fabs(s.evaluate(p)) < 1e-12);
        const double l = lfs(p);
        BOOST_TEST(l >= 0.375 - 1e-12);  // the reach of the ellipsoid, c²/a
        if (std::fabs(p[2]) < 1e-9) continue;
        const Point n{p[0] / 2.25, p[1], p[2] / 0.5625};  // ∇E / 2
        const double t = p[2] / n[2];                    // p − t n lies in z = 0
        const Point m{p[0] - t * n[0], p[1] - t * n[1], 0};
        BOOST_TEST((m[0] / 1.125) * (m[0] / 1.125) + (m[1] / 0.4375) * (m[1] / 0.4375) <= 1 + 1e-12);
        BOOST_TEST(l <= std::hypot(p[0] - m[0], p[1] - m[1], p[2] - m[2]) + 1e-12);
      }
    }
}

BOOST_AUTO_TEST_CASE(surface_never_meets_the_box_boundary_certified) {
  // Interval arithmetic proves E > 0 on all six faces of every box.
  RoundingGuard guard;
  for (const CatalogEntry& e : catalog()) {
    BOOST_TEST_CONTEXT(e.name) {
      const CompiledSystem f = compile_with_gradient(e.surface());
      for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
          Point lo = e.box.lo, hi = e.box.hi;
          lo[axis] = hi[axis] = side ? e.box.hi[axis] : e.box.lo[axis];
          long budget = 20000;
          BOOST_TEST(exclude(f, lo, hi, /*positive=*/true, budget));
        }
    }
  }
}

BOOST_AUTO_TEST_CASE(surfaces_are_smooth_certified) {
  // Interval subdivision proves that E = 0 and ∇E = 0 have no common point in the box.
  RoundingGuard guard;
  {
    // The proof cannot succeed for a singular surface: the cone x² + y² − z² at the origin.
    const CompiledSystem cone = compile_with_gradient(Surface::parse("x^2+y^2-z^2"));
    long budget = 20000;
    BOOST_TEST(!exclude(cone, {-1, -1, -1}, {1, 1, 1}, /*positive=*/false, budget));
  }
  for (const CatalogEntry& e : catalog()) {
    BOOST_TEST_CONTEXT(e.name) {
      const CompiledSystem f = compile_with_gradient(e.surface());
      long budget = 4000000;
      BOOST_TEST(exclude(f, e.box.lo, e.box.hi, /*positive=*/false, budget));
    }
  }
}

BOOST_AUTO_TEST_CASE(grid_topology_matches_components_and_genus, *boost::unit_test::label("slow")) {
  for (const CatalogEntry& e : catalog()) {
    BOOST_TEST_CONTEXT(e.name) {
      const CompiledSystem f = compile_with_gradient(e.surface());
      const GridTopology t = grid_topology(f, e.box, 120);
      BOOST_TEST(t.outside_components == 1);
      BOOST_TEST(t.genus == e.genus_per_component, boost::test_tools::per_element());
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
