#pragma once
// Deterministic data parallelism for the mesher: run(n, f) calls f(0), …, f(n−1), each exactly
// once, on up to `threads` threads (TBB), and returns when all are done.  Callers write each
// f(i)'s result to slot i and use the slots in index order afterwards, so what they compute does
// not depend on the number of threads.  invoke(f, g) runs two independent tasks side by side.

#include <cstddef>
#include <functional>
#include <memory>

namespace delmesh::detail {

class ParallelFor {
 public:
  //! Uses min(threads, hardware_threads()) threads, or every hardware thread for threads < 1; one
  //! thread runs everything on the calling thread.  every_batch: run() ignores `least` and hands
  //! every batch of two or more items to the threads (to exercise that path in tests).
  explicit ParallelFor(int threads, bool every_batch = false);
  ~ParallelFor();
  ParallelFor(ParallelFor&&) noexcept;
  ParallelFor& operator=(ParallelFor&&) noexcept;

  int threads() const { return threads_; }
  //! Calls f(0), …, f(n−1).  A batch of fewer than `least` items (at least 2) runs on the calling
  //! thread: handing a batch to the threads costs tens of microseconds, more than a small batch
  //! of cheap items takes (see the call sites' constants in common/tolerances.h).
  void run(std::size_t n, const std::function<void(std::size_t)>& f, std::size_t least = 2) const;
  //! Calls f and g: on two threads when there are threads, else f then g.  The caller makes them
  //! independent (neither reads what the other writes), so the results do not depend on which.
  //! An exception from either is rethrown here (after both have stopped).
  void invoke(const std::function<void()>& f, const std::function<void()>& g) const;

 private:
  struct Arena;
  int threads_ = 1;
  bool every_batch_ = false;
  std::unique_ptr<Arena> arena_;
};

//! The number of hardware threads (at least 1).
int hardware_threads();

}  // namespace delmesh::detail
