#pragma once
//! \file huge_page_heap.h
//! Backs the program's malloc heap with transparent huge pages, for the programs that mesh
//! (`delmesh`, the experiments).
//!
//! Why.  A run touches its memory once, as the Delaunay triangulation, the records of its
//! Voronoi edges and the work queues grow; with 4 KiB pages that is one page fault per 4 KiB
//! (about 11 000 for the torus at size bound 0.05, 9 % of the run's samples in `perf`), and the
//! random lookups of the record tables miss the TLB.  With 2 MiB pages the faults fall tenfold
//! (10 900 to 1 100 on that torus) and a run takes 8–13 % less CPU time (genus2 and torus at
//! size bound 0.05, median of 10 paired whole-process runs); the peak resident memory grows by
//! a few MiB (2 on both: the last huge page of the heap is backed in full).
//!
//! How.  On Linux with glibc: allocations of up to 32 MiB are kept in the heap (M_MMAP_THRESHOLD)
//! and freed heap memory is never returned to the system (M_TRIM_THRESHOLD); one block is
//! allocated with a top pad of `bytes` (M_TOP_PAD, then set back to its default), so that the
//! heap grows by the whole reservation at once, the range from the block to the program break is
//! advised MADV_HUGEPAGE, and the block is freed again: the heap's first `bytes` are advised and
//! later allocations are carved from them.  (Where the heap cannot grow in one piece, blocks
//! totalling `bytes` are allocated one by one and advised instead.)  Only the page of one chunk
//! header is touched, so only the memory a run uses becomes resident, and the reservation costs
//! about a millisecond.  The kernel
//! honours the advice when transparent huge pages are `always` or `madvise`
//! (/sys/kernel/mm/transparent_hugepage/enabled); with `never` it has no effect.  Elsewhere than
//! Linux and glibc, under AddressSanitizer (its own allocator), and under strict overcommit
//! accounting (vm.overcommit_memory = 2, where untouched heap would still be charged) the call
//! does nothing.  Memory beyond the reserved range is allocated as before, on 4 KiB pages.
//!
//! Under tcmalloc (linked into the meshing programs where it is found, CMakeLists.txt) the
//! programs also link common/tcmalloc/huge_page_system_allocator.cpp, which sets
//! detail::heap_reservation before main(): the call then maps `bytes` of address space
//! (MAP_NORESERVE) advised MADV_HUGEPAGE and makes it tcmalloc's system allocator, from which
//! tcmalloc cuts its spans in order, falling back to its own allocator when the range is used
//! up.  That costs one mmap() and one madvise(); asking tcmalloc for the reservation as blocks
//! costs some milliseconds (112 system allocations, and tcmalloc's page map for the whole range
//! written at once: about 500 page faults).
//!
//! What it changes: where memory lies, never what is computed (no result of delmesh depends on
//! an address; the meshes are byte-identical with and without it).  Call it once, at the start
//! of main(), before other threads exist.

#include <cstddef>

namespace delmesh {

//! The heap's default reservation: 1.75 GiB of address space (not of memory), enough for the
//! torus at size bound 0.01 (1.25 GB) and below glibc's largest trim threshold (2 GiB − 1), which
//! keeps the freed range in the heap.
inline constexpr std::size_t huge_page_heap_default_bytes = std::size_t(7) << 28;

//! See the file comment.  Returns whether the range was advised (false where the call does
//! nothing, or the kernel refused the advice).
bool back_heap_with_huge_pages(std::size_t bytes = huge_page_heap_default_bytes);

namespace detail {
//! The reservation for a malloc other than glibc's, in place of the glibc one; null unless a
//! program links such a reservation (common/tcmalloc/), which sets it during static
//! initialisation.  Returns what back_heap_with_huge_pages() returns.
extern bool (*heap_reservation)(std::size_t bytes);
}  // namespace detail

}  // namespace delmesh
