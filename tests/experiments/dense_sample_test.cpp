#include "experiments/sampling/dense_sample.h"

#include <cmath>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

using Vec = std::array<double, 3>;

double distance(const Vec& a, const Vec& b) { return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

//! Seeded points uniform on the unit sphere (Marsaglia's normal-free method on a fixed LCG).
std::vector<Vec> sphere_probes(std::size_t count) {
  std::vector<Vec> probes;
  std::uint64_t state = 12345;
  auto uniform = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53 * 2 - 1;
  };
  while (probes.size() < count) {
    const double a = uniform(), b = uniform(), s = a * a + b * b;
    if (s >= 1) continue;
    const double t = 2 * std::sqrt(1 - s);
    probes.push_back({a * t, b * t, 1 - 2 * s});
  }
  return probes;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(dense_sample_suite)

BOOST_AUTO_TEST_CASE(sphere_sample_lies_on_the_sphere_and_covers_it) {
  const CatalogEntry& sphere = catalog_entry("sphere");
  DenseSampleOptions options;
  options.relative_spacing = 0.04;
  const DenseSample sample = dense_sample(sphere.surface(), sphere.box, options, sphere.local_feature_size);
  BOOST_TEST(sample.status == DenseSampleStatus::complete);
  BOOST_TEST(sample.finest_cells == 0u);
  for (const Vec& p : sample.points) BOOST_TEST(std::fabs(std::hypot(p[0], p[1], p[2]) - 1) < 1e-12);
  // Cells of edge ≤ 0.04 · lfs = 0.04, one point per cell: about area / edge² points, and every
  // point of the sphere within two cell diagonals of the sample.
  const double edge = options.max_spacing * sphere.box.diagonal();  // 0.0203 ≤ 0.04: no refinement
  BOOST_TEST(sample.points.size() > 4 * M_PI / (edge * edge) / 2);
  BOOST_TEST(sample.points.size() < 4 * M_PI / (edge * edge) * 3);
  double worst = 0;
  for (const Vec& q : sphere_probes(2000)) {
    double nearest = 1e9;
    for (const Vec& p : sample.points) nearest = std::min(nearest, distance(p, q));
    worst = std::max(worst, nearest);
  }
  BOOST_TEST_MESSAGE("sphere: " << sample.points.size() << " points, covering radius >= " << worst);
  BOOST_TEST(worst < 2 * std::sqrt(3.0) * edge);
}

BOOST_AUTO_TEST_CASE(same_seed_same_points_other_seed_other_points) {
  const CatalogEntry& torus = catalog_entry("torus");
  DenseSampleOptions options;
  options.max_spacing = 1.0 / 64;
  const DenseSample a = dense_sample(torus.surface(), torus.box, options);
  const DenseSample b = dense_sample(torus.surface(), torus.box, options);
  BOOST_TEST(a.points == b.points);
  options.seed = 2;
  const DenseSample c = dense_sample(torus.surface(), torus.box, options);
  BOOST_TEST(!(a.points == c.points));
}

BOOST_AUTO_TEST_CASE(cells_shrink_with_the_local_feature_size) {
  // thin_handle: lfs = 0.08 everywhere, so halving relative_spacing below the top grid's edge
  // multiplies the number of points by about 4.
  const CatalogEntry& handle = catalog_entry("thin_handle");
  DenseSampleOptions options;
  options.max_spacing = 1.0 / 32;
  options.relative_spacing = 0.4;
  const DenseSample coarse = dense_sample(handle.surface(), handle.box, options, handle.local_feature_size);
  options.relative_spacing = 0.2;
  const DenseSample fine = dense_sample(handle.surface(), handle.box, options, handle.local_feature_size);
  const double ratio = static_cast<double>(fine.points.size()) / static_cast<double>(coarse.points.size());
  BOOST_TEST_MESSAGE("thin_handle: " << coarse.points.size() << " -> " << fine.points.size());
  BOOST_TEST(ratio > 2.5);
  BOOST_TEST(ratio < 6.0);
}

BOOST_AUTO_TEST_CASE(both_components_are_sampled) {
  const CatalogEntry& blobs = catalog_entry("two_blobs");
  DenseSampleOptions options;
  options.max_spacing = 1.0 / 64;
  const DenseSample sample = dense_sample(blobs.surface(), blobs.box, options);
  std::size_t left = 0, right = 0;
  for (const Vec& p : sample.points) (p[0] < 0 ? left : right)++;
  BOOST_TEST(left > 100u);
  BOOST_TEST(right > 100u);
}

BOOST_AUTO_TEST_CASE(point_limit_is_a_status) {
  const CatalogEntry& sphere = catalog_entry("sphere");
  DenseSampleOptions options;
  options.max_points = 10;
  const DenseSample sample = dense_sample(sphere.surface(), sphere.box, options);
  BOOST_TEST(sample.status == DenseSampleStatus::point_limit);
  BOOST_TEST(sample.points.size() == 10u);
}

BOOST_AUTO_TEST_CASE(invalid_options_throw) {
  const CatalogEntry& sphere = catalog_entry("sphere");
  DenseSampleOptions options;
  options.min_spacing = 0;
  BOOST_CHECK_THROW((void)dense_sample(sphere.surface(), sphere.box, options), PreconditionViolation);
  options = {};
  options.relative_spacing = -1;
  BOOST_CHECK_THROW((void)dense_sample(sphere.surface(), sphere.box, options), PreconditionViolation);
  Box3 empty = sphere.box;
  empty.hi[0] = empty.lo[0];
  BOOST_CHECK_THROW((void)dense_sample(sphere.surface(), empty, DenseSampleOptions{}), PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
