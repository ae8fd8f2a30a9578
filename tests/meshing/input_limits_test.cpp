// Tests that the phases before meshing read the command's limits (common/run_limits.h):
// validate_input (meshing/inputs/input_validation.h) and the mesh readers (meshing/inputs/
// detail/mesh_readers.h) throw RunStopped once they have passed, and run as before outside a scope.
#include <atomic>
#include <string>

#include <boost/test/unit_test.hpp>

#include "common/run_limits.h"
#include "meshing/inputs/detail/mesh_readers.h"
#include "meshing/inputs/input_validation.h"
#include "symbolic/catalog.h"

using namespace delmesh;

namespace {

const std::string octahedron =
    "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
    "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";

const std::string octahedron_ply =
    "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 8\nproperty list uchar int vertex_indices\nend_header\n"
    "1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n"
    "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";

// Asserts that `phase` throws RunStopped for the interrupt, in the phase `name` (any if empty).
template <class F>
void require_stopped(F&& phase, const std::string& name) {
  try {
    phase();
    BOOST_ERROR(name << ": ran to its end under a set interrupt flag");
  } catch (const RunStopped& stopped) {
    BOOST_TEST((stopped.reason() == StopReason::interrupted));
    if (!name.empty()) BOOST_TEST(stopped.phase() == name);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(input_limits)

BOOST_AUTO_TEST_CASE(validation_and_readers_stop_at_the_limits) {
  const auto& sphere = catalog_entry("sphere");
  const Surface surface = sphere.surface();  // built outside the scope
  std::atomic<bool> flag{true};
  const RunLimits interrupted(std::nullopt, &flag);
  {
    const RunLimits::Scope scope(interrupted);
    // Validation compiles E's gradient system first, which reads the limits too.
    require_stopped([&] { (void)validate_input(surface, sphere.box); }, "");
    require_stopped([&] { (void)detail::read_off("o.off", octahedron); }, "reading the mesh file");
    require_stopped([&] { (void)detail::read_ply("o.ply", octahedron_ply); }, "reading the mesh file");
  }
  // Outside the scope they run to their end.
  BOOST_TEST(validate_input(surface, sphere.box).face_boxes > 0u);
  BOOST_TEST(detail::read_off("o.off", octahedron).points.size() == 6u);
  BOOST_TEST(detail::read_ply("o.ply", octahedron_ply).points.size() == 6u);
}

BOOST_AUTO_TEST_SUITE_END()
