#include "common/huge_page_heap.h"

#include <cstdlib>
#include <string>

#include <boost/test/unit_test.hpp>

#include "tests/kernel_memory.h"

namespace {

using delmesh::test::huge_page_mode;
using delmesh::test::strict_overcommit;

// The kB of anonymous huge pages in this process's heap mapping.
long heap_huge_page_kb() {
  long kb = 0;
  for (const auto& m : delmesh::test::mappings())
    if (m.header.find("[heap]") != std::string::npos) kb += m.huge_kb;
  return kb;
}

bool address_sanitizer() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#else
  return false;
#endif
#else
  return false;
#endif
}

}  // namespace

BOOST_AUTO_TEST_SUITE(huge_page_heap)

BOOST_AUTO_TEST_CASE(the_heap_that_follows_lies_on_huge_pages_where_the_kernel_offers_them) {
  const std::string mode = huge_page_mode();
  const bool offered = (mode == "always" || mode == "madvise") && !address_sanitizer() && !strict_overcommit();
#if defined(__linux__) && defined(__GLIBC__)
  BOOST_TEST(delmesh::back_heap_with_huge_pages(std::size_t(64) << 20) == offered);
#else
  BOOST_TEST(!delmesh::back_heap_with_huge_pages(std::size_t(64) << 20));
#endif
  // Memory allocated afterwards is ordinary memory: written and read back in full.
  constexpr std::size_t bytes = std::size_t(16) << 20;
  auto* p = static_cast<unsigned char*>(std::malloc(bytes));
  BOOST_REQUIRE(p != nullptr);
  for (std::size_t i = 0; i < bytes; ++i) p[i] = static_cast<unsigned char>(i * 7);
  bool same = true;
  for (std::size_t i = 0; i < bytes; ++i) same = same && p[i] == static_cast<unsigned char>(i * 7);
  BOOST_TEST(same);
  // With the advice taken, the 16 MiB just touched lie on 2 MiB pages (those wholly inside it,
  // as far as the kernel finds free ones: at least one).
  if (offered && mode == "madvise") BOOST_TEST(heap_huge_page_kb() >= 2048);
  std::free(p);
}

BOOST_AUTO_TEST_SUITE_END()
