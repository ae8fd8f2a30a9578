// The huge-page heap under tcmalloc (common/tcmalloc/huge_page_system_allocator.cpp): this suite
// is linked with tcmalloc and that object, as the meshing programs are.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/huge_page_heap.h"
#include "tests/kernel_memory.h"

namespace {

using delmesh::test::huge_page_mode;
using delmesh::test::strict_overcommit;

// The mapping that holds `address` (a default Mapping, lo = hi = 0, if none does).
delmesh::test::Mapping mapping_of(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  for (const auto& m : delmesh::test::mappings())
    if (m.lo <= a && a < m.hi) return m;
  return {};
}

// Writes every byte of [p, p + n) and reads it back.
bool written_and_read(unsigned char* p, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) p[i] = static_cast<unsigned char>(i * 7);
  bool same = true;
  for (std::size_t i = 0; i < n; ++i) same = same && p[i] == static_cast<unsigned char>(i * 7);
  return same;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(huge_page_system_allocator)

BOOST_AUTO_TEST_CASE(tcmalloc_cuts_its_heap_from_the_advised_range_then_from_its_own_allocator) {
  const std::string mode = huge_page_mode();
  const bool offered = (mode == "always" || mode == "madvise") && !strict_overcommit();
  constexpr std::size_t reserved = std::size_t(64) << 20, block = std::size_t(16) << 20;
  // (With huge pages off, madvise() may still accept the advice: the result is not asserted then.)
  const bool reserved_range = delmesh::back_heap_with_huge_pages(reserved);
  if (offered) BOOST_TEST(reserved_range);
  if (strict_overcommit()) BOOST_TEST(!reserved_range);
  BOOST_TEST(!delmesh::back_heap_with_huge_pages(reserved));  // once per process
  // Blocks totalling twice the reservation: the first come from the advised range (where the
  // kernel backs what is touched with 2 MiB pages, as far as it finds free ones: some), the
  // later ones from tcmalloc's own allocator; all of them are ordinary memory.
  std::vector<unsigned char*> blocks;
  std::size_t advised = 0;
  long huge_kb = 0;
  for (std::size_t taken = 0; taken < 2 * reserved; taken += block) {
    auto* p = static_cast<unsigned char*>(std::malloc(block));
    BOOST_REQUIRE(p != nullptr);
    BOOST_TEST(written_and_read(p, block));
    const delmesh::test::Mapping m = mapping_of(p);
    BOOST_TEST(m.lo < m.hi);
    if (m.advised) {
      ++advised;
      huge_kb = std::max(huge_kb, m.huge_kb);
    }
    blocks.push_back(p);
  }
  if (reserved_range) {
    BOOST_TEST(advised >= 1u);
    BOOST_TEST(advised < blocks.size());
    if (mode == "madvise") BOOST_TEST(huge_kb >= 2048);
  } else {
    BOOST_TEST(advised == 0u);
  }
  for (auto* p : blocks) std::free(p);
}

BOOST_AUTO_TEST_SUITE_END()
