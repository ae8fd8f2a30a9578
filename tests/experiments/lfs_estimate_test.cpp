#include "experiments/sampling/lfs_estimate.h"

#include <cmath>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "symbolic/catalog.h"

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(lfs_estimate_suite)

BOOST_AUTO_TEST_CASE(torus_estimate_within_ten_percent_at_the_default_density) {
  // Torus R = 1, r = 0.4: lfs = min(r, ρ) = 0.4 (the core circle is the nearest medial axis).
  const CatalogEntry& torus = catalog_entry("torus");
  const LfsEstimateResult result = estimate_lfs(torus.surface(), torus.box, LfsEstimateOptions{});
  BOOST_TEST(result.sample.status == DenseSampleStatus::complete);
  std::vector<double> exact;
  for (const auto& p : result.sample.points) exact.push_back(torus.local_feature_size(p));
  const LfsErrorSummary error = lfs_relative_error(result.values, exact);
  BOOST_TEST_MESSAGE("torus: " << result.first_pass.points.size() << " + " << result.sample.points.size()
                               << " points, relative error max " << error.max << " median " << error.median);
  BOOST_TEST(error.points == result.sample.points.size());
  BOOST_TEST(error.max <= 0.10);
  BOOST_TEST(error.median <= 0.01);
}

BOOST_AUTO_TEST_CASE(sphere_poles_lie_near_the_centre) {
  // The medial axis of the unit sphere is its centre: the inner poles converge to it and the
  // estimate to 1.
  const CatalogEntry& sphere = catalog_entry("sphere");
  DenseSampleOptions options;
  options.max_spacing = 1.0 / 128;
  const DenseSample sample = dense_sample(sphere.surface(), sphere.box, options);
  const PoleLfsEstimate estimate(sample.points, sphere.box);
  BOOST_TEST(estimate.poles().size() >= sample.points.size());
  double nearest_pole = 1e9;
  for (const auto& c : estimate.poles()) nearest_pole = std::min(nearest_pole, std::hypot(c[0], c[1], c[2]));
  BOOST_TEST(nearest_pole < 0.05);
  for (std::size_t i = 0; i < sample.points.size(); i += 97) BOOST_TEST(std::fabs(estimate(sample.points[i]) - 1) < 0.05);
  // lfs̃ is a distance to the poles: at the centre it is the nearest pole's distance.
  BOOST_TEST(estimate({0, 0, 0}) == nearest_pole, boost::test_tools::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(relative_error_summary) {
  const LfsErrorSummary s = lfs_relative_error({1.1, 2.0, 2.7}, {1.0, 2.0, 3.0});
  BOOST_TEST(s.max == 0.1, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.median == 0.1, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.mean == 0.2 / 3, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.points == 3u);
  BOOST_CHECK_THROW((void)lfs_relative_error({1.0}, {1.0, 2.0}), PreconditionViolation);
  BOOST_CHECK_THROW((void)lfs_relative_error({1.0}, {0.0}), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(misuse_throws) {
  BOOST_CHECK_THROW(PoleLfsEstimate({{0, 0, 0}, {1, 0, 0}}, Box3::cube(2)), PreconditionViolation);
  BOOST_CHECK_THROW(PoleLfsEstimate({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 5}}, Box3::cube(2)), PreconditionViolation);
  // A surface that leaves no point in the box.
  BOOST_CHECK_THROW((void)estimate_lfs(Surface::parse("x^2+y^2+z^2-100"), Box3::cube(1), LfsEstimateOptions{}),
                    InvalidInput);
}

BOOST_AUTO_TEST_SUITE_END()
