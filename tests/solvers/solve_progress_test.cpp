#include "solvers/detail/solve_progress.h"

#include <boost/test/unit_test.hpp>

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(solve_progress_test)

BOOST_AUTO_TEST_CASE(a_solve_that_does_not_stop_is_complete_or_undecided) {
  detail::SolveProgress progress;
  BOOST_TEST(!progress.stopped());
  BOOST_TEST(progress.status(false) == SolveStatus::complete);
  BOOST_TEST(progress.status(true) == SolveStatus::undecided);
  BOOST_TEST(progress.unexplored_reason() == UndecidedReason::budget);
}

BOOST_AUTO_TEST_CASE(a_budget_stop_gives_its_status_and_budget_regions) {
  detail::SolveProgress progress;
  progress.stop(SolveStatus::box_limit);
  BOOST_TEST(progress.stopped());
  BOOST_TEST(!progress.non_isolated());
  BOOST_TEST(progress.status(false) == SolveStatus::box_limit);
  BOOST_TEST(progress.status(true) == SolveStatus::box_limit);
  BOOST_TEST(progress.unexplored_reason() == UndecidedReason::budget);
}

BOOST_AUTO_TEST_CASE(one_unresolved_region_past_the_count_stops_as_non_isolated) {
  detail::SolveProgress progress;
  for (std::size_t k = 0; k < tolerances::non_isolated_box_count; ++k) progress.count_unresolved();
  BOOST_TEST(!progress.stopped());
  progress.count_unresolved();
  BOOST_TEST(progress.stopped());
  BOOST_TEST(progress.non_isolated());
  BOOST_TEST(progress.status(true) == SolveStatus::non_isolated);
  BOOST_TEST(progress.unexplored_reason() == UndecidedReason::non_isolated);
}

BOOST_AUTO_TEST_SUITE_END()
