#include "experiments/sampling/eps_sample.h"

#include <cmath>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "experiments/sampling/dense_sample.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

using Vec = std::array<double, 3>;

double distance(const Vec& a, const Vec& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

//! The farthest-point order by brute force: O(|R| · |C|).
std::vector<std::size_t> brute_force_order(const std::vector<Vec>& points, const std::vector<double>& lfs, double eps) {
  std::vector<std::size_t> order{0};
  std::vector<double> d(points.size());
  for (std::size_t j = 0; j < points.size(); ++j) d[j] = distance(points[j], points[0]);
  while (true) {
    std::size_t best = 0;
    for (std::size_t j = 1; j < points.size(); ++j)
      if (d[j] / lfs[j] > d[best] / lfs[best]) best = j;
    if (d[best] / lfs[best] <= eps) return order;
    order.push_back(best);
    for (std::size_t j = 0; j < points.size(); ++j) d[j] = std::min(d[j], distance(points[j], points[best]));
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(eps_sample_suite)

BOOST_AUTO_TEST_CASE(sphere_eps_samples_cover_and_are_within_a_factor_four_of_the_covering_bound) {
  // Unit sphere, lfs = 1.  A set C with every point of Σ within ε of C: the caps of chordal radius
  // ε about C cover Σ, and such a cap has area π ε² (Archimedes), so |C| ≥ 4/ε².  The greedy
  // points are more than ε apart, so the caps of chordal radius ε/2 are disjoint: |C| ≤ 16/ε².
  // C covers only the reference R, whose covering radius δ_R (measured below on the sample as
  // the cell edge bound 2√3·h) relaxes the lower bound to 4/(ε + δ_R)².
  const CatalogEntry& sphere = catalog_entry("sphere");
  DenseSampleOptions options;
  const DenseSample reference = dense_sample(sphere.surface(), sphere.box, options, sphere.local_feature_size);
  const std::vector<double> lfs(reference.points.size(), 1.0);
  const EpsSampleResult result = eps_sample(reference.points, lfs, {0.1, 0.19, 0.15});
  BOOST_TEST(result.epsilons == (std::vector<double>{0.19, 0.15, 0.1}));
  BOOST_TEST_REQUIRE(result.sizes.size() == 3u);
  const double h = options.max_spacing * sphere.box.diagonal();
  const double reference_covering = 2 * std::sqrt(3.0) * h;  // dense_sample_test checks this bound
  for (std::size_t k = 0; k < 3; ++k) {
    const double eps = result.epsilons[k];
    const std::size_t n = result.sizes[k];
    BOOST_TEST_MESSAGE("sphere eps " << eps << ": " << n << " points, " << n * eps * eps << " / eps^-2");
    BOOST_TEST(result.covering[k] <= eps);
    // Covering property, checked by brute force.
    double worst = 0;
    for (const Vec& x : reference.points) {
      double nearest = 1e9;
      for (std::size_t i = 0; i < n; ++i) nearest = std::min(nearest, distance(x, reference.points[result.order[i]]));
      worst = std::max(worst, nearest);
    }
    BOOST_TEST(worst <= eps);
    BOOST_TEST(worst == result.covering[k], boost::test_tools::tolerance(1e-12));
    // Separation: each point more than ε from every earlier one.
    for (std::size_t i = 1; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j)
        BOOST_TEST_REQUIRE(distance(reference.points[result.order[i]], reference.points[result.order[j]]) > eps);
    // Within a factor 4 of the covering bound 4/ε².
    BOOST_TEST(static_cast<double>(n) >= 4 / ((eps + reference_covering) * (eps + reference_covering)));
    BOOST_TEST(static_cast<double>(n) <= 16 / (eps * eps));
    if (k > 0) BOOST_TEST(n > result.sizes[k - 1]);
  }
}

BOOST_AUTO_TEST_CASE(delaunay_bookkeeping_gives_the_brute_force_order) {
  // Points on a torus with a varying lfs: the incremental selection equals the brute force.
  const CatalogEntry& torus = catalog_entry("torus");
  DenseSampleOptions options;
  options.max_spacing = 1.0 / 48;
  const DenseSample reference = dense_sample(torus.surface(), torus.box, options);
  std::vector<double> lfs;
  for (const Vec& p : reference.points) lfs.push_back(0.2 + 0.3 * std::fabs(p[2]) + 0.1 * (p[0] > 0));
  const EpsSampleResult result = eps_sample(reference.points, lfs, {0.3});
  const std::vector<std::size_t> expected = brute_force_order(reference.points, lfs, 0.3);
  BOOST_TEST_MESSAGE("torus: " << reference.points.size() << " reference points, " << expected.size() << " chosen");
  BOOST_TEST(expected.size() > 50u);
  BOOST_TEST(result.order == expected, boost::test_tools::per_element());
  BOOST_TEST(result.sizes[0] == expected.size());
}

BOOST_AUTO_TEST_CASE(deterministic) {
  const CatalogEntry& blobs = catalog_entry("two_blobs");
  DenseSampleOptions options;
  options.max_spacing = 1.0 / 64;
  const DenseSample reference = dense_sample(blobs.surface(), blobs.box, options);
  const std::vector<double> lfs(reference.points.size(), 0.3);
  const EpsSampleResult a = eps_sample(reference.points, lfs, {0.15, 0.1});
  const EpsSampleResult b = eps_sample(reference.points, lfs, {0.1, 0.15});
  BOOST_TEST(a.order == b.order);
  BOOST_TEST(a.sizes == b.sizes);
}

BOOST_AUTO_TEST_CASE(misuse_throws) {
  const std::vector<Vec> points{{0, 0, 0}, {1, 0, 0}};
  BOOST_CHECK_THROW((void)eps_sample({}, {}, {0.1}), PreconditionViolation);
  BOOST_CHECK_THROW((void)eps_sample(points, {1.0}, {0.1}), PreconditionViolation);
  BOOST_CHECK_THROW((void)eps_sample(points, {1.0, 0.0}, {0.1}), PreconditionViolation);
  BOOST_CHECK_THROW((void)eps_sample(points, {1.0, 1.0}, {}), PreconditionViolation);
  BOOST_CHECK_THROW((void)eps_sample(points, {1.0, 1.0}, {0.0}), PreconditionViolation);
  const EpsSampleResult two = eps_sample(points, {1.0, 1.0}, {0.5});
  BOOST_TEST(two.sizes[0] == 2u);
}

BOOST_AUTO_TEST_SUITE_END()
