#include <boost/test/unit_test.hpp>

#include <chrono>
#include <string>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/input_validation.h"
#include "meshing/verify/certificate.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

// del_mesh must throw InvalidInput whose message contains `needle`, within a few seconds.
void expect_invalid(const std::string& equation, const Box3& box, const std::string& needle) {
  const auto start = std::chrono::steady_clock::now();
  DelMeshOptions options;
  options.phase = MeshPhase::topology;
  try {
    (void)del_mesh(Surface::parse(equation), box, options);
    BOOST_ERROR(equation << ": no error");
  } catch (const InvalidInput& e) {
    BOOST_TEST_MESSAGE(equation << ": " << e.what());
    BOOST_TEST(std::string(e.what()).find(needle) != std::string::npos, e.what());
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BOOST_TEST(seconds < 20.0);
}

// validate_regular must throw InvalidInput whose message contains `needle`.
void expect_regular_rejected(const std::string& equation, const Box3& box, const std::string& needle) {
  try {
    (void)validate_regular(Surface::parse(equation), box);
    BOOST_ERROR(equation << ": no error");
  } catch (const InvalidInput& e) {
    BOOST_TEST_MESSAGE(equation << ": " << e.what());
    BOOST_TEST(std::string(e.what()).find(needle) != std::string::npos, e.what());
  }
}

const char* const orthocircle =
    "((x^2+y^2-1)^2+z^2)*((y^2+z^2-1)^2+x^2)*((z^2+x^2-1)^2+y^2)-0.075^2*(1+3*(x^2+y^2+z^2))";
}  // namespace

BOOST_AUTO_TEST_SUITE(input_validation)

BOOST_AUTO_TEST_CASE(empty_surface_is_rejected) { expect_invalid("x^2+y^2+z^2+1", Box3::cube(1.5), "empty"); }

BOOST_AUTO_TEST_CASE(surface_leaving_the_box_is_rejected) {
  expect_invalid("x^2+y^2+z^2-4", Box3::cube(1.5), "boundary of the box");
  BOOST_CHECK_THROW(validate_box_faces(Surface::parse("x^2+y^2+z^2-4"), Box3::cube(1.5)), InvalidInput);
  BOOST_CHECK_NO_THROW(validate_box_faces(Surface::parse("x^2+y^2+z^2-1"), Box3::cube(1.5)));
}

BOOST_AUTO_TEST_CASE(cone_is_rejected) { expect_invalid("x^2+y^2-z^2", Box3::cube(1), "box"); }

// Two unit spheres touching at the origin: Σ stays inside the box but ∇E = 0 at the contact.
BOOST_AUTO_TEST_CASE(singular_point_inside_the_box_is_rejected) {
  Box3 box;
  box.lo = {-2.5, -1.5, -1.5};
  box.hi = {2.5, 1.5, 1.5};
  const auto s = Surface::parse("((x-1)^2+y^2+z^2-1)*((x+1)^2+y^2+z^2-1)");
  BOOST_CHECK_NO_THROW(validate_box_faces(s, box));
  try {
    validate_regular(s, box);
    BOOST_ERROR("no error for a singular surface");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("the surface is singular") != std::string::npos, e.what());
  }
  BOOST_CHECK_NO_THROW(validate_regular(Surface::parse("x^2+y^2+z^2-1"), Box3::cube(1.5)));
}

// The orthocircle is smooth but its three rings nearly touch: the regularity proof needs the
// mean-value and gradient-cone exclusions to stay in the fast tier.
BOOST_AUTO_TEST_CASE(orthocircle_validates) {
  const ValidationReport report = validate_input(Surface::parse(orthocircle), Box3::cube(1.5));
  BOOST_TEST(report.face_boxes > 0u);
  BOOST_TEST(report.regular_boxes > 0u);
  BOOST_TEST(report.regular_boxes < tolerances::mesher_box_budget_global);
  BOOST_TEST(report.seconds >= 0.0);
}

BOOST_AUTO_TEST_CASE(catalog_surfaces_validate) {
  for (const char* name : {"torus", "genus2", "tanglecube"}) {
    BOOST_TEST_CONTEXT(name) {
      const CatalogEntry& entry = catalog_entry(name);
      BOOST_CHECK_NO_THROW((void)validate_input(entry.surface(), entry.box));
    }
  }
}

// Three tori of radii 1 and 0.3 centred at x = −1.1, 0, 1.1, and E their product minus 0.01: a
// smooth surface of degree 12 (|∇E| ≥ about 1 on it) whose loose interval enclosures need more
// than one round of mesher_box_budget_global boxes; each round decides volume, so the budget
// grows until the proof is complete.
std::string three_tori() {
  std::string e;
  for (const char* shift : {"+1.1", "", "-1.1"})
    e += std::string(e.empty() ? "" : "*") + "(((x" + shift + ")^2+y^2+z^2+0.91)^2-4*((x" + shift + ")^2+y^2))";
  return e + "-0.01";
}
const Box3 three_tori_box{{-2.6, -1.6, -0.6}, {2.6, 1.6, 0.6}};

BOOST_AUTO_TEST_CASE(three_overlapping_tori_validate_in_more_than_one_round) {
  const std::size_t boxes = validate_regular(Surface::parse(three_tori()), three_tori_box);
  BOOST_TEST(boxes > tolerances::mesher_box_budget_global);
  BOOST_TEST(boxes < tolerances::validation_box_rounds * tolerances::mesher_box_budget_global);
}

BOOST_AUTO_TEST_CASE(three_overlapping_tori_mesh_complete_and_certified, *boost::unit_test::label("slow")) {
  const Surface surface = Surface::parse(three_tori());
  const DelMeshResult result = del_mesh(surface, three_tori_box, DelMeshOptions{});
  BOOST_TEST_REQUIRE(result.status == MeshStatus::complete);
  const MeshReport report = check_mesh(result.mesh);
  BOOST_TEST(report.manifold);
  BOOST_TEST(report.orientable);
  // The certificate, from the mesh alone, proves it homeomorphic to the surface.
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  mesh_to_soup(result.mesh, points, triangles);
  const Certificate certificate = certify_mesh(points, triangles, surface, three_tori_box);
  BOOST_TEST(certificate.status == CertificateStatus::certified);
  BOOST_TEST(certificate.restricted_matches_mesh);
}

// The cone's apex is a singular point, and "singular" comes with its proof: E and ∇E are exactly
// 0 at the apex, in rational arithmetic.
BOOST_AUTO_TEST_CASE(cone_apex_is_singular) {
  expect_regular_rejected("x^2+y^2-z^2", Box3::cube(1),
                          "the surface is singular: the gradient of E vanishes on it at (0, 0, 0): E and its gradient "
                          "evaluate to exactly 0 there");
  // Off-centre apex (not a dyadic point: found by rounding to decimal places).
  Box3 box;
  box.lo = {-1.3, -0.9, -1.1};
  box.hi = {0.7, 1.2, 0.8};
  expect_regular_rejected("(x-0.1)^2+(y+0.2)^2-(z-0.3)^2", box, "at (1/10, -1/5, 3/10): E and its gradient evaluate to exactly 0");
}

// E = f² vanishes to second order on the whole sphere f = 0: every point of Σ is singular.  The
// sphere x² + y² + z² = 7 has no rational point at all (7 is not a sum of three rational squares),
// so the proof is the common factor f of E and ∇E, which changes sign in the box.
BOOST_AUTO_TEST_CASE(squared_sphere_is_singular) {
  expect_regular_rejected("(x^2+y^2+z^2-1)^2", Box3::cube(1.5), "singular: the gradient of E vanishes on it");
  expect_regular_rejected("(x^2+y^2+z^2-7)^2", Box3::cube(3.5), "singular: the gradient of E vanishes on it");
  expect_regular_rejected("(x^2+y^2+z^2-7)^2", Box3::cube(3.5), "the common factor");
}

// Two unit spheres 2·10⁻¹⁷ apart: smooth (E > 0 between them), but double precision rounds
// 1.00000000000000001 to 1 and cannot separate E from ∇E at the origin, nor can MPFI within its
// budget (the sheets' gap is below the boxes' double resolution).  Not called singular: no
// rational point makes E and ∇E exactly 0, and the message says how small |∇E| is there.
BOOST_AUTO_TEST_CASE(spheres_closer_than_double_precision_are_not_called_singular) {
  Box3 box;
  box.lo = {-2.5, -1.5, -1.5};
  box.hi = {2.5, 1.5, 1.5};
  try {
    (void)validate_regular(
        Surface::parse("((x-1.00000000000000001)^2+y^2+z^2-1)*((x+1.00000000000000001)^2+y^2+z^2-1)"), box);
    BOOST_ERROR("no error although double precision cannot separate the sheets");
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    BOOST_TEST(what.find("cannot certify") != std::string::npos, what);
    BOOST_TEST(what.find("singular:") == std::string::npos, what);
    BOOST_TEST(what.find("|grad E| may be as small as") != std::string::npos, what);
  }
  // The same two spheres touching (a gap of 0) are singular, with the proof at the origin.
  expect_regular_rejected("((x-1)^2+y^2+z^2-1)*((x+1)^2+y^2+z^2-1)", box, "at (0, 0, 0): E and its gradient evaluate");
}

// Two unit spheres 1e-6 apart (the case) and two spheres of radius 0.5 2e-7 apart are
// smooth: the boxes between the sheets, below the first width limit and with no evidence of a
// singular point, are bisected on until they are decided, and the input validates.
BOOST_AUTO_TEST_CASE(nearly_touching_spheres_validate) {
  Box3 box;
  box.lo = {-2.5, -1.5, -1.5};
  box.hi = {2.5, 1.5, 1.5};
  const ValidationReport report =
      validate_input(Surface::parse("((x-1.0000005)^2+y^2+z^2-1)*((x+1.0000005)^2+y^2+z^2-1)"), box);
  BOOST_TEST(report.regular_boxes < tolerances::mesher_box_budget_global);
  BOOST_TEST(report.seconds < 10.0);
  BOOST_CHECK_NO_THROW((void)validate_regular(
      Surface::parse("((x-0.5)^2+y^2+z^2-0.2499999)*((x+0.5)^2+y^2+z^2-0.2499999)"), Box3::cube(1.3)));
}

// Two spheres 2e-10 apart: smooth, but the gap is below the deepest box, so regularity cannot be
// certified; it must not be reported as a singular point either.
BOOST_AUTO_TEST_CASE(nearly_touching_spheres_are_not_called_singular) {
  try {
    (void)validate_regular(
        Surface::parse("((x-0.5)^2+y^2+z^2-0.2499999999)*((x+0.5)^2+y^2+z^2-0.2499999999)"), Box3::cube(1.3));
    BOOST_ERROR("no error although the gap is below the smallest box");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("cannot certify") != std::string::npos, e.what());
    BOOST_TEST(std::string(e.what()).find("singular:") == std::string::npos, e.what());
  }
}

// A box so large that E overflows double precision on it: said so, not called singular.
BOOST_AUTO_TEST_CASE(overflow_on_a_huge_box_is_named) {
  Box3 box;
  box.lo = {-1e100, -2, -2};
  box.hi = {1e100, 2, 2};
  expect_regular_rejected("x^4+y^2+z^2-1", box, "overflows double precision there");
  try {
    (void)validate_regular(Surface::parse("x^4+y^2+z^2-1"), box);
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("singular:") == std::string::npos, e.what());
  }
}

// A sphere tangent to the face x = 1.1 at (1.1, 0.3, -0.2), not at a subdivision centre.
BOOST_AUTO_TEST_CASE(surface_touching_the_box_is_rejected) {
  Box3 box;
  box.lo = {-1.0, -1.0, -1.5};
  box.hi = {1.1, 1.5, 1.0};
  const auto s = Surface::parse("(x-0.1)^2+(y-0.3)^2+(z+0.2)^2-1");
  try {
    (void)validate_box_faces(s, box);
    BOOST_ERROR("no error for a surface touching the face x = 1.1");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()).find("face x = 1.1") != std::string::npos, e.what());
  }
  BOOST_CHECK_THROW((void)validate_input(s, box), InvalidInput);
  // Moved inwards by 0.01 it validates.
  BOOST_CHECK_NO_THROW((void)validate_input(Surface::parse("(x-0.09)^2+(y-0.3)^2+(z+0.2)^2-1"), box));
}

BOOST_AUTO_TEST_SUITE_END()
