#include <boost/test/unit_test.hpp>

#include <chrono>
#include <string>

#include "common/errors.h"
#include "meshing/del_mesh.h"
#include "meshing/input_validation.h"

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
    BOOST_TEST(std::string(e.what()).find("singular") != std::string::npos, e.what());
  }
  BOOST_CHECK_NO_THROW(validate_regular(Surface::parse("x^2+y^2+z^2-1"), Box3::cube(1.5)));
}

BOOST_AUTO_TEST_SUITE_END()
