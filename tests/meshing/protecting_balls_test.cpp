#include "meshing/inputs/protecting_balls.h"

#include <algorithm>
#include <cmath>

#include <boost/test/unit_test.hpp>

#include "common/errors.h"
#include "meshing/inputs/input_mesh.h"
#include "tests/meshing/feature_meshes.h"
#include "tests/meshing/known_meshes.h"

using namespace delmesh;

namespace {

// Independent of verify_protection: points every 1/200 of each feature edge lie in some ball
// (cover), and no point lies in three balls at once (checked at the same points and at the
// centres).
void require_cover(const SurfaceMesh& mesh, const FeatureSet& features, const Protection& protection) {
  const auto in_balls = [&](const Point3& x) {
    std::size_t count = 0;
    for (const ProtectingBall& b : protection.balls)
      count += CGAL::squared_distance(x, b.centre) <= b.radius * b.radius;
    return count;
  };
  for (auto e : features.feature_edges) {
    const Point3 &a = mesh.point(mesh.vertex(e, 0)), &b = mesh.point(mesh.vertex(e, 1));
    for (int k = 0; k <= 200; ++k) {
      const Point3 x = a + (k / 200.0) * (b - a);
      const std::size_t count = in_balls(x);
      BOOST_TEST_REQUIRE(count >= 1u);
      BOOST_TEST_REQUIRE(count <= 2u);
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(protecting_balls_suite)

BOOST_AUTO_TEST_CASE(the_cube_is_protected) {
  for (int n : {1, 3}) {
    const SurfaceMesh mesh = test::grid_cube(n).to_surface_mesh();
    const FeatureSet features = detect_features(mesh);
    for (double size : {std::numeric_limits<double>::infinity(), 0.1}) {
      ProtectionOptions options;
      options.size = size;
      const Protection protection = protect_features(mesh, features, options);
      BOOST_TEST_INFO("n = " << n << ", size = " << size);
      BOOST_TEST(protection.check.holds);
      for (const auto& v : protection.check.first) BOOST_TEST_MESSAGE(v.message);
      BOOST_TEST(protection.anchors == 8u);
      BOOST_TEST(protection.kinks == 0u);
      BOOST_TEST(protection.pieces.size() == 12u);
      for (const ProtectingBall& b : protection.balls) BOOST_TEST(b.radius <= size);
      // Corner balls: no other corner inside, each meets only its three edges: r < 1 / 2 at most.
      for (std::size_t a = 0; a < protection.anchors; ++a) {
        BOOST_TEST((protection.balls[a].kind == ProtectingBall::Kind::corner));
        BOOST_TEST(protection.balls[a].radius < 0.5);
      }
      for (const ProtectedPiece& piece : protection.pieces) BOOST_TEST(piece.balls.size() >= 3u);
      require_cover(mesh, features, protection);
      const ProtectionCheck again = verify_protection(mesh, features, protection, options);
      BOOST_TEST(again.holds);
      BOOST_TEST(again.violations == 0u);
    }
  }
}

BOOST_AUTO_TEST_CASE(a_crease_with_its_border_is_protected) {
  for (double angle : {90.0, 150.0}) {
    const SurfaceMesh mesh = test::crease(angle, 4).to_surface_mesh();
    const FeatureSet features = detect_features(mesh);
    const Protection protection = protect_features(mesh, features);
    BOOST_TEST_INFO("angle " << angle);
    BOOST_TEST(protection.check.holds);
    for (const auto& v : protection.check.first) BOOST_TEST_MESSAGE(v.message);
    // The two crease ends and the border's four corners (turning 90°: kinks).
    BOOST_TEST(protection.anchors == 6u);
    BOOST_TEST(protection.kinks == 4u);
    require_cover(mesh, features, protection);
  }
  // A closed border without corner gets an anchor at its start.
  const SurfaceMesh sheet = test::crease(0.0001, 2).to_surface_mesh();
  const FeatureSet border = detect_features(sheet);
  const Protection protection = protect_features(sheet, border);
  BOOST_TEST(protection.check.holds);
  BOOST_TEST(protection.anchors == 4u);  // the start and three more kinks of the rectangle
  BOOST_TEST((protection.balls.front().kind == ProtectingBall::Kind::curve_start ||
              protection.balls.front().kind == ProtectingBall::Kind::kink));
  require_cover(sheet, border, protection);
}

BOOST_AUTO_TEST_CASE(violations_are_reported_with_their_location) {
  const SurfaceMesh mesh = test::grid_cube(2).to_surface_mesh();
  const FeatureSet features = detect_features(mesh);
  Protection protection = protect_features(mesh, features);
  BOOST_REQUIRE(protection.check.holds);
  // A corner ball grown past the next corner: it contains another corner (E), meets
  // non-adjacent balls (C) and feature edges of other pieces (E).
  protection.balls[0].radius = 1.5;
  const ProtectionCheck check = verify_protection(mesh, features, protection);
  BOOST_TEST(!check.holds);
  BOOST_TEST(check.violations >= 3u);
  BOOST_REQUIRE(!check.first.empty());
  bool c = false, e = false;
  for (const ProtectionViolation& v : check.first) {
    c = c || v.condition == 'C';
    e = e || v.condition == 'E';
    BOOST_TEST(!v.message.empty());
  }
  BOOST_TEST(c);
  BOOST_TEST(e);
  // A curve ball shrunk to nothing breaks the overlap with its neighbours (A), at its place.
  Protection gap = protect_features(mesh, features);
  const std::size_t shrunk = gap.pieces.front().balls[1];
  gap.balls[shrunk].radius = 1e-6;
  const ProtectionCheck holes = verify_protection(mesh, features, gap);
  BOOST_TEST(!holes.holds);
  BOOST_REQUIRE(!holes.first.empty());
  BOOST_TEST(holes.first.front().condition == 'A');
  BOOST_TEST((holes.first.front().ball == shrunk || holes.first.front().other == shrunk));
}

BOOST_AUTO_TEST_CASE(a_placement_that_cannot_finish_is_reported_not_dropped) {
  // A ball budget too small for a size bound of 0.01 on the unit cube: the construction stops,
  // and the result says which condition fails where.
  const SurfaceMesh mesh = test::grid_cube(1).to_surface_mesh();
  const FeatureSet features = detect_features(mesh);
  ProtectionOptions options;
  options.size = 0.01;
  options.max_balls = 50;
  const Protection protection = protect_features(mesh, features, options);
  BOOST_TEST(!protection.check.holds);
  BOOST_TEST(protection.check.violations > 0u);
  BOOST_REQUIRE(!protection.check.first.empty());
  const ProtectionViolation& first = protection.check.first.front();
  BOOST_TEST(first.message.find("(" + std::string(1, first.condition) + ")") == 0u);
  BOOST_TEST(std::isfinite(first.where.x()));
  BOOST_CHECK_THROW(protect_features(mesh, features, ProtectionOptions{.size = 0}), PreconditionViolation);
}

BOOST_AUTO_TEST_CASE(a_mesh_without_features_has_no_balls) {
  const SurfaceMesh sphere = test::icosphere(1).to_surface_mesh();
  const Protection protection = protect_features(sphere, detect_features(sphere));
  BOOST_TEST(protection.balls.empty());
  BOOST_TEST(protection.check.holds);
}

BOOST_AUTO_TEST_CASE(cgal_meshes_with_features_are_protected) {
  // The CAD parts of CGAL's data, and femur (a folded vertex among its corners): the feature
  // counts at 60° and a protection whose every condition holds.
  struct Expected {
    const char* name;
    std::size_t sharp_edges, curves, corners, folded_corners;
  };
  for (const Expected& e : {Expected{"fandisk", 699, 34, 24, 0}, Expected{"joint", 225, 22, 12, 0},
                            Expected{"anchor", 506, 32, 16, 0}, Expected{"femur", 1634, 783, 903, 1}}) {
    test::TempDir dir;
    const InputMesh input = read_input_mesh(test::cgal_data_mesh(e.name, dir));
    const FeatureSet features = detect_features(input.mesh, default_feature_angle_deg, input.folded_vertices);
    BOOST_TEST_INFO(e.name);
    BOOST_TEST(features.sharp_edges == e.sharp_edges);
    BOOST_TEST(features.curves.size() == e.curves);
    BOOST_TEST(features.corners.size() == e.corners);
    BOOST_TEST(features.folded_corners == e.folded_corners);
    const Protection protection = protect_features(input.mesh, features);
    BOOST_TEST(protection.check.holds);
    for (const auto& v : protection.check.first) BOOST_TEST_MESSAGE(v.message);
    BOOST_TEST(verify_protection(input.mesh, features, protection).holds);
  }
}

BOOST_AUTO_TEST_SUITE_END()
