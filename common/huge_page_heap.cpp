// The malloc heap on transparent huge pages.  See huge_page_heap.h.
#include "common/huge_page_heap.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <vector>

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#define DELMESH_HUGE_PAGE_HEAP 1
#endif
#if defined(__SANITIZE_ADDRESS__)
#undef DELMESH_HUGE_PAGE_HEAP
#endif
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#undef DELMESH_HUGE_PAGE_HEAP
#endif
#endif

namespace delmesh {

bool (*detail::heap_reservation)(std::size_t) = nullptr;

bool back_heap_with_huge_pages(std::size_t bytes) {
  // Under strict overcommit accounting (vm.overcommit_memory = 2) reserved address space is
  // charged whether touched or not, so a reservation could starve later allocations: none then,
  // whichever malloc reserves.
  {
    std::ifstream overcommit("/proc/sys/vm/overcommit_memory");
    int mode = 0;
    if (overcommit >> mode && mode == 2) return false;
  }
  if (detail::heap_reservation) return detail::heap_reservation(bytes);
#ifdef DELMESH_HUGE_PAGE_HEAP
  // glibc's largest M_MMAP_THRESHOLD on 64-bit systems; blocks of half of it stay in the heap.
  constexpr std::size_t heap_threshold = std::size_t(32) << 20;
  constexpr std::size_t block = heap_threshold / 2;
  constexpr std::uintptr_t huge_page = std::uintptr_t(2) << 20;
  if (mallopt(M_MMAP_THRESHOLD, static_cast<int>(heap_threshold)) != 1) return false;
  // The heap is never trimmed: trimming would hand the advised range back to the system.
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
  // A larger reservation would exceed the trim threshold and be handed back when freed.
  bytes = std::min<std::size_t>(bytes, std::numeric_limits<int>::max() - block);
  // The huge pages wholly inside [lo, hi).
  auto advise = [](std::uintptr_t lo, std::uintptr_t hi) {
    const std::uintptr_t first = (lo + huge_page - 1) & ~(huge_page - 1), last = hi & ~(huge_page - 1);
    return first < last && madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE) == 0;
  };
  // First, the heap grown once: one block asked for with a top pad of `bytes` makes glibc extend
  // the heap by both in one step, so the chunk headers it writes at the new top touch one page,
  // not one per block (each touch is a page fault, some microseconds each in a virtual machine).
  // The block and the pad then lie between the block's address and the program break, where the
  // heap ends: that range is advised.  The pad is set back to glibc's documented default.
  if (mallopt(M_TOP_PAD, static_cast<int>(bytes)) == 1) {
    void* first = std::malloc(block);
    const auto lo = reinterpret_cast<std::uintptr_t>(first), hi = reinterpret_cast<std::uintptr_t>(sbrk(0));
    mallopt(M_TOP_PAD, 128 * 1024);
    // Unless glibc mapped the block elsewhere (the heap could not grow by that much).
    const bool grown = first != nullptr && lo < hi && hi - lo >= bytes;
    const bool advised = grown && advise(lo, hi);
    std::free(first);
    if (grown) return advised;
  }
  // Otherwise block by block.
  std::vector<void*> blocks;
  blocks.reserve(bytes / block + 1);
  for (std::size_t taken = 0; taken < bytes; taken += block) {
    void* p = std::malloc(block);
    if (!p) break;
    blocks.push_back(p);
  }
  // The blocks follow one another in the heap (each after the previous one's chunk header), and
  // are advised as one range; if the heap could not grow in one piece (glibc then maps further
  // blocks elsewhere), each block is advised on its own, so that nothing between them is.
  bool contiguous = !blocks.empty();
  for (std::size_t i = 1; i < blocks.size() && contiguous; ++i) {
    const auto gap = reinterpret_cast<std::uintptr_t>(blocks[i]) - reinterpret_cast<std::uintptr_t>(blocks[i - 1]);
    contiguous = gap >= block && gap <= block + 64;
  }
  bool advised = false;
  if (contiguous) {
    advised = advise(reinterpret_cast<std::uintptr_t>(blocks.front()),
                     reinterpret_cast<std::uintptr_t>(blocks.back()) + block);
  } else {
    for (void* p : blocks) {
      const auto start = reinterpret_cast<std::uintptr_t>(p);
      advised = advise(start, start + block) || advised;
    }
  }
  for (void* p : blocks) std::free(p);
  return advised;
#else
  (void)bytes;
  return false;
#endif
}

}  // namespace delmesh
