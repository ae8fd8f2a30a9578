// The huge-page heap under tcmalloc (common/tcmalloc/huge_page_system_allocator.cpp): this suite
// is linked with tcmalloc and that object, as the meshing programs are.
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "common/huge_page_heap.h"

namespace {

std::string huge_page_mode() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  const auto open = line.find('['), close = line.find(']');
  return open == std::string::npos || close == std::string::npos ? "" : line.substr(open + 1, close - open - 1);
}

bool strict_overcommit() {
  std::ifstream in("/proc/sys/vm/overcommit_memory");
  int mode = 0;
  return in >> mode && mode == 2;
}

// The mapping of /proc/self/smaps that holds `address`: whether it is advised MADV_HUGEPAGE
// (VmFlags "hg") and its kB of anonymous huge pages.
struct Mapping {
  bool found = false, advised = false;
  long huge_kb = 0;
};

Mapping mapping_of(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream in("/proc/self/smaps");
  std::string line;
  Mapping m;
  bool inside = false;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string first;
    fields >> first;
    if (first.empty()) continue;
    if (first.back() != ':') {
      // A header "lo-hi perms ...": the fields of the mapping follow.
      if (m.found) break;
      const auto dash = first.find('-');
      if (dash == std::string::npos) continue;
      const std::uintptr_t lo = std::stoull(first.substr(0, dash), nullptr, 16);
      const std::uintptr_t hi = std::stoull(first.substr(dash + 1), nullptr, 16);
      inside = lo <= a && a < hi;
      m.found = inside;
    } else if (inside && first == "AnonHugePages:") {
      fields >> m.huge_kb;
    } else if (inside && first == "VmFlags:") {
      std::string flag;
      while (fields >> flag) m.advised = m.advised || flag == "hg";
    }
  }
  return m;
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
    const Mapping m = mapping_of(p);
    BOOST_TEST(m.found);
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
