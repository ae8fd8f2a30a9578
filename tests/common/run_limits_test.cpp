// Tests of common/run_limits.h: the deadline and the interrupt flag as every phase reads them.
#include <atomic>
#include <chrono>
#include <thread>

#include <boost/test/unit_test.hpp>

#include "common/run_limits.h"

using namespace delmesh;
using Clock = std::chrono::steady_clock;

BOOST_AUTO_TEST_SUITE(run_limits)

BOOST_AUTO_TEST_CASE(unlimited_never_expires) {
  const RunLimits none;
  BOOST_TEST(none.unlimited());
  for (int i = 0; i < 1000; ++i) BOOST_TEST((none.expired() == StopReason::none));
  BOOST_TEST((none.expired_now() == StopReason::none));
  BOOST_TEST(!none.seconds_left());
  BOOST_CHECK_NO_THROW(none.check("a phase", true));
  // A time limit of 0 means none.
  BOOST_TEST(!RunLimits::after(0, nullptr).deadline());
}

BOOST_AUTO_TEST_CASE(the_deadline_is_seen_within_one_stride_of_calls) {
  const RunLimits limits = RunLimits::after(0.05, nullptr);
  BOOST_TEST((limits.expired_now() == StopReason::none));
  BOOST_TEST(*limits.seconds_left() > 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  BOOST_TEST(*limits.seconds_left() < 0);
  // Some call among the next calls_per_clock_reading reads the clock and sees it; every later
  // call then reports it at once.
  std::uint32_t calls = 0;
  while (limits.expired() == StopReason::none) ++calls;
  BOOST_TEST(calls < RunLimits::calls_per_clock_reading);
  BOOST_TEST((limits.expired() == StopReason::time_limit));
  BOOST_CHECK_THROW(limits.check("a phase"), RunStopped);
}

BOOST_AUTO_TEST_CASE(the_interrupt_flag_is_read_on_every_call) {
  std::atomic<bool> flag{false};
  const RunLimits limits = RunLimits::after(1e6, &flag);
  BOOST_TEST((limits.expired() == StopReason::none));
  flag = true;
  BOOST_TEST((limits.expired() == StopReason::interrupted));
  try {
    limits.check("differentiating the expression");
    BOOST_ERROR("check() did not throw");
  } catch (const RunStopped& stopped) {
    BOOST_TEST((stopped.reason() == StopReason::interrupted));
    BOOST_TEST(stopped.phase() == "differentiating the expression");
    BOOST_TEST(std::string(stopped.what()) == "interrupted by a signal while differentiating the expression");
  }
}

BOOST_AUTO_TEST_CASE(a_scope_makes_its_limits_current_on_its_thread_only) {
  std::atomic<bool> flag{true};
  const RunLimits limits(std::nullopt, &flag);
  BOOST_TEST(RunLimits::current().unlimited());
  {
    const RunLimits::Scope scope(limits);
    BOOST_TEST((RunLimits::current().expired() == StopReason::interrupted));
    bool other_thread_unlimited = false;
    std::thread([&] { other_thread_unlimited = RunLimits::current().unlimited(); }).join();
    BOOST_TEST(other_thread_unlimited);
  }
  BOOST_TEST(RunLimits::current().unlimited());
}

// The clock is read once every calls_per_clock_reading calls: a deadline that has passed is
// seen within that many calls, and once seen it stays seen.
BOOST_AUTO_TEST_CASE(a_passed_deadline_is_seen_within_one_reading_period) {
  const RunLimits far = RunLimits::after(1e6, nullptr);
  for (int i = 0; i < 1000; ++i) BOOST_TEST_REQUIRE((far.expired() == StopReason::none));
  const RunLimits limits = RunLimits::after(0.02, nullptr);
  std::this_thread::sleep_for(std::chrono::milliseconds(40));
  std::uint32_t calls = 1;
  while (limits.expired() == StopReason::none) ++calls;
  BOOST_TEST(calls <= RunLimits::calls_per_clock_reading);
  for (int i = 0; i < 100; ++i) BOOST_TEST((limits.expired() == StopReason::time_limit));
}

BOOST_AUTO_TEST_SUITE_END()
