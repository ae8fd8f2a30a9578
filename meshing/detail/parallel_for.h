#pragma once
// Deterministic data parallelism for the mesher: run(n, f) calls f(0), …, f(n−1), each exactly
// once, on up to `threads` threads (TBB), and returns when all are done.  Callers write each
// f(i)'s result to slot i and use the slots in index order afterwards, so what they compute does
// not depend on the number of threads.

#include <cstddef>
#include <functional>
#include <memory>

namespace delmesh::detail {

class ParallelFor {
 public:
  //! Uses min(threads, hardware_threads()) threads, or every hardware thread for threads < 1; one
  //! thread runs everything on the calling thread.
  explicit ParallelFor(int threads);
  ~ParallelFor();
  ParallelFor(ParallelFor&&) noexcept;
  ParallelFor& operator=(ParallelFor&&) noexcept;

  int threads() const { return threads_; }
  void run(std::size_t n, const std::function<void(std::size_t)>& f) const;

 private:
  struct Arena;
  int threads_ = 1;
  std::unique_ptr<Arena> arena_;
};

//! The number of hardware threads (at least 1).
int hardware_threads();

}  // namespace delmesh::detail
