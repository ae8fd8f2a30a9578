#include "experiments/child_process.h"

#include <stdexcept>
#include <string>

#include <boost/test/unit_test.hpp>

using namespace delmesh::experiments;

BOOST_AUTO_TEST_SUITE(child_process)

BOOST_AUTO_TEST_CASE(the_child_s_output_exit_code_and_memory_are_reported) {
  const ChildResult r = run_child("/bin/sh", {"-c", "echo vertices 12; echo status done; exit 3"});
  BOOST_TEST(r.exit_code == 3);
  BOOST_TEST(r.out == "vertices 12\nstatus done\n");
  BOOST_TEST(r.peak_bytes > 0u);
}

BOOST_AUTO_TEST_CASE(a_child_that_touches_more_memory_has_a_larger_peak) {
  // dd copies through one buffer of its block size, so a 256 MiB block is resident at once.  The
  // small run's peak is at least this process's own size at the spawn (ChildResult::peak_bytes),
  // which stays far below 256 MiB, sanitizers included.
  const ChildResult small = run_child("/bin/dd", {"if=/dev/zero", "of=/dev/null", "bs=1M", "count=1", "status=none"});
  const ChildResult large = run_child("/bin/dd", {"if=/dev/zero", "of=/dev/null", "bs=256M", "count=1", "status=none"});
  BOOST_TEST(small.exit_code == 0);
  BOOST_TEST(large.exit_code == 0);
  BOOST_TEST(large.peak_bytes >= (std::uint64_t{256} << 20));
  BOOST_TEST(large.peak_bytes > small.peak_bytes);
}

BOOST_AUTO_TEST_CASE(a_program_that_cannot_start_throws) {
  BOOST_CHECK_THROW(run_child("/nonexistent/program", {}), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()
