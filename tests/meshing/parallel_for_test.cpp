#include "meshing/core/detail/parallel_for.h"

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include <boost/test/unit_test.hpp>

using delmesh::detail::ParallelFor;

BOOST_AUTO_TEST_SUITE(parallel_for)

// Every index is called exactly once, on one thread and on several, below and above the least
// batch that goes to the threads.
BOOST_AUTO_TEST_CASE(calls_every_index_once) {
  for (int threads : {1, 2, 4}) {
    const ParallelFor parallel(threads);
    for (std::size_t n : {0, 1, 2, 7, 300}) {
      for (std::size_t least : {2, 64}) {
        std::vector<std::atomic<int>> calls(n);
        parallel.run(n, [&](std::size_t i) { calls[i].fetch_add(1); }, least);
        for (std::size_t i = 0; i < n; ++i) BOOST_TEST(calls[i].load() == 1);
      }
    }
  }
}

// A batch smaller than `least` runs on the calling thread whatever the number of threads.
BOOST_AUTO_TEST_CASE(a_batch_below_least_runs_on_the_calling_thread) {
  const ParallelFor parallel(4);
  const auto caller = std::this_thread::get_id();
  std::atomic<int> elsewhere{0};
  parallel.run(63, [&](std::size_t) { elsewhere += std::this_thread::get_id() != caller; }, 64);
  BOOST_TEST(elsewhere.load() == 0);
}

// invoke() calls each task exactly once, f before g on one thread, and rethrows a task's
// exception after both have stopped.
BOOST_AUTO_TEST_CASE(invoke_calls_both_tasks_once) {
  for (int threads : {1, 2, 4}) {
    const ParallelFor parallel(threads);
    std::atomic<int> f_calls{0}, g_calls{0}, order{0};
    int f_at = -1, g_at = -1;
    parallel.invoke([&] { f_at = order++; ++f_calls; }, [&] { g_at = order++; ++g_calls; });
    BOOST_TEST(f_calls.load() == 1);
    BOOST_TEST(g_calls.load() == 1);
    if (threads == 1) BOOST_TEST((f_at == 0 && g_at == 1));
    std::atomic<int> other{0};
    BOOST_CHECK_THROW(parallel.invoke([] { throw std::runtime_error("f"); }, [&] { ++other; }), std::runtime_error);
    BOOST_TEST(other.load() <= 1);
  }
}

// The thread count is the request capped by the hardware; 0 asks for every hardware thread.
BOOST_AUTO_TEST_CASE(threads_are_capped_by_the_hardware) {
  const int hardware = delmesh::detail::hardware_threads();
  BOOST_TEST(ParallelFor(0).threads() == hardware);
  BOOST_TEST(ParallelFor(1).threads() == 1);
  BOOST_TEST(ParallelFor(1024).threads() == hardware);
}

BOOST_AUTO_TEST_SUITE_END()
