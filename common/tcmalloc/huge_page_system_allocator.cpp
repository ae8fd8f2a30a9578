// The huge-page heap (common/huge_page_heap.h) for the programs linked with tcmalloc.
//
// tcmalloc takes the memory it carves its spans from through a SysAllocator, which a program may
// replace (gperftools' malloc_extension.h).  This file replaces it, when back_heap_with_huge_pages()
// is called, by one that hands out consecutive pieces of a single anonymous mapping of `bytes`
// advised MADV_HUGEPAGE, and passes requests that no longer fit to the allocator it replaced.
// Reserving is one mmap() and one madvise(): nothing is touched, no page is faulted in, and
// tcmalloc's page map grows only as the heap does.  (Asking tcmalloc itself for blocks totalling
// `bytes`, as the glibc path does, costs some milliseconds per process: 112 system allocations,
// and the page map's leaf for the whole range, 2 MiB zeroed at once, about 500 page faults, even
// in a process that never uses the range.)
//
// The object is linked only into those programs (CMakeLists.txt); it registers its reservation
// with huge_page_heap.cpp before main() runs.
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <new>

#include <gperftools/malloc_extension.h>

#include "common/huge_page_heap.h"

namespace delmesh {

namespace {

constexpr std::uintptr_t huge_page = std::uintptr_t(2) << 20;

std::uintptr_t align_up(std::uintptr_t x, std::uintptr_t alignment) {
  return (x + alignment - 1) / alignment * alignment;
}

//! Consecutive pieces of [next_, end_), then the replaced allocator.  tcmalloc calls Alloc()
//! under its own lock; the mutex makes the object safe without relying on that.
class HugePageSystemAllocator final : public SysAllocator {
 public:
  HugePageSystemAllocator(std::uintptr_t begin, std::uintptr_t end, SysAllocator* replaced)
      : next_(begin), end_(end), replaced_(replaced) {}

  void* Alloc(std::size_t size, std::size_t* actual_size, std::size_t alignment) override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      const std::uintptr_t start = align_up(next_, alignment > 0 ? alignment : 1);
      if (start >= next_ && start <= end_ && size <= end_ - start) {
        next_ = start + size;
        if (actual_size) *actual_size = size;
        return reinterpret_cast<void*>(start);
      }
    }
    return replaced_ ? replaced_->Alloc(size, actual_size, alignment) : nullptr;
  }

 private:
  std::mutex mutex_;
  std::uintptr_t next_, end_;
  SysAllocator* replaced_;
};

bool reserve(std::size_t bytes) {
  // Once: a second call finds the allocator replaced.
  static bool reserved = false;
  if (reserved) return false;
  // A mapping one huge page longer than asked, so that `bytes` of it start on a huge page.
  const std::size_t length = bytes + huge_page;
  void* mapping = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (mapping == MAP_FAILED) return false;
  const std::uintptr_t begin = align_up(reinterpret_cast<std::uintptr_t>(mapping), huge_page);
  const std::uintptr_t end = (begin + bytes) & ~(huge_page - 1);
  if (!(begin < end) || madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE) != 0) {
    munmap(mapping, length);
    return false;
  }
  // Never destroyed: tcmalloc may ask for memory until the process ends.
  alignas(HugePageSystemAllocator) static unsigned char storage[sizeof(HugePageSystemAllocator)];
  MallocExtension* extension = MallocExtension::instance();
  auto* allocator = new (storage) HugePageSystemAllocator(begin, end, extension->GetSystemAllocator());
  extension->SetSystemAllocator(allocator);
  reserved = true;
  return true;
}

[[maybe_unused]] const bool registered = [] {
  detail::heap_reservation = &reserve;
  return true;
}();

}  // namespace

}  // namespace delmesh
