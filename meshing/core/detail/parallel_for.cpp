#include "meshing/core/detail/parallel_for.h"

#include <algorithm>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

namespace delmesh::detail {

struct ParallelFor::Arena {
  tbb::task_arena arena;
  explicit Arena(int threads) : arena(threads) {}
};

ParallelFor::ParallelFor(int threads, bool every_batch)
    : threads_(threads < 1 ? hardware_threads() : std::min(threads, hardware_threads())), every_batch_(every_batch) {
  if (threads_ > 1) arena_ = std::make_unique<Arena>(threads_);
}
ParallelFor::~ParallelFor() = default;
ParallelFor::ParallelFor(ParallelFor&&) noexcept = default;
ParallelFor& ParallelFor::operator=(ParallelFor&&) noexcept = default;

void ParallelFor::run(std::size_t n, const std::function<void(std::size_t)>& f, std::size_t least) const {
  if (!arena_ || n < (every_batch_ ? 2 : std::max<std::size_t>(least, 2))) {
    for (std::size_t i = 0; i < n; ++i) f(i);
    return;
  }
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
    });
  });
}

void ParallelFor::invoke(const std::function<void()>& f, const std::function<void()>& g) const {
  if (!arena_) {
    f();
    g();
    return;
  }
  arena_->arena.execute([&] { tbb::parallel_invoke(f, g); });
}

int hardware_threads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

}  // namespace delmesh::detail
